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
  two workers share them (the notebooks: nine kernels of 5-20 s each, one module; the modules of a few
  long tests each);
* the units of :data:`LONG_FIRST` (the longest in a full run, ``--durations=0``, notebooks among them)
  go out first, longest first, then the rest as ``loadscope`` orders them, then the other units of
  :data:`SPREAD`: short ones that fill the end of both workers. The list is a hint for the order only: a
  unit missing from it, or one that got faster, runs all the same.
"""

from __future__ import annotations

from xdist.scheduler import LoadScopeScheduling

#: Modules whose tests share no module-scoped fixture: one unit per test. The notebooks (nine kernels of
#: 5-20 s each), and the modules whose few long tests would otherwise hold one worker for minutes (the
#: ``validate`` points of the zone example, the random sets against a scan, the Hertz vehicles, the soil's
#: moving load, the undamped boundaries). ``tests/test_xdist_balance.py`` checks that none of them has a
#: fixture of module or session scope of its own.
SPREAD = (
    "tests/test_notebooks.py",
    "tests/test_sleepers_finite_beam.py",
    "tests/test_search_random.py",
    "tests/test_contact_springs.py",
    "tests/test_soil_track.py",
    "tests/test_soil_threshold.py",
    "tests/test_undamped_stability.py",
)

#: Groups of modules that share what a process computes once: each group is one unit, on one worker.
TOGETHER = (
    # the searches of Table 1's cases (``table1_search`` in conftest.py)
    ("tests/test_frequencies.py", "tests/test_response.py", "tests/test_ball_polish.py"),
    # the parsed source files (parsed_sources.py)
    ("tests/test_layout.py", "tests/test_declared_dependencies.py", "tests/test_docs.py"),
)

_ZONE = "tests/test_sleepers_finite_beam.py::test_validate_agrees_inside_the_zone_of_the_example"
_HERTZ = (
    "tests/test_contact_springs.py::"
    "test_contact_spring_vehicle_on_a_continuous_track_tends_to_the_rigid_contact"
)

#: The units that took longest in a full run (``pytest -n 2 --durations=0``, seconds per module, per test
#: in :data:`SPREAD`), longest first: handed out in this order, the many short modules left to fill the
#: end of both workers. The derivations come first: on a fresh clone (CI) their regeneration is not
#: cached and takes them to the top. ``tests/test_xdist_balance.py`` checks that each entry names a
#: module and a test that exist.
LONG_FIRST = (
    "tests/test_derivations_current.py",
    "tests/test_reproduce.py",
    f"{_ZONE}[71.5-2685-None]",
    "tests/test_car.py",
    "tests/test_search_random.py::test_seeded_random_sets_never_fail_and_agree_with_a_scan",
    "tests/test_sweep.py",
    "tests/test_readme.py",
    "tests/test_validation.py",
    "tests/test_floquet_strip.py",
    "tests/test_soil_track.py::test_moving_load_against_direct_two_dimensional_quadrature",
    "tests/test_floquet_receptance.py",
    "tests/test_response_layered.py",
    "tests/test_undamped_verdict.py",
    "tests/test_hostile_inputs.py",
    "tests/test_floquet_lines.py",
    f"{_ZONE}[97.2881-1400-2.90111]",
    "tests/test_sleepers_finite_beam.py::test_the_steady_force_is_checked_beside_a_slowly_decaying_vibration",
    "tests/test_finite_beam_tr.py",
    "tests/test_layered_search.py",
    "tests/test_car_certified.py",
    f"{_HERTZ}[car]",
    "tests/test_soil_track.py::test_moving_load_command_peak",
    "tests/test_examples.py",
    "tests/test_notebooks.py::test_notebook_runs[05-change-the-model]",
    "tests/test_certify.py",
    "tests/test_finite_beam.py",
    "tests/test_finite_beam_vehicles.py",
    "tests/test_frequencies.py",
    "tests/test_model_as_data.py",
    "tests/test_long_jobs.py",
    "tests/test_notebooks.py::test_notebook_runs[09-sleepers]",
    "tests/test_layout.py",
    f"{_ZONE}[97.2881-1416-3.22093]",
    "tests/test_search_window.py",
    "tests/test_response_tr.py",
    "tests/test_beam_as_data.py",
    "tests/test_stability_lines.py",
    "tests/test_undamped_stability.py::test_limit_boundaries_are_the_limit_of_small_damping",
    "tests/test_sweep_quiet.py",
    "tests/test_alpha_zero.py",
    "tests/test_finite_rail_layered.py",
    "tests/test_notebooks.py::test_notebook_runs[06-sweeps]",
    "tests/test_undamped_stability.py::test_cli_states_the_convention_and_what_is_computed",
    "tests/test_notebooks.py::test_notebook_runs[04-instability-lines]",
    "tests/test_notebooks.py::test_notebook_runs[08-a-full-car]",
    "tests/test_soil_track.py::test_ballasted_example_critical_velocity_against_disba",
    "tests/test_notebooks.py::test_notebook_runs[07-layered-track]",
    "tests/test_notebooks.py::test_notebook_runs[02-table2]",
    "tests/test_notebooks.py::test_notebook_runs[03-vibrations-and-validation]",
    "tests/test_notebooks.py::test_notebook_runs[01-quickstart]",
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
    """0, 1, ... for the units of LONG_FIRST, then the rest (their loadscope order kept), SPREAD last."""
    if scope in LONG_FIRST:
        return LONG_FIRST.index(scope)
    return len(LONG_FIRST) + (_module(scope) in SPREAD)
