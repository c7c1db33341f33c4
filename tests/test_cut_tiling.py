"""The traced cut of K and the search cells that follow it (kernels/cut.py, roots/search/search_regions.py).

References: the cut points come from an independent dense scan (numpy.roots of N(p, .) at each real p of a
fine grid); the tiling is checked with f(z) = z - z0, whose only zero is z0: the winding numbers over all
regions must add up to 1 and name the region that ``contains`` z0, for points placed just above, just
below and inside the lens of the Timoshenko-Rayleigh cut and around its fold.
"""

import numpy as np
import pytest

from moving_bogie.api import induced_frequencies
from moving_bogie.kernels.bound import bind
from moving_bogie.kernels.characteristic import CharacteristicArray
from moving_bogie.kernels.cut import cut_locus
from moving_bogie.model.cases import table1_case
from moving_bogie.roots.count.contour import winding_number, winding_numbers
from moving_bogie.roots.frequencies import default_window
from moving_bogie.roots.search.search_regions import tile_window

TR_CASES = [("10", "0.09"), ("100", "0.03")]


def _tr(S, r):
    return table1_case(7).replace(beam="tr", S=S, r=r)


# the fast subset scans the first beam of TR_CASES, the full suite both
@pytest.mark.parametrize(
    ("S", "r"), [TR_CASES[0], *(pytest.param(*c, marks=pytest.mark.slow) for c in TR_CASES[1:])]
)
def test_traced_arms_match_a_dense_scan(S, r):
    params = _tr(S, r)
    cut = cut_locus(bind(params), 0.0, 3.0)
    track = bind(params).foundation_model
    args = track.float_arguments(params)
    ps = np.linspace(-3, 3, 601)
    scan = []
    for p in ps:
        roots = np.roots(np.array(track.module.n_coeffs_in_q(p, **args), dtype=complex))
        scan += [q for q in roots if 0.0 < q.real < 3.0]
    scan = np.array(scan)
    assert scan.size > 100
    for q in scan:
        best = min(
            abs(arm.y_at(np.array([q.real]))[0] - q.imag)
            for arm in cut.arms
            if arm.x_lo <= q.real <= arm.x_hi
        )
        assert best < 1e-12
    assert len(cut.folds) == 1 and not cut.folds[0].cusp  # the fold at q_c: a lens opens to its right


def test_cells_partition_the_window_minus_the_sliver():
    params = _tr(*TR_CASES[0])
    window = default_window(bind(params))
    cut = cut_locus(bind(params), window.x0, window.x1)
    tiling = tile_window(window, cut, eps=2e-11, eps_branch=1e-5, gap_height=0.1 * window.height)
    assert max(u.height for u in tiling.unsearched) <= 1e-10
    fold = cut.folds[0].q
    points = [
        fold - 1e-6,
        fold + 1e-5,
        fold + 1e-4,
        fold + 2e-3,
        fold + 1e-3j,
        fold - 1e-3j,
        1.5 + 1j,
        2.9 - 2j,
    ]
    for arm in cut.arms:
        xs = np.array([fold.real + 1e-6, fold.real + 5e-4, 2.5])
        ys = arm.y_at(xs)
        for d in (1e-9, 1e-4):
            points += list(xs + 1j * (ys + d)) + list(xs + 1j * (ys - d))
    for z0 in points:
        counts = [winding_number(lambda z, z0=z0: z - z0, region) for region in tiling.regions]
        assert sum(counts) == 1, z0
        assert tiling.regions[counts.index(1)].contains(z0), z0


@pytest.mark.parametrize(("S", "r"), TR_CASES)
def test_tr_frequencies_leave_no_sliver_above_1e_10(S, r):
    result = induced_frequencies(_tr(S, r), dps=20)
    assert result.count_ok, result.warnings
    assert result.count == 4
    assert result.unsearched and max(u.height for u in result.unsearched) <= 1e-10


@pytest.mark.slow
@pytest.mark.parametrize("case", [1, 2])
def test_counts_next_to_the_euler_bernoulli_branch_point(case):
    """The box around the branch point q_c is 2e-9 wide (eps_branch = 1e-9), so contours pass within 1e-9 of
    a point where K is infinite like 1/sqrt(q - q_c). Reference: a zero z0 placed by hand. The winding
    numbers of E_chr(z) (z - z0) must exceed those of E_chr by exactly one, in the region that contains z0,
    for z0 at 3e-9 to 1e-5 from q_c on every side but the cut itself (Case 2: eta_f = 0, the cut on the real
    axis)."""
    params = table1_case(case)
    window = default_window(bind(params))
    cut = cut_locus(bind(params), window.x0, window.x1)
    assert cut.flat
    tiling = tile_window(window, cut, eps=2e-11, eps_branch=1e-9, gap_height=0.1 * window.height)
    assert max(u.height for u in tiling.unsearched) <= 2.1e-9
    E = CharacteristicArray(bind(params))
    base = winding_numbers(E, tiling.regions)
    assert not any(isinstance(b, Exception) for b in base)
    q_c = complex(cut.x_start, cut.im_low)
    angles = np.pi * np.array([0.5, -0.5, 1.0, 0.75, -0.75, 0.25, -0.25])
    points = [q_c + r * np.exp(1j * t) for r in (3e-9, 1e-7, 1e-5) for t in angles]
    for z0 in points:
        counts = winding_numbers(lambda z, z0=z0: E(z) * (z - z0), tiling.regions)
        diff = [c - b for c, b in zip(counts, base)]
        assert sorted(diff) == [0] * (len(diff) - 1) + [1], z0
        assert tiling.regions[diff.index(1)].contains(z0), z0


@pytest.mark.parametrize(("S", "r"), TR_CASES)
def test_newton_on_a_few_cut_points_matches_the_batch_and_numpy_roots(S, r):
    """CutTracer.refine takes scalar steps for a handful of points: the same points as the batched steps,
    and as numpy.roots of N(p, .) (an independent companion-matrix solve), to rounding."""
    params = _tr(S, r)
    cut = cut_locus(bind(params), 0.0, 3.0)
    track = bind(params).foundation_model
    args = track.float_arguments(params)
    tracer = cut.arms[0].tracer
    checked = 0
    for arm in cut.arms:
        ps = np.linspace(arm.p[0], arm.p[-1], 7)[1:-1]
        guess = arm.guess(ps)
        batch = tracer.refine(ps, guess)  # 5 points: the batched path
        for p, g, b in zip(ps, guess, batch):
            (one,) = tracer.refine(np.array([p]), np.array([g]))
            roots = np.roots(np.array(track.module.n_coeffs_in_q(p, **args), dtype=complex))
            scale = max(1.0, abs(b))
            assert abs(one - b) <= 1e-12 * scale, (p, one, b)
            assert np.min(np.abs(roots - one)) <= 1e-9 * scale, (p, one, roots)
            checked += 1
    assert checked >= 10
