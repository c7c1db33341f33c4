"""Instability lines, D-decomposition, stability maps, frequency lines, critical stiffness (Sections 3.5-3.8).

References: :func:`~moving_bogie.roots.frequencies.induced_frequencies` (argument principle + polish at 20-30
digits) is the independent judge of every count; the paper calls Cases 1, 5, 12 and 13 unstable.
"""

from fractions import Fraction

import mpmath
import numpy as np
import pytest

from moving_bogie.api import (
    critical_stiffness,
    d_decomposition,
    frequency_lines,
    induced_frequencies,
    instability_lines,
    stability_map,
)
from moving_bogie.errors import ParameterError
from moving_bogie.kernels.bound import bind
from moving_bogie.kernels.characteristic import Characteristic
from moving_bogie.kernels.sweep_characteristic import SweepCharacteristic
from moving_bogie.model.cases import table1_case
from moving_bogie.stability.maps.map import stability_column

COARSE = dict(alpha_step=0.02, q_step=0.008, h_max=0.02)


def _fr(x):
    return Fraction(str(float(x)))


def _unstable(params):
    return len(induced_frequencies(params, dps=20).unstable_roots)


@pytest.fixture(scope="module")
def case1_lines():
    """Bogie of Case 1 (d = 1, eta_f = 0.1, cf2 = 0.01, kappa_v = 0.02)."""
    return instability_lines(table1_case(1), alpha_range=(0.3, 1.2), **COARSE)


@pytest.fixture(scope="module")
def masses_lines():
    p = table1_case(1).replace(eta_f="0.05")
    return instability_lines(p.replace(vehicle="masses"), spacings=[1.5, 2.0], **COARSE)


