"""The layout rules of docs/architecture.md ("Rules"), checked on the source text with :mod:`ast`.

(a) no library module imports the command-line interface ``moving_bogie.cli``;
(b) no module imports a private (``_name``) helper or module from another module of the package;
(c) neither the modules nor the subpackages import each other in a cycle, counting the imports inside
    functions too (a deferred import hides a circle, it does not remove it); only imports under
    ``if TYPE_CHECKING:``, which never run, are left out;
(d) no tracked file refers to a file outside the repository;
(e) no module reaches into another module's private attribute (``obj._name`` where ``_name`` is not
    defined in the module that uses it).

Each check runs on the files themselves, so each fails with the file, line and name that break the rule.
"""

from __future__ import annotations

import ast
import functools
import re
import subprocess
import tomllib
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import pytest
from parsed_sources import parsed

REPO = Path(__file__).resolve().parent.parent
SRC = REPO / "src"
PACKAGE = SRC / "moving_bogie"
ROOT = "moving_bogie"

#: Private names still imported across modules in areas being split/redone; each entry is
#: (importing module, imported module, name). The coordinator empties this list when those areas land.
PRIVATE_IMPORTS_ALLOWED: set[tuple[str, str, str]] = {
    # being split/redone (kernels/, response/): the polynomial helpers move to kernels/polyroots.py
    ("moving_bogie.response.shapes", "moving_bogie.kernels.track", "_min_relative_separation"),
    ("moving_bogie.response.shapes", "moving_bogie.kernels.track", "_polyder"),
    ("moving_bogie.response.shapes", "moving_bogie.kernels.track", "_polyval"),
}


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(SRC).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


MODULES: dict[str, Path] = {_module_name(p): p for p in sorted(PACKAGE.rglob("*.py"))}


@functools.cache
def _parsed() -> tuple[tuple[str, ast.Module], ...]:
    """Every module of the package parsed once for all the checks (the trees are only read)."""
    return tuple((name, parsed(path)) for name, path in MODULES.items())


def _trees() -> Iterator[tuple[str, ast.Module]]:
    yield from _parsed()


def _is_private(name: str) -> bool:
    return name.startswith("_") and not name.startswith("__")


def _resolve(module: str, node: ast.ImportFrom) -> str:
    """The absolute module name of ``from <node.module> import ...`` written in `module`."""
    if not node.level:
        return node.module or ""
    parts = module.split(".")
    if MODULES[module].name != "__init__.py":
        parts.pop()  # a relative import in a plain module starts from its package
    parts = parts[: len(parts) - node.level + 1]
    return ".".join(parts + ([node.module] if node.module else []))


def _imports(module: str, nodes: list[ast.stmt] | ast.Module) -> Iterator[tuple[int, str, list[str]]]:
    """(line, imported module, names) for every import statement among `nodes` (all levels)."""
    for node in _walk(nodes) if isinstance(nodes, ast.AST) else nodes:
        if isinstance(node, ast.Import):
            for alias in node.names:
                yield node.lineno, alias.name, []
        elif isinstance(node, ast.ImportFrom):
            yield node.lineno, _resolve(module, node), [alias.name for alias in node.names]


def _targets(imported: str, names: list[str]) -> set[str]:
    """The package modules an import loads: ``from pkg import mod`` loads ``pkg.mod``."""
    submodules = {f"{imported}.{name}" for name in names if f"{imported}.{name}" in MODULES}
    if submodules:
        return submodules
    # the root package is imported before any of its modules anyway: it is no dependency of its own
    return {imported} if imported in MODULES and imported != ROOT else set()


def _top_level_statements(body: list[ast.stmt]) -> Iterator[ast.stmt]:
    """Statements executed when the module is imported: not inside functions or ``if TYPE_CHECKING``."""
    for node in body:
        if isinstance(node, ast.If):
            test = ast.unparse(node.test)
            if test in ("TYPE_CHECKING", "typing.TYPE_CHECKING"):
                yield from _top_level_statements(node.orelse)
                continue
            yield from _top_level_statements(node.body)
            yield from _top_level_statements(node.orelse)
        elif isinstance(node, ast.Try):
            for block in (node.body, *(h.body for h in node.handlers), node.orelse, node.finalbody):
                yield from _top_level_statements(block)
        elif isinstance(node, ast.With | ast.ClassDef):
            yield from _top_level_statements(node.body)
        else:
            yield node


def _runtime_nodes(tree: ast.AST) -> tuple[ast.AST, ...]:
    """Every node of `tree` that can run: all of it, inside functions too, except ``if TYPE_CHECKING:``.

    Depth first, each node before its children (computed once per tree, :func:`_once`)."""
    return _once("runtime", tree, lambda: tuple(_runtime_walk(tree)))


def _runtime_walk(tree: ast.AST) -> Iterator[ast.AST]:
    """The nodes of :func:`_runtime_nodes`, with a stack (a recursive generator passes every node up
    through each level above it: quadratic in the depth). ``checked``: whether the nodes of that level
    are tested for ``if TYPE_CHECKING:`` (the statements of its ``else:`` are taken whole)."""
    stack: list[tuple[Iterator[ast.AST], bool]] = [(ast.iter_child_nodes(tree), True)]
    while stack:
        level, checked = stack[-1]
        node = next(level, None)
        if node is None:
            stack.pop()
        elif checked and isinstance(node, ast.If) and _is_type_checking(node.test):
            stack.append((iter(node.orelse), False))
        else:
            yield node
            stack.append((ast.iter_child_nodes(node), True))


def _is_type_checking(test: ast.expr) -> bool:
    return ast.unparse(test) in ("TYPE_CHECKING", "typing.TYPE_CHECKING")


#: Results computed once per tree (the trees of :func:`_parsed` live as long as the session; a tree is
#: kept here with its results, so that its ``id`` is never reused by another tree).
_ONCE: dict[tuple[str, int], tuple[ast.AST, Any]] = {}


