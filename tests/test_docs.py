"""The hand-written docs stay true to the code: every equation is mapped, every name they cite exists.

docs/theory_to_code.md must cover each equation (1)-(66) of the paper; the files, functions and tests that
docs/theory_to_code.md, docs/validation.md, docs/troubleshooting.md and docs/architecture.md cite must
exist; relative links between the docs and from the README must point at files that exist.
"""

from __future__ import annotations

import ast
import re
from functools import cache
from pathlib import Path

import pytest
from parsed_sources import parsed

ROOT = Path(__file__).resolve().parent.parent
DOCS = ("theory_to_code.md", "validation.md", "troubleshooting.md", "architecture.md")
SEARCHED = (
    "src/moving_bogie",
    "src/moving_bogie/cli",
    "derivations",
    "generated",
    "tests",
    "benchmarks",
    "notebooks",
)


def _text(name: str) -> str:
    return (ROOT / "docs" / name).read_text(encoding="utf-8")


def test_every_equation_of_the_paper_is_mapped():
    text = _text("theory_to_code.md")
    covered = set()
    for row in text.splitlines():
        cell = row.split("|")[1].strip() if row.startswith("| (") else ""
        for a, b in re.findall(r"\((\d+)\)(?:-\((\d+)\))?", cell):
            covered.update(range(int(a), int(b or a) + 1))
    missing = sorted(set(range(1, 67)) - covered)
    assert not missing, f"equations without a row in docs/theory_to_code.md: {missing}"


@cache
def _find(filename: str) -> Path | None:
    """A cited file: a path from the repository root, or a bare name in one of the source folders."""
    if (ROOT / filename).is_file():
        return ROOT / filename
    hits = [ROOT / folder / filename for folder in SEARCHED if (ROOT / folder / filename).is_file()]
    return hits[0] if len(hits) == 1 else None


@cache
def _defined(path: Path) -> frozenset[str]:
    names = set()
    for node in ast.walk(parsed(path)):
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef):
            names.add(node.name)
        elif isinstance(node, ast.Assign):
            names.update(t.id for t in node.targets if isinstance(t, ast.Name))
    return frozenset(names)


def _citations(text: str):
    """(file, name or None) for every `path.py` and `path.py::name` in backticks."""
    for body in re.findall(r"`([^`]+)`", text):
        match = re.fullmatch(r"([\w./-]+\.py)(?:::(\w+))?", body.strip())
        if match:
            yield match.group(1), match.group(2)


@pytest.mark.parametrize("doc", DOCS)
def test_cited_files_and_names_exist(doc):
    problems = []
    text = _text(doc)
    for filename, name in _citations(text):
        path = _find(filename)
        if path is None:
            problems.append(f"{filename}: no such file (or ambiguous)")
        elif name and name not in _defined(path):
            problems.append(f"{filename}::{name}: not defined there")
    # names cited after a `file.py::name`, as in "`tests/x.py::test_a`, `test_b`"
    for filename, _first, rest in re.findall(r"`([\w./-]+\.py)::(\w+)`((?:, `\w+`)+)", text):
        path = _find(filename)
        for name in re.findall(r"`(\w+)`", rest):
            if path is not None and name not in _defined(path):
                problems.append(f"{filename}::{name}: not defined there")
    assert not problems, "\n".join(problems)


@pytest.mark.parametrize("doc", (*(f"docs/{d}" for d in DOCS), "README.md"))
def test_relative_links_resolve(doc):
    path = ROOT / doc
    text = path.read_text(encoding="utf-8")
    broken = [
        target
        for target in re.findall(r"\]\(([^)#:\s]+)(?:#[^)]*)?\)", text)
        if not (path.parent / target).exists()
    ]
    assert not broken, f"{doc}: broken links {broken}"
