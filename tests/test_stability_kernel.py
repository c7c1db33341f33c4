"""The vectorised E_chr of the stability sweeps against the reference kernels; its polynomial structure."""

import numpy as np
import pytest

from moving_bogie.kernels.bound import bind
from moving_bogie.kernels.characteristic import CharacteristicArray
from moving_bogie.kernels.sweep_characteristic import (
    SweepCharacteristic,
    poly_roots,
    polynomial_degree,
    quartic_roots,
)
from moving_bogie.kernels.track import TrackKernelArray
from moving_bogie.model.cases import table1_case

Q = np.array([0.3, 0.1, 0.7 + 0.01j, 0.2 - 0.3j, 1.3 - 0.02j])


def _params(beam):
    p = table1_case(1)
    return p if beam == "eb" else p.replace(beam="tr", S=10, r="0.09")


def test_quartic_roots_match_companion_eigenvalues():
    rng = np.random.default_rng(3)
    c = rng.normal(size=(2000, 5)) + 1j * rng.normal(size=(2000, 5))
    ours = quartic_roots(c)
    for k in range(0, 2000, 97):
        ref = np.roots(c[k])
        assert np.max(np.min(np.abs(ours[k][:, None] - ref[None, :]), axis=1)) < 1e-11 * max(
            1, np.abs(ref).max()
        )


def test_one_quartic_at_a_time_matches_companion_eigenvalues_and_the_batch():
    """Small batches (continuation steps) take the scalar path of quartic_roots; numpy's eigenvalues are
    the reference, and the batched path (the same formulas on arrays) agrees to rounding."""
    rng = np.random.default_rng(4)
    c = rng.normal(size=(300, 5)) + 1j * rng.normal(size=(300, 5))
    batched = quartic_roots(c)
    for k in range(300):
        one = quartic_roots(c[k : k + 1])[0]
        ref = np.roots(c[k])
        scale = max(1, np.abs(ref).max())
        assert np.max(np.min(np.abs(one[:, None] - ref[None, :]), axis=1)) < 1e-11 * scale
        assert np.max(np.min(np.abs(one[:, None] - batched[k][None, :]), axis=1)) < 1e-14 * scale


@pytest.mark.parametrize("beam", ["eb", "tr"])
@pytest.mark.parametrize("model", ["bogie", "masses"])
def test_sweep_equals_reference_characteristic(beam, model):
    p = _params(beam)
    sweep = SweepCharacteristic(bind(p.replace(vehicle=model)))
    # The sweep evaluates the closed form of Eq. (38); CharacteristicArray the block determinant, which is
    # -1/2 times it for the bogie and equal for two masses (proved in tests/test_vehicles.py).
    ref = {"bogie": -2, "masses": 1}[model] * CharacteristicArray(bind(p.replace(vehicle=model)))(Q)
    assert np.all(np.abs(sweep(Q, float(p.alpha)) - ref) <= 1e-12 * np.abs(ref))
    K, dK, _ = sweep.kernel(Q, float(p.alpha), derivative=True)
    kv = TrackKernelArray(bind(p))(Q, [0, float(p.d), -float(p.d)], derivative=True)
    for a, b in zip(K + dK, kv.K + kv.dK):
        assert np.all(np.abs(a - b) <= 1e-11 * np.maximum(1, np.abs(b)))


@pytest.mark.parametrize("beam", ["eb", "tr"])
def test_derivatives_match_finite_differences(beam):
    p = _params(beam)
    sweep = SweepCharacteristic(bind(p))
    a = np.full(Q.shape, 0.8)
    th = np.array([20.0, 50.0, 3.0, 7.0, 120.0])
    E, E_q, E_a, E_t = sweep.derivatives(Q, a, th)
    h = 1e-6
    for exact, plus, minus in (
        (E_q, sweep(Q + h, a, th), sweep(Q - h, a, th)),
        (E_a, sweep(Q, a + h, th), sweep(Q, a - h, th)),
        (E_t, sweep(Q, a, th + h), sweep(Q, a, th - h)),
    ):
        assert np.all(np.abs((plus - minus) / (2 * h) - exact) <= 1e-7 * np.abs(exact))


@pytest.mark.parametrize(
    ("model", "parameter"),
    [("bogie", "eta_M"), ("masses", "eta_M"), ("bogie", "kappa_v"), ("bogie", "eta_v")],
)
def test_e_chr_is_a_polynomial_of_the_stated_degree(model, parameter):
    """Interpolation at deg + 1 nodes reproduces E_chr everywhere; a higher-degree fit finds nothing more."""
    p = table1_case(1)
    sweep = SweepCharacteristic(bind(p.replace(vehicle=model)), parameter)
    deg = polynomial_degree(bind(p.replace(vehicle=model)), parameter)
    K, _, _ = sweep.kernel(Q, 0.8)
    scale = 200.0 if parameter == "eta_M" else 2.0
    c = sweep.coefficients(Q, K, scale=scale)
    assert c.shape[-1] == deg + 1
    for theta in (0.37 * scale, 0.91 * scale, 0.05 * scale):
        direct = sweep.e_chr(Q, K, theta)
        interp = np.array([np.polyval(c[k], theta / scale) for k in range(len(Q))])
        assert np.all(np.abs(interp - direct) <= 1e-9 * np.abs(direct))
    nodes = np.linspace(0, scale, 12)
    values = np.array([sweep.e_chr(Q, K, t) for t in nodes])
    fit = np.polyfit(nodes / scale, values, deg + 3)
    assert np.all(np.abs(fit[:3]) <= 1e-7 * np.abs(fit).max(axis=0))


def test_poly_roots_handles_degrees_and_vanishing_leading_coefficient():
    c = np.array([[1, -3, 2], [0, 1, -1]], dtype=complex)
    r = poly_roots(c)
    assert sorted(r[0].real) == pytest.approx([1, 2])
    # the degree drops: the root of the lower-degree polynomial, and one at infinity (nan)
    assert r[1][0] == pytest.approx(1) and np.isnan(r[1][1])
    assert np.all(np.isnan(poly_roots(np.array([[np.nan, 1, 1]], dtype=complex))))
    # degree 6 whose leading coefficient vanishes on one row (a layered track at alpha = 0); reference:
    # numpy.roots of the degree-5 polynomial
    c6 = np.array([[0, 2, -1, 3j, 0.5, -2, 1], [1, 2, -1, 3j, 0.5, -2, 1]], dtype=complex)
    r6 = poly_roots(c6)
    assert np.isnan(r6[0][-1]) and np.all(np.isfinite(r6[1]))
    assert np.sort_complex(r6[0][:-1]) == pytest.approx(np.sort_complex(np.roots(c6[0][1:])), abs=1e-12)
    assert np.sort_complex(r6[1]) == pytest.approx(np.sort_complex(np.roots(c6[1])), abs=1e-12)
    c4 = np.array([[1, -10, 35, -50, 24]], dtype=complex)
    assert sorted(poly_roots(c4)[0].real) == pytest.approx([1, 2, 3, 4])
