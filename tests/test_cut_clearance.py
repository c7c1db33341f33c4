"""Contour edges beside the cut where q moves fast with p (kernels/cut.py ``clearance``,
roots/search/cut_cells.py).

Next to an avoided crossing of two cut curves q_j(p) (a light sleeper layer), |dq/dp| reaches 2.5e4: the
cut point q(p) from N(p, q) = 0 in double precision is good to about 1e-11 only, and a point 2e-11 beside
the cut has a p-root with Im p ~ 1e-15, whose side double precision decides at random. Edges at the plain
offset eps = 2e-11 then crossed the true cut back and forth (the argument of E_chr jumped by pi/2 between
neighbouring samples) and whole columns next to the fold were left out, 2.9e-3 high.

Reference: the p-roots at 40 digits (mpmath, :class:`~moving_bogie.kernels.track.TrackKernel`) at every
edge point: the root nearest the real axis must lie on the same side as the double-precision one (the
side the residue sum of Eq. (29) uses), well away from it, and on opposite sides for the two edges of
one arm.
"""

import mpmath
import numpy as np
import pytest

from moving_bogie.kernels.bound import bind
from moving_bogie.kernels.characteristic import CharacteristicArray
from moving_bogie.kernels.cut import CLEARANCE, cut_locus
from moving_bogie.kernels.track import TrackKernel
from moving_bogie.model.params import DimensionlessParams
from moving_bogie.roots.count.contour import winding_numbers
from moving_bogie.roots.search.cut_cells import ColumnCell, Edge

# Set 72 of the random benchmark's two-layer sets (seed 24): bogie at 0.86 v_cr, m_2 = 71 kg/m. A fold of
# the cut at q = 0.18507 + 0.25965i opens towards smaller Re q, and another curve passes 5e-7 above it.
AVOIDED_CROSSING = DimensionlessParams(
    beam="eb",
    track="two-layer",
    vehicle="bogie",
    alpha="0.333361",
    eta_f="0.243511471291",
    eta_M="29.6306930923",
    d="4.50342035984",
    mu_v="56.9061756827",
    J_b="311.18833294",
    kappa_v="0.00654206126482",
    eta_v="0.149843490531",
    mu_2="1.19305496916",
    kappa_2="0.107306675325",
    eta_2="0.520493512657",
)
EPS = 2e-11  # the search's default eps


@pytest.fixture(scope="module")
def fold_arms():
    cut = cut_locus(bind(AVOIDED_CROSSING), 0.0, 0.4)
    (fold,) = [f for f in cut.folds if abs(f.q - (0.18507 + 0.25965j)) < 1e-4]
    pair = [a for a in cut.arms if any(abs(a.q[k] - fold.q) < 1e-9 for k in (0, -1))]
    assert len(pair) == 2 and fold.opens == -1
    return cut, fold, pair


def _near_real_mp(kernel, z):
    with mpmath.workdps(40):
        roots = kernel.p_roots(mpmath.mpc(z))
        return complex(min(roots, key=lambda p: abs(mpmath.im(p))))


def test_edges_beside_fast_arms_are_on_the_side_they_claim(fold_arms):
    cut, fold, pair = fold_arms
    fast = CharacteristicArray(bind(AVOIDED_CROSSING))
    precise = TrackKernel(bind(AVOIDED_CROSSING))
    xs = fold.q.real - np.geomspace(1e-3, 1e-6, 12)
    fastest = 0.0
    for arm in pair:
        p = arm.p_at(xs)
        fastest = max(fastest, float(np.abs(arm.tracer.dq_dp(p, arm.q_at(p))).max()))
        sides = {}
        for side in (-1, 1):
            z = Edge(arm=arm, side=side, delta=EPS).points(xs)
            doubles = fast.kernel.p_roots(z)
            for zk, row in zip(z, doubles):
                p_mp = _near_real_mp(precise, zk)
                p_double = row[np.argmin(np.abs(row - p_mp))]
                # Im p ~ distance / |dq/dp| >= CLEARANCE max(1, |p|) to first order: far above the 1e-16
                # rounding of the double-precision roots
                assert abs(p_mp.imag) > 0.5 * CLEARANCE * max(1.0, abs(p_mp))
                assert np.sign(p_double.imag) == np.sign(p_mp.imag), (zk, p_double, p_mp)
                sides.setdefault(side, set()).add(np.sign(p_mp.imag))
        assert len(sides[-1]) == len(sides[1]) == 1 and sides[-1] != sides[1]
    assert fastest > 1e4  # the arms this test is about: q moves fast with p


def test_the_cell_between_the_fold_and_the_curve_above_it_is_counted(fold_arms):
    cut, fold, pair = fold_arms
    x0, x1 = fold.q.real - 1e-3, fold.q.real - 6.1e-8
    xm = np.array([0.5 * (x0 + x1)])
    upper = max(pair, key=lambda a: a.y_at(xm)[0])
    spans = [a for a in cut.arms if a.x_lo < x0 and a.x_hi > x1]
    above = [a for a in spans if 0 < a.y_at(xm)[0] - upper.y_at(xm)[0] < 0.1]
    assert len(above) == 1
    cell = ColumnCell(x0, x1, Edge(arm=upper, side=1, delta=EPS), Edge(arm=above[0], side=-1, delta=EPS))
    (n,) = winding_numbers(CharacteristicArray(bind(AVOIDED_CROSSING)), [cell])
    assert n == 0  # E_chr has no zero there: |E| ~ 1.2e5 on a 301 x 301 scan of the region
