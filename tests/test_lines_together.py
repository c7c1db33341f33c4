"""Instability lines traced together: the shared-call tracer against a tracer alone, panels stacked
against each panel alone, a stacked sweep against its members.

References: one tracer traced by itself (:func:`trace_all_many` of one job, no call shared) and
:func:`instability_lines` of one parameter set at a time.
"""

from __future__ import annotations

import numpy as np
import pytest

from moving_bogie.kernels.bound import bind
from moving_bogie.kernels.stacked_sweep import StackedSweep
from moving_bogie.kernels.sweep_characteristic import SweepCharacteristic
from moving_bogie.model.params import DimensionlessParams
from moving_bogie.stability.lines.continuation import PathTracer
from moving_bogie.stability.lines.instability_lines import instability_lines, instability_lines_many
from moving_bogie.stability.lines.seeds import seed_groups
from moving_bogie.stability.lines.walkers import trace_all_many

GRID = dict(alpha_step=0.02, q_step=0.008, h_max=0.02, tol=1e-11)
SPACINGS = (1.0, 1.5)


def _params(eta_f: str = "0.05", **kw: object) -> DimensionlessParams:
    values = dict(eta_f=eta_f, eta_M=20, d=1, cf1="1.7", cf2="0.01", kappa_v="0.02", eta_v=0, alpha="0.5")
    values.update(kw)
    return DimensionlessParams.from_coefficients(**values)


def _same_paths(a: list, b: list, rtol: float = 1e-13) -> None:
    assert len(a) == len(b)
    for (da, pa, ea), (db, pb, eb) in zip(a, b):
        assert da == db and ea == eb and pa.shape == pb.shape
        np.testing.assert_allclose(pa, pb, rtol=rtol, atol=rtol)


# the bogie's panels take longer: the fast subset traces the two masses
@pytest.mark.parametrize("vehicle", [pytest.param("bogie", marks=pytest.mark.slow), "masses"])
def test_shared_calls_trace_the_paths_of_the_tracer_alone(vehicle):
    """Same curves, same points, same reasons at the ends as the tracer traced by itself, when its calls
    are shared with the tracer of another panel (another eta_f: the sweeps stack)."""
    panels = []
    for eta_f in ("0.1", "0.2"):
        sweep = SweepCharacteristic(bind(_params(eta_f).replace(vehicle=vehicle)))
        groups, box = seed_groups(sweep, SPACINGS[1:], (0.0, 1.0), 200.0, 1.5, GRID, None)
        panels.append((sweep, box, groups))

    def tracer(sweep, box):
        return PathTracer(sweep, 200.0, box, GRID["h_max"], GRID["tol"])

    alone = tracer(*panels[0][:2])
    paths = trace_all_many([(alone, panels[0][2])])[0]
    assert paths, "no line traced"
    shared = [tracer(sweep, box) for sweep, box, _ in panels]
    _same_paths(paths, trace_all_many([(t, g) for t, (_, _, g) in zip(shared, panels)])[0])
    assert alone.warnings == shared[0].warnings


# slow: four whole panels; the fast subset checks the shared calls themselves, the same paths as a tracer
# alone (test_shared_calls_trace_the_paths_of_the_tracer_alone, masses)
@pytest.mark.slow
def test_panels_traced_together_are_the_panels_alone():
    """instability_lines_many of four panels (two models, each with two parameter sets, one panel
    with another theta_max) returns what each call of instability_lines returns."""
    requests = [
        (_params("0.05"), dict(theta_max=200.0)),
        (_params("0.05").replace(vehicle="masses"), dict(theta_max=370.0)),
        (_params("0.2", cf2="0.1", eta_v="0.05"), dict(theta_max=200.0)),
        (_params("0.2").replace(vehicle="masses"), dict(theta_max=370.0)),
    ]
    options = dict(spacings=SPACINGS[1:], alpha_range=(0, 1), **GRID)
    together = instability_lines_many([(bind(p), options | kw) for p, kw in requests])
    for (p, kw), lines in zip(requests, together):
        alone = instability_lines(bind(p), **options, **kw)  # type: ignore[arg-type]
        assert lines.warnings == alone.warnings and lines.q_max == alone.q_max
        assert len(lines.branches) == len(alone.branches) > 0
        for a, b in zip(alone.branches, lines.branches):
            assert (a.d, len(a.folds)) == (b.d, len(b.folds))
            assert [e.reason for e in a.ends] == [e.reason for e in b.ends]
            ends = [[(e.alpha, e.theta, e.q) for e in x.ends + x.folds] for x in (a, b)]
            np.testing.assert_allclose(ends[1], ends[0], rtol=1e-12, atol=1e-14)
            for name in ("alpha", "theta", "q", "residual"):
                np.testing.assert_allclose(getattr(b, name), getattr(a, name), rtol=1e-12, atol=1e-14)
            np.testing.assert_array_equal(a.unstable_above, b.unstable_above)


def test_stacked_sweep_is_its_members():
    """Each point of a stacked call gets its member's E, E_q, E_alpha, E_theta, to the last bit (every
    operation acts point by point)."""
    members = [
        SweepCharacteristic(bind(_params(eta_f, cf2=cf2)))
        for eta_f, cf2 in (("0.05", "0.01"), ("0.3", "0.1"))
    ]
    rng = np.random.default_rng(1)
    n = 7
    q = rng.uniform(0.1, 1.4, n) + 0j
    alpha, theta, d = rng.uniform(0.1, 1.1, n), rng.uniform(1, 200, n), rng.choice(SPACINGS, n)
    member = rng.integers(0, 2, n)
    stacked = StackedSweep(members).at(member)
    got = stacked.derivatives(q, alpha, theta, d=d)
    for k, sweep in enumerate(members):
        mine = member == k
        want = sweep.derivatives(q[mine], alpha[mine], theta[mine], d=d[mine])
        for g, w in zip(got, want):
            np.testing.assert_array_equal(g[mine], w)
