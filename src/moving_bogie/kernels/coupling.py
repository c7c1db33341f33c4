"""The vehicle-rail coupling, written once for every number type: D(q), the block system, dA/dq and b.

A vehicle with N DOFs, its n contacts first, has the dynamic stiffness (d/dtau -> i q, Eq. (21))

    D(q) = -q^2 M + i q C + K,        dD/dq = -2 q M + i C,

from its generated matrices M, C, K. The rail answers a contact force f_j with the deflection
pi W_i = 2 sum_j G_ij f_j (the beam rows of Eq. (28)); on a continuous track G is the kernel matrix
G_ij = K(xi_i - xi_j, q) of Eq. (29). With the wheel forces f = s - (D x)_c (s the static loads) the
deflections x = [W; Y] (Y the internal DOFs, times i q as in Eq. (30)) solve

    A x = b,   A = [[pi I + 2 G D_cc, 2 G D_ci], [D_ic, D_ii]],   b = [2 G s; 0],

whose determinant is E_chr (Eq. (38) for n wheels, up to a constant factor), and

    dA/dq = [[2 (dG/dq D_cc + G dD_cc/dq), 2 (dG/dq D_ci + G dD_ci/dq)], [dD_ic/dq, dD_ii/dq]]

(Eq. (40) by Jacobi's formula). :func:`coupled_system` takes D and G as given, so the rail side is any
receptance matrix between contacts and the derivative may be taken along any parameter (dG, dD given).

One number type at a time, through an arithmetic object: :class:`Rows` holds matrices as lists of rows of
scalars (mpmath, gmpy2, Arb's acb and acb_series, SymPy), with the integer 0 as a structural zero that is
never multiplied or added (so the eliminations of :mod:`moving_bogie.kernels.elimination` keep it);
:class:`Batched` holds numpy arrays of shape ``batch + (rows, columns)`` and evaluates many q (and
parameters) at once with matrix products. Both run the same operations in the same order.

**Harmonics (a track on sleepers).** On a periodically supported rail a contact force at frequency Omega
excites the harmonics Omega_m = Omega + m Omega_0, and the rail's receptance couples them: the contact
deflection at harmonic m is w_m = sum_m' H_mm'(Omega) F_m', with one entry per (contact, harmonic) pair
(n contacts at their phases: an n x n block per pair of harmonics). The vehicle answers each harmonic at its
own frequency, F_m = -D(Omega_m) x_m over its contact rows. The coupled system is then the block system above
with

- D = :func:`harmonic_blocks` of [D(Omega_-h), ..., D(Omega_h)], block diagonal over the harmonics with every
  contact DOF (contact, harmonic) first, then the internal DOFs of every harmonic;
- G = (pi / 2) H, the receptance between (contact, harmonic) pairs in the rows and columns of D's contacts;

so that det A = det D_ii det(pi I + 2 G S) = (pi^(n H) det D_ii) det(I + H S), S the Schur complement on
D_ii (the vehicle condensed to its contacts, harmonic by harmonic). For a vehicle of contact masses
(D_ii empty) this is det[delta_mm' + H_mm' D(Omega_m')], the Hill determinant of the sleeper track's
characteristic function det[delta_mm' - D_vehicle(Omega_m) H_mm'] with that track's sign of the vehicle's
dynamic stiffness (receptance and stiffness in the e^{i Omega t} convention there). With one harmonic and
G the kernel matrix, it is the continuous track's system above.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, Protocol

import numpy as np

__all__ = [
    "Batched",
    "Coupled",
    "Rows",
    "coupled_derivative",
    "coupled_system",
    "dynamic_stiffness",
    "harmonic_blocks",
    "kernel_matrix",
]


class Arithmetic(Protocol):
    """The operations the coupling uses, on the matrices of one number type (:class:`Rows`,
    :class:`Batched`, ``roots.proof.ball_block.ArbMatrices``)."""

    pi: Any
    i: Any

    def count(self, G: Any) -> int:
        """The number of rows."""

    def scale(self, s: Any, P: Any) -> Any:
        """s P."""

    def add(self, P: Any, Q: Any) -> Any:
        """P + Q."""

    def matmul(self, P: Any, Q: Any) -> Any:
        """P Q."""

    def polynomial(self, q: Any, coefficients: Sequence[Any]) -> Any:
        """sum_k q^k P_k, lowest power first."""

    def plus_identity(self, P: Any, s: Any) -> Any:
        """P + s I."""

    def split(self, P: Any, n: int) -> tuple[Any, Any]:
        """(the first n rows, the others)."""

    def stack(self, top: Any, bottom: Any) -> Any:
        """The rows of ``top`` over those of ``bottom``."""

    def zeros(self, rows: int, columns: int) -> Any:
        """A rows x columns matrix of zeros."""

    def column(self, values: Sequence[Any]) -> Any:
        """A vector as a one-column matrix."""

    def gather(self, values: Sequence[Any], index: Sequence[Sequence[int]]) -> Any:
        """The matrix with entry (r, c) = values[index[r][c]]."""

    def embed(self, blocks: Sequence[Any], places: Sequence[Sequence[int]], size: int) -> Any:
        """size x size zeros with block k at rows and columns ``places[k]``."""


def structural_zero(x: Any) -> bool:
    """Whether ``x`` is the integer 0 that marks an entry the vehicle does not couple."""
    return isinstance(x, int) and x == 0


def _plus(x: Any, y: Any) -> Any:
    """x + y, where a structural zero adds nothing (and two of them stay one)."""
    if structural_zero(y):
        return x
    return y if structural_zero(x) else x + y


class Rows:
    """Matrices as lists of rows of scalars of one number type (mpmath, gmpy2, acb, acb_series, SymPy).

    Parameters
    ----------
    pi, i : number
        pi and the imaginary unit in that number type (``mpmath.pi``, ``gmpy2.const_pi()`` in the context
        of the computation, ``acb(arb.pi())``, ...).
    """

    def __init__(self, pi: Any, i: Any) -> None:
        self.pi, self.i = pi, i

    @staticmethod
    def count(G: list) -> int:
        """The number of rows."""
        return len(G)

    @staticmethod
    def scale(s: Any, P: list) -> list:
        """s P (structural zeros stay)."""
        return [[0 if structural_zero(x) else s * x for x in row] for row in P]

    def polynomial(self, q: Any, coefficients: Sequence[list]) -> list:
        """sum_k q^k P_k (``coefficients`` P_0, P_1, ... lowest power first), highest power first."""
        powers = [1, q]
        for _ in range(2, len(coefficients)):
            powers.append(powers[-1] * q)
        out = self.scale(powers[-1], coefficients[-1])
        for k in range(len(coefficients) - 2, 0, -1):
            out = self.add(out, self.scale(powers[k], coefficients[k]))
        return self.add(out, coefficients[0])

    @staticmethod
    def add(P: list, Q: list) -> list:
        """P + Q."""
        return [[_plus(x, y) for x, y in zip(p, r)] for p, r in zip(P, Q)]

    @staticmethod
    def matmul(P: list, Q: list) -> list:
        """P Q, the terms in the order of the inner index, products by a structural zero skipped."""
        inner = range(len(Q))
        out = []
        for p in P:
            line = []
            for c in range(len(Q[0]) if Q else 0):
                terms = [
                    p[k] * Q[k][c] for k in inner if not (structural_zero(p[k]) or structural_zero(Q[k][c]))
                ]
                line.append(sum(terms[1:], terms[0]) if terms else 0)
            out.append(line)
        return out

    @staticmethod
    def plus_identity(P: list, s: Any) -> list:
        """P + s I (P with at least as many columns as rows)."""
        return [[x + s if r == c else x for c, x in enumerate(row)] for r, row in enumerate(P)]

    @staticmethod
    def split(P: list, n: int) -> tuple[list, list]:
        """(the first n rows, the others)."""
        return P[:n], P[n:]

    @staticmethod
    def stack(top: list, bottom: list) -> list:
        """The rows of ``top`` over those of ``bottom``."""
        return [list(row) for row in top] + [list(row) for row in bottom]

    @staticmethod
    def zeros(rows: int, columns: int) -> list:
        """A rows x columns matrix of structural zeros."""
        return [[0] * columns for _ in range(rows)]

    @staticmethod
    def column(values: Sequence[Any]) -> list:
        """A vector as a one-column matrix."""
        return [[x] for x in values]

    @staticmethod
    def gather(values: Sequence[Any], index: Sequence[Sequence[int]]) -> list:
        """The matrix with entry (r, c) = values[index[r][c]]."""
        return [[values[k] for k in row] for row in index]

    @staticmethod
    def embed(blocks: Sequence[list], places: Sequence[Sequence[int]], size: int) -> list:
        """A size x size matrix of structural zeros with block k at rows and columns ``places[k]``."""
        out = [[0] * size for _ in range(size)]
        for block, place in zip(blocks, places):
            for a, row in zip(place, block):
                for c, x in zip(place, row):
                    out[a][c] = x
        return out


class Batched:
    """Matrices as numpy arrays of shape ``batch + (rows, columns)``, broadcast over the batch.

    The scalars of :meth:`scale` are numbers or arrays of the batch shape (one q per matrix).
    """

    pi = np.pi
    i = 1j

    @staticmethod
    def count(G: np.ndarray) -> int:
        return G.shape[-2]

    @staticmethod
    def scale(s: Any, P: np.ndarray) -> np.ndarray:
        return (np.asarray(s)[..., None, None] if np.ndim(s) else s) * P

    @staticmethod
    def polynomial(q: Any, coefficients: Sequence[np.ndarray]) -> np.ndarray:
        """sum_k q^k P_k: one matrix product [1, q, q^2, ...] @ [P_0, P_1, ...] over the batch when the P_k
        are the same at every point, else the terms highest power first (as :class:`Rows`)."""
        q = np.asarray(q)
        powers = [np.ones_like(q), q]
        for _ in range(2, len(coefficients)):
            powers.append(powers[-1] * q)
        if all(np.ndim(P) == 2 for P in coefficients):
            stacked = np.stack([np.ravel(P) for P in coefficients])
            shape = q.shape + np.shape(coefficients[0])
            return (np.stack(powers[: len(coefficients)], axis=-1) @ stacked).reshape(shape)
        out = Batched.scale(powers[-1], coefficients[-1])
        for k in range(len(coefficients) - 2, 0, -1):
            out = out + Batched.scale(powers[k], coefficients[k])
        return out + coefficients[0]

    @staticmethod
    def add(P: np.ndarray, Q: np.ndarray) -> np.ndarray:
        return P + Q

    @staticmethod
    def matmul(P: np.ndarray, Q: np.ndarray) -> np.ndarray:
        return P @ Q

    @staticmethod
    def plus_identity(P: np.ndarray, s: Any) -> np.ndarray:
        out = np.array(P, dtype=complex)
        diagonal = range(min(P.shape[-2:]))
        out[..., diagonal, diagonal] += s
        return out

    @staticmethod
    def split(P: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
        return P[..., :n, :], P[..., n:, :]

    @staticmethod
    def stack(top: np.ndarray, bottom: np.ndarray) -> np.ndarray:
        batch = np.broadcast_shapes(top.shape[:-2], bottom.shape[:-2])
        parts = [np.broadcast_to(x, batch + x.shape[-2:]) for x in (top, bottom)]
        return np.concatenate(parts, axis=-2)

    @staticmethod
    def zeros(rows: int, columns: int) -> np.ndarray:
        return np.zeros((rows, columns), dtype=complex)

    @staticmethod
    def column(values: Sequence[Any]) -> np.ndarray:
        return np.asarray(values, dtype=float)[:, None]

    @staticmethod
    def gather(values: Sequence[Any], index: Sequence[Sequence[int]]) -> np.ndarray:
        shape = np.broadcast_shapes(*(np.shape(k) for k in values))
        return np.stack([np.broadcast_to(k, shape) for k in values], axis=-1)[..., np.asarray(index)]

    @staticmethod
    def embed(blocks: Sequence[np.ndarray], places: Sequence[Sequence[int]], size: int) -> np.ndarray:
        batch = np.broadcast_shapes(*(np.shape(b)[:-2] for b in blocks))
        out = np.zeros(batch + (size, size), dtype=complex)
        for block, place in zip(blocks, places):
            ix = np.asarray(place)
            out[..., ix[:, None], ix[None, :]] = block
        return out


@dataclass(frozen=True)
class Coupled:
    """The block system A x = b at one q (or a batch), and dA (None unless a derivative was asked for)."""

    A: Any
    b: Any
    dA: Any


def dynamic_stiffness(q: Any, matrices: Sequence[Any], ops: Arithmetic, derivative: bool = False) -> tuple:
    """(D(q), dD/dq or None): D = -q^2 M + i q C + K, dD/dq = -2 q M + i C (Eq. (21), d/dtau -> i q).

    Parameters
    ----------
    q : number or array
        The point (an array of the batch shape for :class:`Batched`).
    matrices : (M, C, K)
        The vehicle's generated matrices in the number type of ``ops``.
    ops : Rows or Batched
        The arithmetic.
    derivative : bool
        Also dD/dq.
    """
    M, C, K = matrices
    D = ops.polynomial(q, (K, ops.scale(ops.i, C), ops.scale(-1, M)))
    if not derivative:
        return D, None
    return D, ops.add(ops.scale(-2 * q, M), ops.scale(ops.i, C))


def kernel_matrix(values: Sequence[Any], index: Sequence[Sequence[int]], ops: Arithmetic) -> Any:
    """G_ij = K(xi_i - xi_j, q) (Eq. (29)) from the kernel ``values`` at the distinct offsets and
    ``index[i][j]``, the offset of xi_i - xi_j: the receptance of a continuous track."""
    return ops.gather(values, index)


def harmonic_blocks(blocks: Sequence[Any], contacts: int, ops: Arithmetic) -> Any:
    """The dynamic stiffness over harmonics: block diagonal in [D(Omega_m) for each harmonic m], every
    (contact, harmonic) DOF first (harmonic by harmonic), then the internal DOFs of every harmonic.

    Parameters
    ----------
    blocks : sequence
        D at each harmonic (N x N, the ``contacts`` first), from :func:`dynamic_stiffness`.
    contacts : int
        The vehicle's contacts n.
    ops : Rows or Batched
        The arithmetic.
    """
    H = len(blocks)
    size = ops.count(blocks[0])
    inside = size - contacts
    places = [
        [h * contacts + j for j in range(contacts)] + [H * contacts + h * inside + a for a in range(inside)]
        for h in range(H)
    ]
    return ops.embed(blocks, places, H * size)


def coupled_system(
    D: Any,
    G: Any,
    ops: Arithmetic,
    *,
    loads: Sequence[Any] | None = None,
    dD: Any = None,
    dG: Any = None,
) -> Coupled:
    """The block system of the vehicle on the rail (module docstring; Eqs. (28), (30), (38) for n wheels).

    Parameters
    ----------
    D : matrix
        The vehicle's dynamic stiffness (contacts first), :func:`dynamic_stiffness` or
        :func:`harmonic_blocks`.
    G : matrix
        The rail's receptance between the contacts (n x n; :func:`kernel_matrix` on a continuous track).
    ops : Rows or Batched
        The arithmetic of D and G.
    loads : sequence, optional
        The static loads s_j at the contacts: b = [2 G s; 0] (else b is None).
    dD, dG : matrix, optional
        Derivatives of D and G along one variable (q, or a parameter): dA along it (None if neither).

    Returns
    -------
    Coupled
        A, b and dA in the arithmetic of ``ops``.
    """
    n, size = ops.count(G), ops.count(D)
    Dc, Di = ops.split(D, n)
    A = ops.stack(ops.plus_identity(ops.scale(2, ops.matmul(G, Dc)), ops.pi), Di)
    b = None
    if loads is not None:
        b = ops.stack(ops.scale(2, ops.matmul(G, ops.column(loads))), ops.zeros(size - n, 1))
    dA = None if dD is None and dG is None else _derivative(Dc, G, ops, dD, dG, size)
    return Coupled(A, b, dA)


def coupled_derivative(D: Any, G: Any, ops: Arithmetic, *, dD: Any = None, dG: Any = None) -> Any:
    """dA = [[2 (dG D_c + G dD_c)], [dD_i]] of :func:`coupled_system` along one variable (Eq. (40)).

    Parameters
    ----------
    D, G : matrix
        As for :func:`coupled_system`.
    ops : Rows or Batched
        The arithmetic.
    dD, dG : matrix, optional
        The derivatives of D and G along the variable (a term whose derivative is None is left out; at least
        one is given).

    Returns
    -------
    matrix
        dA in the arithmetic of ``ops``.
    """
    return _derivative(ops.split(D, ops.count(G))[0], G, ops, dD, dG, ops.count(D))


def _derivative(Dc: Any, G: Any, ops: Arithmetic, dD: Any, dG: Any, size: int) -> Any:
    """dA from the contact rows D_c of D (see :func:`coupled_derivative`)."""
    n = ops.count(G)
    terms = []
    if dG is not None:
        terms.append(ops.matmul(dG, Dc))
    if dD is not None:
        dDc, bottom = ops.split(dD, n)
        terms.append(ops.matmul(G, dDc))
    else:
        bottom = ops.zeros(size - n, size)
    top = terms[0] if len(terms) == 1 else ops.add(terms[0], terms[1])
    return ops.stack(ops.scale(2, top), bottom)