def _once(what: str, tree: ast.AST, compute: Callable[[], Any]) -> Any:
    key = (what, id(tree))
    if key not in _ONCE:
        _ONCE[key] = (tree, compute())
    return _ONCE[key][1]


def _walk(tree: ast.AST) -> tuple[ast.AST, ...]:
    """``ast.walk(tree)`` (breadth first), listed once per tree: every check reads the same trees."""
    return _once("walk", tree, lambda: tuple(ast.walk(tree)))


def _layer(module: str) -> str:
    """The subpackage (``roots``) or top-level module (``errors``) that `module` belongs to."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else parts[0]


def _find_cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """One cycle of the directed `graph` as a list of nodes (first == last), or None."""
    state: dict[str, int] = {}  # 1: on the current path, 2: finished
    path: list[str] = []

    def visit(node: str) -> list[str] | None:
        state[node] = 1
        path.append(node)
        for succ in sorted(graph.get(node, ())):
            if state.get(succ) == 1:
                return path[path.index(succ) :] + [succ]
            if succ not in state and (cycle := visit(succ)):
                return cycle
        path.pop()
        state[node] = 2
        return None

    for node in sorted(graph):
        if node not in state and (cycle := visit(node)):
            return cycle
    return None


def test_no_library_module_imports_the_cli():
    offenders = []
    for module, tree in _trees():
        if _layer(module) in ("cli", "__main__"):
            continue
        for line, imported, names in _imports(module, tree):
            loaded = {imported} | {f"{imported}.{name}" for name in names}
            if any(m == f"{ROOT}.cli" or m.startswith(f"{ROOT}.cli.") for m in loaded):
                offenders.append(f"{MODULES[module].relative_to(REPO)}:{line} imports {imported}")
    assert not offenders, "library modules must not import the CLI:\n" + "\n".join(offenders)


def test_no_private_name_is_imported_across_modules():
    offenders = []
    for module, tree in _trees():
        for line, imported, names in _imports(module, tree):
            if imported.split(".")[0] != ROOT:
                continue
            private_module = any(_is_private(part) for part in imported.split("."))
            for name in names or [""]:
                if (module, imported, name) in PRIVATE_IMPORTS_ALLOWED:
                    continue
                if private_module or _is_private(name):
                    what = f"{imported}.{name}" if name else imported
                    offenders.append(f"{MODULES[module].relative_to(REPO)}:{line} imports {what}")
    assert not offenders, (
        "private helpers imported across modules (make them public, documented, in the module that owns "
        "the concept):\n" + "\n".join(offenders)
    )


def _import_graphs(statements) -> tuple[dict[str, set[str]], dict[str, set[str]]]:
    """(module -> modules it imports, subpackage -> subpackages it imports) over `statements(tree)`."""
    modules: dict[str, set[str]] = {}
    layers: dict[str, set[str]] = {}
    for module, tree in _trees():
        for _, imported, names in _imports(module, list(statements(tree))):
            for target in _targets(imported, names) - {module}:
                modules.setdefault(module, set()).add(target)
                if _layer(target) != _layer(module):
                    layers.setdefault(_layer(module), set()).add(_layer(target))
    return modules, layers


def test_modules_import_each_other_without_a_cycle():
    """Counting imports inside functions: a circle closed by a deferred import is still a circle."""
    modules, layers = _import_graphs(_runtime_nodes)
    assert layers, "no import between subpackages found: the scan is broken"
    assert (cycle := _find_cycle(modules)) is None, "modules import each other: " + " -> ".join(cycle)


def test_data_flows_one_way_between_subpackages():
    """Counting imports inside functions too, no subpackage reaches back up the pipeline."""
    _, layers = _import_graphs(_runtime_nodes)
    assert (cycle := _find_cycle(layers)) is None, "subpackages import each other: " + " -> ".join(cycle)


#: The stages of the pipeline (docs/architecture.md, "The pipeline" and its table of imports): which of them
#: each subpackage (or entry module) may import. Every subpackage of the runtime has its line, so a new
#: package, or a new import between stages, is a decision written here and in the table. The shared helpers
#: (``errors.py``, ``typing.py``, ``output.py``, ``presentation.py``, ``html_repr.py``, ``export.py``,
#: ``checkpoint.py``, ``processes.py``, ``generated/``, ``data/``) are not stages: any module may use them,
#: without a cycle (:func:`test_modules_import_each_other_without_a_cycle`).
STAGE_IMPORTS: dict[str, frozenset[str]] = {
    "model": frozenset(),
    "kernels": frozenset(),
    "roots": frozenset({"kernels", "model"}),
    "response": frozenset({"roots", "kernels", "model"}),
    "stability": frozenset({"roots", "kernels", "model"}),
    "validation": frozenset({"response", "roots", "kernels", "model"}),
    "sweep": frozenset({"stability", "roots", "kernels", "model", "soil"}),
    "soil": frozenset({"kernels"}),
    "soil_vehicle": frozenset({"model", "soil", "kernels", "stability"}),
    "api": frozenset({"stability", "validation", "response", "roots", "kernels", "model", "soil"})
    | {"soil_vehicle"},
    "paper": frozenset({"api", "stability", "validation", "response", "roots", "model"}),
    "cli": frozenset(
        {"api", "paper", "sweep", "validation", "stability", "response", "roots", "kernels", "model"}
        | {"soil"}
    ),
    ROOT: frozenset({"model"}),  # __init__.py: the public names, loaded lazily from api.py and the rest
    "__main__": frozenset({"cli"}),
}
#: Imports between two stages that only some modules make, each with its reason: (importer, imported) ->
#: the importing modules.
NARROW_STAGE_IMPORTS: dict[tuple[str, str], frozenset[str]] = {}
SHARED_HELPERS = frozenset(
    {"errors", "typing", "output", "presentation", "html_repr", "export", "checkpoint", "processes"}
    | {"generated", "data"}
)


def _stage_imports() -> Iterator[tuple[str, str, str]]:
    """(module, its stage, imported stage) of every runtime import between two stages of the pipeline."""
    for module, tree in _trees():
        for _, imported, names in _imports(module, list(_runtime_nodes(tree))):
            for target in _targets(imported, names):
                if _layer(target) != _layer(module) and _layer(target) not in SHARED_HELPERS:
                    yield module, _layer(module), _layer(target)


def _stage_offenders(
    found: Iterator[tuple[str, str, str]],
    narrow: dict[tuple[str, str], frozenset[str]] = NARROW_STAGE_IMPORTS,
    stages: dict[str, frozenset[str]] = STAGE_IMPORTS,
) -> list[str]:
    offenders = []
    for module, stage, target in found:
        if stage in SHARED_HELPERS:
            offenders.append(f"{module} is a shared helper and imports the stage {target}")
        elif stage not in stages:
            offenders.append(f"{module}: the stage {stage} has no line in STAGE_IMPORTS")
        elif target not in stages[stage]:
            offenders.append(f"{module} imports {target}, which {stage} does not import")
        elif module not in narrow.get((stage, target), frozenset({module})):
            offenders.append(f"{module} imports {target}, which only {narrow[stage, target]} may")
    return offenders


def test_every_stage_imports_only_the_stages_above_it():
    """Every package of the runtime is a stage of STAGE_IMPORTS (or a shared helper), and imports only the
    stages its line names (docs/architecture.md, the table of imports), counting imports inside functions."""
    stages = {_layer(module) for module in MODULES}
    assert not stages - set(STAGE_IMPORTS) - SHARED_HELPERS, stages - set(STAGE_IMPORTS) - SHARED_HELPERS
    offenders = sorted(set(_stage_offenders(_stage_imports())))
    assert not offenders, "imports between stages not in the table:\n" + "\n".join(offenders)


def test_the_stage_check_sees_what_it_checks():
    found = set(_stage_imports())
    assert ("moving_bogie.roots.frequencies", "roots", "kernels") in found
    assert ("moving_bogie.roots.table2", "roots", "model") in found
    # a narrow import (only some modules of a stage may make it), checked on a table of its own
    narrow = {("roots", "model"): frozenset({"moving_bogie.roots.table2"})}
    assert _stage_offenders(
        iter(
            [
                ("moving_bogie.roots.window", "roots", "model"),  # narrow: another module
                ("moving_bogie.kernels.track", "kernels", "model"),  # upward: kernels imports no stage
                ("moving_bogie.new.x", "new", "model"),  # a stage without its line
                ("moving_bogie.errors", "errors", "model"),  # a helper importing a stage
                ("moving_bogie.roots.table2", "roots", "model"),
                ("moving_bogie.roots.strip", "roots", "kernels"),
            ]
        ),
        narrow,
    ) == [
        "moving_bogie.roots.window imports model, which only "
        + str(frozenset({"moving_bogie.roots.table2"}))
        + " may",
        "moving_bogie.kernels.track imports model, which kernels does not import",
        "moving_bogie.new.x: the stage new has no line in STAGE_IMPORTS",
        "moving_bogie.errors is a shared helper and imports the stage model",
    ]


def _room(module: str) -> str:
    """The room of `module` inside its subpackage (``moving_bogie.roots.count``), or the module itself."""
    parts = module.split(".")
    room = ".".join(parts[:3])
    return room if len(parts) > 3 or MODULES.get(room, Path()).name == "__init__.py" else module


def test_the_rooms_of_a_subpackage_import_each_other_without_a_cycle():
    """Importing one module of a room runs the room's ``__init__.py``, which imports all of its modules: the
    rooms (``roots/count/``, ``roots/search/``, ...) and the modules beside them form no circle either."""
    graph: dict[str, set[str]] = {}
    for module, tree in _trees():
        for _, imported, names in _imports(module, list(_runtime_nodes(tree))):
            for target in _targets(imported, names):
                if _layer(target) == _layer(module) and _room(target) != _room(module):
                    graph.setdefault(_room(module), set()).add(_room(target))
    assert "moving_bogie.roots.count" in graph.get("moving_bogie.roots.search", ()), "the scan is broken"
    assert (cycle := _find_cycle(graph)) is None, "rooms import each other: " + " -> ".join(cycle)


def test_no_package_hides_one_of_its_modules():
    """A name re-exported by a package's ``__init__.py`` never equals one of its modules: otherwise
    ``from pkg import mod`` (and a monkeypatch target ``"pkg.mod.name"``) would get the re-exported object."""
    offenders = []
    for module, tree in _trees():
        path = MODULES[module]
        if path.name != "__init__.py":
            continue
        submodules = {p.stem for p in path.parent.glob("*.py")} | {
            p.parent.name for p in path.parent.glob("*/__init__.py")
        }
        for node in tree.body:
            bound = []
            if isinstance(node, ast.ImportFrom | ast.Import):
                bound = [a.asname or a.name.split(".")[0] for a in node.names]
                if isinstance(node, ast.ImportFrom) and _resolve(module, node) == module:
                    bound = []  # ``from . import mod`` binds the module itself
            elif isinstance(node, ast.FunctionDef | ast.ClassDef):
                bound = [node.name]
            offenders += [
                f"{path.relative_to(REPO)}:{node.lineno} binds {n}" for n in bound if n in submodules
            ]
    assert not offenders, "a package's name hides its module of the same name:\n" + "\n".join(offenders)


def _private_names_defined(tree: ast.Module) -> set[str]:
    """Private names a module defines: functions, classes, assigned names and attributes (``self._x = ``)
    (once per tree)."""
    return _once("private", tree, lambda: _private_names_found(tree))


def _may_set_attributes(func: ast.expr) -> bool:
    """``func`` is ``setattr`` or ``object.__setattr__`` (the name looked at first: unparsing every callee
    of the package is most of this check's time)."""
    name = func.id if isinstance(func, ast.Name) else func.attr if isinstance(func, ast.Attribute) else ""
    return name in ("setattr", "__setattr__") and ast.unparse(func) in ("setattr", "object.__setattr__")


def _private_names_found(tree: ast.Module) -> set[str]:
    names = set()
    for node in _walk(tree):
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef):
            names.add(node.name)
        elif isinstance(node, ast.Name) and isinstance(node.ctx, ast.Store):
            names.add(node.id)
        elif isinstance(node, ast.Attribute) and isinstance(node.ctx, ast.Store | ast.Del):
            names.add(node.attr)
        elif isinstance(node, ast.arg):
            names.add(node.arg)
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            names.add(node.target.id)  # dataclass fields
        elif isinstance(node, ast.Call) and _may_set_attributes(node.func):
            if len(node.args) > 1 and isinstance(node.args[1], ast.Constant):
                names.add(str(node.args[1].value))
    return {name for name in names if _is_private(name)}


