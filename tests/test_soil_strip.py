"""The equivalent stiffness chi(k1, omega) of a strip on the soil (docs/soil.md, Eq. (S5)).

References: the closed form of the homogeneous half-space's static chi, through J(x) = int_0^x K_0 written
with modified Struve functions (mpmath), J(x) = (pi x / 2) (K_0(x) L_{-1}(x) + K_1(x) L_0(x)); its
logarithmic law for k1 b -> 0 (Dieterman & Metrikine 1996), chi = pi mu / ((1 - nu) (ln(2 / (k1 b)) + 1 -
gamma)); and the defining integral with Lamb's flexibility, summed by mpmath's quadosc (an oscillatory
quadrature at 20 digits, independent of the Gauss-Kronrod panels and of the subtracted asymptotics).
"""

from __future__ import annotations

import mpmath as mp
import numpy as np
import pytest

from moving_bogie.soil.profile import soil_profile
from moving_bogie.soil.strip import NODES, WEIGHTS_G, WEIGHTS_K, strip_stiffness

B = 1.5
HALF = {"rho": 2000.0, "c_s": 100.0, "nu": 0.3}


def test_gauss_kronrod_rules_are_exact():
    for degree in range(23):  # Kronrod 15 points: exact to degree 22; Gauss 7: to degree 13
        exact = 2 / (degree + 1) if degree % 2 == 0 else 0.0
        assert abs(WEIGHTS_K @ NODES**degree - exact) < 1e-15
        if degree <= 13:
            assert abs(WEIGHTS_G @ NODES**degree - exact) < 1e-15
    assert abs(WEIGHTS_G @ NODES**14 - 2 / 15) > 1e-6


def _static_closed_form(a: float, mu: float, nu: float) -> float:
    x = mp.mpf(a * B)
    j = mp.pi * x / 2 * (mp.besselk(0, x) * mp.struvel(-1, x) + mp.besselk(1, x) * mp.struvel(0, x))
    integral = (1 - nu) / mu * 2 * j / x
    return float(2 * mp.pi / integral)


def test_static_homogeneous_closed_form_and_log_law():
    soil = soil_profile([HALF])
    mu, nu = soil.layers[0].mu, soil.layers[0].nu
    k1 = np.array([1e-3, 1e-2, 0.3, 2.0])
    chi = strip_stiffness(k1, 0.0, soil, B).chi
    ref = [_static_closed_form(a, mu, nu) for a in k1]
    assert np.allclose(chi, ref, rtol=1e-12, atol=0)
    x = k1[:2] * B
    law = np.pi * mu / ((1 - nu) * (np.log(2 / x) + 1 - np.euler_gamma))
    assert np.all(np.abs(chi[:2] / law - 1) < x**2)  # the next term of the law is O(x^2 ln x)


def _quadosc(a: float, omega: float, eta: float) -> complex:
    mp.mp.dps = 20
    mu = HALF["rho"] * HALF["c_s"] ** 2 * (1 + 1j * omega * eta)
    ks2 = HALF["rho"] * omega**2 / mu
    kp2 = ks2 * (1 - 2 * HALF["nu"]) / (2 * (1 - HALF["nu"]))

    def root(z):
        r = mp.sqrt(z)
        return -r if mp.re(r) < 0 else r

    def lamb(k):
        p, s = root(k * k - kp2), root(k * k - ks2)
        return -ks2 * p / (mu * ((2 * k * k - ks2) ** 2 - 4 * k * k * p * s))

    def f(t):
        u = lamb(mp.sqrt(a * a + t * t))
        return u if t == 0 else mp.sin(t * B) / (t * B) * u

    return complex(2 * mp.pi / (2 * mp.quadosc(f, [0, mp.inf], omega=B)))


@pytest.mark.parametrize(
    ("k1", "omega", "eta"),
    [
        (0.25, 20.0, 0.0),
        (2.0, 150.0, 2e-3),
        (0.6, 120.0 - 40.0j, 2e-3),
        pytest.param(0.6, 150.0, 2e-3, marks=pytest.mark.slow),
    ],
)
def test_dynamic_homogeneous_against_quadosc(k1, omega, eta):
    """Undamped: k1 above the Rayleigh wavenumber (0.216 at 20 rad/s); damped: a pole near the path;
    complex omega below the real axis (the soil's receptance of Eq. (S9) at a growing frequency): the
    same defining integral, Lamb's flexibility with Re p, Re s >= 0 continued to complex omega."""
    soil = soil_profile([HALF | {"eta": eta}])
    result = strip_stiffness(np.array([k1]), omega, soil, B)
    ref = _quadosc(k1, omega, eta)
    assert abs(result.chi[0] / ref - 1) < 1e-8
    assert result.error[0] < 1e-6 * abs(result.chi[0])


def test_equal_layers_give_the_halfspace():
    k1 = np.array([0.05, 0.4, 3.0])
    for omega, eta in ((0.0, 0.0), (60.0, 1e-3)):
        one = soil_profile([HALF | {"eta": eta}])
        stack = soil_profile(
            [HALF | {"eta": eta, "h": 2.0}, HALF | {"eta": eta, "h": 7.0}, HALF | {"eta": eta}]
        )
        assert np.allclose(
            strip_stiffness(k1, omega, stack, B).chi, strip_stiffness(k1, omega, one, B).chi, rtol=1e-9
        )


@pytest.mark.parametrize(
    ("k1", "omega", "eta"),
    [
        (2.0, 150.0, 2e-3),
        pytest.param(0.25, 20.0, 0.0, marks=pytest.mark.slow),
        pytest.param(0.6, 120.0 - 40.0j, 2e-3, marks=pytest.mark.slow),
    ],
)
def test_coarse_start_meets_its_tolerance(k1, omega, eta):
    """A chi asked to 1e-4 (the receptance's rule) starts from the coarse grid: against mpmath's quadosc
    of the defining integral, within 1e-4 and within its own stated error."""
    soil = soil_profile([HALF | {"eta": eta}])
    result = strip_stiffness(np.array([k1]), omega, soil, B, rtol=1e-4)
    actual = abs(result.chi[0] / _quadosc(k1, omega, eta) - 1)
    assert actual < 1e-4
    assert actual * abs(result.chi[0]) <= result.error[0]
