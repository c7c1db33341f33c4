"""Implicit Newmark time stepping for structural systems "diagonal + low rank".

The finite-beam validation model (paper, Section 3.2, Eqs. (49)-(54)) is a linear, time-varying
second-order system

    M(t) z'' + C(t) z' + K(t) z = f(t),

whose matrices are each a diagonal plus the same few columns ``U`` times a few rows, ``X = diag(x)
+ U Vx^T`` with ``U`` of width ``r`` (``r = 2`` for two moving masses, ``4`` for the bogie). The
implicit step needs ``S^{-1}`` of ``S = M + gamma h C + beta h^2 K``, again diagonal + rank ``r``,
so the Sherman-Morrison-Woodbury identity solves it in ``O(n r + r^3)`` operations instead of the
``O(n^3)`` of a dense factorization.

References
----------
N. M. Newmark, "A method of computation for structural dynamics", Journal of the Engineering
Mechanics Division (ASCE) 85(EM3), 67-94 (1959): the scheme; ``beta = 1/4, gamma = 1/2`` (average
acceleration, trapezoidal rule) is unconditionally stable for linear time-invariant systems,
second-order accurate and free of numerical damping.

W. W. Hager, "Updating the inverse of a matrix", SIAM Review 31(2), 221-239 (1989): the
Sherman-Morrison-Woodbury identity used by :func:`woodbury_solve`.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

__all__ = [
    "AVERAGE_ACCELERATION",
    "ModeBlocks",
    "DiagLowRankSystem",
    "NewmarkScheme",
    "NewmarkState",
    "effective_matrix_dense",
    "initial_state",
    "newmark_step",
    "woodbury_solve",
]


@dataclass(frozen=True)
class NewmarkScheme:
    """Newmark parameters ``beta`` and ``gamma`` (Newmark 1959).

    Attributes
    ----------
    beta, gamma : float
        ``z_{n+1} = z_n + h v_n + h^2 ((1/2 - beta) a_n + beta a_{n+1})`` and
        ``v_{n+1} = v_n + h ((1 - gamma) a_n + gamma a_{n+1})``.
    """

    beta: float = 0.25
    gamma: float = 0.5


#: Average acceleration (trapezoidal rule): unconditionally stable, second order, no numerical damping.
AVERAGE_ACCELERATION = NewmarkScheme(beta=0.25, gamma=0.5)


@dataclass(frozen=True)
class ModeBlocks:
    """Couplings within small groups of unknowns: the off-diagonal entries of block-diagonal matrices.

    A mode of a Timoshenko-Rayleigh beam (deflection and rotation) or of a rail on mass layers (rail and
    layer deflections) couples its unknowns with each other only, so the part of ``M``, ``C``, ``K`` that is
    not diagonal (besides the low-rank vehicle coupling) is block diagonal with one small block per mode.

    Attributes
    ----------
    index : ndarray of int, shape (n_blocks, s)
        The unknowns of each block; each unknown in at most one block. Column ``j`` lists the ``j``-th
        unknown of every block (for the modal models: unknown ``j`` of modes ``1..N``, stored contiguously,
        which the products below read as slices).
    m_off, c_off, k_off : ndarray, shape (n_blocks, s, s)
        Off-diagonal entries of ``M``, ``C``, ``K`` within each block (zero diagonals: the diagonals are
        the system's ``m_diag`` etc.).
    """

    index: np.ndarray
    m_off: np.ndarray
    c_off: np.ndarray
    k_off: np.ndarray

    #: Cache of :attr:`columns` (filled by its first call).
    _columns: list[slice | np.ndarray] = field(default_factory=list, compare=False, repr=False)
    #: Cache of :meth:`solve`: the last effective blocks (``"blocks"``) and their inverses (``"inverse"``).
    _inverse: dict[str, np.ndarray] = field(default_factory=dict, compare=False, repr=False)

    @property
    def columns(self) -> list[slice | np.ndarray]:
        """Per position ``j`` in the blocks, a slice (contiguous unknowns) or the index array."""
        if not self._columns:
            for j in range(self.index.shape[1]):
                col = self.index[:, j]
                contiguous = np.array_equal(col, col[0] + np.arange(col.size))
                self._columns.append(slice(int(col[0]), int(col[0]) + col.size) if contiguous else col)
        return self._columns

    def subtract_products(self, out: np.ndarray, pairs: Sequence[tuple[np.ndarray, np.ndarray]]) -> None:
        """``out -= sum over (off, x) of off @ x`` on the blocks' unknowns (x of shape (n,))."""
        cols = self.columns
        s = len(cols)
        for i in range(s):
            for off, x in pairs:
                for j in range(s):
                    if j != i:
                        out[cols[i]] -= off[:, i, j] * x[cols[j]]

    def solve(self, diag: np.ndarray, off: np.ndarray, rhs: np.ndarray) -> np.ndarray:
        """``D^{-1} rhs`` for ``D = diag(diag) + off`` on the blocks (rhs of shape (n,) or (r, n)).

        The blocks' inverses are kept for the next call with the same blocks (a run with a fixed step
        has the same effective blocks at every step: only the wheel rows, outside them, change).
        """
        out = rhs / diag
        cols = self.columns
        s = len(cols)
        blocks = off.copy()
        for j in range(s):
            blocks[:, j, j] += diag[cols[j]]
        cached = self._inverse.get("blocks")
        if cached is None or not np.array_equal(cached, blocks):
            self._inverse.update(blocks=blocks, inverse=np.linalg.inv(blocks))
        inverse = self._inverse["inverse"]
        parts = [rhs[..., col] for col in cols]
        for i in range(s):
            acc = inverse[:, i, 0] * parts[0]
            for j in range(1, s):
                acc += inverse[:, i, j] * parts[j]
            out[..., cols[i]] = acc
        return out

    def dense(self, off: np.ndarray, n: int) -> np.ndarray:
        """The couplings as a dense ``n x n`` matrix (tests)."""
        out = np.zeros((n, n))
        rows = np.repeat(self.index[:, :, None], self.index.shape[1], axis=2)
        out[rows, np.swapaxes(rows, 1, 2)] = off
        return out


@dataclass(frozen=True)
class DiagLowRankSystem:
    """The matrices of ``M z'' + C z' + K z = f`` at one instant, each ``diag + U V^T``.

    All three share the left factor ``U`` because in the moving-load problem every off-diagonal
    term enters the equations through the same few vectors (the mode shapes at the contact points,
    the bar's own two rows); only the right factors differ.

    Attributes
    ----------
    m_diag, c_diag, k_diag : ndarray, shape (n,)
        Diagonals of ``M``, ``C``, ``K``.
    ut : ndarray, shape (r, n)
        Shared left factor, transposed (``U^T``; ``r`` may be 0). Stored by rows so that every
        per-step operation runs over contiguous memory.
    vmt, vct, vkt : ndarray, shape (r, n)
        Right factors, transposed: ``M = diag(m_diag) + ut.T @ vmt``, and so on.
    force : ndarray, shape (n,)
        Right-hand side ``f``.
    blocks : ModeBlocks, optional
        Couplings within each mode's unknowns (Timoshenko-Rayleigh rotation, mass layers): the diagonal
        part becomes block diagonal, still solved in ``O(n)``. Default: none.
    """

    m_diag: np.ndarray
    c_diag: np.ndarray
    k_diag: np.ndarray
    ut: np.ndarray
    vmt: np.ndarray
    vct: np.ndarray
    vkt: np.ndarray
    force: np.ndarray
    blocks: ModeBlocks | None = None

    def residual_force(self, v: np.ndarray, z: np.ndarray) -> np.ndarray:
        """``f - C v - K z`` in ``O(n r)``."""
        low_rank = (self.vct @ v + self.vkt @ z) @ self.ut
        out = self.force - self.c_diag * v - self.k_diag * z - low_rank
        b = self.blocks
        if b is not None:
            b.subtract_products(out, ((b.c_off, v), (b.k_off, z)))
        return out

    def dense(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Dense ``(M, C, K)``: for tests and small systems only (``O(n^2)`` memory)."""
        out = []
        for diag, vt, name in (
            (self.m_diag, self.vmt, "m_off"),
            (self.c_diag, self.vct, "c_off"),
            (self.k_diag, self.vkt, "k_off"),
        ):
            matrix = np.diag(diag) + self.ut.T @ vt
            if self.blocks is not None:
                matrix += self.blocks.dense(getattr(self.blocks, name), diag.size)
            out.append(matrix)
        return out[0], out[1], out[2]


def woodbury_solve(
    diag: np.ndarray,
    ut: np.ndarray,
    vt: np.ndarray,
    rhs: np.ndarray,
    blocks: ModeBlocks | None = None,
    off: np.ndarray | None = None,
) -> np.ndarray:
    """Solve ``(D + U V^T) x = rhs`` by the Sherman-Morrison-Woodbury identity.

    ``x = D^{-1} rhs - D^{-1} U (I + V^T D^{-1} U)^{-1} V^T D^{-1} rhs`` (Hager 1989), which costs
    ``O(n r + r^3)``.

    Parameters
    ----------
    diag : ndarray, shape (n,)
        Nonzero diagonal of ``D``.
    ut, vt : ndarray, shape (r, n)
        Low-rank factors, transposed (``U^T``, ``V^T``); ``r = 0`` reduces to a diagonal solve.
    rhs : ndarray, shape (n,)
    blocks, off : optional
        ``D`` also has the off-diagonal entries `off` (shape ``(n_blocks, s, s)``) within the groups
        ``blocks.index``; its inverse is then block diagonal with ``s x s`` blocks, still ``O(n)``.

    Returns
    -------
    ndarray, shape (n,)
    """
    if blocks is None:
        y = rhs / diag
        d_inv_ut = ut / diag
    else:
        if off is None:
            raise ValueError("woodbury_solve: `blocks` needs their off-diagonal entries `off`")
        both = blocks.solve(diag, off, np.vstack([rhs, ut]))
        y, d_inv_ut = both[0], both[1:]
    if ut.shape[0] == 0:
        return y
    capacitance = np.eye(ut.shape[0]) + vt @ d_inv_ut.T
    return y - np.linalg.solve(capacitance, vt @ y) @ d_inv_ut


@dataclass(frozen=True)
class NewmarkState:
    """Displacement, velocity and acceleration at one time."""

    t: float
    z: np.ndarray
    v: np.ndarray
    a: np.ndarray


def initial_state(t0: float, z0: np.ndarray, v0: np.ndarray, system: DiagLowRankSystem) -> NewmarkState:
    """Complete the initial conditions with the acceleration from the equation of motion at ``t0``.

    The loads of the finite-beam model are applied suddenly, so ``a(t0)`` is not zero even though
    the system starts at rest: it is ``M^{-1} (f - C v0 - K z0)``.
    """
    b = system.blocks
    rhs = system.residual_force(v0, z0)
    a0 = woodbury_solve(system.m_diag, system.ut, system.vmt, rhs, b, None if b is None else b.m_off)
    return NewmarkState(t0, z0, v0, a0)


def newmark_step(
    state: NewmarkState,
    h: float,
    system: DiagLowRankSystem,
    scheme: NewmarkScheme = AVERAGE_ACCELERATION,
) -> NewmarkState:
    """Advance one implicit Newmark step of length `h` (Newmark 1959).

    The equation of motion is enforced at ``t_{n+1}`` with the matrices `system` assembled there
    (the contact points have moved), in the acceleration form: with the predictors
    ``z* = z_n + h v_n + h^2 (1/2 - beta) a_n`` and ``v* = v_n + h (1 - gamma) a_n``,

        (M + gamma h C + beta h^2 K) a_{n+1} = f - C v* - K z*,

    solved by :func:`woodbury_solve` since the effective matrix is diagonal + rank ``r``.

    Parameters
    ----------
    state : NewmarkState
        State at ``t_n``.
    h : float
        Step length.
    system : DiagLowRankSystem
        Matrices and load at ``t_{n+1} = t_n + h``.
    scheme : NewmarkScheme, optional
        Default: average acceleration.

    Returns
    -------
    NewmarkState
        State at ``t_{n+1}``.
    """
    beta, gamma = scheme.beta, scheme.gamma
    z_pred = state.z + h * state.v + (h * h * (0.5 - beta)) * state.a
    v_pred = state.v + (h * (1.0 - gamma)) * state.a
    rhs = system.residual_force(v_pred, z_pred)
    gh, bh2 = gamma * h, beta * h * h
    s_diag = system.m_diag + gh * system.c_diag + bh2 * system.k_diag
    s_vt = system.vmt + gh * system.vct + bh2 * system.vkt
    b = system.blocks
    s_off = None if b is None else b.m_off + gh * b.c_off + bh2 * b.k_off
    a_new = woodbury_solve(s_diag, system.ut, s_vt, rhs, b, s_off)
    return NewmarkState(state.t + h, z_pred + bh2 * a_new, v_pred + gh * a_new, a_new)


def effective_matrix_dense(
    system: DiagLowRankSystem, h: float, scheme: NewmarkScheme = AVERAGE_ACCELERATION
) -> np.ndarray:
    """Dense ``M + gamma h C + beta h^2 K`` (for tests of the Woodbury step)."""
    m, c, k = system.dense()
    return m + scheme.gamma * h * c + scheme.beta * h * h * k