def _private_attribute_uses(tree: ast.Module, package_private: set[str]) -> Iterator[tuple[int, str]]:
    """(line, text) of every ``obj._name`` in `tree` that reaches into another module of the package.

    ``_name`` is one of the package's private names (`package_private`; so ``argparse``'s own internals do
    not count) that this module does not define itself; ``self._name`` and ``cls._name`` are the object's
    own (a base class in another module counts as its own).
    """
    own = _private_names_defined(tree)
    for node in _walk(tree):
        if not (isinstance(node, ast.Attribute) and _is_private(node.attr)):
            continue
        if isinstance(node.value, ast.Name) and node.value.id in ("self", "cls"):
            continue
        if node.attr in package_private and node.attr not in own:
            yield node.lineno, ast.unparse(node)


def test_no_private_attribute_is_used_across_modules():
    trees = dict(_trees())
    package_private = set().union(*(_private_names_defined(tree) for tree in trees.values()))
    offenders = [
        f"{MODULES[module].relative_to(REPO)}:{line} uses {text}"
        for module, tree in trees.items()
        for line, text in _private_attribute_uses(tree, package_private)
    ]
    assert not offenders, (
        "private attributes of other modules' objects used (add a public, documented method to the class "
        "that owns them):\n" + "\n".join(offenders)
    )


