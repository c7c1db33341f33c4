"""SymPy for the tests of derivations/: present, or a clear failure; skipped only when asked to.

Without SymPy the check that ``generated/`` and ``docs/proofs.md`` are current cannot run. A skip would
make it disappear from the summary of a CI run without anyone noticing, so a missing SymPy fails the
collection of these test files with the command that installs it. A developer who works without SymPy on
purpose sets ``MOVING_BOGIE_SKIP_DERIVATIONS=1`` (README, "Tests"); the files are then reported as skipped
with that reason.
"""

from __future__ import annotations

import importlib
import os

import pytest

SKIP_VARIABLE = "MOVING_BOGIE_SKIP_DERIVATIONS"
INSTALL = "pip install --no-deps -r requirements-derive.txt"


def require_sympy():
    """The ``sympy`` module; a module-level skip if :data:`SKIP_VARIABLE` is ``1``, else a failure."""
    if os.environ.get(SKIP_VARIABLE) == "1":
        pytest.skip(
            f"{SKIP_VARIABLE}=1: the tests of derivations/ are skipped on request", allow_module_level=True
        )
    try:
        return importlib.import_module("sympy")
    except ImportError:
        pytest.fail(
            f"SymPy is not installed, so the tests of derivations/ (generated/ is current, kernels against "
            f"the derivation, proofs) cannot run. Install it with `{INSTALL}`, or set {SKIP_VARIABLE}=1 to "
            "skip them on purpose.",
            pytrace=False,
        )
