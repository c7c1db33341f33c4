"""A track model whose N(p, q) has degree 6 in p (the two-layer track) through the whole runtime.

The two-layer track of derivations/foundations.py (rail on pads k_1, c_1 over a mass layer m_2 on
k_2, c_2, the layout of ballasted track) is bound to the runtime as a ``Foundation`` with the values of
its layer groups: ``BoundModel(params, foundation=Foundation(module, values))``, another bound model.
References, all independent of the residue sums and the root search being tested:

* K(xi, q) and dK/dq: QUADPACK quadrature of Eq. (29) over real p (``test_track_kernel.quadrature_module_K``);
* roots in p: the local minima of |N| on a dense grid of the complex p-plane, and mpmath.polyroots at 40
  digits;
* roots in q (induced frequencies): with a stiff second layer (kappa_2 -> infinity the mass layer is clamped
  and the model becomes the Euler-Bernoulli track of Table 2) the roots, extrapolated in 1/kappa_2 from
  two stiffnesses, must reproduce the printed Table 2 values of Case 1.
"""

from __future__ import annotations

import csv
from pathlib import Path

import mpmath
import numpy as np
import pytest
from test_track_kernel import quadrature_module_K

from moving_bogie.kernels.bound import BoundModel, bind
from moving_bogie.kernels.polyroots import stack_coefficients
from moving_bogie.kernels.track import Foundation, TrackKernel, TrackKernelArray
from moving_bogie.model.cases import table1_case
from moving_bogie.model.catalogue import get_model

REPO = Path(__file__).resolve().parent.parent


@pytest.fixture(scope="module")
def two_layer():
    """The generated module of the Euler-Bernoulli beam on the two-layer track (derivations/)."""
    return get_model("eb", "two-layer").foundation


PARAMS = table1_case(1)  # alpha = 0.5, eta_f = 0.1 (the pads), and the vehicle of Case 1
LAYER = {"mu_2": "0.8", "kappa_2": "1.5", "eta_2": "0.3"}


def test_generated_model_has_degree_6(two_layer):
    assert two_layer.DEGREE_N == 6
    assert two_layer.ARGUMENTS[-3:] == ("mu_2", "kappa_2", "eta_2")


@pytest.mark.parametrize("q", [0.3 + 0.02j, 0.9 - 0.3j, 1.4 + 0.5j, 0.05 - 0.6j])
def test_K_and_dK_against_quadrature(two_layer, q):
    bound = BoundModel(PARAMS, foundation=Foundation(two_layer, LAYER))
    args = bound.foundation_floats()
    mpmath.mp.dps = 30
    d = float(PARAMS.d)
    kv = TrackKernel(bound)(mpmath.mpc(q), [0, d, -d], derivative=True)
    arr = TrackKernelArray(bound)(np.array([q]), [0.0, d, -d], derivative=True)
    assert len(kv.roots) == 6
    for k, xi in enumerate((0.0, d, -d)):
        ref = quadrature_module_K(two_layer, args, q, xi)
        assert abs(complex(kv.K[k]) - ref) < 1e-9 * max(1, abs(ref)), (xi, kv.K[k], ref)
        assert abs(arr.K[k][0] - ref) < 1e-9 * max(1, abs(ref))
        dref = quadrature_module_K(two_layer, args, q, xi, derivative=True)
        assert abs(complex(kv.dK[k]) - dref) < 1e-8 * max(1, abs(dref)), (xi, kv.dK[k], dref)
        assert abs(arr.dK[k][0] - dref) < 1e-8 * max(1, abs(dref))


def test_p_roots_against_a_dense_scan(two_layer):
    bound = bind(PARAMS).with_foundation(Foundation(two_layer, LAYER))
    args = bound.foundation_floats()
    qs = np.array([0.3 + 0.02j, 1.7 - 0.4j, 0.05 + 2.0j])
    roots = TrackKernelArray(bound).p_roots(qs)
    coeffs = stack_coefficients(two_layer.n_coeffs(qs, **args), qs.shape)
    for j in range(qs.size):
        c = coeffs[j]
        # local minima of |N| on a grid of spacing h (in a box holding every root: Cauchy's bound)
        bound = 1 + np.max(np.abs(c[1:] / c[0]))
        h = 2 * bound / 1500
        x = np.arange(-bound, bound + h, h)
        P = x[None, :] + 1j * x[:, None]
        a = np.log(np.abs(np.polyval(c, P)))
        inner = a[1:-1, 1:-1]
        is_min = np.ones_like(inner, dtype=bool)
        for di in (-1, 0, 1):
            for dj in (-1, 0, 1):
                if di or dj:
                    is_min &= inner < a[1 + di : a.shape[0] - 1 + di, 1 + dj : a.shape[1] - 1 + dj]
        minima = P[1:-1, 1:-1][is_min]
        assert minima.size == 6
        for m in minima:
            assert np.min(np.abs(roots[j] - m)) < 1.5 * h
        with mpmath.workdps(40):
            ref = mpmath.polyroots([mpmath.mpc(complex(v)) for v in c], maxsteps=200, extraprec=200)
        for r in ref:
            assert np.min(np.abs(roots[j] - complex(r))) < 1e-12 * max(1, abs(complex(r)))


