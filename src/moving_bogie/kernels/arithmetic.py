"""The arithmetics of the vehicle-rail coupling (:mod:`moving_bogie.kernels.coupling`): its operations on
the matrices of one number type.

:class:`Arithmetic` names the operations (sum, product, scaling, a matrix polynomial, rows split and
stacked, ...); :class:`Rows` implements them on lists of rows of scalars (mpmath, gmpy2, Arb's acb and
acb_series, SymPy: anything with ``+`` and ``*``), with the integer 0 as a structural zero that is never
multiplied or added, so that the eliminations of :mod:`moving_bogie.kernels.elimination` keep it;
:class:`Batched` on numpy arrays of shape ``batch + (rows, columns)``, many q (and parameters) at once.
Arb's matrices have theirs beside the proofs (``roots/proof/ball_block.py``).

>>> Rows.matmul([[1, 0], [2, 3]], [[4], [5]])
[[4], [23]]
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, Protocol

import numpy as np

__all__ = ["Arithmetic", "Batched", "Rows", "structural_zero"]


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
        """P + s I (P is a fresh result, which the arithmetic may overwrite)."""

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
        return (s[..., None, None] if isinstance(s, np.ndarray) and s.ndim else s) * P

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
        out = P if P.dtype == complex else P.astype(complex)  # P is fresh: overwritten
        diagonal = range(min(P.shape[-2:]))
        out[..., diagonal, diagonal] += s
        return out

    @staticmethod
    def split(P: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
        return P[..., :n, :], P[..., n:, :]

    @staticmethod
    def stack(top: np.ndarray, bottom: np.ndarray) -> np.ndarray:
        if top.shape[:-2] != bottom.shape[:-2]:
            batch = np.broadcast_shapes(top.shape[:-2], bottom.shape[:-2])
            top, bottom = (np.broadcast_to(x, batch + x.shape[-2:]) for x in (top, bottom))
        return np.concatenate((top, bottom), axis=-2)

    @staticmethod
    def zeros(rows: int, columns: int) -> np.ndarray:
        return np.zeros((rows, columns), dtype=complex)

    @staticmethod
    def column(values: Sequence[Any]) -> np.ndarray:
        return np.asarray(values, dtype=float)[:, None]

    @staticmethod
    def gather(values: Sequence[Any], index: Sequence[Sequence[int]]) -> np.ndarray:
        shapes = {np.shape(k) for k in values}
        if len(shapes) > 1:
            shape = np.broadcast_shapes(*shapes)
            values = [np.broadcast_to(k, shape) for k in values]
        return np.stack(values, axis=-1)[..., np.asarray(index)]

    @staticmethod
    def embed(blocks: Sequence[np.ndarray], places: Sequence[Sequence[int]], size: int) -> np.ndarray:
        batch = np.broadcast_shapes(*(np.shape(b)[:-2] for b in blocks))
        out = np.zeros(batch + (size, size), dtype=complex)
        for block, place in zip(blocks, places):
            ix = np.asarray(place)
            out[..., ix[:, None], ix[None, :]] = block
        return out


def structural_zero(x: Any) -> bool:
    """Whether ``x`` is the integer 0 that marks an entry the vehicle does not couple."""
    return isinstance(x, int) and x == 0


def _plus(x: Any, y: Any) -> Any:
    """x + y, where a structural zero adds nothing (and two of them stay one)."""
    if structural_zero(y):
        return x
    return y if structural_zero(x) else x + y
