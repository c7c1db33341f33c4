"""Modal equations with the static correction of the truncated modes (mode-acceleration method).

The ``N``-mode beam of :mod:`moving_bogie.validation.modal` is too stiff at the contact points by
the residual flexibility ``R`` of the modes it leaves out (:mod:`moving_bogie.validation.residual`,
about ``4 / (3 pi k_max^3)``, 0.7 % of the contact compliance at ``k_max = 4``). With the heavy
wheels of Table 1 that stiffness shifts the induced frequencies and the finite beam drifts out of
phase with the infinite one over a long run. Here the truncated modes are put back as what they are
at the wheels' frequencies, a 2x2 quasi-static spring ``R(tau)`` between the modal beam and the
wheels:

    w_j = a_j.q + sum_l R_jl F_l,    i.e.   F = R^{-1} (w - A^T q),

where ``w = (w_1, w_2)`` are the deflections under the wheels, now unknowns of their own, and
``F`` the contact forces. With the vehicle of Eqs. (2)-(4) the equations read

    M q'' + C q' + K q = (2/L) A R^{-1} (w - A^T q)    (the track's blocks; rail rows driven),
    eta_M w_j'' + kappa_v (w_j - u + s_j theta d/2) + 2 eta_v (w_j' - u' + s_j theta' d/2)
        + [R^{-1} (w - A^T q)]_j = 2,

plus the bar rows of Eqs. (3)-(4) with the same ``w_j``. The wheel acceleration is the plain second
derivative of the unknown ``w_j``: the convective terms ``2 alpha b_j.q'`` and ``alpha^2 c_j.q`` of
the uncorrected model are gone, because the wheel no longer has to follow the modal shape ``a_j.q``
rigidly. ``M`` is diagonal; ``C`` and ``K`` are diagonal plus rank ``2 + n_w`` (the two load vectors
``(2/L) a_j`` and the ``n_w`` wheel and bar rows: 4 for two masses, 6 for the bogie), so the
Newmark step of :mod:`moving_bogie.validation.newmark` is unchanged.

Two constant forces (no wheel mass) need no coupling: their static correction ``R (2, 2)`` is added
to the modal deflection at output.
"""

from __future__ import annotations

import numpy as np

from moving_bogie.validation.modal import ContactResponse, ModalBeam, ModalSystem, Vehicle
from moving_bogie.validation.newmark import DiagLowRankSystem
from moving_bogie.validation.residual import ResidualFlexibility

__all__ = ["CorrectedModalSystem"]


