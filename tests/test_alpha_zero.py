"""The search on layered tracks at alpha = 0 (kernels/cut.py, kernels/cut_curves.py, roots/refine/locate.py).

At alpha = 0, N(p, q) is even in p: every cut curve is traced twice (over p < 0 and p > 0), a curve can lie
on Re q = 0 (Re dq/dp at rounding level, of either sign), and a mass layer's curves end at its resonance,
where roots of E_chr gather. Before: a ZeroDivisionError (a column of zero width between a fold and its
repeat one rounding apart), a ValueError from brentq (a turn of the cut at p = 0 found at rounding level)
and a search that did not end (dozens of folds of rounding noise on Re q = 0).

References: the symmetry itself (the cut of an even N is its own mirror -conj(q), so its folds are
mirror pairs or lie on Re q = 0, and no two folds of the same kind coincide), and the brute-force scan of
benchmarks/bench_search_random.py (no contour code) for the roots with Im q < 0.
"""

import functools

import numpy as np
import pytest
from scripts import load_script
from test_cut_clearance import AVOIDED_CROSSING

from moving_bogie.api import induced_frequencies
from moving_bogie.kernels.bound import bind
from moving_bogie.kernels.cut import cut_locus
from moving_bogie.model.params import DimensionlessParams

# Sets 144 and 149 of the random benchmark (seed 24) with alpha = 0: a light sleeper layer whose cut has a
# segment on Re q = 0, and two masses on three layers (the ZeroDivisionError).
ON_THE_AXIS = AVOIDED_CROSSING.replace(alpha="0")
THREE_LAYERS = DimensionlessParams(
    beam="eb",
    track="three-layer",
    vehicle="masses",
    alpha="0",
    eta_f="0.351014827221",
    eta_M="60.1720489881",
    d="4.62968736896",
    mu_2="1.53001958281",
    kappa_2="0.958168918972",
    eta_2="0.28558331351",
    mu_3="5.59156844304",
    kappa_3="1.06632942801",
    eta_3="0.364723910684",
)


@pytest.mark.parametrize("params", [ON_THE_AXIS, THREE_LAYERS], ids=["two-layer", "three-layer"])
def test_folds_are_distinct_and_mirror_symmetric(params):
    cut = cut_locus(bind(params), -3.0, 3.0)
    folds = cut.folds
    assert sum(abs(f.q.real) <= 1e-9 for f in folds) <= 2  # 35 of rounding noise on Re q = 0 before
    for k, f in enumerate(folds):
        for g in folds[k + 1 :]:
            same_kind = (f.opens, f.cusp, f.end) == (g.opens, g.cusp, g.end)
            assert not (same_kind and abs(f.q - g.q) <= 1e-9), (f, g)
        # the mirror -conj(q) of a fold is a fold (with the opposite opening) or it lies on Re q = 0
        mirror = -np.conj(f.q)
        assert abs(f.q.real) <= 1e-9 or min(abs(g.q - mirror) for g in folds) <= 1e-7, f


@functools.cache
def _search(params: DimensionlessParams):
    """The search from scratch, once per parameter set for the tests of this module that share it."""
    return induced_frequencies(params)


# the three-layer search is slow; the fast subset searches the two-layer set (the folds of both are fast)
@pytest.mark.parametrize(
    "params",
    [
        pytest.param(ON_THE_AXIS, id="two-layer"),
        pytest.param(THREE_LAYERS, id="three-layer", marks=pytest.mark.slow),
    ],
)
def test_the_search_ends_with_a_decided_verdict(params):
    res = _search(params)
    assert res.verdict.determined
    assert res.evaluations < 1_000_000


@pytest.mark.slow
def test_three_layers_at_rest_agree_with_the_scan():
    bench = load_script("benchmarks/bench_search_random.py")
    res = _search(THREE_LAYERS)
    assert res.count_ok and max(u.height for u in res.unsearched) <= 1e-8
    reference = bench.scan_roots(THREE_LAYERS, res.window, n=(401, 401))
    ok, worst = bench.compare(res, reference)
    assert ok, worst
    assert res.verdict.state == ("unstable" if reference else "stable")
