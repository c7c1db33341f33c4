"""Tools the tests need beyond the runtime: present, or a clear failure; skipped only when asked to.

A skip would make a check disappear from the summary of a CI run without anyone noticing, so a missing
tool fails the test with the command that installs it. A developer who works without a tool on purpose
sets the tool's documented variable to ``1`` (README, "Tests"); the tests are then reported as
skipped with that reason.
"""

from __future__ import annotations

import importlib
import os

import pytest

#: The notebook runner's tools (the dev extra) and the variable that skips the notebook tests on purpose.
NOTEBOOK_TOOLS = ("jupytext", "nbformat", "nbclient", "ipykernel")
NOTEBOOK_VARIABLE = "MOVING_BOGIE_SKIP_NOTEBOOKS"
NOTEBOOK_INSTALL = "pip install -e '.[dev]'"


def require(modules, *, needed_for: str, install: str, variable: str) -> list:
    """The imported ``modules``; a (module-level) skip if ``variable`` is ``1``; a failure if one is missing.

    The failure names the missing modules, what they are needed for, the install command and the variable.
    """
    if os.environ.get(variable) == "1":
        pytest.skip(
            f"{variable}=1: the tests of {needed_for} are skipped on request", allow_module_level=True
        )
    found, missing = [], []
    for name in modules:
        try:
            found.append(importlib.import_module(name))
        except ImportError:
            missing.append(name)
    if missing:
        pytest.fail(
            f"{', '.join(missing)} not installed, so the tests of {needed_for} cannot run. Install with "
            f"`{install}`, or set {variable}=1 to skip them on purpose.",
            pytrace=False,
        )
    return found


def require_notebook_tools() -> list:
    """jupytext, nbformat, nbclient and ipykernel, or a failure naming ``pip install -e '.[dev]'``."""
    return require(
        NOTEBOOK_TOOLS,
        needed_for="the notebooks (notebooks/run.py)",
        install=NOTEBOOK_INSTALL,
        variable=NOTEBOOK_VARIABLE,
    )
