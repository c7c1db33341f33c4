"""docs/architecture.md names every module of the package and of derivations/, and only modules that exist;
its table of imports between the stages of the pipeline is the one that tests/test_layout.py enforces.

A module is named by its path in backticks: ``stability/maps/map.py`` for
``src/moving_bogie/stability/maps/map.py``,
``__init__.py`` for the package's own, ``derivations/model.py`` for the derivation. The reverse check keeps
the document's own sections (not the list of examples from other codebases) from describing modules that
were renamed or removed.
"""

from __future__ import annotations

import re
from pathlib import Path

from test_layout import SHARED_HELPERS, STAGE_IMPORTS

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


#: A row of the table of imports: the stage (``kernels/``, ``api.py``) and what it imports.
ROW = re.compile(r"^\| `(\w+)(?:/|\.py)` \| (.*) \|$", re.MULTILINE)
#: A stage named in a row: a backticked subpackage (``roots/``) or entry module (``api.py``).
STAGE = re.compile(r"`(\w+)(?:/|\.py)`")


def _table(text: str) -> dict[str, set[str]]:
    """The stages each row of the table of imports names (``cli/`` imports "everything above": its row
    names only ``cli/``, which nothing imports)."""
    return {stage: set(STAGE.findall(imports)) - SHARED_HELPERS for stage, imports in ROW.findall(text)}


def test_the_table_of_imports_is_the_one_the_layout_test_enforces():
    """Each row names the stages its stage may import, as STAGE_IMPORTS of tests/test_layout.py has them
    (the shared helpers, which any stage uses, aside); every stage but the command line has a row."""
    table = _table(DOC.read_text(encoding="utf-8"))
    assert "cli" in table.pop("cli", set()), "the row of cli/ (everything above; nothing imports cli/)"
    expected = {
        stage: set(imports)
        for stage, imports in STAGE_IMPORTS.items()
        if stage not in ("cli", "moving_bogie", "__main__")
    }
    assert table == expected


def test_the_table_scan_sees_what_it_checks():
    text = "| `roots/` | `kernels/`, `model/` (`model/x.py`), `errors.py` |\n| `api.py` | `roots/` |\n"
    assert _table(text) == {"roots": {"kernels", "model"}, "api": {"roots"}}
