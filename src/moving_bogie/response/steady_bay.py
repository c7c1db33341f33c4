"""The steady periodic response under the constant loads on a rail on supports (docs/sleepers.md).

A vehicle moving at constant speed over the supports, pressed on the rail by its static wheel loads s_j, ends
in a response periodic in the bay passage: the contact forces and the rail deflection under each wheel carry
the harmonics n Omega_0 of the sleeper-passing frequency only (the Floquet formulation at Omega = 0,
Eqs. (S16)-(S18)). With the harmonics n = -N..N (a set symmetric under n -> -n, which keeps the
response real), the contact displacements U_n and the internal DOFs Y_n solve the Hill system of Eq. (S13)
with the static loads on its right-hand side,

    [[I + H D_cc, H D_ci], [D_ic, D_ii]] [U; Y] = [H s e_0; 0],

H the receptance between (contact, harmonic) pairs at Omega = 0 and D_v(n Omega_0) the vehicle's dynamic
stiffness. The contact forces are F_n = s delta_n0 - (D_cc U + D_ci Y)_n, and at time tau, when the rear
wheel is at ``offset + alpha tau`` from a support, ``U(tau) = sum_n U_n e^{i n Omega_0 tau}``.
N doubles until the time series change by less than ``tol`` of their largest value: the contact force
has a kink where a wheel passes a support (the rail's shear jumps there), so F_n falls like n^-2 only
while U_n falls like n^-4.
"""

from __future__ import annotations

from dataclasses import dataclass
from types import ModuleType

import numpy as np

from moving_bogie.kernels.hill import FloquetSystem, VehicleMatrices
from moving_bogie.kernels.sleeper_track import SleeperTrack

__all__ = ["SteadyResponse", "static_loads", "steady_harmonics", "steady_response"]

#: relative tolerance of the receptance (docs/sleepers.md (S11)); its error is far below the truncation's
RECEPTANCE_TOL = 1e-7


def static_loads(module: ModuleType, values: dict) -> np.ndarray:
    """The vehicle's constant wheel loads s_j (2 per load P, the paper's Eq. (16) scaling), as floats."""
    args = {name: values[name] for name in module.MATRIX_ARGUMENTS}
    return np.array([float(x) for x in module.static_loads(**args)])


class _SymmetricSystem(FloquetSystem):
    """The Hill matrix with the harmonics -N..N (the steady response at Omega = 0 is real)."""

    @property
    def harmonics(self) -> np.ndarray:
        return np.arange(-self.N, self.N + 1)


@dataclass(frozen=True)
class SteadyResponse:
    """The steady periodic response over one bay (dimensionless, the scaling of docs/sleepers.md (S2)).

    Attributes
    ----------
    position : ndarray
        The rear wheel's distance from the support behind it, ``offset + alpha tau`` over one bay.
    tau : ndarray
        The times of ``position`` (0 to one bay-passing period 2 pi / Omega_0).
    contact_force : ndarray, shape (contacts, P)
        The force of each wheel on the rail (the static load 2 per P, Eq. (16)).
    deflection : ndarray, shape (contacts, P)
        The rail deflection under each wheel (units of w_st).
    harmonics : ndarray
        The harmonics n = -N..N kept.
    force_harmonics, deflection_harmonics : ndarray, shape (2 N + 1, contacts)
        The complex amplitudes F_n, U_n of e^{i n Omega_0 tau}.
    change : float
        The largest change of the time series between the last two N, relative to their largest value.
    converged : bool
        Whether ``change`` fell below the tolerance.
    """

    position: np.ndarray
    tau: np.ndarray
    contact_force: np.ndarray
    deflection: np.ndarray
    harmonics: np.ndarray
    force_harmonics: np.ndarray
    deflection_harmonics: np.ndarray
    change: float
    converged: bool


def steady_harmonics(
    track: SleeperTrack, vehicle: VehicleMatrices, loads: np.ndarray, N: int, offset: float = 0.0
) -> tuple[np.ndarray, np.ndarray]:
    """(F_n, U_n), shape (2 N + 1, contacts) each: the harmonic balance of Eq. (S17) with n = -N..N."""
    system = _SymmetricSystem(track, vehicle, N, offset=offset, tol=RECEPTANCE_TOL)
    A, rec = system.matrix(0.0)
    h, nc, nd = system.harmonics, vehicle.contacts, vehicle.mass.shape[0]
    R = h.size * nc
    static = np.zeros(R, dtype=complex)
    i0 = int(np.flatnonzero(h == 0)[0])
    static[i0 * nc : (i0 + 1) * nc] = loads
    rhs = np.zeros(A.shape[0], dtype=complex)
    rhs[:R] = rec.matrix @ static
    x = np.linalg.solve(A, rhs)
    U = x[:R].reshape(h.size, nc)
    Y = x[R:].reshape(h.size, nd - nc)
    F = static.reshape(h.size, nc).copy()
    for i, n in enumerate(h):
        D = -((n * track.Omega0) ** 2) * vehicle.mass + 1j * n * track.Omega0 * vehicle.damping
        D = D + vehicle.stiffness
        F[i] -= D[:nc, :nc] @ U[i] + D[:nc, nc:] @ Y[i]
    return F, U


def _series(amplitudes: np.ndarray, harmonics: np.ndarray, Omega0: float, tau: np.ndarray) -> np.ndarray:
    """sum_n a_n e^{i n Omega_0 tau} (real part), shape (contacts, P)."""
    phase = np.exp(1j * Omega0 * np.outer(tau, harmonics))
    return np.real(phase @ amplitudes).T


def steady_response(
    track: SleeperTrack,
    vehicle: VehicleMatrices,
    loads: np.ndarray,
    *,
    offset: float = 0.0,
    points: int = 65,
    N0: int = 4,
    N_max: int = 32,
    tol: float = 1e-3,
) -> SteadyResponse:
    """The steady contact forces and rail deflections under the wheels over one bay (Eqs. (S16)-(S18)).

    Parameters
    ----------
    track, vehicle : SleeperTrack, VehicleMatrices
        The rail on its supports (``alpha > 0``) and the vehicle.
    loads : ndarray
        The static wheel loads s_j (:func:`static_loads`).
    offset : float
        The rear wheel's distance from a support at tau = 0.
    points : int
        Points over the bay (both ends included).
    N0, N_max : int
        The first and the largest N of the harmonics -N..N; N doubles from N0 until the series converge.
    tol : float
        Largest change of the time series between N - 1 and N, relative to their largest value.
    """
    if track.Omega0 <= 0:
        raise ValueError("alpha: the steady response over a bay needs a moving vehicle (v > 0)")
    tau = np.linspace(0.0, 2 * np.pi / track.Omega0, points)
    loads = np.asarray(loads, dtype=float)
    previous = None
    change = np.inf
    N = N0
    while N <= N_max:
        F, U = steady_harmonics(track, vehicle, loads, N, offset)
        h = np.arange(-N, N + 1)
        force, deflection = (_series(a, h, track.Omega0, tau) for a in (F, U))
        if previous is not None:
            scale = max(np.max(np.abs(force)), np.max(np.abs(deflection)))
            change = float(
                max(np.max(np.abs(force - previous[0])), np.max(np.abs(deflection - previous[1]))) / scale
            )
            if change < tol:
                break
        previous = (force, deflection)
        N *= 2
    return SteadyResponse(
        position=offset + track.alpha * tau,
        tau=tau,
        contact_force=force,
        deflection=deflection,
        harmonics=h,
        force_harmonics=F,
        deflection_harmonics=U,
        change=change,
        converged=change < tol,
    )