def test_the_checks_see_what_they_check():
    """The scanners find known imports, so an empty result above means the rule holds, not a blind scan."""
    tree = ast.parse(MODULES["moving_bogie.cli.reproduce_cmd"].read_text(encoding="utf-8"))
    found = {imported for _, imported, _ in _imports("moving_bogie.cli.reproduce_cmd", tree)}
    assert {"moving_bogie.paper.reproduce", "moving_bogie.cli.progress"} <= found
    assert _find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert _find_cycle({"a": {"b"}, "b": {"c"}}) is None
    guarded = ast.parse(
        "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    import x\ndef f():\n    import y\n"
    )
    assert [type(s).__name__ for s in _top_level_statements(guarded.body)] == ["ImportFrom", "FunctionDef"]
    # imports inside functions are followed; those under TYPE_CHECKING never run and are not
    assert [imported for _, imported, _ in _imports("moving_bogie", list(_runtime_nodes(guarded)))] == [
        "typing",
        "y",
    ]
    # a private attribute of another module's object is seen; the module's own private attributes are not
    reach = ast.parse(
        "class A:\n    def __init__(self):\n        self._own = 1\n    def f(self, c):\n"
        "        return self._own + c._args() + c.__len__()\n"
    )
    assert [text for _, text in _private_attribute_uses(reach, {"_args", "_own"})] == ["c._args"]


# --- (d) self-contained ------------------------------------------------------------------------------------

#: References to files outside the repository: the sibling folder of shared material, absolute paths of
#: the machine the project was developed on. Built from pieces so that this file does not match itself.
OUTSIDE = re.compile(
    "|".join(
        [
            re.escape(".." + "/shared"),
            r"(?<![\w./-])" + "shared" + "/",
            r"(?<![\w.~:-])" + "/" + "work/",
        ]
    )
)


def _tracked_files() -> list[Path]:
    try:
        listing = subprocess.run(
            ["git", "ls-files", "-z"], cwd=REPO, capture_output=True, check=True, timeout=60
        ).stdout
    except (OSError, subprocess.SubprocessError):
        pytest.skip("not a git checkout: no list of tracked files")
    return [REPO / name for name in listing.decode().split("\0") if name]


def test_no_file_refers_outside_the_repository():
    offenders = []
    for path in _tracked_files():
        if not path.is_file():
            continue
        data = path.read_bytes()
        if b"\0" in data:
            continue  # binary
        text = data.decode("utf-8", errors="replace")
        for line_no, line in enumerate(text.splitlines(), 1):
            if OUTSIDE.search(line):
                offenders.append(f"{path.relative_to(REPO)}:{line_no}: {line.strip()[:120]}")
    assert not offenders, "files refer to paths outside the repository:\n" + "\n".join(offenders)


def test_the_outside_pattern_matches_what_it_should():
    assert OUTSIDE.search("see " + ".." + "/shared/paper.md")
    assert OUTSIDE.search("`" + "shared" + "/ARCHITECTURE.md`")
    assert OUTSIDE.search("python " + "/" + "work/main/x.py")
    assert not OUTSIDE.search("multiprocessing.shared_memory, https://example.org/work/x")
    assert not OUTSIDE.search("docs/architecture.md, src/moving_bogie/generated/")


# --- (e) one bound model ------------------------------------------------------------------------------------

#: Where the generic runtime lives: no beam or vehicle of the catalogue is named there.
GENERIC = ("kernels", "roots", "response", "validation", "stability", "sweep", "soil")
#: The entry points, which may choose a model by name (the command line) or name the paper's (its recipes).
ENTRY_POINTS = ("moving_bogie.cli", "moving_bogie.paper")


