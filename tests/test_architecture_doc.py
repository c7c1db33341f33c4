"""docs/architecture.md names every module of the package and of derivations/, and only modules that exist.

A module is named by its path in backticks: ``stability/maps/map.py`` for
``src/moving_bogie/stability/maps/map.py``,
``__init__.py`` for the package's own, ``derivations/model.py`` for the derivation. The reverse check keeps
the document's own sections (not the list of examples from other codebases) from describing modules that
were renamed or removed.
"""

from __future__ import annotations

import re
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
PACKAGE = REPO / "src" / "moving_bogie"
DOC = REPO / "docs" / "architecture.md"

#: A backticked path of a Python file, optionally followed by ``::name``.
NAMED = re.compile(r"`([\w/]+\.py)(?:::[\w.]+)?`")


def _modules() -> list[str]:
    package = [str(p.relative_to(PACKAGE)) for p in sorted(PACKAGE.rglob("*.py"))]
    derivations = [str(p.relative_to(REPO)) for p in sorted((REPO / "derivations").glob("*.py"))]
    return package + derivations


def _named(text: str | None = None) -> set[str]:
    return set(NAMED.findall(DOC.read_text(encoding="utf-8") if text is None else text))


def _own_sections() -> str:
    """The pipeline, the layout and the rules: the part that describes this repository (the examples
    followed name files of other codebases)."""
    text = DOC.read_text(encoding="utf-8")
    return text[: text.index("## Examples followed")]


def test_every_module_is_named():
    missing = [module for module in _modules() if module not in _named()]
    assert not missing, "docs/architecture.md does not name these modules (add a line in 'The layout'):\n" + (
        "\n".join(missing)
    )


def test_every_named_module_exists():
    stale = [
        name
        for name in sorted(_named(_own_sections()))
        if not (PACKAGE / name).is_file()
        and not (REPO / name).is_file()
        and not (REPO / "src" / name).is_file()
    ]
    assert not stale, "docs/architecture.md names modules that do not exist:\n" + "\n".join(stale)


def test_the_scan_sees_what_it_checks():
    """The lists are not empty and the pattern reads the document's forms, so an empty diff means a match."""
    assert len(_modules()) > 100 and "generated/asymptotics.py" in _modules()
    assert NAMED.findall("`roots/frequencies.py::FrequencyResult`, `__init__.py` and `x.pyc`") == [
        "roots/frequencies.py",
        "__init__.py",
    ]
