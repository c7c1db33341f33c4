"""A finite rail on discrete supports in beam finite elements (docs/sleepers.md, Eqs. (S23)-(S24)).

The check of the Floquet theory by a model that does not use it: a rail of ``bays`` bays, pinned at its ends,
on a support at every interior multiple of the bay ``lam``, in the dimensionless variables of docs/sleepers.md
(S2) (the rail's mass per length 1, its bending stiffness 1/4, lengths in units of 1 / chi, times in units of
1 / omega_e). Each bay is cut into ``elements`` Euler-Bernoulli elements with quintic Hermite shape functions
(nodal unknowns: deflection, slope and curvature, so that the curvature under a moving wheel, which its
acceleration contains, is continuous when it crosses a node); the continuous foundation ``kappa_f``, ``2
eta_f`` takes the element's consistent mass matrix as its shape
(:meth:`~moving_bogie.kernels.sleeper_track.SleeperTrack.rail_foundation`). A support is the finite element of
its track (:meth:`~moving_bogie.kernels.sleeper_track.SleeperTrack.support_element`), whose dynamic stiffness
at the rail is ``lam z(w)``: a spring-dashpot to the ground on ``sleepers``; on ``sleepers-two-layer`` a
railpad over a sleeper of mass ``lam mu_sl`` on the ballast, the sleeper an unknown of its own.

An absorbing layer of ``absorbing`` bays at each end adds a foundation damping ``ABSORBING_DAMPING s^2``
(mass-proportional, ``s`` the depth into the layer, 0 to 1): the waves the vehicle radiates along the rail
(its start, and its passage over the supports even in the steady state) die there instead of returning from
the pinned ends to the wheels, as they do not return on the infinite rail of the Floquet theory.

The matrices are sparse (scipy.sparse), assembled once; :mod:`moving_bogie.validation.sleepers_beam` adds
the moving vehicle.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import scipy.sparse as sp

from moving_bogie.errors import MovingBogieError
from moving_bogie.kernels.sleeper_track import SleeperTrack

__all__ = ["ABSORBING", "MARGIN", "SleeperBeamSettings", "SleeperRail", "hermite_shapes", "rail_for_run"]


#: unknowns per node: the deflection and its first two x-derivatives (quintic Hermite elements, C2)
PER_NODE = 3
#: Gauss-Legendre nodes and weights on [0, 1] (exact for the degree-10 products of two quintics)
_GAUSS = tuple(np.polynomial.legendre.leggauss(8))
_GX, _GW = (_GAUSS[0] + 1) / 2, _GAUSS[1] / 2

#: the foundation damping added at the outer end of an absorbing layer (units of omega_e, as 2 eta_f): the
#: quadratic ramp to it over the layer reflects little, and a wave crossing a layer of L / chi at the group
#: velocity c_g and back loses the factor e^{-2 L / (3 c_g)} (e^{-4} and less for the rail's waves up to 3
#: omega_e, c_g <= 2.4, across the 15 / chi of the check's layers), besides the rest of the rail's damping
ABSORBING_DAMPING = 2.0


def _quintic_basis() -> np.ndarray:
    """Coefficients (lowest power first) of the six quintics on [0, 1] that take unit value, slope or
    curvature at one end and zero for every other of the six end conditions."""
    rows = []
    for xi in (0.0, 1.0):
        for d in range(3):
            row = np.zeros(6)
            for k in range(d, 6):
                row[k] = np.prod(np.arange(k - d + 1, k + 1)) * xi ** (k - d)
            rows.append(row)
    return np.linalg.inv(np.array(rows))  # column i: the basis function of condition i


_BASIS = _quintic_basis()
#: the basis and its first two derivatives, coefficients of the powers xi^0..xi^5 (rows)
_DERIVATIVES = tuple(
    np.vstack([np.polynomial.polynomial.polyder(_BASIS, d, axis=0), np.zeros((d, 6))]) for d in range(3)
)


def hermite_shapes(xi: float | np.ndarray, h: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The six quintic Hermite shape functions of an element of length ``h`` and their first two
    x-derivatives at the local coordinate ``xi`` in [0, 1] (unknowns: w, w', w'' at both ends)."""
    powers = np.asarray(xi, dtype=float)[..., None] ** np.arange(6)
    scale = np.array([1, h, h * h, 1, h, h * h])
    n, d1, d2 = (powers @ c * scale for c in _DERIVATIVES)
    return n, d1 / h, d2 / (h * h)