def _functions(tree: ast.AST) -> Iterator[ast.FunctionDef | ast.AsyncFunctionDef]:
    yield from (n for n in _walk(tree) if isinstance(n, ast.FunctionDef | ast.AsyncFunctionDef))


def _model_name_arguments(tree: ast.AST) -> Iterator[tuple[int, str]]:
    """Functions that take a model by name: ``model: str`` or a ``model`` beside ``params``."""
    for node in _functions(tree):
        args = [*node.args.posonlyargs, *node.args.args, *node.args.kwonlyargs]
        names = {a.arg for a in args}
        for a in args:
            annotated = a.annotation is not None and "str" in ast.unparse(a.annotation)
            if a.arg == "model" and (annotated or "params" in names):
                yield node.lineno, node.name


def test_no_function_takes_a_model_name_beside_its_parameters():
    """Bind once (kernels/bound.py): the parameters carry their model; no ``f(params, model: str)``."""
    offenders = [
        f"{module}:{line} {name}"
        for module, tree in _trees()
        if not module.startswith(ENTRY_POINTS)
        for line, name in _model_name_arguments(tree)
    ]
    assert not offenders, "functions take a model name beside the parameters:\n" + "\n".join(offenders)


def _model_names() -> set[str]:
    from moving_bogie.model.catalogue import default_catalogue

    catalogue = default_catalogue()
    return set(catalogue.beams) | set(catalogue.vehicles)


#: Beam or vehicle names the generic runtime keeps, each with its reason: (module, name).
MODEL_NAMES_ALLOWED: dict[tuple[str, str], str] = {
    (
        "moving_bogie.kernels.sleeper_track",
        "eb",
    ): "the finite rail of the sleeper check has Euler-Bernoulli elements",
    (
        "moving_bogie.kernels.sleeper_track",
        "eb_axial",
    ): "the free waves' damping floor is known on EB rails (S15)",
}


def test_the_generic_runtime_names_no_beam_or_vehicle():
    """A quoted beam or vehicle name of the catalogue (code, docstrings, comments) only outside GENERIC
    (and MODEL_NAMES_ALLOWED)."""
    offenders = []
    for module, path in MODULES.items():
        names = _model_names() - {name for m, name in MODEL_NAMES_ALLOWED if m == module}
        pattern = re.compile(r"[\"'](" + "|".join(sorted(map(re.escape, names))) + r")[\"']")
        if module.split(".")[1:2] and module.split(".")[1] in GENERIC:
            for line_no, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
                if pattern.search(line):
                    offenders.append(f"{module}:{line_no}: {line.strip()[:100]}")
    assert not offenders, "the generic runtime names a model:\n" + "\n".join(offenders)


def test_the_model_checks_see_what_they_check():
    tree = ast.parse(
        "def f(params, model=None): pass\ndef g(x, *, model: str | None = None): pass\n"
        "def h(params, *, foundation=None): pass\ndef k(values, *, model: Model | None = None): pass\n"
    )
    assert [name for _, name in _model_name_arguments(tree)] == ["f", "g"]
    assert {"bogie", "masses", "eb", "tr"} <= _model_names()


_S24 = "the support's finite element (S24), to be generated"

#: The model-parameter literals the generic runtime keeps, each with its reason: (module or "*", name).
PARAMETER_LITERALS_ALLOWED: dict[tuple[str, str], str] = {
    ("*", "alpha"): "the velocity of the moving load: an argument of every generated foundation (Eq. (16))",
    ("moving_bogie.kernels.sweep_characteristic", "d"): "the spacing axis of E_chr(q; alpha, d, theta)",
    ("moving_bogie.stability.lines.line_results", "d"): "the spacing of a traced line (Figures 3, 4, 7, 8)",
    ("moving_bogie.stability.figures.plots", "d"): "the legend of the lines' spacings",
    ("moving_bogie.stability.figures.track_comparison", "d"): "the legend of the lines' spacings",
    ("moving_bogie.sweep.map_store", "d"): "a dependency of Eq. (63)'s J_b = cf2 eta_M d^2 in the map's text",
    ("moving_bogie.sweep.store", "r"): "the read mode of a zarr group, not the radius of gyration",
    ("moving_bogie.response.axis_sequence", "S"): "Re q = sqrt(S)/r, where the real-axis roots of a beam "
    "with rotary inertia begin (docs/frequencies.md)",
    ("moving_bogie.response.axis_sequence", "r"): "the same start sqrt(S)/r",
    ("moving_bogie.stability.velocity.critical_velocity", "eta_s"): "the keywords of Eqs. (65)-(66)",
    ("moving_bogie.stability.velocity.critical_velocity", "S"): "the keywords of Eqs. (65)-(66)",
    ("moving_bogie.stability.velocity.critical_velocity", "r"): "the keywords of Eqs. (65)-(66)",
    (
        "moving_bogie.stability.stiffness.d_decomposition",
        "eta_f",
    ): "names the damping it needs > 0",
    (
        "moving_bogie.stability.maps.sleeper_map",
        "eta_f",
    ): "names the damping along the rail it needs > 0 (S15)",
    (
        "moving_bogie.stability.maps.sleeper_map",
        "eta_M",
    ): "the vertical axis of a map's JSON, as the continuous map's",
    (
        "moving_bogie.stability.maps.d_map",
        "eta_M",
    ): "the key of a crossing's wheel mass in a map's checkpoint",
    ("moving_bogie.roots.strip", "eta_f"): "a rail undamped along its length: singular points on the axis",
    # the rail on supports as finite elements (S24) and its bay: typed here until generated with the track
    **{("moving_bogie.kernels.sleeper_track", name): _S24 for name in ("eta_sup", "mu_sl", "kappa_bal")},
    **{("moving_bogie.kernels.sleeper_track", name): _S24 for name in ("eta_pad", "eta_bal")},
    ("moving_bogie.kernels.sleeper_track", "lam"): "the bay of a periodic track (Omega_0 = 2 pi alpha / lam)",
    (
        "moving_bogie.kernels.sleeper_track",
        "kappa_bal",
    ): "the support's finite element (S24), to be generated",
    ("moving_bogie.kernels.sleeper_track", "kappa_f"): "the finite rail's foundation (S24), to be generated",
    ("moving_bogie.kernels.sleeper_track", "eta_f"): "the finite rail's foundation (S24), to be generated",
}