def _printed_case1():
    rows = csv.reader(
        line
        for line in open(REPO / "src/moving_bogie/data/table2_induced_frequencies.csv")
        if not line.startswith("#")
    )
    next(rows)
    return sorted(
        (complex(float(re), float(im)) for case, _, re, im in rows if case == "1"), key=lambda z: z.real
    )


# slow: two searches; the fast subset checks the degree-6 kernel itself (K and dK against quadrature, the
# p-roots against a dense scan)
@pytest.mark.slow
def test_induced_frequencies_tend_to_table2_for_a_stiff_second_layer(two_layer):
    """kappa_2 -> infinity clamps the mass layer: the model becomes the Euler-Bernoulli track of Case 1.

    The roots move by O(1/kappa_2); Richardson extrapolation from kappa_2 = 1000 and 2000 removes that term,
    leaving O(1/kappa_2^2) ~ 1e-8, far below the 6 printed decimals of Table 2 (the reference).
    """
    from moving_bogie.api import induced_frequencies

    found = {}
    for k2 in ("1000", "2000"):
        layer = dict(LAYER, kappa_2=k2)
        result = induced_frequencies(BoundModel(PARAMS, foundation=Foundation(two_layer, layer)), dps=20)
        assert result.count_ok and result.count == 4, result.warnings
        found[k2] = sorted((complex(r.q) for r in result.roots), key=lambda z: z.real)
    limit = [2 * b - a for a, b in zip(found["1000"], found["2000"])]
    printed = _printed_case1()
    assert len(printed) == 4
    for q, ref in zip(limit, printed):
        assert abs(q - ref) < 1.5e-6, (q, ref)
    # and the stiffness matters at the level of the first-order term (the test can tell the models apart)
    assert max(abs(a - b) for a, b in zip(found["1000"], printed)) > 1e-5


def test_a_sweep_hands_its_bound_model_to_every_block(two_layer):
    """The quick guard of the test below: the spec and every block's task carry the bound model itself."""
    from moving_bogie.sweep import make_spec
    from moving_bogie.sweep.engine import block_task

    bound = BoundModel(PARAMS, foundation=Foundation(two_layer, LAYER))
    spec = make_spec(bound, {"alpha": "1/2,9/10", "eta_M": "5,60"}, check=0)
    assert spec.bound == bound
    assert all(block_task(spec, block).bound == bound for block in spec.blocks())
    assert bound != bind(PARAMS)  # the comparison sees the foundation


@pytest.mark.slow
def test_a_sweep_keeps_the_foundation_of_its_bound_model(two_layer, tmp_path):
    """A sweep of a bound model on another foundation sweeps that model: each point's count equals the
    full search on ``bound.replace(...)`` of the same bound model (argument principle, roots confirmed at
    15 digits), and differs from the sweep of the one-layer track of the same parameters at three of the
    four points, so a sweep that rebinds the bare parameters fails here."""
    from moving_bogie.roots.frequencies import induced_frequencies
    from moving_bogie.sweep import make_spec, open_sweep
    from moving_bogie.sweep.engine import run_sweep

    alphas, masses = ("1/2", "9/10"), (5, 60)
    vary = {"alpha": ",".join(alphas), "eta_M": "5,60"}
    swept = {}
    for name, bound in (
        ("two", BoundModel(PARAMS, foundation=Foundation(two_layer, LAYER))),
        ("one", bind(PARAMS)),
    ):
        run_sweep(make_spec(bound, vary, check=0), tmp_path / f"{name}.zarr", processes=False)
        swept[name] = open_sweep(tmp_path / f"{name}.zarr").n_unstable.values
    two = BoundModel(PARAMS, foundation=Foundation(two_layer, LAYER))
    for i, alpha in enumerate(alphas):
        for j, eta_M in enumerate(masses):
            found = induced_frequencies(two.replace(alpha=alpha, eta_M=eta_M), dps=15)
            assert swept["two"][i, j] == len(found.unstable_roots), (alpha, eta_M)
    assert np.sum(swept["two"] != swept["one"]) == 3
