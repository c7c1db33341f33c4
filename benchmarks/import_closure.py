"""The files of ``src/moving_bogie`` that a benchmark's work can load: the modules it loaded in its own
process, and the import closure of the entry modules of the work it ran in child processes (a command, Dask
workers).

A record keeps the hash of each such file (``records.write_record(..., entries=...)``), so an edit elsewhere
in the package leaves it current. The closure is read from the source, not from a run: every ``import`` and
``from ... import`` statement of a module counts, those inside functions too (the commands import their
heavy modules inside ``run``), so work done in a subprocess or a Dask worker is covered as long as its entry
is named. Importing ``a.b.c`` runs ``a/__init__.py`` and ``a/b/__init__.py``: those count too. A package's
data files (``*.csv`` beside its modules) count with the package. Names looked up at run time (the lazy
attributes of ``moving_bogie/__init__.py``, the subcommand table of ``cli/__init__.py``) are not followed:
name their modules among the entries.
"""

from __future__ import annotations

import ast
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SRC = ROOT / "src"
PACKAGE = "moving_bogie"


def module_file(name: str, src: Path = SRC) -> Path | None:
    """The file of module ``name`` under ``src`` (its ``__init__.py`` for a package), None outside it."""
    base = src.joinpath(*name.split("."))
    for candidate in (base / "__init__.py", base.with_suffix(".py")):
        if candidate.is_file():
            return candidate
    return None


def imported_names(path: Path, name: str) -> set[str]:
    """Every module named by an import statement of the module ``name`` at ``path``, relative ones resolved;
    ``from m import x`` names both ``m`` and ``m.x`` (``x`` may be a submodule)."""
    is_package = path.name == "__init__.py"
    package = name if is_package else name.rpartition(".")[0]
    found: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), str(path))):
        if isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                parts = package.split(".")
                base = ".".join(parts[: len(parts) - node.level + 1])
                module = f"{base}.{node.module}" if node.module else base
            else:
                module = node.module or ""
            found.add(module)
            found.update(f"{module}.{alias.name}" for alias in node.names)
    return {m for m in found if m == PACKAGE or m.startswith(PACKAGE + ".")}


def closure(entries: tuple[str, ...], src: Path = SRC) -> list[str]:
    """The repository-relative paths of every file the modules ``entries`` can load, sorted."""
    seen: set[str] = set()
    todo = list(entries)
    files: set[Path] = set()
    while todo:
        name = todo.pop()
        parts = name.split(".")
        for depth in range(1, len(parts) + 1):  # the parent packages run first
            prefix = ".".join(parts[:depth])
            if prefix in seen:
                continue
            seen.add(prefix)
            path = module_file(prefix, src)
            if path is None:
                continue
            files.add(path)
            if path.name == "__init__.py":
                files.update(p for p in path.parent.glob("*.csv"))
            todo.extend(imported_names(path, prefix))
    return sorted(str(p.relative_to(src.parent)) for p in files)


def loaded(src: Path = SRC) -> list[str]:
    """The repository-relative paths of the package's modules loaded in this process (and the data files of
    its loaded packages), sorted."""
    root = (src / PACKAGE).resolve()
    files: set[Path] = set()
    for module in list(sys.modules.values()):
        path = Path(getattr(module, "__file__", None) or "/").resolve()
        if path.is_relative_to(root) and path.suffix == ".py":
            files.add(path)
            if path.name == "__init__.py":
                files.update(path.parent.glob("*.csv"))
    return sorted(str(p.relative_to(src.resolve().parent)) for p in files)


def measured_files(entries: tuple[str, ...], src: Path = SRC) -> list[str]:
    """The files a record depends on: :func:`closure` of ``entries`` and the modules :func:`loaded` here."""
    return sorted(set(closure(entries, src)) | set(loaded(src)))
