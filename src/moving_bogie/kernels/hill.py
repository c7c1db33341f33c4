"""The Floquet characteristic function of a vehicle on a rail on supports: the truncated Hill determinant.

With the harmonics q_n = q + n Omega_0, n = -N-1, ..., N (a set that the symmetry q -> Omega_0 - conj(q)
maps onto itself), the contact displacements U and the vehicle's internal DOFs Y of every harmonic solve
(docs/sleepers.md, Eq. (S13))

    [[I + H D_cc, H D_ci], [D_ic, D_ii]] [U; Y] = 0,

H the receptance between (contact, harmonic) pairs (:mod:`moving_bogie.kernels.periodic_receptance`) and D the
vehicle's dynamic stiffness -q_n^2 M + i q_n C + K at each harmonic, block diagonal over the harmonics.
The characteristic function is the determinant; its zeros are the induced frequencies.

D and the block system are the one vehicle-rail coupling of :mod:`moving_bogie.kernels.coupling`
(``dynamic_stiffness`` at every harmonic, ``harmonic_blocks``, ``coupled_system``) with the rail's receptance
G = H / 2 in an arithmetic whose pi is 1: its A = [[pi I + 2 G D_cc, 2 G D_ci], [D_ic, D_ii]] is then the
system above, the coupling's A with its contact rows divided by pi (the determinant divided by pi^P, P the
number of (contact, harmonic) pairs; the factor 1/2 and the division are exact in floating point).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from types import ModuleType
from typing import TYPE_CHECKING

import numpy as np

from moving_bogie.kernels.arithmetic import Batched
from moving_bogie.kernels.coupling import (
    Dynamic,
    coupled_system,
    dynamic_coefficients,
    dynamic_stiffness,
    harmonic_blocks,
)
from moving_bogie.kernels.free_wave_poles import Sheet
from moving_bogie.kernels.periodic_receptance import Receptance, receptance
from moving_bogie.kernels.sleeper_track import SleeperTrack

if TYPE_CHECKING:
    from moving_bogie.kernels.bound import BoundModel

__all__ = ["FloquetSystem", "VehicleMatrices", "harmonic_set"]


class HillArithmetic(Batched):
    """numpy's batched arithmetic of the coupling with pi = 1: the contact rows of the coupling's system
    divided by pi, so that with G = H / 2 they read I + H D_cc (docs/sleepers.md, Eq. (S13))."""

    pi = 1.0


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

    @classmethod
    def of(cls, bound: BoundModel) -> VehicleMatrices:
        """The vehicle of a bound model (its generated module, its groups as floats)."""
        return cls.from_module(bound.vehicle, bound.vehicle_values(bound.floats))

    @cached_property
    def dynamic(self) -> Dynamic:
        """D(q) = -q^2 M + i q C + K as the coupling's matrix polynomial (Eq. (21), d/dtau -> i q)."""
        return dynamic_coefficients((self.mass, self.damping, self.stiffness), HillArithmetic)


def harmonic_set(N: int) -> np.ndarray:
    """The harmonics -N-1, ..., N (2 N + 2 of them), symmetric under n -> -n - 1."""
    return np.arange(-N - 1, N + 1)


@dataclass
class FloquetSystem:
    """The characteristic function of ``vehicle`` on ``track`` with harmonics -N-1..N.

    ``offset`` is the rear wheel's position at tau = 0 relative to a support (dimensionless; the
    determinant does not depend on it). ``tol`` is the relative tolerance of the receptance. ``sheet``,
    when given, continues the receptance across the rail's free waves' singular lines
    (:func:`~moving_bogie.kernels.periodic_receptance.receptance`).
    """

    track: SleeperTrack
    vehicle: VehicleMatrices
    N: int
    offset: float = 0.0
    tol: float = 1e-8
    evaluations: int = 0
    sheet: Sheet | None = None

    @property
    def harmonics(self) -> np.ndarray:
        return harmonic_set(self.N)

    def matrix(self, q: complex) -> tuple[np.ndarray, Receptance]:
        """The Hill block matrix at q and the receptance it was built from."""
        v = self.vehicle
        h = self.harmonics
        rec = receptance(self.track, q, h, v.positions + self.offset, tol=self.tol, continued_from=self.sheet)
        D, _ = dynamic_stiffness(q + h * self.track.Omega0, v.dynamic, HillArithmetic)
        blocks = harmonic_blocks(list(D), v.contacts, HillArithmetic)
        return coupled_system(blocks, rec.matrix / 2, HillArithmetic).A, rec

    def __call__(self, q: complex | np.ndarray) -> np.ndarray:
        """det of the Hill matrix at each q (an array); the function the argument principle counts."""
        qs = np.atleast_1d(np.asarray(q, dtype=complex))
        out = np.empty(qs.shape, dtype=complex)
        for idx, qq in np.ndenumerate(qs):
            out[idx] = np.linalg.det(self.matrix(complex(qq))[0])
        self.evaluations += qs.size
        return out.reshape(np.shape(q)) if np.ndim(q) else out[0]