def test_every_traced_point_is_a_real_root(case1_lines, masses_lines):
    """|E/E'| at each point is tiny in double precision; a few points re-checked at 30 digits."""
    for lines, model in ((case1_lines, "bogie"), (masses_lines, "masses")):
        assert lines.branches and not lines.warnings
        for b in lines.branches:
            assert np.all(b.residual < 1e-10)
            assert np.all((b.theta > 0) & (b.theta <= 200 + 1e-9))
        b = max(lines.branches, key=lambda br: len(br.alpha))
        for k in (len(b.alpha) // 3, 2 * len(b.alpha) // 3):
            p = lines.params.replace(alpha=_fr(b.alpha[k]), eta_M=_fr(b.theta[k]), d=_fr(b.d))
            with mpmath.workdps(30):
                E, dE = Characteristic(bind(p.replace(vehicle=model))).value_and_derivative(
                    mpmath.mpf(b.q[k])
                )
                assert abs(E / dE) < 1e-9  # float-rounded (alpha, eta_M, q): the root is real to ~1e-12


@pytest.mark.slow
def test_crossing_a_line_changes_the_unstable_count_by_one(masses_lines, case1_lines):
    for lines, model in ((masses_lines, "masses"), (case1_lines, "bogie")):
        b = max(lines.branches, key=lambda br: len(br.alpha))
        k = len(b.alpha) // 2
        base = lines.params.replace(alpha=_fr(b.alpha[k]), d=_fr(b.d))
        below = _unstable(base.replace(eta_M=_fr(b.theta[k] * 0.97)).replace(vehicle=model))
        above = _unstable(base.replace(eta_M=_fr(b.theta[k] * 1.03)).replace(vehicle=model))
        assert abs(above - below) == 1
        assert (above > below) == bool(b.unstable_above[k])


@pytest.mark.slow
def test_paper_unstable_cases_lie_on_the_unstable_side():
    """Cases 1, 5, 12, 13 (unstable in the paper) have unstable counts > 0 at (alpha, eta_M); 6 and 7 none."""
    for case, expected in ((1, 1), (5, 1), (12, 1), (13, 1), (6, 0), (7, 0)):
        p = table1_case(case)
        col = stability_column(
            SweepCharacteristic(bind(p)), float(p.alpha), np.array([float(p.eta_M), 200.0])
        )
        assert col.count[0] == expected and not col.uncertain[0]
        dd = d_decomposition(p)
        # the D-decomposition, counted from a reference near eta_M = 0 (stable), agrees
        ref = stability_column(SweepCharacteristic(bind(p)), float(p.alpha), np.array([0.5, 200.0])).count[0]
        assert dd.counts([float(p.eta_M)], 0.5, ref)[0] == expected


def test_case1_is_inside_an_unstable_region_of_its_instability_lines(case1_lines):
    """At alpha = 0.8, an instability line of Case 1 crosses below eta_M = 20 with the unstable side above."""
    crossings = []
    for b in case1_lines.branches:
        s = np.sign(b.alpha - 0.8)
        for i in np.nonzero(s[:-1] * s[1:] < 0)[0]:
            crossings.append((b.theta[i], b.unstable_above[i]))
    below = [(t, u) for t, u in crossings if t < 20]
    assert len(below) % 2 == 1 and below[-1][1]


def test_d_decomposition_agrees_with_instability_lines_and_counts(case1_lines):
    p = table1_case(1)
    sweep = SweepCharacteristic(bind(p))
    for alpha in (0.8, 0.95, 1.1):
        dd = d_decomposition(p, alpha)
        traced = []
        for b in case1_lines.branches:
            s = np.sign(b.alpha - alpha)
            for i in np.nonzero(s[:-1] * s[1:] < 0)[0]:
                w = (alpha - b.alpha[i]) / (b.alpha[i + 1] - b.alpha[i])
                traced.append(b.theta[i] + w * (b.theta[i + 1] - b.theta[i]))
        assert len(traced) == len(dd.crossings)
        for c, t in zip(dd.crossings, sorted(traced)):
            assert t == pytest.approx(c.theta, rel=2e-3)  # linear interpolation between traced points
        thetas = np.linspace(0.5, 200, 80)
        col = stability_column(sweep, alpha, thetas)
        assert np.array_equal(dd.counts(thetas, thetas[0], col.count[0]), col.count)


@pytest.mark.slow
def test_stability_map_agrees_with_induced_frequencies():
    p = table1_case(1)
    alphas = np.array([0.6, 0.85, 1.05])
    thetas = np.array([10.0, 60.0, 150.0])
    m = stability_map(p, alphas=alphas, thetas=thetas, workers=1)
    for i, j in ((1, 0), (1, 2), (2, 1), (0, 1)):
        r = induced_frequencies(p.replace(alpha=_fr(alphas[i]), eta_M=_fr(thetas[j])), dps=20)
        assert m.count[j, i] == len(r.unstable_roots)
        assert m.degree[j, i] == pytest.approx(float(r.degree_of_instability), abs=1e-10)


@pytest.mark.slow
def test_frequency_lines_match_the_checkpoints():
    """Case 1 from alpha = 0.7 to 0.9: four lines, each root found afresh at the checkpoints is reached."""
    res = frequency_lines(table1_case(1), alpha_range=(0.7, 0.9), checkpoints=3, h_max=0.02)
    assert not res.warnings
    assert [(n, m) for _, n, m in res.checkpoints] == [(4, 4), (4, 4), (4, 4)]
    assert len(res.lines) == 4
    q = {round(float(line.q[np.argmin(abs(line.alpha - 0.8))].real), 6) for line in res.lines}
    assert {0.307227, 0.222538, 0.184817, 0.03391} <= {round(x, 6) for x in q} | {round(x, 5) for x in q}


def test_lines_followed_together_equal_each_line_followed_alone():
    """The lockstep continuation of Figure 2 (``FrequencyTracker.follow_many``) against each line alone.

    Case 1's roots at alpha = 0.9 (found by the argument principle), followed to 1.0 (one of them meets the
    cut of K near alpha = 0.946 and is bisected there) and back to 0.85: every alpha, q and end equal
    those of :meth:`follow` on that line alone, to the last bit (the evaluations are elementwise)."""
    from moving_bogie.stability.lines.frequency_tracker import FrequencyTracker

    params = table1_case(1)
    roots = [complex(r.q) for r in induced_frequencies(params.replace(alpha=Fraction(9, 10)), dps=15).roots]
    tracker = FrequencyTracker(SweepCharacteristic(bind(params)), 0.02)
    starts = [(0.9, q, 1.0) for q in roots] + [(0.9, q, 0.85) for q in roots]
    together = tracker.follow_many(starts)
    assert together == [tracker.follow(*start) for start in starts]
    ends = [how for _, _, how in together]
    assert ends.count("cut") == 1 and ends.count("reached") == len(starts) - 1, ends
    (cut,) = [alphas[-1] for alphas, _, how in together if how == "cut"]
    assert 0.94 < cut < 0.95


def test_critical_stiffness_of_case5():
    """Case 5 (unstable at kappa_v = 0.2, alpha = 0.7): the interval holding 0.2 is unstable; counts agree."""
    res = critical_stiffness(table1_case(5), [0.7], kappa_max=0.6, check_points=20)
    assert res.mismatches == 0
    (ivs,) = res.intervals
    assert any(lo < 0.2 < hi and n == 1 for lo, hi, n in ivs)
    assert res.critical[0] and all(0 < k < 0.6 for k in res.critical[0])


def test_d_decomposition_needs_foundation_damping():
    """The D-decomposition degenerates at eta_f = 0 (the commands use stability/maps/undamped.py there)."""
    with pytest.raises(ParameterError, match="eta_f"):
        d_decomposition(table1_case(2))
