"""The verdict on an undamped foundation (eta_f = 0, Table 1's Cases 2-4, 9, 10) is decided.

With eta_f = 0 the cut of K lies on the real axis; the sliver the search leaves around it reaches below the
axis, and the strip there is counted with K as the limit from below (roots/count/strip.py). References: the
same
case at small eta_f > 0 (the cut then lies above the axis and the strip below it is counted with the
ordinary E_chr, no limit from below), and the roots located by the ordinary search.
"""

from fractions import Fraction

import mpmath
import numpy as np
import pytest

from moving_bogie.api import induced_frequencies
from moving_bogie.kernels.bound import bind
from moving_bogie.kernels.characteristic import Characteristic
from moving_bogie.kernels.sweep_characteristic import SweepCharacteristic
from moving_bogie.model.cases import table1_case
from moving_bogie.roots.count.contour import Rectangle
from moving_bogie.roots.count.strip import strip_below_cut
from moving_bogie.roots.damping_limit import damping_limit
from moving_bogie.roots.table2 import case_list, compute_table2, format_table2, summary_lines

UNDAMPED = (2, 3, 4, 9, 10)


def _verdict_agrees_with_small_damping(case):
    p = table1_case(case)
    assert p.eta_f == 0
    exact = induced_frequencies(p, dps=20)
    assert exact.verdict.determined, exact.verdict.reasons
    assert exact.strip.mode == "from below" and exact.strip.count == 0
    # next to the branch point E_chr is infinite like K (the notch left out): |E| sqrt(distance) about
    # constant, and equal to the mpmath E_chr below the axis (no limit from below needed there)
    (x,), (growth,) = exact.strip.notches, exact.strip.growth
    reference = abs(Characteristic(bind(p))(mpmath.mpc(x, -1e-7))) * mpmath.sqrt(1e-7)
    # the strip evaluates E_chr through the sweep kernels, which may normalise E_chr by another constant
    # than the block determinant of Characteristic: take the ratio at a point far from the cut
    far = complex(x, -0.5)
    scale = abs(
        SweepCharacteristic(bind(p), below=True)(np.array([far]), np.array([float(p.alpha)]))[0]
    ) / abs(complex(Characteristic(bind(p))(mpmath.mpc(far))))
    reference *= scale
    assert max(growth) < 1.1 * min(growth) and growth[1] == pytest.approx(float(reference), rel=1e-6)
    searched = {}
    for eta_f in ("1e-6", "1e-8"):
        damped = searched[eta_f] = induced_frequencies(p.replace(eta_f=Fraction(eta_f)), dps=20)
        # the box around the branch point (half-width 1e-9) stays above the axis at eta_f = 1e-8: then
        # nothing below the axis is unsearched and no strip is counted
        assert damped.strip is None or damped.strip.mode == "below the cut"
        assert damped.verdict.determined, damped.verdict.reasons
        assert damped.verdict.state == exact.verdict.state, (case, eta_f)
        # the roots move by O(eta_f) (first order in eta_f, stability/maps/undamped.py)
        got = sorted((complex(r.q) for r in damped.roots), key=lambda z: z.real)
        ref = sorted((complex(r.q) for r in exact.roots), key=lambda z: z.real)
        assert len(got) == len(ref) and np.allclose(got, ref, atol=1e3 * float(Fraction(eta_f)))
    limit = damping_limit(exact)
    if limit is None:  # a damped vehicle: no real root at eta_f = 0
        assert not any(r.marginal for r in exact.roots)
        return
    # first order in eta_f against the roots the ordinary search finds at eta_f = 1e-6 (searched above)
    damped = searched["1e-6"]
    for root, slope in zip(limit.roots, limit.slopes):
        (near,) = [r for r in damped.roots if abs(complex(r.q).real - float(root.q.real)) < 1e-4]
        assert float(near.q.imag) / 1e-6 == pytest.approx(slope, rel=1e-3)
    assert (limit.destabilised == 0) == (exact.verdict.state == "stable")


@pytest.mark.parametrize("case", [2, pytest.param(9, marks=pytest.mark.slow)])  # Case 9 with Cases 3, 4, 10
def test_undamped_verdict_matches_the_limit_of_small_damping(case):
    """Case 2 (four real roots, undamped vehicle) and Case 9 (damped vehicle)."""
    _verdict_agrees_with_small_damping(case)