def _parameter_names() -> set[str]:
    """Every dimensionless group of the catalogue and every alternative input (cf1, cf2 of Eq. (63))."""
    from moving_bogie.model.catalogue import default_catalogue

    catalogue = default_catalogue()
    return set(catalogue.specs) | set(catalogue.parameters.ALTERNATIVES)


def _docstring_nodes(tree: ast.AST) -> set[int]:
    nodes = set()
    for node in _walk(tree):
        if isinstance(node, ast.Module | ast.ClassDef | ast.FunctionDef | ast.AsyncFunctionDef):
            first = node.body[0] if node.body else None
            if isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant):
                nodes.add(id(first.value))
    return nodes


def _parameter_literals(module: str, tree: ast.AST, names: set[str]) -> Iterator[tuple[int, str]]:
    """String constants (docstrings left out) equal to a parameter name and not allowed for ``module``."""
    docstrings = _docstring_nodes(tree)
    for node in _walk(tree):
        if isinstance(node, ast.Constant) and isinstance(node.value, str) and id(node) not in docstrings:
            name = node.value
            if name in names and ("*", name) not in PARAMETER_LITERALS_ALLOWED:
                if (module, name) not in PARAMETER_LITERALS_ALLOWED:
                    yield node.lineno, name


def test_the_generic_runtime_names_no_model_parameter():
    """Which group is the wheel mass or the primary stiffness comes from the vehicle's metadata
    (``Model.wheel_mass``, ``Model.primary_stiffness``), the alternatives from ``Model.alternatives``: no
    parameter of the catalogue is a string literal in GENERIC but those of PARAMETER_LITERALS_ALLOWED."""
    names = _parameter_names()
    offenders = [
        f"{module}:{line}: {name!r}"
        for module, tree in _trees()
        if module.split(".")[1:2] and module.split(".")[1] in GENERIC
        for line, name in _parameter_literals(module, tree, names)
    ]
    assert not offenders, "the generic runtime names a model parameter:\n" + "\n".join(offenders)


def test_the_parameter_check_sees_what_it_checks():
    tree = ast.parse(
        '"""eta_M in a docstring."""\ndef f(params, parameter="eta_M"):\n    """kappa_v."""\n'
        '    return params.replace(**{"cf1": 2}), "alpha", "eta_Mx"\n'
    )
    found = [name for _, name in _parameter_literals("m", tree, _parameter_names())]
    assert sorted(found) == ["cf1", "eta_M"]
    allowed = {module for module, _ in PARAMETER_LITERALS_ALLOWED} - {"*"}
    assert allowed <= set(MODULES), allowed - set(MODULES)  # no stale entry


#: The one place where a bound model is made from parameters (``bind``) and takes a foundation beside them.
BOUND = "moving_bogie.kernels.bound"


def _generic(module: str) -> bool:
    return module.split(".")[1:2] != [] and module.split(".")[1] in GENERIC and module != BOUND


def _call_name(node: ast.Call) -> str:
    """The name a call calls: ``f`` of ``f(...)`` and of ``obj.f(...)`` ("" for anything else)."""
    func = node.func
    return func.id if isinstance(func, ast.Name) else func.attr if isinstance(func, ast.Attribute) else ""


def _offenders(
    keep: Callable[[str], bool], find: Callable[[ast.AST], Iterator[tuple[int, str]]]
) -> list[str]:
    """``module:line text`` of every finding of ``find`` in the modules ``keep`` selects."""
    return [
        f"{module}:{line} {text}" for module, tree in _trees() if keep(module) for line, text in find(tree)
    ]


def _binds(tree: ast.AST) -> Iterator[tuple[int, str]]:
    """Calls of ``bind`` (``bind(...)``, ``bound.bind(...)``) and imports of it, anywhere in `tree`."""
    for node in _walk(tree):
        if isinstance(node, ast.Call):
            if _call_name(node) == "bind":
                yield node.lineno, ast.unparse(node)[:80]
        elif isinstance(node, ast.ImportFrom) and any(a.name == "bind" for a in node.names):
            yield node.lineno, f"from {node.module} import bind"


def _foundation_arguments(tree: ast.AST) -> Iterator[tuple[int, str]]:
    """Functions with an optional or keyword parameter ``foundation=`` (a second channel beside the bound
    model). A generated module passed as the one thing a helper evaluates (``PRootDiscs(foundation, args)``
    in ball arithmetic) is not a second channel."""
    for node in _functions(tree):
        positional = [*node.args.posonlyargs, *node.args.args]
        optional = positional[len(positional) - len(node.args.defaults) :]
        if any(a.arg == "foundation" for a in [*optional, *node.args.kwonlyargs]):
            yield node.lineno, node.name


def test_the_generic_runtime_never_binds():
    """Bind once (kernels/bound.py): the entry points bind (the sweep's too, :data:`BINDERS`), the generic
    layers take ``bound: BoundModel``."""
    offenders = [
        f"{module}:{line} {text}"
        for module, tree in _trees()
        if _generic(module) and module not in BOUND_MODELS_ALLOWED and not module.startswith(BINDERS)
        for line, text in _binds(tree)
    ]
    assert not offenders, "the generic runtime binds again:\n" + "\n".join(offenders)


def test_no_generic_function_takes_a_foundation():
    """Another foundation is another bound model (``BoundModel(params, foundation=...)``), not a parameter."""
    offenders = [
        f"{module}:{line} {name}"
        for module, tree in _trees()
        if _generic(module)
        for line, name in _foundation_arguments(tree)
    ]
    assert not offenders, "functions take a foundation beside the bound model:\n" + "\n".join(offenders)


