"""The Floquet characteristic function of a vehicle on a rail on supports: the truncated Hill determinant.

With the harmonics q_n = q + n Omega_0, n = -N-1, ..., N (a set that the symmetry q -> Omega_0 - conj(q)
maps onto itself), the contact displacements U and the vehicle's internal DOFs Y of every harmonic solve
(docs/sleepers.md, Eq. (S13))

    [[I + H D_cc, H D_ci], [D_ic, D_ii]] [U; Y] = 0,

H the receptance between (contact, harmonic) pairs (:mod:`moving_bogie.floquet.receptance`) and D the
vehicle's dynamic stiffness -q_n^2 M + i q_n C + K at each harmonic, block diagonal over the harmonics.
The characteristic function is the determinant; its zeros are the induced frequencies.
"""

from __future__ import annotations

from dataclasses import dataclass
from types import ModuleType

import numpy as np

from moving_bogie.floquet.receptance import Receptance, receptance
from moving_bogie.floquet.track import SleeperTrack

__all__ = ["FloquetSystem", "VehicleMatrices", "dynamic_stiffness", "harmonic_set"]


@dataclass(frozen=True)
class VehicleMatrices:
    """A vehicle's dimensionless M, C, K (contacts first), its contact count and positions xi_j."""

    mass: np.ndarray
    damping: np.ndarray
    stiffness: np.ndarray
    contacts: int
    positions: np.ndarray

    @classmethod
    def from_module(cls, module: ModuleType, values: dict) -> VehicleMatrices:
        """From a generated vehicle module and its group values (floats)."""
        args = {name: values[name] for name in module.MATRIX_ARGUMENTS}
        mass, damping, stiffness = (
            np.array(f(**args), dtype=complex)
            for f in (module.mass_matrix, module.damping_matrix, module.stiffness_matrix)
        )
        positions = np.array([float(x) for x in module.contact_positions(**args)])
        return cls(mass, damping, stiffness, int(module.CONTACTS), positions)


def dynamic_stiffness(vehicle: VehicleMatrices, q: complex) -> np.ndarray:
    """D(q) = -q^2 M + i q C + K: the vehicle's force at its DOFs per unit displacement (e^{i q tau}).

    The one place where the vehicle meets the rail; the rail receives -D_c. x at its contacts.
    """
    return -(q**2) * vehicle.mass + 1j * q * vehicle.damping + vehicle.stiffness


def harmonic_set(N: int) -> np.ndarray:
    """The harmonics -N-1, ..., N (2 N + 2 of them), symmetric under n -> -n - 1."""
    return np.arange(-N - 1, N + 1)


@dataclass
class FloquetSystem:
    """The characteristic function of ``vehicle`` on ``track`` with harmonics -N-1..N.

    ``offset`` is the rear wheel's position at tau = 0 relative to a support (dimensionless; the
    determinant does not depend on it). ``tol`` is the relative tolerance of the receptance.
    """

    track: SleeperTrack
    vehicle: VehicleMatrices
    N: int
    offset: float = 0.0
    tol: float = 1e-8
    evaluations: int = 0

    @property
    def harmonics(self) -> np.ndarray:
        return harmonic_set(self.N)

    def matrix(self, q: complex) -> tuple[np.ndarray, Receptance]:
        """The Hill block matrix at q and the receptance it was built from."""
        v = self.vehicle
        h = self.harmonics
        nc, nd = v.contacts, v.mass.shape[0]
        ni = nd - nc
        rec = receptance(self.track, q, h, v.positions + self.offset, tol=self.tol)
        R = h.size * nc
        A = np.zeros((h.size * nd, h.size * nd), dtype=complex)
        Dcc = np.zeros((R, R), dtype=complex)
        Dci = np.zeros((R, h.size * ni), dtype=complex)
        for i, n in enumerate(h):
            D = dynamic_stiffness(v, q + n * self.track.Omega0)
            c, k = slice(i * nc, (i + 1) * nc), slice(i * ni, (i + 1) * ni)
            Dcc[c, c] = D[:nc, :nc]
            Dci[c, k] = D[:nc, nc:]
            A[R + i * ni : R + (i + 1) * ni, c] = D[nc:, :nc]
            A[R + i * ni : R + (i + 1) * ni, R + i * ni : R + (i + 1) * ni] = D[nc:, nc:]
        A[:R, :R] = np.eye(R) + rec.matrix @ Dcc
        A[:R, R:] = rec.matrix @ Dci
        return A, rec

    def __call__(self, q: complex | np.ndarray) -> np.ndarray:
        """det of the Hill matrix at each q (an array); the function the argument principle counts."""
        qs = np.atleast_1d(np.asarray(q, dtype=complex))
        out = np.empty(qs.shape, dtype=complex)
        for idx, qq in np.ndenumerate(qs):
            out[idx] = np.linalg.det(self.matrix(complex(qq))[0])
        self.evaluations += qs.size
        return out.reshape(np.shape(q)) if np.ndim(q) else out[0]
