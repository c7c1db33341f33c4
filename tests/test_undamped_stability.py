"""Stability commands on an undamped (eta_f = 0) or near-undamped foundation (issue 13, item 4).

References, independent of the counts along a column that locate the boundaries:
- :func:`~moving_bogie.roots.frequencies.induced_frequencies` (argument principle on tiles avoiding the cut,
  mpmath polish) on both sides of a boundary, at eta_f = 0 and at small eta_f > 0 where its verdict is
  certified;
- the D-decomposition (:mod:`~moving_bogie.stability.stiffness.d_decomposition`) at eta_f = 1e-2, 1e-3, 1e-4,
  whose
  crossings must converge to the limit eta_f -> 0+ boundaries;
- K on the cut from below against K just below the cut (eta_f = 0, q - i h) and at a tiny eta_f > 0.
"""

import json
from fractions import Fraction

import numpy as np
import pytest

from moving_bogie.api import critical_stiffness, d_decomposition, induced_frequencies, instability_lines
from moving_bogie.cli import main
from moving_bogie.kernels.bound import bind
from moving_bogie.kernels.sweep_characteristic import SweepCharacteristic
from moving_bogie.model.cases import table1_case
from moving_bogie.stability.maps.undamped import UndampedCounter, boundaries, parameter_grid


def _fr(x):
    return Fraction(str(float(x)))


def _unstable(params):
    """Unstable induced frequencies by the full search (roots with Im q < 0 beyond their confirmed digits)."""
    return len(induced_frequencies(params, dps=20).unstable_roots)


@pytest.mark.parametrize("beam", [{}, {"beam": "tr", "S": 10, "r": "0.09"}])
def test_kernel_on_the_cut_is_the_limit_from_below(beam):
    """eta_f = 0, real q beyond the branch point: K(q) equals K(q - i h) up to O(h), not K(q + i h)."""
    p = table1_case(2).replace(**beam)
    q, a = np.array([0.7, 1.0, 1.5, 3.0]), np.full(4, 0.5)
    K = np.array(SweepCharacteristic(bind(p), below=True).kernel(q, a)[0])
    plain = SweepCharacteristic(bind(p))
    errors = [np.abs(K - np.array(plain.kernel(q - 1j * h, a)[0])).max() for h in (1e-5, 1e-7)]
    assert errors[1] < errors[0] / 50  # converges like h
    assert np.abs(K - np.array(plain.kernel(q + 1e-7j, a)[0])).max() > 0.1  # the other side jumps
    tiny = SweepCharacteristic(bind(p.replace(eta_f=Fraction(1, 10**7))))
    assert np.abs(K - np.array(tiny.kernel(q, a)[0])).max() < 10 * errors[1]


def test_case5_real_root_is_destabilised_by_small_foundation_damping():
    """Case 5 (bogie, alpha = 0.7, kappa_v = 0.2): at eta_f = 0 every root is real or stable, but for small
    eta_f > 0 one real root moves below the axis, Im q proportional to eta_f: the limit count is 1."""
    p = table1_case(5)
    ims = []
    for eta_f in ("0.001", "0.0001"):
        res = induced_frequencies(p.replace(eta_f=eta_f), dps=20)
        assert len(res.unstable_roots) == 1
        ims.append(float(res.unstable_roots[0].q.imag) / float(eta_f))
    assert ims[0] == pytest.approx(ims[1], rel=1e-3)  # linear in eta_f
    assert _unstable(p.replace(eta_f=0)) == 0
    col = UndampedCounter(bind(p), "kappa_v")(0.7, np.array([0.2]))
    assert (col.undamped[0], col.limit[0]) == (0, 1)


@pytest.mark.slow
@pytest.mark.parametrize(("model", "alpha"), [("bogie", 0.7), ("masses", 0.6)])
def test_subcritical_limit_boundaries_confirmed_by_counts_on_both_sides(model, alpha):
    """Case 2 (undamped, d = 2), subcritical, eta_M up to 200: one boundary, of the limit kind; 3 % on
    either side the full search at eta_f = 1e-4 counts one more unstable root on the unstable side, while at
    eta_f = 0 the count is 0 on both sides (the roots there are real)."""
    p = table1_case(2)
    bounds, col, unsure = boundaries(
        UndampedCounter(bind(p.replace(vehicle=model))), alpha, parameter_grid(200.0, 20), tol=0.01
    )
    assert unsure == 0
    assert len(bounds) == 1 and (bounds[0].kind, bounds[0].mechanism) == ("limit", "damping sign")
    assert not np.any(col.undamped)
    for b in bounds:
        base = p.replace(alpha=_fr(alpha))
        below, above = (base.replace(eta_M=_fr(b.theta * f)) for f in (0.97, 1.03))
        damped = [_unstable(x.replace(eta_f="0.0001").replace(vehicle=model)) for x in (below, above)]
        assert damped == [b.count_below, b.count_above]
        assert [_unstable(x.replace(vehicle=model)) for x in (below, above)] == [0, 0]


