"""The lists by which ``pytest -n 2`` hands out the tests (``tests/xdist_balance.py``) name what exists.

A unit of :data:`~xdist_balance.LONG_FIRST` that matches nothing is silently handed out last (the list is a
hint for the order only), and a module of :data:`~xdist_balance.SPREAD` with a fixture of module or session
scope would compute it once per worker instead of once: both are read here from the test modules' text.
"""

from __future__ import annotations

import ast
import functools
from pathlib import Path

import pytest
from xdist_balance import LONG_FIRST, SPREAD, TOGETHER

ROOT = Path(__file__).resolve().parent.parent


@functools.cache
def _tree(module: str) -> ast.Module:
    path = ROOT / module
    assert path.is_file(), f"{module} does not exist"
    return ast.parse(path.read_text(encoding="utf-8"))


def _shared_fixtures(tree: ast.Module) -> set[str]:
    """The fixtures of module, package or session scope ``tree`` defines (``@pytest.fixture(scope=...)``)."""
    names = set()
    for node in tree.body:
        if not isinstance(node, ast.FunctionDef):
            continue
        for decorator in node.decorator_list:
            scope = next(
                (k.value for k in getattr(decorator, "keywords", ()) if k.arg == "scope"),
                None,
            )
            if isinstance(scope, ast.Constant) and scope.value != "function":
                names.add(node.name)
    return names


def test_every_unit_of_long_first_names_a_module_and_a_test_that_exist():
    assert len(set(LONG_FIRST)) == len(LONG_FIRST)
    for unit in LONG_FIRST:
        module, _, test = unit.partition("::")
        if not test:
            assert (ROOT / module).is_file(), f"{module} does not exist"
            assert module not in SPREAD, f"{unit}: a module of SPREAD is handed out per test"
            continue
        assert module in SPREAD, f"{unit}: only the modules of SPREAD are handed out per test"
        name = test.split("[", 1)[0]
        defined = {node.name for node in _tree(module).body if isinstance(node, ast.FunctionDef)}
        assert name in defined, unit


@pytest.mark.parametrize("module", SPREAD)
def test_spread_modules_share_nothing_a_process_computes_once(module):
    """Neither a fixture of module or session scope of their own nor one of conftest.py's."""
    shared = _shared_fixtures(_tree("tests/conftest.py"))
    assert shared, "conftest.py's shared fixtures are no longer found: update this test"
    tree = _tree(module)
    assert not _shared_fixtures(tree), module
    used = {node.id for node in ast.walk(tree) if isinstance(node, ast.Name)}
    used |= {node.arg for node in ast.walk(tree) if isinstance(node, ast.arg)}
    used |= {node.value for node in ast.walk(tree) if isinstance(node, ast.Constant)}
    assert not (shared & used), (module, shared & used)


def test_together_groups_name_modules_that_exist_outside_spread():
    for group in TOGETHER:
        for module in group:
            assert (ROOT / module).is_file(), f"{module} does not exist"
            assert module not in SPREAD, module
