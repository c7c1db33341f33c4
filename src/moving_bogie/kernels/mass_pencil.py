"""The Hill matrix of a vehicle on sleepers as a pencil in its wheel mass (docs/sleepers.md, Eq. (S19)).

The vehicle's dynamic stiffness D(q) = -q^2 M + i q C + K is affine in the wheel mass group eta_M (it enters
M only), and the receptance H does not depend on the vehicle, so the Hill matrix of Eq. (S13) is

    A(q) + eta_M B(q),   A = the Hill matrix at eta_M = 0,   B = its derivative in eta_M,

both from one receptance. At eta_M = 0 a rigid contact is massless and A = I (no root); a wheel on a
Hertz spring leaves det A = prod_n (k_H + i q_n c_H), zero only in the upper half-plane. On the real q axis
the values of eta_M that make the matrix singular are the generalised eigenvalues of the pencil; they are
taken here as mu = 1 / eta_M, the eigenvalues of -A^{-1} B, which stay finite where B is singular (a
harmonic q_n = 0 carries no inertia: eta_M = infinity there).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from types import ModuleType

import numpy as np

from moving_bogie.errors import ParameterError
from moving_bogie.kernels.coupling import coupled_system, dynamic_stiffness, harmonic_blocks
from moving_bogie.kernels.hill import HillArithmetic, VehicleMatrices, harmonic_set
from moving_bogie.kernels.periodic_receptance import receptance
from moving_bogie.kernels.sleeper_track import SleeperTrack

__all__ = ["MassPencil", "mass_pencil"]


@dataclass(frozen=True)
class MassPencil:
    """A(q) + eta_M B(q) for ``vehicle`` (at eta_M = 0 and at eta_M = 1) on ``track`` with harmonics -N-1..N.

    ``tol`` is the relative tolerance of the receptance; ``evaluations`` counts the receptances computed.
    """

    track: SleeperTrack
    base: VehicleMatrices
    unit: VehicleMatrices
    N: int
    tol: float = 1e-9
    evaluations: list[int] = field(default_factory=lambda: [0], compare=False)

    def but(self, *, N: int | None = None, tol: float | None = None) -> MassPencil:
        """The same pencil with harmonics -N-1..N or receptance tolerance ``tol`` (the count shared)."""
        N = self.N if N is None else N
        return MassPencil(
            self.track, self.base, self.unit, N, self.tol if tol is None else tol, self.evaluations
        )

    def matrices(self, q: complex) -> tuple[np.ndarray, np.ndarray]:
        """(A, B) at q (Eq. (S19)): the Hill matrices of the massless and of the unit wheel, subtracted."""
        h = harmonic_set(self.N)
        rec = receptance(self.track, q, h, self.base.positions, tol=self.tol)
        self.evaluations[0] += 1
        out = []
        for vehicle in (self.base, self.unit):
            D, _ = dynamic_stiffness(q + h * self.track.Omega0, vehicle.dynamic, HillArithmetic)
            blocks = harmonic_blocks(list(D), vehicle.contacts, HillArithmetic)
            out.append(coupled_system(blocks, rec.matrix / 2, HillArithmetic).A)
        return out[0], out[1] - out[0]

    def inverse_masses(self, q: complex) -> np.ndarray:
        """mu = 1 / eta_M for every eta_M that makes the Hill matrix singular at q: eig(-A^{-1} B)."""
        A, B = self.matrices(q)
        return np.linalg.eigvals(-np.linalg.solve(A, B))


def mass_pencil(
    track: SleeperTrack, module: ModuleType, values: dict, N: int, *, tol: float = 1e-9
) -> MassPencil:
    """The pencil of a generated vehicle ``module`` with group ``values``; its wheel mass must enter M only,
    linearly (checked: the matrices at eta_M = 0, 1, 2), else a ParameterError naming the vehicle."""
    name = getattr(module, "WHEEL_MASS", None)
    if name is None or name not in values:
        raise ParameterError("vehicle", f"vehicle {module.__name__.rsplit('_', 1)[-1]!r} has no wheel mass")
    at = [VehicleMatrices.from_module(module, values | {name: float(x)}) for x in (0, 1, 2)]
    for label, (m0, m1, m2) in (
        ("damping", [v.damping for v in at]),
        ("stiffness", [v.stiffness for v in at]),
    ):
        if not (np.array_equal(m0, m1) and np.array_equal(m1, m2)):
            raise ParameterError("vehicle", f"the wheel mass {name} enters the vehicle's {label} matrix")
    m0, m1, m2 = (v.mass for v in at)
    if not np.allclose(m2 - 2 * m1 + m0, 0, atol=1e-14):
        raise ParameterError("vehicle", f"the vehicle's mass matrix is not affine in {name}")
    if not np.array_equal(at[0].positions, at[1].positions):
        raise ParameterError("vehicle", f"the contact positions depend on the wheel mass {name}")
    return MassPencil(track, at[0], at[1], N, tol)
