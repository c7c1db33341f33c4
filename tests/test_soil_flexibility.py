"""The layered half-space's surface flexibility U(k, omega) and its soil profile (docs/soil.md).

References: Boussinesq's static solution, U = (1 - nu) / (mu k) in the wavenumber domain; Lamb's (1904)
closed form for the homogeneous half-space under exp(i (omega t - k x)), U = -k_s^2 p / (mu R) with
R = (2 k^2 - k_s^2)^2 - 4 k^2 p s, evaluated here from its own formula; a stack of equal layers is the
homogeneous half-space.
"""

from __future__ import annotations

import numpy as np
import pytest

from moving_bogie.errors import ParameterError
from moving_bogie.soil.flexibility import surface_flexibility
from moving_bogie.soil.profile import soil_profile

HALF = {"rho": 2000.0, "c_s": 100.0, "nu": 0.3}


def lamb(k, omega, c_s, nu, rho, eta=0.0):
    """Lamb's vertical surface flexibility of a homogeneous half-space (Kelvin-Voigt moduli)."""
    mu = rho * c_s**2 * (1 + 1j * omega * eta)
    ks2 = rho * omega**2 / mu
    kp2 = ks2 * (1 - 2 * nu) / (2 * (1 - nu))
    k = np.asarray(k, dtype=complex)
    p, s = np.sqrt(k**2 - kp2), np.sqrt(k**2 - ks2)
    p, s = np.where(p.real < 0, -p, p), np.where(s.real < 0, -s, s)
    return -ks2 * p / (mu * ((2 * k**2 - ks2) ** 2 - 4 * k**2 * p * s))


def test_static_boussinesq():
    soil = soil_profile([HALF])
    k = np.geomspace(1e-3, 1e3, 13)
    mu = HALF["rho"] * HALF["c_s"] ** 2
    assert np.allclose(surface_flexibility(k, 0.0, soil), (1 - HALF["nu"]) / (mu * k), rtol=1e-13, atol=0)


@pytest.mark.parametrize("eta", [0.0, 2e-3])
def test_homogeneous_lamb(eta):
    soil = soil_profile([HALF | {"eta": eta}])
    omega = 40.0
    # evanescent (k > k_s), between k_p and k_s (one wave radiating) and below k_p (both radiating)
    k = np.array([0.05, 0.2, 0.3, 0.5, 2.0, 30.0])
    ref = lamb(k, omega, HALF["c_s"], HALF["nu"], HALF["rho"], eta)
    assert np.allclose(surface_flexibility(k, omega, soil), ref, rtol=1e-11, atol=0)


def test_equal_layers_are_the_halfspace():
    soil = soil_profile([HALF])
    stack = soil_profile([HALF | {"h": 3.0}, HALF | {"h": 0.01}, HALF | {"h": 40.0}, HALF])
    for omega in (0.0, 1e-9, 5.0, 300.0, 3000.0):  # static, quasi-static, and k h up to ~1e3
        k = np.array([0.07, 0.8, 4.0, 60.0])
        assert np.allclose(
            surface_flexibility(k, omega, stack), surface_flexibility(k, omega, soil), rtol=1e-9
        )


def test_quasi_static_limit_is_continuous():
    """The regular basis: no loss of digits as omega / (c k) -> 0 (a potential basis loses them all)."""
    soil = soil_profile([HALF | {"h": 2.0, "c_s": 60.0}, HALF])
    k = np.geomspace(1e-2, 1e4, 7)
    static = surface_flexibility(k, 0.0, soil)
    for omega in (1e-6, 1e-4):
        # the first correction is O((omega / (c_s k))^2)
        bound = 10 * (omega / (60.0 * k)) ** 2 + 1e-13
        assert np.all(np.abs(surface_flexibility(k, omega, soil) / static - 1) < bound)


def test_layer_on_stiffer_halfspace_static_limits():
    """k h >> 1: the top layer alone; k h << 1: the half-space below (static, Boussinesq both)."""
    top, below = HALF | {"h": 1.0, "c_s": 50.0}, HALF | {"c_s": 200.0}
    soil = soil_profile([top, below])
    mu_top, mu_below = HALF["rho"] * 50.0**2, HALF["rho"] * 200.0**2
    u_top = surface_flexibility(np.array([50.0]), 0.0, soil)[0] * mu_top * 50.0 / (1 - HALF["nu"])
    u_deep = surface_flexibility(np.array([1e-5]), 0.0, soil)[0] * mu_below * 1e-5 / (1 - HALF["nu"])
    assert abs(u_top - 1) < 1e-12  # layer terms ~ e^{-2 k h}
    assert abs(u_deep - 1) < 1e-3  # the layer adds O(k h)


@pytest.mark.parametrize(
    ("tables", "key", "where"),
    [
        ([{"rho": 1800, "c_s": 80, "c_p": 300}, HALF], "h", "soil[1]"),
        ([HALF | {"h": 2}, HALF | {"h": 3}], "h", "soil[2]"),
        ([HALF | {"h": 2, "rho": -1}, HALF], "rho", "soil[1]"),
        ([HALF | {"h": 2}, HALF | {"nu": 0.5}], "nu", "soil[2]"),
        ([HALF | {"h": 2, "c_p": 400}, HALF], "nu", "soil[1]"),
        ([{"h": 2, "rho": 1800, "E": 1e7, "c_s": 80}, HALF], "c_s", "soil[1]"),
        ([HALF | {"h": 2, "eta": -1e-3}, HALF], "eta", "soil[1]"),
        ([HALF | {"h": 2, "rh": 1}, HALF], "rh", "soil[1]"),
        ([{"rho": 1800, "c_s": 80, "c_p": 90}], "c_p", "soil[1]"),
        ([{"rho": 1800, "E": 1e7}], "nu", "soil[1]"),
    ],
)
def test_profile_errors_name_layer_and_key(tables, key, where):
    with pytest.raises(ParameterError) as info:
        soil_profile(tables)
    assert info.value.parameter == key
    assert where in str(info.value)
