"""The steady periodic response under the constant loads on a rail on supports
(moving_bogie.response.steady_bay).

References: the continuous rail's steady deflection under a constant moving load, the integral
(1 / 2 pi) int 2 G_c(p, alpha p) dp by scipy's QUADPACK (no residues, no Floquet harmonics); the same
response computed with the vehicle started one distance further along the bay, which must equal the first
one a time later (docs/sleepers.md, Eq. (S18)).
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import quad

from moving_bogie.generated import vehicle_mass
from moving_bogie.kernels.hill import VehicleMatrices
from moving_bogie.kernels.sleeper_track import SleeperTrack
from moving_bogie.model.catalogue import default_catalogue
from moving_bogie.response.steady_bay import static_loads, steady_harmonics, steady_response

#: the catalogue's rails on periodic supports, (beam, track) -> their generated functions
PERIODIC = default_catalogue().periodic

ALPHA, ETA_F, ETA_SUP = 0.25, 0.05, 0.05
VALUES = {"eta_M": 2.0}


def _track(lam: float) -> SleeperTrack:
    groups = {"lam": lam, "alpha": ALPHA, "kappa_f": 0.0, "eta_f": ETA_F, "eta_sup": ETA_SUP}
    return SleeperTrack(PERIODIC["eb", "sleepers"], groups)


def _continuous_deflection() -> float:
    """The one-layer rail (k_f = k_e, c_f + c_sup / l) under the load 2 moving at alpha, by quadrature."""

    def g(p: float) -> complex:
        w = ALPHA * p
        return 2 / (p**4 / 4 - w**2 + 2j * (ETA_F + ETA_SUP) * w + 1)

    real = quad(lambda p: g(p).real, -np.inf, np.inf, epsabs=1e-13, epsrel=1e-13)[0]
    return real / (2 * np.pi)


def test_short_bays_give_the_continuous_steady_deflection_at_rate_l4():
    """l -> 0 with k_sup / l fixed: the deflection under the wheel over a bay tends to the continuous rail's,
    the largest error falling like l^4 (S - G is of order K^-4, docs/sleepers.md); the force tends to the
    static load 2."""
    vehicle = VehicleMatrices.from_module(vehicle_mass, VALUES)
    loads = static_loads(vehicle_mass, VALUES)
    ref = _continuous_deflection()
    errors, forces = [], []
    for lam in (0.4, 0.2):
        steady = steady_response(_track(lam), vehicle, loads, N0=2, points=33)
        assert steady.converged
        errors.append(np.max(np.abs(steady.deflection - ref)))
        forces.append(np.max(np.abs(steady.contact_force - 2)))
    assert abs(np.log2(errors[0] / errors[1]) - 4) < 0.7
    assert errors[1] < 1e-3 * ref
    assert forces[1] < forces[0]


def test_a_later_start_in_the_bay_is_the_same_response_later():
    """Starting the wheel a distance d further along the bay gives at tau = 0 the response of the first start
    at tau = d / alpha (Eq. (S18)); the harmonics of a real response are conjugate pairs."""
    track = _track(1.5)
    vehicle = VehicleMatrices.from_module(vehicle_mass, VALUES)
    loads = static_loads(vehicle_mass, VALUES)
    d, N = 0.4, 4
    F, U = steady_harmonics(track, vehicle, loads, N)
    F_d, U_d = steady_harmonics(track, vehicle, loads, N, offset=d)
    phase = np.exp(1j * np.arange(-N, N + 1) * track.Omega0 * d / ALPHA)
    assert abs(phase @ U[:, 0] - np.sum(U_d[:, 0])) < 1e-9
    assert abs(phase @ F[:, 0] - np.sum(F_d[:, 0])) < 1e-9
    assert np.allclose(F[::-1], np.conj(F), atol=1e-9) and np.allclose(U[::-1], np.conj(U), atol=1e-9)