def _element_matrices(h: float) -> tuple[np.ndarray, np.ndarray]:
    """Consistent mass (unit mass per length) and bending stiffness (EI = 1/4) of one element (S23)."""
    n, _, d2 = hermite_shapes(_GX, h)  # (points, 6)
    mass = h * np.einsum("p,pi,pj->ij", _GW, n, n)
    stiffness = 0.25 * h * np.einsum("p,pi,pj->ij", _GW, d2, d2)
    return mass, stiffness


@dataclass(frozen=True)
class SleeperRail:
    """The rail of ``bays`` bays on its supports in ``elements`` Hermite elements per bay.

    Unknowns: the deflection and slope of every node but the deflections of the two pinned ends
    (``rail_dofs`` of them), then one per sleeper on ``sleepers-two-layer``. ``absorbing``: the bays of the
    absorbing layer at each end (module doc), inside the ``bays``.
    """

    track: SleeperTrack
    bays: int
    elements: int
    absorbing: int = 0

    def __post_init__(self) -> None:
        try:
            self.track.rail_foundation()
        except ValueError as exc:
            raise MovingBogieError(f"the finite rail on supports: {exc}") from None
        if self.bays < 4 + 2 * self.absorbing or self.elements < 1 or self.absorbing < 0:
            raise MovingBogieError(
                "the finite rail needs at least 4 bays between its absorbing layers and 1 element per bay "
                f"(got {self})"
            )

    @property
    def lam(self) -> float:
        return self.track.lam

    @property
    def length(self) -> float:
        """Rail length ``bays lam``."""
        return self.bays * self.lam

    @property
    def h(self) -> float:
        """Element length ``lam / elements``."""
        return self.lam / self.elements

    @property
    def nodes(self) -> int:
        return self.bays * self.elements + 1

    @cached_property
    def _index(self) -> np.ndarray:
        """Full node unknown (2 i + {0, 1}) -> kept unknown, -1 for the pinned ends' deflections."""
        full = np.arange(PER_NODE * self.nodes)
        keep = np.ones(full.size, bool)
        keep[[0, PER_NODE * (self.nodes - 1)]] = False
        index = -np.ones(full.size, int)
        index[keep] = np.arange(int(keep.sum()))
        return index

    @property
    def rail_dofs(self) -> int:
        return PER_NODE * self.nodes - 2

    @property
    def per_support(self) -> int:
        """Unknowns of one support besides the rail's deflection (the sleeper of a two-layer support)."""
        return self.track.support_element()[0].shape[0] - 1

    @property
    def sleepers(self) -> int:
        """Unknowns of the supports: ``per_support`` at each interior support."""
        return (self.bays - 1) * self.per_support

    @property
    def size(self) -> int:
        return self.rail_dofs + self.sleepers

    def support_nodes(self) -> np.ndarray:
        """Nodes on a support: every ``elements``-th, the pinned ends excluded."""
        return np.arange(1, self.bays) * self.elements

    def absorbing_damping(self) -> np.ndarray:
        """The foundation damping added in each element: ``ABSORBING_DAMPING s^2`` at the depth ``s`` of its
        middle into an absorbing layer (0 outside the layers)."""
        middles = (np.arange(self.nodes - 1) + 0.5) / self.elements  # in bays
        if self.absorbing == 0:
            return np.zeros(middles.size)
        depth = np.maximum(self.absorbing - middles, middles - (self.bays - self.absorbing)) / self.absorbing
        return ABSORBING_DAMPING * np.clip(depth, 0.0, None) ** 2

    @cached_property
    def matrices(self) -> tuple[sp.csc_matrix, sp.csc_matrix, sp.csc_matrix]:
        """Sparse M, C, K of the rail on its supports (Eqs. (S23)-(S24)), the absorbing layers' damping in
        C."""
        k_f, c_f = self.track.rail_foundation()
        me, ke = _element_matrices(self.h)
        kfe = ke + k_f * me
        added = self.absorbing_damping()
        rows, cols, m_val, c_val, k_val = [], [], [], [], []
        for e in range(self.nodes - 1):
            ce = (c_f + added[e]) * me
            dofs = self._index[PER_NODE * e : PER_NODE * e + 2 * PER_NODE]
            ok = dofs >= 0
            r, c = np.meshgrid(dofs[ok], dofs[ok], indexing="ij")
            sub = np.ix_(ok, ok)
            rows.append(r.ravel())
            cols.append(c.ravel())
            m_val.append(me[sub].ravel())
            c_val.append(ce[sub].ravel())
            k_val.append(kfe[sub].ravel())
        extra = self._support_entries()
        rows_a = np.concatenate(rows + [extra[0]])
        cols_a = np.concatenate(cols + [extra[1]])
        n = self.size
        out = []
        for values, added in zip((m_val, c_val, k_val), extra[2:]):
            data = np.concatenate(values + [added])
            out.append(sp.csc_matrix((data, (rows_a, cols_a)), shape=(n, n)))
        return out[0], out[1], out[2]

    def _support_entries(self) -> tuple[np.ndarray, ...]:
        """(rows, cols, mass, damping, stiffness) entries of the supports' elements (S24)."""
        element = self.track.support_element()
        size = element[0].shape[0]
        rail = self._index[PER_NODE * self.support_nodes()]
        own = self.rail_dofs + np.arange(rail.size * (size - 1)).reshape(rail.size, size - 1)
        dofs = np.column_stack([rail, own])  # (supports, size)
        rows = np.repeat(dofs, size, axis=1).ravel()
        cols = np.tile(dofs, (1, size)).ravel()
        values = [np.tile(matrix.ravel(), rail.size) for matrix in element]
        return rows, cols, values[0], values[1], values[2]

    def contact_shapes(self, x: float) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """(unknowns, N, N', N'') at the rail position ``x``: w(x) = N . z[unknowns] and its x-derivatives.

        The pinned ends' deflections are dropped (they are zero).
        """
        if not 0 <= x <= self.length:
            raise MovingBogieError(f"a wheel left the finite rail (x = {x:g}, length {self.length:g})")
        e = min(int(x / self.h), self.nodes - 2)
        shapes = hermite_shapes(x / self.h - e, self.h)
        dofs = self._index[PER_NODE * e : PER_NODE * e + 2 * PER_NODE]
        ok = dofs >= 0
        return dofs[ok], shapes[0][ok], shapes[1][ok], shapes[2][ok]


