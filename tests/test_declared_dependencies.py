"""What the code imports is declared in pyproject.toml, and what is declared is imported somewhere."""

import ast
import functools
import re
import sys
import tomllib
from importlib.metadata import packages_distributions
from pathlib import Path

from parsed_sources import parsed

ROOT = Path(__file__).resolve().parent.parent
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())
#: SymPy for derivations/ is pinned in its own file (installed with --no-deps, see the README).
DERIVE = [
    line.split("#")[0].strip()
    for line in (ROOT / "requirements-derive.txt").read_text().splitlines()
    if line.split("#")[0].strip()
]
#: Declared for what they bring without being imported by name.
INDIRECT = {
    "gmpy2": "mpmath's GMP backend, picked up automatically",
    "ruff": "the linter, a command",
    "mypy": "the type checker, a command (.ci/run runs it on src/)",
    "ipykernel": "the kernel that runs the notebooks (started by nbclient)",
    "pytest-xdist": "a pytest plugin: the suite runs on two workers (pytest -n 2, --dist=loadscope)",
}


def _names(requirements) -> set:
    return {re.split(r"[<>=!~\[ ;]", r, maxsplit=1)[0].lower().replace("_", "-") for r in requirements}


@functools.cache
def _distributions() -> dict:
    """Top-level module -> distributions, read once (it scans every installed distribution)."""
    return packages_distributions()


#: The fields of a statement that hold statements: an import, at any depth, sits in one of them.
_BODIES = ("body", "orelse", "finalbody", "handlers", "cases")


def _statements(tree: ast.Module):
    """Every statement of ``tree``, nested ones included (the expressions are not walked)."""
    stack = [tree]
    while stack:
        node = stack.pop()
        yield node
        for field in _BODIES:
            stack.extend(getattr(node, field, ()))


@functools.cache
def _modules_named(path: Path) -> tuple:
    """Every module name ``path`` imports (``import``, absolute ``from ... import``, ``importorskip``).

    Parsed once per file for all the folders that hold it. The imports are read off the statements; the
    whole tree is walked for ``importorskip(...)`` calls only where the word occurs in the text."""
    text, tree = path.read_text(encoding="utf-8"), parsed(path)
    modules = []
    for node in _statements(tree):
        if isinstance(node, ast.Import):
            modules += [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            modules.append(node.module)
    if "importorskip" in text:
        modules += [
            node.args[0].value
            for node in ast.walk(tree)
            if isinstance(node, ast.Call)
            and getattr(node.func, "attr", None) == "importorskip"
            and node.args
            and isinstance(node.args[0], ast.Constant)
        ]
    return tuple(modules)


@functools.cache
def _imported(folder: Path) -> frozenset:
    """Distributions of every top-level third-party module imported under ``folder``."""
    dists = _distributions()
    local = {path.stem for path in folder.rglob("*.py")}  # sibling modules (tests import helpers)
    found = set()
    for path in folder.rglob("*.py"):
        for module in _modules_named(path):
            top = module.split(".")[0]
            if top in sys.stdlib_module_names or top in local or top in ("moving_bogie", "derivations"):
                continue
            for dist in dists.get(top, [top]):
                found.add(dist.lower().replace("_", "-"))
    return frozenset(found)


def test_runtime_imports_are_runtime_dependencies():
    declared = _names(PYPROJECT["project"]["dependencies"])
    missing = _imported(ROOT / "src" / "moving_bogie") - declared
    assert not missing, f"imported by the runtime but not in [project] dependencies: {sorted(missing)}"


def test_test_and_derivation_imports_are_declared():
    extras = PYPROJECT["project"]["optional-dependencies"]
    declared = _names(PYPROJECT["project"]["dependencies"]) | _names(extras["dev"]) | _names(DERIVE)
    declared |= _names(extras["docs"])  # selenium: tests/test_docs_site.py drives the browser
    used = _imported(ROOT / "tests") | _imported(ROOT / "derivations")
    missing = used - declared
    assert not missing, f"imported by tests or derivations but not declared: {sorted(missing)}"


def test_every_dev_dependency_is_used():
    # notebooks/run.py, the headless notebook runner, imports jupytext, nbformat and nbclient
    folders = ("tests", "derivations", "src", "notebooks")
    used = set().union(*(_imported(ROOT / folder) for folder in folders))
    unused = _names(PYPROJECT["project"]["optional-dependencies"]["dev"]) - used - set(INDIRECT)
    assert not unused, f"declared in [dev] but never imported: {sorted(unused)}"