def test_the_bind_checks_see_what_they_check():
    tree = ast.parse(
        "from moving_bogie.kernels.bound import bind\ndef f(params):\n    return g(bind(params))\n"
        "def h(bound, *, foundation=None): pass\nclass K:\n    def __init__(self, p, foundation=None): pass\n"
        "def k(bound: BoundModel, binder=None): return bound.params\ndef m(foundation, args): pass\n"
    )
    assert [line for line, _ in _binds(tree)] == [1, 3]
    assert [name for _, name in _foundation_arguments(tree)] == ["h", "__init__"]
    assert _generic("moving_bogie.roots.frequencies") and _generic("moving_bogie.kernels.track")
    assert (
        not _generic(BOUND) and not _generic("moving_bogie.api") and not _generic("moving_bogie.cli.common")
    )


#: Where a bound model may be made from parameters: ``bind`` (kernels/bound.py, api.py) and the entry points.
#: ``sweep/api.py`` is the sweep's public entry: it binds once, and each point is ``bound.replace(...)``.
BINDERS = ("moving_bogie.kernels.bound", "moving_bogie.api", "moving_bogie.sweep.api", *ENTRY_POINTS)
BINDERS += ("moving_bogie.soil_vehicle",)  # the soil's public entry: a vehicle read, bound to its track once

#: Bound models made from parameters, or unwrapped to their parameters and bound again, below the entry
#: points, each with its reason (module, line text). The coordinator empties this list as they move up
#: to the entry points (a sweep point is ``bound.replace(...)`` of the sweep's bound model).
BOUND_MODELS_ALLOWED: dict[str, str] = {
    "moving_bogie.roots.table2": "Table 2 binds each case of Table 1 once: the table is its own entry",
    "moving_bogie.validation.finite_beam": "simulate_finite_beam (public) reads the groups of a bound model",
}


def _bound_models(tree: ast.AST) -> Iterator[tuple[int, str]]:
    """Calls of ``BoundModel(...)`` and ``bind(...)``, and ``x.params if isinstance(x, BoundModel)`` (a bound
    model unwrapped to its parameters), anywhere in `tree`."""
    for node in _walk(tree):
        if isinstance(node, ast.Call):
            if _call_name(node) in ("BoundModel", "bind"):
                yield node.lineno, ast.unparse(node)[:80]
        elif isinstance(node, ast.IfExp) and "BoundModel" in ast.unparse(node.test):
            if isinstance(node.body, ast.Attribute) and node.body.attr == "params":
                yield node.lineno, ast.unparse(node)[:80]


def test_no_bound_model_is_made_below_the_entry_points():
    """Bind once: ``BoundModel(...)`` and ``bind(...)`` only in kernels/bound.py, api.py and the entry points
    (the command line, the paper's recipes); below them a bound model comes in as ``bound`` and other
    parameter sets are ``bound.replace(...)``, which keeps its track."""
    offenders = _offenders(
        lambda module: not module.startswith(BINDERS) and module not in BOUND_MODELS_ALLOWED, _bound_models
    )
    assert not offenders, "bound models made below the entry points:\n" + "\n".join(offenders)


#: Modules that look a module or a generated function up by a formatted name, each with its reason: the
#: catalogue (model/) and the registries of the package's entry points. Everywhere else a model's kernels
#: come from the catalogue (``Model.foundation``, ``Model.vehicle_kernels``, the bound model).
LOOKUPS_ALLOWED: dict[str, str] = {
    "moving_bogie": "the lazy public names of __init__.py (a fixed table, not a model)",
    "moving_bogie.cli": "the subcommand modules of SUBCOMMAND_MODULES (a fixed list)",
    "moving_bogie.cli.stability_cmd": "the paper's figures by their number (stability-figure N)",
    "moving_bogie.kernels.sweep_characteristic": "the generated set_by_<alternative> of Eq. (63)",
}


def _formatted_lookups(tree: ast.AST) -> Iterator[tuple[int, str]]:
    """``import_module(f"...")`` and ``getattr(obj, f"...")``: a module or function found by a formatted
    name."""
    for node in _walk(tree):
        if isinstance(node, ast.Call):
            position = {"import_module": 0, "getattr": 1}.get(_call_name(node))
            if position is not None and len(node.args) > position:
                if isinstance(node.args[position], ast.JoinedStr):
                    yield node.lineno, ast.unparse(node)[:80]


def test_no_module_is_looked_up_by_a_formatted_name():
    """No ``import_module(f"...vehicle_{name}")`` nor ``getattr(generated, f"...")`` outside the catalogue
    (model/) and LOOKUPS_ALLOWED."""
    offenders = _offenders(
        lambda module: not module.startswith("moving_bogie.model.") and module not in LOOKUPS_ALLOWED,
        _formatted_lookups,
    )
    assert not offenders, "modules looked up by a formatted name:\n" + "\n".join(offenders)


def test_the_bound_model_and_lookup_checks_see_what_they_check():
    tree = ast.parse(
        "b = BoundModel(p)\nc = bind(p)\nq = x.params if isinstance(x, BoundModel) else x\n"
        "m = importlib.import_module(f'moving_bogie.generated.vehicle_{v}')\nf = getattr(g, f'scales_{t}')\n"
        "h = getattr(g, 'fixed')\nk = bound.replace(alpha=1)\n"
    )
    assert [line for line, _ in _bound_models(tree)] == [1, 2, 3]
    assert [line for line, _ in _formatted_lookups(tree)] == [4, 5]
    stale = (set(BOUND_MODELS_ALLOWED) | set(LOOKUPS_ALLOWED)) - set(MODULES)
    assert not stale, stale


# -- signatures and function length -----------------------------------------------------------------------

#: The longest function the runtime may hold, in lines from ``def`` to its end.
MAX_FUNCTION_LINES = 80