@pytest.mark.slow
@pytest.mark.parametrize("case", [3, 4, 10])
def test_undamped_verdict_matches_the_limit_of_small_damping_other_cases(case):
    _verdict_agrees_with_small_damping(case)


def test_strip_count_finds_the_root_next_to_a_branch_point():
    """Case 3 at alpha = 1.1, eta_M = 13.7 (eta_f = 0): the ordinary search locates a root 1.9e-4 below the
    axis next to the branch point q = 0.14496 and another at Im q = -0.0149. The strip count over the
    rectangles below the axis, with K from below on their top edges, must find the same ones."""
    p = table1_case(3).replace(alpha=Fraction(11, 10), eta_M=Fraction(137, 10))
    result = induced_frequencies(p, dps=20)
    unstable = [complex(r.q) for r in result.unstable_roots]
    near = Rectangle(0.13, 0.16, -1e-3, 1e-3)
    deep = Rectangle(0.0, 3.0, -0.5, 1e-3)
    for rect in (near, deep):
        strip = strip_below_cut(bind(p), result.window, (rect,))
        assert strip.mode == "from below" and strip.notches
        inside = sum(rect.x0 < q.real < rect.x1 and rect.y0 < q.imag < 0 for q in unstable)
        assert strip.count == inside and inside >= 1


def test_table2_summary_is_truthful():
    """The closing lines name the unstable cases, the stable ones and, on a line of their own, the undamped
    ones decided by the strip below the cut: each list read from the computed verdicts and strips."""
    table = compute_table2(cases=(2, 12))
    text = format_table2(table)
    summary = text.splitlines()[-len(summary_lines(table)) :]
    unstable = [row.case for row in table.rows if row.result.verdict.state == "unstable"]
    stable = [row.case for row in table.rows if row.result.verdict.state == "stable"]
    undamped = [row.case for row in table.rows if row.result.strip is not None and row.result.strip.decided]
    assert unstable and stable and undamped  # the three lists are exercised
    assert "UNDETERMINED" not in text
    verdicts = next(line for line in summary if line.startswith("verdicts:"))
    assert verdicts == (
        f"verdicts: {len(unstable)} unstable ({case_list(unstable)}: an induced frequency with Im q < 0), "
        f"{len(stable)} stable ({case_list(stable)})"
    )
    undamped_line = next(line for line in summary if line.startswith("undamped"))
    assert undamped_line.startswith(f"undamped (eta_f = 0): {case_list(undamped)}, ")
    assert "count ok, stable (4 real root(s), neutral)" in text


def test_case_lists_name_every_case():
    assert case_list([]) == "no case"
    assert case_list([3]) == "Case 3"
    assert case_list([1, 5, 12, 13]) == "Cases 1, 5, 12, 13"
    assert case_list([2, 3, 4, 6, 7, 8, 9, 10, 11]) == "Cases 2-4, 6-11"
    assert case_list(list(range(1, 14))) == "Cases 1-13"


@pytest.mark.slow
def test_certify_proves_the_strip_below_the_axis_except_the_branch_point():
    """Ball arithmetic with K from below: the strip below the cut of Case 2 holds no root; what remains is
    the square under the branch point, and the reason names it."""
    result = induced_frequencies(table1_case(2), certify=True)
    c = result.certificate
    assert c.all_proven and c.below is not None and c.below.count == 0
    assert c.verdict == "not proven" and "only that square remains" in c.reason


@pytest.mark.slow
def test_ball_count_from_below_finds_the_root_next_to_a_branch_point():
    """The proven count (K from below on the top edge) against the root the ordinary search locates."""
    from moving_bogie.roots.count.strip import pieces_below_axis
    from moving_bogie.roots.proof.balls import BallCharacteristic
    from moving_bogie.roots.proof.winding import proven_count

    p = table1_case(3).replace(alpha=Fraction(11, 10), eta_M=Fraction(137, 10))
    result = induced_frequencies(p, dps=20)
    inside = [complex(r.q) for r in result.unstable_roots if 0.13 < r.q.real < 0.16]
    bc = BallCharacteristic(bind(p), prec=96, below=True)
    pieces = pieces_below_axis(Rectangle(0.13, 0.16, -1e-3, 0.0), [result.strip.notches[0]])
    count = sum(proven_count(bc, r, min_length=1e-14).count for r in pieces)
    assert len(inside) == 1 and count == 1