@pytest.mark.slow
@pytest.mark.parametrize(("case", "model"), [(3, "bogie"), (4, "masses")])
def test_supercritical_boundaries_at_eta_f_zero_confirmed_by_counts(case, model):
    """Cases 3 and 4 (d = 5) at alpha = 1.1: the eta_f = 0 boundaries above eta_M = 5 carry the counts the
    full search finds at eta_f = 0 on both sides of them. (The bogie's boundary at eta_M = 13.2 lies next to
    a branch point of K at q = 0.14496: without dense samples of the top edge around it the column count
    missed a root 2e-4 below the axis and put the boundary at 14.09.)"""
    p = table1_case(case)
    bounds, _, _ = boundaries(
        UndampedCounter(bind(p.replace(vehicle=model))), 1.1, parameter_grid(100.0, 20), tol=0.01
    )
    exact = [b for b in bounds if b.kind == "undamped" and b.theta > 5]
    assert exact and {b.mechanism for b in bounds} == {"crossing"}  # no gap above the critical velocity
    base = p.replace(alpha=_fr(1.1))
    for b in exact[:2]:
        counts = [
            _unstable(base.replace(eta_M=_fr(b.theta * f)).replace(vehicle=model)) for f in (0.97, 1.03)
        ]
        assert counts == [b.count_below, b.count_above]


@pytest.mark.slow
def test_limit_boundaries_are_the_limit_of_small_damping():
    """The limit boundaries equal the D-decomposition crossings at eta_f -> 0+: the difference shrinks by at
    least a factor 10 per decade of eta_f (first order or better), in eta_M (two masses, d = 1.5,
    alpha = 0.8) and in kappa_v (Case 5, alpha = 0.7)."""
    for p, model, parameter, alpha, top in (
        (table1_case(2).replace(d="1.5"), "masses", "eta_M", 0.8, 200.0),
        (table1_case(5), "bogie", "kappa_v", 0.7, 0.6),
    ):
        counter = UndampedCounter(bind(p.replace(vehicle=model)), parameter)
        bounds, _, _ = boundaries(counter, alpha, parameter_grid(top, 20), tol=1e-12 * top)
        limit = [b.theta for b in bounds if b.kind == "limit"]
        assert limit
        for k, theta in enumerate(limit):
            diffs = []
            for eta_f in ("0.01", "0.001", "0.0001"):
                dd = d_decomposition(
                    p.replace(eta_f=eta_f, alpha=_fr(alpha)).replace(vehicle=model),
                    parameter=parameter,
                    theta_max=top,
                )
                assert len(dd.crossings) == len(limit)
                diffs.append(abs(dd.crossings[k].theta - theta))
            assert diffs[1] < diffs[0] / 10 and diffs[2] < diffs[1] / 10


@pytest.mark.slow
def test_instability_lines_at_eta_f_zero_say_what_they_are():
    """No refusal any more: boundaries of both kinds for eta_f = 0, of the limit kind only for 1e-6."""
    p = table1_case(2).replace(d="1.5")
    res = instability_lines(p.replace(vehicle="masses"), alpha_range=(0.7, 0.9), alpha_step=0.05)
    assert res.regime == "undamped" and "limit eta_f -> 0+" in res.statement
    (b,) = res.branches
    assert b.kind == "limit" and len(b.alpha) == 5 and b.unstable_side == "above"
    assert np.all((b.theta > 35) & (b.theta < 80))
    near = instability_lines(
        p.replace(eta_f="0.000001").replace(vehicle="masses"), alpha_range=(0.7, 0.9), alpha_step=0.05
    )
    assert near.regime == "near-undamped" and {x.kind for x in near.branches} == {"limit"}
    np.testing.assert_allclose(near.branches[0].theta, b.theta)
    data = res.to_dict()
    point = data["branches"][0]["points"][0]
    assert data["branches"][0]["kind"] == "limit" and point["q"] is None
    assert point["mechanism"] == "damping sign"