def _runtime() -> Iterator[tuple[str, ast.Module]]:
    """The runtime's modules without the generated kernels (written by derivations/emit.py)."""
    for module, tree in _trees():
        if not module.startswith(f"{ROOT}.generated"):
            yield module, tree


def _not_yet_annotated() -> set[str]:
    """The modules pyproject.toml's ``[tool.mypy]`` still lets through with unannotated signatures."""
    with open(REPO / "pyproject.toml", "rb") as file:
        overrides = tomllib.load(file)["tool"]["mypy"].get("overrides", [])
    return {
        module
        for override in overrides
        if override.get("disallow_untyped_defs") is False
        for module in override["module"]
        if not module.startswith(f"{ROOT}.generated")
    }


def _public_functions(tree: ast.Module) -> Iterator[ast.FunctionDef | ast.AsyncFunctionDef]:
    """The module's public functions and the public methods (dunders included) of its public classes."""
    functions = ast.FunctionDef | ast.AsyncFunctionDef
    for node in tree.body:
        if isinstance(node, functions) and not _is_private(node.name):
            yield node
        elif isinstance(node, ast.ClassDef) and not _is_private(node.name):
            yield from (
                item for item in node.body if isinstance(item, functions) and not _is_private(item.name)
            )


def _unannotated(node: ast.FunctionDef | ast.AsyncFunctionDef, method: bool) -> list[str]:
    """The parameters of `node` without an annotation (``self``/``cls`` of a method excepted), and
    ``return`` if its return is not annotated."""
    args = node.args
    params = [*args.posonlyargs, *args.args, *args.kwonlyargs, *filter(None, (args.vararg, args.kwarg))]
    static = any(ast.unparse(d) == "staticmethod" for d in node.decorator_list)
    if method and not static and params and params[0].arg in ("self", "cls", "mcs"):
        params = params[1:]
    missing = [p.arg for p in params if p.annotation is None]
    return missing + (["return"] if node.returns is None else [])


def test_every_public_signature_is_annotated():
    """Annotated parameters and return on every public function and method of the runtime (the package
    ships ``py.typed``), even where mypy does not run; the modules pyproject.toml's ``[tool.mypy]`` still
    lists as not annotated are the only exception, and they exist."""
    pending = _not_yet_annotated()
    assert not pending - set(MODULES), (
        f"pyproject.toml lists modules that do not exist: {pending - set(MODULES)}"
    )
    offenders = []
    for module, tree in _runtime():
        if module in pending:
            continue
        methods = {id(item) for node in tree.body if isinstance(node, ast.ClassDef) for item in node.body}
        for node in _public_functions(tree):
            if missing := _unannotated(node, id(node) in methods):
                offenders.append(f"{module}:{node.lineno} {node.name}: {', '.join(missing)}")
    assert not offenders, "public signatures without annotations:\n" + "\n".join(offenders)


def test_no_function_is_longer_than_the_limit():
    offenders = [
        f"{module}:{node.lineno} {node.name}: {node.end_lineno - node.lineno + 1} lines"
        for module, tree in _runtime()
        for node in _walk(tree)
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef)
        and node.end_lineno - node.lineno + 1 > MAX_FUNCTION_LINES
    ]
    assert not offenders, f"functions over {MAX_FUNCTION_LINES} lines:\n" + "\n".join(offenders)


def test_the_signature_checks_see_what_they_check():
    tree = ast.parse(
        "def f(a: int, b) -> int: pass\ndef g(a: int): pass\ndef _h(a): pass\n"
        "class C:\n    def m(self, x: int) -> None: pass\n    @staticmethod\n    def s(self): pass\n"
        "    def _p(self, y): pass\nclass _D:\n    def m(self, z): pass\n"
        "def long():\n" + "    x = 1\n" * MAX_FUNCTION_LINES
    )
    found = [(node.name, _unannotated(node, node.name in ("m", "s"))) for node in _public_functions(tree)]
    assert found == [
        ("f", ["b"]),
        ("g", ["return"]),
        ("m", []),
        ("s", ["self", "return"]),
        ("long", ["return"]),
    ]
    assert (
        max(n.end_lineno - n.lineno + 1 for n in _walk(tree) if isinstance(n, ast.FunctionDef))
        > MAX_FUNCTION_LINES
    )


#: The commands that run one path on every track: the options of each kind of track come from a table, and
#: the one result type (a TimeSeries, a ValidationResult) prints, writes and draws itself on any track.
ONE_PATH_COMMANDS = ("moving_bogie.cli.timeseries_cmd", "moving_bogie.cli.validate_cmd")

#: What a branch on the kind of track tests: the model's periodic supports, or the result's own part.
TRACK_WORDS = re.compile(r"periodic|sleeper|supports|\.bay\b")


def _track_branches(module: str, tree: ast.AST) -> Iterator[str]:
    for node in _walk(tree):
        if isinstance(node, ast.If | ast.IfExp):
            test = ast.unparse(node.test)
            if TRACK_WORDS.search(test):
                yield f"{module}:{node.lineno}: if {test}"


def test_the_one_path_commands_do_not_branch_on_the_track():
    """``timeseries`` and ``validate`` make one call of the library on every track and hand its one result
    type to one output: no ``if`` (statement or expression) on the track in the command."""
    found = {module for module, _ in _trees() if module in ONE_PATH_COMMANDS}
    assert found == set(ONE_PATH_COMMANDS)
    offenders = [
        line
        for module, tree in _trees()
        if module in ONE_PATH_COMMANDS
        for line in _track_branches(module, tree)
    ]
    assert not offenders, "a command branches on the kind of track:\n" + "\n".join(offenders)


def test_the_track_branch_check_sees_a_branch():
    tree = ast.parse("def run(params):\n    if params.model.periodic:\n        return 1\n    return 0\n")
    assert list(_track_branches("m", tree)) == ["m:2: if params.model.periodic"]