class CorrectedModalSystem(ModalSystem):
    """Eq. (49) with the residual flexibility of the truncated modes at the wheels.

    Unknowns ``z = [q_1..q_N, w_1, w_2, u, theta]`` (bogie), ``[q, w_1, w_2]`` (two masses) or
    ``[q]`` (two forces).

    Parameters
    ----------
    beam : ModalBeam
    vehicle : Vehicle
    """

    def __init__(self, beam: ModalBeam, vehicle: Vehicle) -> None:
        super().__init__(beam, vehicle)
        v = vehicle
        where = ", ".join(f"{name}={value:g}" for name, value in beam.track.values.items())
        self.residual = ResidualFlexibility(
            beam.wavenumbers, beam.length, v.d, beam.track.symbol_polynomials(), where
        )
        self.n_wheel = 0 if v.model == "force" else 2
        n, nw, ne = beam.n_dof, self.n_wheel, v.n_extra  # n: beam unknowns (2N for TR)
        self.n_dof = n + nw + ne
        self.bar_index = n + nw if ne else None
        m_diag, c_diag, k_diag = (np.concatenate([x, np.ones(nw + ne)]) for x in beam.diagonals)
        c_diag[n:], k_diag[n:] = 0.0, 0.0
        # Constant part of the wheel and bar block, dense (rows and columns n..n_dof-1).
        block_c, block_k = np.zeros((nw + ne, nw + ne)), np.zeros((nw + ne, nw + ne))
        if nw:
            m_diag[n : n + 2] = v.eta_M
        if ne:
            kv, ev, d = v.kappa_v, v.eta_v, v.d
            m_diag[n + 2 :] = (v.mu_v, 2.0 * v.J_b)
            # Wheel rows: kappa_v (w_j - u + s_j theta d/2) + 2 eta_v (w_j' - u' + s_j theta' d/2).
            # Bar rows: -kappa_v (w_1 + w_2 - 2u) - 2 eta_v (...)'; kappa_v d (w_1 - w_2 + theta d) + ...
            stiffness = np.array(
                [
                    [1.0, 0.0, -1.0, 0.5 * d],
                    [0.0, 1.0, -1.0, -0.5 * d],
                    [-1.0, -1.0, 2.0, 0.0],
                    [d, -d, 0.0, d * d],
                ]
            )
            block_k[:], block_c[:] = kv * stiffness, 2.0 * ev * stiffness
        self._block = (block_c, block_k)
        self._diag = (m_diag, c_diag, k_diag)
        self._buffers: tuple[np.ndarray, ...] | None = None

    def flexibility(self, tau: float) -> np.ndarray:
        """Residual flexibility ``R(tau)`` (2x2) at the wheel positions at `tau`."""
        x1, x2 = self.vehicle.positions(tau)
        a, b, _ = self.contact_shapes(tau)
        lam = self.beam.wavenumbers
        cos1, cos2 = b[0] / lam, b[1] / lam
        return self.residual.matrix(x1, x2, cos1 + 1j * a[0], cos2 + 1j * a[1])

    def assemble(self, tau: float) -> DiagLowRankSystem:
        """Matrices and load of the corrected equations at `tau` (module docstring).

        The returned arrays are buffers reused by the next call (a Newmark step consumes them at
        once); copy them to keep them.
        """
        if self.n_wheel == 0:
            return super().assemble(tau)
        if self._buffers is None:
            self._buffers = self._constant_parts()
        k_diag, ut, vmt, vct, vkt, force, k_wheels = self._buffers
        modes, n = self.beam.n_modes, self.beam.n_dof  # deflection modes; wheels start at n
        a, _, _ = self.contact_shapes(tau)
        (r11, r12), (r21, r22) = self.flexibility(tau)
        stiff = np.array([[r22, -r12], [-r21, r11]]) / (r11 * r22 - r12 * r21)  # R^{-1}
        # Modal rows: - (2/L) a_j [R^{-1} (w - A^T q)]_j on the left-hand side.
        ut[:2, :modes] = (2.0 / self.beam.length) * a
        stiff_a = stiff @ a
        vkt[:2, :modes] = stiff_a
        vkt[:2, n : n + 2] = -stiff
        # Wheel rows: R^{-1} (w - A^T q) besides the suspension (diagonal and off-diagonal parts).
        vkt[2:4, :modes] = -stiff_a
        k_diag[n : n + 2] = k_wheels + np.diag(stiff)
        vkt[2, n + 1] = self._block[1][0, 1] + stiff[0, 1]
        vkt[3, n] = self._block[1][1, 0] + stiff[1, 0]
        m_diag, c_diag, _ = self._diag
        beam = self.beam
        return DiagLowRankSystem(m_diag, c_diag, k_diag, ut, vmt, vct, vkt, force, beam.blocks)

    def _constant_parts(self) -> tuple[np.ndarray, ...]:
        """Buffers of :meth:`assemble` holding every entry that does not change with time."""
        n, nb = self.beam.n_dof, self.n_dof - self.beam.n_dof
        m_diag, c_diag, k_diag = self._diag
        block_c, block_k = self._block
        c_diag[n:] += np.diag(block_c)
        k_diag = k_diag.copy()
        k_diag[n:] += np.diag(block_k)
        ut, vmt, vct, vkt = (np.zeros((2 + nb, self.n_dof)) for _ in range(4))
        for i in range(nb):
            ut[2 + i, n + i] = 1.0
        off_c, off_k = block_c.copy(), block_k.copy()
        np.fill_diagonal(off_c, 0.0)
        np.fill_diagonal(off_k, 0.0)
        vct[2:, n:] = off_c
        vkt[2:, n:] = off_k
        force = np.zeros(self.n_dof)
        force[n : n + 2] = 2.0
        return k_diag, ut, vmt, vct, vkt, force, k_diag[n : n + 2].copy()

    def contact(self, tau: float, z: np.ndarray, v: np.ndarray) -> ContactResponse:
        """Deflections under the wheels (the unknowns ``w_j``; modal part plus ``2 R`` for forces)."""
        n = self.beam.n_dof
        if self.n_wheel:
            return ContactResponse((float(z[n]), float(z[n + 1])), (float(v[n]), float(v[n + 1])))
        modal = super().contact(tau, z, v)
        static = self.flexibility(tau) @ np.array([2.0, 2.0])
        return ContactResponse((modal.w[0] + static[0], modal.w[1] + static[1]), modal.dw)