@pytest.mark.slow
def test_critical_stiffness_undamped_and_near_undamped():
    """Case 5 at alpha = 0.7: stable for every kappa_v at eta_f = 0; in the limit (and for eta_f = 1e-6)
    unstable between the two limit boundaries, as the D-decomposition at eta_f = 1e-4 says."""
    p = table1_case(5)
    res = critical_stiffness(p.replace(eta_f=0), [0.7], kappa_max=0.6, check_points=20)
    assert res.regime == "undamped" and [n for *_, n in res.intervals[0]] == [0]
    assert [n for *_, n in res.limit_intervals[0]] == [0, 1, 0]
    near = critical_stiffness(p.replace(eta_f="0.000001"), [0.7], kappa_max=0.6, check_points=20)
    crossings = d_decomposition(p.replace(eta_f="0.0001"), parameter="kappa_v", theta_max=0.6).crossings
    np.testing.assert_allclose(near.critical[0], [c.theta for c in crossings], rtol=1e-5)
    assert "limit eta_f -> 0+" in near.method


def _run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


@pytest.mark.slow
def test_cli_states_the_convention_and_what_is_computed(capsys, compute_once):
    import moving_bogie.stability.lines.instability_lines as lines

    # the text and the JSON runs below trace the same lines (same options): once, each run prints it
    compute_once(lines, "instability_lines_many")
    common = ("--model", "masses", "--d", "1.5", "--alpha-min", "0.75", "--alpha-max", "0.85")
    code, out, _ = _run(capsys, "instability-lines", *common, "--eta-f", "0")
    assert code == 0
    assert out.startswith("eta_f = 0: real induced frequencies fill whole regions")
    assert "limit from below" in out and "[limit:" in out
    code, out, _ = _run(capsys, "instability-lines", *common, "--eta-f", "0", "--json")
    data = json.loads(out)
    assert data["regime"] == "undamped" and "limit from below" in data["statement"]
    code, out, _ = _run(
        capsys, "critical-stiffness", "--case", "5", "--eta-f", "0", "--alphas", "1", "--alpha-min", "0.7",
        "--alpha-max", "0.7", "--kappa-max", "0.6",
    )  # fmt: skip
    assert code == 0 and "undamped foundation" in out and "limit eta_f -> 0+ unstable counts" in out


@pytest.mark.slow
def test_stability_map_counts_change_exactly_across_the_undamped_boundaries():
    """A coarse stability map at eta_f = 0 (its own columns, with the top edge just below the cut) changes
    its unstable count between two cells exactly by the changes of the eta_f = 0 boundaries between them."""
    from moving_bogie.api import stability_map

    p = table1_case(3)
    alphas, thetas = np.linspace(1.05, 1.2, 4), np.linspace(10.0, 100.0, 10)
    smap = stability_map(p, alphas=alphas, thetas=thetas, workers=1)
    counter = UndampedCounter(bind(p))
    changes = 0
    for i, a in enumerate(alphas):
        bounds, _, _ = boundaries(counter, a, thetas, tol=1e-3)
        for j in range(len(thetas) - 1):
            if smap.uncertain[j, i] or smap.uncertain[j + 1, i]:
                continue
            step = int(smap.count[j + 1, i]) - int(smap.count[j, i])
            mine = sum(
                b.count_above - b.count_below
                for b in bounds
                if b.kind == "undamped" and thetas[j] < b.theta < thetas[j + 1]
            )
            assert step == mine
            changes += abs(step)
    assert changes >= 4


def test_stability_map_sees_the_root_next_to_a_branch_point():
    """Case 3 (bogie) at alpha = 1.1, eta_M = 13.7: a root 1.9e-4 below the axis next to the branch point
    q = 0.14496 of K; the full search at eta_f = 0 counts 2 unstable roots, and so must the map's column
    (it said 1, uncertified, before the top edge was sampled densely around the branch points)."""
    from moving_bogie.api import stability_map

    p = table1_case(3)
    reference = _unstable(p.replace(alpha=_fr(1.1), eta_M=_fr(13.7)))
    smap = stability_map(p, alphas=np.array([1.1]), thetas=np.array([13.0, 13.7]), workers=1)
    assert reference == 2 and list(smap.count[:, 0]) == [1, 2]