#: the rail beyond the wheels' path at each end, in units of 1 / chi (the static deflection decays like
#: e^{-x} cos x: below 1e-4 of its peak there)
MARGIN = 10.0

#: the absorbing layer beyond the margin at each end, in units of 1 / chi (sleepers_rail.ABSORBING_DAMPING):
#: the waves the wheels radiate along the rail die in it rather than return from the ends to the wheels
ABSORBING = 15.0


@dataclass(frozen=True)
class SleeperBeamSettings:
    """The finite model's resolution: Hermite elements per bay, time steps per bay-passing period, the
    periods of the free run, the fraction of them left out of the fit as the transient, the rail beyond
    the wheels' path at each end and the absorbing layer beyond it (units of 1 / chi; 0: pinned ends
    that reflect)."""

    elements: int = 8
    steps_per_period: int = 200
    periods: int = 40
    transient: float = 0.4
    margin: float = MARGIN
    absorbing: float = ABSORBING


def rail_for_run(
    track: SleeperTrack,
    positions: np.ndarray,
    travel: float,
    elements: int,
    margin: float,
    absorbing: float,
) -> tuple[SleeperRail, float]:
    """The rail for a run over ``travel`` (in units of 1 / chi) of wheels at ``positions`` (their offsets from
    the rear wheel), and the rear wheel's start on it: the wheels' path (the travel and the vehicle's
    length) between two ``margin`` long, each with an ``absorbing`` layer beyond (units of 1 / chi), in
    ``elements`` Hermite elements per bay."""
    margin_bays = math.ceil(margin / track.lam)
    layer = math.ceil(absorbing / track.lam)
    offsets = np.asarray(positions, float)
    span = float(np.ptp(offsets)) if offsets.size else 0.0
    bays = math.ceil((travel + span) / track.lam) + 1
    rail = SleeperRail(track, 2 * (margin_bays + layer) + bays, elements, layer)
    return rail, (margin_bays + layer) * track.lam - float(np.min(offsets, initial=0.0))
