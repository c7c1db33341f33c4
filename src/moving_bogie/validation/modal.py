"""Modal equations of any vehicle crossing a finite rail on any track, Eqs. (49)-(54).

Dimensionless, fixed coordinate ``x`` (``x = chi x_phys``, ``tau = t sqrt(k_f/m)``, Eqs. (15)-(17)): a
simply supported rail of length ``L`` on its track, expanded in ``N`` modes ``sin(lambda_k x)``,
``lambda_k = k pi / L`` (and the same modes of the track's other unknowns). The Galerkin projection
divided by ``2 L`` gives per mode

    M_k y_k'' + C_k y_k' + K_k y_k = (2/L) sum_j F_j a_jk e_0,

with ``y_k`` the amplitudes of mode ``k`` of every unknown of the track (rail deflection first) and
``M_k, C_k, K_k`` the track model's generated per-mode blocks (:mod:`~moving_bogie.validation.track_modes`;
on the one-layer Euler-Bernoulli track the scalars ``1``, ``2 eta_f`` and ``1 + eta_s lambda_k^2 +
lambda_k^4 / 4`` of Eq. (1)). The wheels are at ``x_j = x0 + alpha tau + xi_j`` and push on the rail with

    F_j = s_j - (M x'' + C x' + K x)_j,    (M x'' + C x' + K x)_i = 0 for the internal rows,

``M, C, K`` the vehicle's generated matrices (:mod:`~moving_bogie.validation.vehicle`; the paper's bogie,
Eqs. (2)-(4) and (19)-(20), is one of them). With ``a_j = sin(lambda x_j)``, ``b_j = lambda cos(lambda
x_j)``, ``c_j = -lambda^2 a_j`` the mode shapes and their x-derivatives at the contacts, and the wheels
following the rail (``d/dtau = d_tau + alpha d_x`` along a contact, Eqs. (5)-(6)),

    w_j = a_j.q,   w_j' = a_j.q' + alpha b_j.q,   w_j'' = a_j.q'' + 2 alpha b_j.q' + alpha^2 c_j.q,

so ``F_j`` is linear in the modes and the internal degrees of freedom. This is Eq. (49) with the paper's
extra variables ``Q_j`` of Eqs. (50)-(51) eliminated (``Q_j,tt`` *is* the contact force ``F_j``). Every one
of the system's ``M``, ``C``, ``K`` is a (block) diagonal plus rank ``r = n + m`` (``n`` wheels, ``m``
internal degrees of freedom): everything else enters the modal rows through the ``n`` load vectors
``a_j`` and the vehicle through its own ``m`` rows (``r = 4`` for the bogie, ``2`` for two masses, ``0``
for constant forces). :mod:`moving_bogie.validation.newmark` steps such a system in ``O(N)``.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from moving_bogie.validation.newmark import DiagLowRankSystem, ModeBlocks
from moving_bogie.validation.track_modes import ModalTrack
from moving_bogie.validation.vehicle import Vehicle

__all__ = ["ContactResponse", "ModalBeam", "ModalSystem"]


@dataclass(frozen=True)
class ModalBeam:
    """Simply supported rail on its track, in ``n_modes`` sine modes of every unknown.

    Attributes
    ----------
    length : float
        Dimensionless length ``L`` (``chi`` times the physical length).
    n_modes : int
        Number of modes ``N``; the highest wavenumber is ``k_max = N pi / L``.
    track : ModalTrack
        The generated per-mode blocks of the track model (:mod:`~moving_bogie.validation.track_modes`):
        the rail's modes, coupled within each mode number with the same modes of its other unknowns (the
        rotation of a Timoshenko-Rayleigh beam, the deflection of each mass layer).
    """

    length: float
    n_modes: int
    track: ModalTrack

    @cached_property
    def wavenumbers(self) -> np.ndarray:
        """``lambda_k = k pi / L``, ``k = 1..N``."""
        return np.arange(1, self.n_modes + 1) * (np.pi / self.length)

    @property
    def per_mode(self) -> int:
        """Unknowns per mode number: the track's block size (1 for the Euler-Bernoulli rail alone)."""
        return self.track.size

    @property
    def n_dof(self) -> int:
        """Beam unknowns: ``q_1..q_N`` (rail deflection) first, then each further unknown's ``N`` modes."""
        return self.per_mode * self.n_modes

    @cached_property
    def track_blocks(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The track's ``M, C, K`` per mode, shape ``(N, s, s)``."""
        return self.track.blocks(self.wavenumbers)

    @cached_property
    def diagonals(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Diagonals of the beam block of ``M``, ``C``, ``K`` (rows divided by ``L/2``), unknown by unknown.

        Unknown ``j`` of mode ``k`` sits at ``j N + k``. On the one-layer Euler-Bernoulli track they are
        ``1``, ``2 eta_f`` and ``omega_k^2 = 1 + eta_s lambda_k^2 + lambda_k^4 / 4``.
        """
        m, c, k = (np.diagonal(b, axis1=1, axis2=2).T.reshape(-1).copy() for b in self.track_blocks)
        return m, c, k

    @cached_property
    def blocks(self) -> ModeBlocks | None:
        """Couplings within each mode (the track blocks' off-diagonal entries); None for one unknown."""
        n, s = self.n_modes, self.per_mode
        if s == 1:
            return None
        index = np.arange(n)[:, None] + n * np.arange(s)[None, :]
        off = []
        for b in self.track_blocks:
            b = b.copy()
            b[:, np.arange(s), np.arange(s)] = 0.0
            off.append(b)
        return ModeBlocks(index, off[0], off[1], off[2])

    @property
    def k_max(self) -> float:
        """Highest modelled wavenumber ``N pi / L``."""
        return self.n_modes * np.pi / self.length


@dataclass(frozen=True)
class ContactResponse:
    """The vehicle's degrees of freedom and their total time derivatives at one time (``Vehicle.dofs``)."""

    x: np.ndarray
    dx: np.ndarray

    @property
    def w(self) -> np.ndarray:
        """Every degree of freedom (the wheel deflections first)."""
        return self.x


class ModalSystem:
    """Assembles Eq. (49) as ``diag + U V^T`` at any time and reads the vehicle's response.

    Unknowns ``z = [beam modes, the vehicle's internal degrees of freedom]``: the wheels follow the modal
    shape rigidly (``w_j = a_j.q``), so their deflections are not unknowns of their own.

    Parameters
    ----------
    beam : ModalBeam
    vehicle : Vehicle
    """

    def __init__(self, beam: ModalBeam, vehicle: Vehicle) -> None:
        self.beam = beam
        self.vehicle = vehicle
        n, size = vehicle.contacts, vehicle.size
        nb = beam.n_dof
        self.n_dof = nb + size - n
        #: Index of the first internal degree of freedom in the unknowns (None without any).
        self.internal_index = nb if size > n else None
        internal = slice(n, size)
        m_diag, c_diag, k_diag = (np.concatenate([x, np.zeros(size - n)]) for x in beam.diagonals)
        m_diag[nb:] = np.diag(vehicle.mass)[internal]
        c_diag[nb:] = np.diag(vehicle.damping)[internal]
        k_diag[nb:] = np.diag(vehicle.stiffness)[internal]
        self._diag = (m_diag, c_diag, k_diag)
        lam_offsets = np.outer(vehicle.offsets, beam.wavenumbers)
        self._cos_off, self._sin_off = np.cos(lam_offsets), np.sin(lam_offsets)
        #: The last :meth:`contact_shapes`: its `tau` and its shapes (None before the first call).
        self._cached_shapes: tuple[float, tuple[np.ndarray, np.ndarray, np.ndarray]] | None = None

    def contact_shapes(self, tau: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(a, b, c)``, each of shape ``(n, N)``: mode shapes and x-derivatives at the contacts.

        Every contact's values follow from the rear contact's by the addition theorem (the offsets are
        fixed), which saves transcendental evaluations; the last call is cached because
        :meth:`assemble` and :meth:`response` need the same values at each step.
        """
        if self._cached_shapes is not None and self._cached_shapes[0] == tau:
            return self._cached_shapes[1]
        lam = self.beam.wavenumbers
        x1 = self.vehicle.entry + self.vehicle.alpha * tau
        sin1, cos1 = np.sin(lam * x1), np.cos(lam * x1)
        a = sin1 * self._cos_off + cos1 * self._sin_off
        cos_ = cos1 * self._cos_off - sin1 * self._sin_off
        shapes = (a, lam * cos_, -(lam * lam) * a)
        self._cached_shapes = (tau, shapes)
        return shapes

    def assemble(self, tau: float) -> DiagLowRankSystem:
        """Matrices and load of Eq. (49) at time `tau` (modal rows divided by ``L/2``).

        Returns
        -------
        DiagLowRankSystem
            Left factor ``U = [(2/L) a_1 .. (2/L) a_n, e_(internal)]``; right factors: the vehicle's rows
            ``(M x'' + C x' + K x)_i`` with ``w_j = a_j.q``, ``w_j' = a_j.q' + alpha b_j.q``,
            ``w_j'' = a_j.q'' + 2 alpha b_j.q' + alpha^2 c_j.q`` (constant forces: none).
        """
        beam, veh = self.beam, self.vehicle
        n, N, nb, L = veh.contacts, beam.n_modes, beam.n_dof, beam.length
        a, b, c = self.contact_shapes(tau)
        force = np.zeros(self.n_dof)
        force[:N] = (2.0 / L) * (veh.loads @ a)
        m_diag, c_diag, k_diag = self._diag
        r = 0 if veh.forces_only else veh.size
        ut, vmt, vct, vkt = (np.zeros((r, self.n_dof)) for _ in range(4))
        if r:
            al = veh.alpha
            mw, cw, kw = veh.mass[:, :n], veh.damping[:, :n], veh.stiffness[:, :n]
            ut[:n, :N] = (2.0 / L) * a
            ut[n:, nb:] = np.eye(r - n)
            vmt[:, :N] = mw @ a
            vct[:, :N] = (2.0 * al) * (mw @ b) + cw @ a
            vkt[:, :N] = (al * al) * (mw @ c) + al * (cw @ b) + kw @ a
            for vt, matrix in ((vmt, veh.mass), (vct, veh.damping), (vkt, veh.stiffness)):
                vt[:, nb:] = matrix[:, n:]
                vt[np.arange(n, r), nb + np.arange(r - n)] = 0.0  # internal diagonals are in the diagonal
        return DiagLowRankSystem(m_diag, c_diag, k_diag, ut, vmt, vct, vkt, force, beam.blocks)

    def response(self, tau: float, z: np.ndarray, v: np.ndarray) -> ContactResponse:
        """Every degree of freedom: ``w_j = a_j.q``, ``w_j' = a_j.q' + alpha b_j.q``, then the internal."""
        N, nb = self.beam.n_modes, self.beam.n_dof
        a, b, _ = self.contact_shapes(tau)
        w = a @ z[:N]
        dw = a @ v[:N] + self.vehicle.alpha * (b @ z[:N])
        return ContactResponse(np.concatenate([w, z[nb:]]), np.concatenate([dw, v[nb:]]))
