"""How ``pytest -n 2`` hands the test modules to its two workers (``tests/conftest.py`` installs it).

pytest-xdist's ``--dist=loadscope`` keeps the tests of one module on one worker, so that a module fixture
(a regeneration, a ``reproduce --quick`` run, a certified car) is computed once, not once per worker. It
hands the modules out by their number of tests, most first: the few-test modules that hold the long
fixtures come last, and one worker ends alone on one of them while the other waits. (``--dist=loadgroup``
with ``xdist_group`` marks would be finer, but pytest-xdist 3.8 renames the node ids by an attribute that
pytest 9 no longer reads: its groups are silently split.)

:class:`BalancedScopes` is ``loadscope`` with three changes, none of which moves a test to another worker
than the rest of its module except where that costs nothing:

* each group of :data:`TOGETHER` shares what a process computes once: it is one unit, on one worker;
* the modules of :data:`SPREAD` share no module fixture: each of their tests is a unit of its own, so the
  two workers share them (the notebooks: eight kernels of 5-20 s each, one module);
* the modules of :data:`LONG_FIRST` (the longest in a full run, ``--durations=0``) go out first, in
  that order, then the rest as ``loadscope`` orders them, then the units of :data:`SPREAD`, short ones
  that fill the end of both workers. The list is a hint for the order only: a module missing from it, or
  one that got faster, runs all the same.
"""

from __future__ import annotations

from xdist.scheduler import LoadScopeScheduling

#: Modules whose tests share no module-scoped fixture: one unit per test.
SPREAD = ("tests/test_notebooks.py",)

#: Groups of modules that share what a process computes once: each group is one unit, on one worker.
TOGETHER = (
    # the searches of Table 1's cases (``table1_search`` in conftest.py)
    ("tests/test_frequencies.py", "tests/test_response.py", "tests/test_ball_polish.py"),
    # the parsed source files (parsed_sources.py)
    ("tests/test_layout.py", "tests/test_declared_dependencies.py", "tests/test_docs.py"),
)

#: The modules that took longest on one worker in a full run (``pytest -n 2 --durations=0``), longest first.
LONG_FIRST = (
    "tests/test_derivations_current.py",
    "tests/test_search_random.py",
    "tests/test_reproduce.py",
    "tests/test_car_certified.py",
    "tests/test_readme.py",
    "tests/test_response_tr.py",
    "tests/test_generated_kernels.py",
    "tests/test_undamped_stability.py",
    "tests/test_response_bromwich.py",
    "tests/test_undamped_verdict.py",
    "tests/test_beam_as_data.py",
    "tests/test_validation.py",
    "tests/test_layered_search.py",
)


def _module(nodeid: str) -> str:
    return nodeid.split("::", 1)[0]


class BalancedScopes(LoadScopeScheduling):
    """``--dist=loadscope`` with :data:`TOGETHER` one unit, :data:`SPREAD` split per test and
    :data:`LONG_FIRST` handed out first."""

    def __init__(self, config, log=None) -> None:
        super().__init__(config, log)
        self.ordered = False

    def _split_scope(self, nodeid: str) -> str:
        if _module(nodeid) in SPREAD:
            return nodeid
        for group in TOGETHER:
            if _module(nodeid) in group:
                return group[0]
        return super()._split_scope(nodeid)

    def _assign_work_unit(self, node) -> None:
        if not self.ordered:  # the first call: schedule() has filled the whole queue by now
            self.ordered = True
            units = sorted(self.workqueue.items(), key=lambda unit: _rank(unit[0]))
            self.workqueue.clear()
            self.workqueue.update(units)
        super()._assign_work_unit(node)


def _rank(scope: str) -> int:
    """0, 1, ... for the modules of LONG_FIRST, then the rest (their loadscope order kept), SPREAD last."""
    module = _module(scope)
    if module in LONG_FIRST:
        return LONG_FIRST.index(module)
    return len(LONG_FIRST) + (module in SPREAD)
