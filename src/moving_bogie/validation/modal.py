"""Modal equations of a bogie (or two masses, or two forces) crossing a finite beam, Eqs. (49)-(54).

Dimensionless, fixed coordinate ``x`` (``x = chi x_phys``, ``tau = t sqrt(k_f/m)``, Eqs. (15)-(17)),
simply supported rail of length ``L`` on its track (any beam on any track of the catalogue: the
generated per-mode blocks below). For the Euler-Bernoulli beam on the viscoelastic Winkler foundation with
an optional Pasternak layer, Eq. (1) with the shear layer, divided by ``k_f w_st / 4``, reads

    w_xxxx - 4 eta_s w_xx + 4 w_tautau + 8 eta_f w_tau + 4 w = 4 F_1 delta(x - x_1) + 4 F_2 delta(x - x_2),

with the rear wheel at ``x_1 = x0 + alpha tau`` and the front wheel at ``x_2 = x_1 + d``. With
``w_j(tau) = w(x_j(tau), tau)`` followed along the contact point (``d/dtau = d_tau + alpha d_x``,
Eqs. (5)-(6)) and ``s_1 = +1``, ``s_2 = -1``, the contact forces, Eq. (2) made dimensionless, are

    F_j = 2 - eta_M w_j'' - kappa_v (w_j - u + s_j theta d/2) - 2 eta_v (w_j' - u' + s_j theta' d/2),

and the bar obeys Eqs. (3)-(4) (dimensionless: Eqs. (19)-(20), where the pitch equation carries the
factor ``d`` on its stiffness term that Eq. (14) lacks):

    mu_v u'' - kappa_v (w_1 + w_2 - 2u) - 2 eta_v (w_1' + w_2' - 2u') = 0,
    2 J_b theta'' + kappa_v (w_1 - w_2 + theta d) d + 2 eta_v (w_1' - w_2' + theta' d) d = 0.

Two masses (paper, Fig. 1a) keep only ``F_j = 2 - eta_M w_j''``; two forces keep ``F_j = 2``.

Modal expansion ``w = sum_k q_k sin(lambda_k x)``, ``lambda_k = k pi / L``: the Galerkin projection
divided by ``2 L`` gives per mode

    M_k y_k'' + C_k y_k' + K_k y_k = (2/L) sum_j F_j a_jk e_0,

with ``y_k`` the amplitudes of mode ``k`` of every unknown of the track (rail deflection first) and
``M_k, C_k, K_k`` the track model's generated per-mode blocks
(:mod:`~moving_bogie.validation.track_modes`); on the one-layer Euler-Bernoulli track they are the
scalars ``1``, ``2 eta_f`` and ``omega_k^2 = 1 + eta_s lambda_k^2 + lambda_k^4 / 4``,

with ``a_j = sin(lambda x_j)``, ``b_j = lambda cos(lambda x_j)``, ``c_j = -lambda^2 a_j`` the mode
shapes and their x-derivatives at the contact points. Because the wheels are followed,

    w_j = a_j.q,   w_j' = a_j.q' + alpha b_j.q,   w_j'' = a_j.q'' + 2 alpha b_j.q' + alpha^2 c_j.q,

so ``F_j`` is linear in ``(q'', q', q, u, u', theta, theta')``. This is Eq. (49) with the paper's extra
variables ``Q_j`` of Eqs. (50)-(51) eliminated (``Q_j,tt`` *is* the contact force ``F_j``): the paper's
mass matrix (52) ``[[I, -A], [eta_M A^T, I]]`` over ``(q, Q)`` becomes ``I + (2 eta_M / L) A A^T``
over ``q`` alone. Every one of ``M``, ``C``, ``K`` is a diagonal plus rank ``r``: all terms that are
not diagonal enter the modal rows through the two load vectors ``a_1, a_2`` (the wheel forces act
only there) and the bar through its own two rows, so ``r = 4`` for the bogie, ``2`` for two masses
and ``0`` for two forces. :mod:`moving_bogie.validation.newmark` steps such a system in ``O(N)``.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from moving_bogie.validation.newmark import DiagLowRankSystem, ModeBlocks
from moving_bogie.validation.track_modes import ModalTrack

__all__ = ["MODELS", "ContactResponse", "ModalBeam", "ModalSystem", "Vehicle"]

#: Vehicle models: the bogie (Fig. 1b), two moving masses (Fig. 1a), two constant moving forces.
MODELS = ("bogie", "masses", "force")


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
        return tuple(np.diagonal(b, axis1=1, axis2=2).T.reshape(-1).copy() for b in self.track_blocks)

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
        return ModeBlocks(index, *off)

    @property
    def k_max(self) -> float:
        """Highest modelled wavenumber ``N pi / L``."""
        return self.n_modes * np.pi / self.length


@dataclass(frozen=True)
class Vehicle:
    """Dimensionless vehicle of Eqs. (2)-(4) (floats) and its entry point.

    Attributes
    ----------
    model : {"bogie", "masses", "force"}
    eta_M, d, mu_v, J_b, kappa_v, eta_v, alpha : float
        Eqs. (16)-(17); ``mu_v``, ``J_b``, ``kappa_v``, ``eta_v`` only matter for the bogie and
        ``eta_M`` not for the forces.
    entry : float
        Rear-wheel position ``x0`` at ``tau = 0``.
    """

    model: str
    eta_M: float
    d: float
    mu_v: float
    J_b: float
    kappa_v: float
    eta_v: float
    alpha: float
    entry: float

    @property
    def n_extra(self) -> int:
        """Degrees of freedom besides the modes: ``(u, theta)`` for the bogie, none otherwise."""
        return 2 if self.model == "bogie" else 0

    def positions(self, tau: float) -> tuple[float, float]:
        """Rear and front wheel positions ``x0 + alpha tau`` and ``x0 + alpha tau + d``."""
        x1 = self.entry + self.alpha * tau
        return x1, x1 + self.d


@dataclass(frozen=True)
class ContactResponse:
    """Wheel-followed deflections and their total time derivatives at one time."""

    w: tuple[float, float]
    dw: tuple[float, float]


class ModalSystem:
    """Assembles Eq. (49) as ``diag + U V^T`` at any time and reads the contact response.

    Parameters
    ----------
    beam : ModalBeam
    vehicle : Vehicle
    """

    def __init__(self, beam: ModalBeam, vehicle: Vehicle) -> None:
        if vehicle.model not in MODELS:
            raise ValueError(f"model must be one of {MODELS} (got {vehicle.model!r})")
        self.beam = beam
        self.vehicle = vehicle
        nb, ne = beam.n_dof, vehicle.n_extra
        self.n_dof = nb + ne
        #: Index of the bar bounce ``u`` in the unknowns (``theta`` follows), None without a bar.
        self.bar_index = nb if ne else None
        # The diagonals do not depend on time: beam rows, then the bar's bounce and pitch rows.
        m_diag, c_diag, k_diag = (np.concatenate([x, np.zeros(ne)]) for x in beam.diagonals)
        if ne:
            v, d = vehicle, vehicle.d
            m_diag[nb:] = (v.mu_v, 2.0 * v.J_b)
            c_diag[nb:] = (4.0 * v.eta_v, 2.0 * v.eta_v * d * d)
            k_diag[nb:] = (2.0 * v.kappa_v, v.kappa_v * d * d)
        self._diag = (m_diag, c_diag, k_diag)
        lam_d = beam.wavenumbers * vehicle.d
        self._cos_d, self._sin_d = np.cos(lam_d), np.sin(lam_d)
        self._cache_tau: float | None = None
        self._cache_shapes: tuple[np.ndarray, np.ndarray, np.ndarray] = ()

    def contact_shapes(self, tau: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(a, b, c)``, each of shape ``(2, N)``: mode shapes and x-derivatives at both wheels.

        The front wheel's values follow from the rear wheel's by the addition theorem (the spacing
        ``d`` is fixed), which halves the transcendental evaluations; the last call is cached
        because :meth:`assemble` and :meth:`contact` need the same values at each step.
        """
        if self._cache_tau == tau:
            return self._cache_shapes
        lam = self.beam.wavenumbers
        x1 = self.vehicle.positions(tau)[0]
        a, cos_ = np.empty((2, lam.size)), np.empty((2, lam.size))
        np.sin(lam * x1, out=a[0])
        np.cos(lam * x1, out=cos_[0])
        a[1] = a[0] * self._cos_d + cos_[0] * self._sin_d
        cos_[1] = cos_[0] * self._cos_d - a[0] * self._sin_d
        shapes = (a, lam * cos_, -(lam * lam) * a)
        self._cache_tau, self._cache_shapes = tau, shapes
        return shapes

    def assemble(self, tau: float) -> DiagLowRankSystem:
        """Matrices and load of Eq. (49) at time `tau` (modal rows divided by ``L/2``).

        Returns
        -------
        DiagLowRankSystem
            Left factor ``U = [(2/L) a_1, (2/L) a_2, e_u, e_theta]`` (bogie; the first two columns
            for masses, none for forces) and right factors from the expressions of ``F_j`` and the
            bar equations in the module docstring.
        """
        beam, veh = self.beam, self.vehicle
        n, nb, ne, L = beam.n_modes, beam.n_dof, veh.n_extra, beam.length
        a, b, c = self.contact_shapes(tau)
        force = np.zeros(self.n_dof)
        # Both static wheel loads are 2 (eta_p = 1), projected with weight 2/L.
        force[:n] = (4.0 / L) * (a[0] + a[1])
        m_diag, c_diag, k_diag = self._diag
        r = 0 if veh.model == "force" else 2 + ne
        ut, vmt, vct, vkt = (np.zeros((r, self.n_dof)) for _ in range(4))
        if r:
            al, em = veh.alpha, veh.eta_M
            ut[:2, :n] = (2.0 / L) * a
            # eta_M w_j'' = eta_M (a_j.q'' + 2 alpha b_j.q' + alpha^2 c_j.q)
            vmt[:2, :n] = em * a
            vct[:2, :n] = (2.0 * em * al) * b
            vkt[:2, :n] = (em * al * al) * c
        if ne:
            kv, ev, d = veh.kappa_v, veh.eta_v, veh.d
            sign_half = (0.5 * d, -0.5 * d)
            # kappa_v (w_j - u + s_j theta d/2) + 2 eta_v (w_j' - u' + s_j theta' d/2), s = (+1, -1)
            vct[:2, :n] += (2.0 * ev) * a
            vkt[:2, :n] += kv * a + (2.0 * ev * al) * b
            for j in range(2):
                vct[j, nb:] = (-2.0 * ev, 2.0 * ev * sign_half[j])
                vkt[j, nb:] = (-kv, kv * sign_half[j])
            ut[2, nb], ut[3, nb + 1] = 1.0, 1.0
            a_sum, a_dif = a[0] + a[1], a[0] - a[1]
            b_sum, b_dif = b[0] + b[1], b[0] - b[1]
            # Bounce row: - kappa_v (w_1 + w_2) - 2 eta_v (w_1' + w_2') besides its diagonal.
            vct[2, :n] = (-2.0 * ev) * a_sum
            vkt[2, :n] = -kv * a_sum - (2.0 * ev * al) * b_sum
            # Pitch row: kappa_v d (w_1 - w_2) + 2 eta_v d (w_1' - w_2') besides its diagonal.
            vct[3, :n] = (2.0 * ev * d) * a_dif
            vkt[3, :n] = (kv * d) * a_dif + (2.0 * ev * d * al) * b_dif
        return DiagLowRankSystem(m_diag, c_diag, k_diag, ut, vmt, vct, vkt, force, beam.blocks)

    def contact(self, tau: float, z: np.ndarray, v: np.ndarray) -> ContactResponse:
        """Deflections ``w_j = a_j.q`` under the wheels and ``w_j' = a_j.q' + alpha b_j.q``."""
        n = self.beam.n_modes
        a, b, _ = self.contact_shapes(tau)
        w = a @ z[:n]
        dw = a @ v[:n] + self.vehicle.alpha * (b @ z[:n])
        return ContactResponse((float(w[0]), float(w[1])), (float(dw[0]), float(dw[1])))
