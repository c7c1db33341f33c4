"""Modal equations with the static correction of the truncated modes (mode-acceleration method).

The ``N``-mode beam of :mod:`moving_bogie.validation.modal` is too stiff at the contact points by
the residual flexibility ``R`` of the modes it leaves out (:mod:`moving_bogie.validation.residual`,
about ``4 / (3 pi k_max^3)``, 0.7 % of the contact compliance at ``k_max = 4`` on the Euler-Bernoulli
track). With the heavy wheels of Table 1 that stiffness shifts the induced frequencies and the finite beam
drifts out of phase with the infinite one over a long run. Here the truncated modes are put back as what
they are at the wheels' frequencies, an ``n x n`` quasi-static spring ``R(tau)`` between the modal beam
and the ``n`` wheels:

    w_j = a_j.q + sum_l R_jl F_l,    i.e.   F = R^{-1} (w - A^T q),

where ``w = (w_1 .. w_n)`` are the deflections under the wheels, now unknowns of their own, and ``F``
the contact forces. With the vehicle's generated matrices (:mod:`moving_bogie.validation.vehicle`) the
equations read

    M_k y_k'' + C_k y_k' + K_k y_k = (2/L) A R^{-1} (w - A^T q)    (the track's blocks; rail rows driven),
    M x'' + C x' + K x + E R^{-1} (w - A^T q) = E s,

``x`` the vehicle's degrees of freedom (wheels first), ``E`` the embedding of the ``n`` wheel rows and ``s``
the static loads. The wheel acceleration is the plain second derivative of the unknown ``w_j``: the
convective terms ``2 alpha b_j.q'`` and ``alpha^2 c_j.q`` of the uncorrected model are gone, because the
wheel no longer has to follow the modal shape ``a_j.q`` rigidly. ``M``, ``C`` and ``K`` of the whole
system are (block) diagonal plus rank ``n + (n + m)`` (the ``n`` load vectors ``(2/L) a_j`` and the
vehicle's rows), so the Newmark step of :mod:`moving_bogie.validation.newmark` is unchanged.

Constant forces (a vehicle with its matrices zeroed) need no coupling: their static correction ``R s`` is
added to the modal deflection at output.
"""

from __future__ import annotations

import numpy as np

from moving_bogie.validation.modal import ContactResponse, ModalBeam, ModalSystem
from moving_bogie.validation.newmark import DiagLowRankSystem
from moving_bogie.validation.residual import ResidualFlexibility
from moving_bogie.validation.vehicle import Vehicle

__all__ = ["CorrectedModalSystem"]


class CorrectedModalSystem(ModalSystem):
    """Eq. (49) with the residual flexibility of the truncated modes at the wheels.

    Unknowns ``z = [beam modes, the vehicle's degrees of freedom]`` (wheel deflections first); constant
    forces: ``[beam modes]``.

    Parameters
    ----------
    beam : ModalBeam
    vehicle : Vehicle
    """

    def __init__(self, beam: ModalBeam, vehicle: Vehicle) -> None:
        super().__init__(beam, vehicle)
        where = ", ".join(f"{name}={value:g}" for name, value in beam.track.values.items())
        self.residual = ResidualFlexibility(
            beam.wavenumbers, beam.length, vehicle.offsets, beam.track.symbol_polynomials(), where
        )
        if vehicle.forces_only:
            return
        n, size, nb = vehicle.contacts, vehicle.size, beam.n_dof
        self.n_dof = nb + size
        self.internal_index = nb + n if size > n else None
        m_diag, c_diag, k_diag = (
            np.concatenate([beam_diag, np.diag(matrix)])
            for beam_diag, matrix in zip(beam.diagonals, (vehicle.mass, vehicle.damping, vehicle.stiffness))
        )
        self._diag = (m_diag, c_diag, k_diag)
        self._buffers: tuple[np.ndarray, ...] | None = None

    def flexibility(self, tau: float) -> np.ndarray:
        """Residual flexibility ``R(tau)`` (``n x n``) at the contact positions at `tau`."""
        a, b, _ = self.contact_shapes(tau)
        lam = self.beam.wavenumbers
        return self.residual.matrix(self.vehicle.positions(tau), b / lam + 1j * a)

    def assemble(self, tau: float) -> DiagLowRankSystem:
        """Matrices and load of the corrected equations at `tau` (module docstring).

        The returned arrays are buffers reused by the next call (a Newmark step consumes them at
        once); copy them to keep them.
        """
        if self.vehicle.forces_only:
            return super().assemble(tau)
        if self._buffers is None:
            self._buffers = self._constant_parts()
        k_diag, ut, vmt, vct, vkt, force, k_vehicle = self._buffers
        n, N, nb = self.vehicle.contacts, self.beam.n_modes, self.beam.n_dof
        wheels = slice(nb, nb + n)
        a, _, _ = self.contact_shapes(tau)
        stiff = np.linalg.inv(self.flexibility(tau))  # R^{-1}
        stiff_a = stiff @ a
        # Modal rows: - (2/L) a_j [R^{-1} (w - A^T q)]_j on the left-hand side.
        ut[:n, :N] = (2.0 / self.beam.length) * a
        vkt[:n, :N] = stiff_a
        vkt[:n, wheels] = -stiff
        # Wheel rows: + R^{-1} (w - A^T q) besides the vehicle's own rows.
        vkt[n : 2 * n, :N] = -stiff_a
        off = stiff.copy()
        np.fill_diagonal(off, 0.0)
        vkt[n : 2 * n, wheels] = k_vehicle[:n, :n] + off
        k_diag[wheels] = np.diag(self.vehicle.stiffness)[:n] + np.diag(stiff)
        m_diag, c_diag, _ = self._diag
        return DiagLowRankSystem(m_diag, c_diag, k_diag, ut, vmt, vct, vkt, force, self.beam.blocks)

    def _constant_parts(self) -> tuple[np.ndarray, ...]:
        """Buffers of :meth:`assemble` holding every entry that does not change with time."""
        veh, nb = self.vehicle, self.beam.n_dof
        n, size = veh.contacts, veh.size
        k_diag = self._diag[2].copy()
        ut, vmt, vct, vkt = (np.zeros((n + size, self.n_dof)) for _ in range(4))
        ut[n:, nb:] = np.eye(size)
        offs = []
        for vt, matrix in ((vmt, veh.mass), (vct, veh.damping), (vkt, veh.stiffness)):
            off = matrix.copy()
            np.fill_diagonal(off, 0.0)
            vt[n:, nb:] = off
            offs.append(off)
        force = np.zeros(self.n_dof)
        force[nb : nb + n] = veh.loads
        return k_diag, ut, vmt, vct, vkt, force, offs[2]

    def response(self, tau: float, z: np.ndarray, v: np.ndarray) -> ContactResponse:
        """Every degree of freedom (unknowns of their own); constant forces: modal part plus ``R s``."""
        nb = self.beam.n_dof
        if not self.vehicle.forces_only:
            return ContactResponse(z[nb:].copy(), v[nb:].copy())
        modal = super().response(tau, z, v)
        return ContactResponse(modal.x + self.flexibility(tau) @ self.vehicle.loads, modal.dx)
