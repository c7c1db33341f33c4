"""Gaussian elimination on lists of rows, for numbers of any backend (mpmath, python ints), keeping the
structural zeros of a vehicle's block system (Eq. (38) for n wheels) exact so that they cost nothing.

An exact integer 0 marks an entry the vehicle's matrices do not couple; the elimination neither multiplies
by it nor turns it into a rounded zero, so the values are those of the dense elimination, bit for bit.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from moving_bogie.typing import Matrix


def exact_zero(x: object) -> bool:
    """Whether ``x`` is the exact integer 0 that marks a structural zero (a coupling the vehicle lacks)."""
    return isinstance(x, int) and x == 0


def lu_factor(A: Matrix) -> tuple[Matrix, list[int], Any]:
    """LU factors with partial pivoting of a square list of rows (numbers of any backend): (lu, perm, det).

    A zero pivot (A singular to working precision) ends the elimination with det = 0.
    """
    N = len(A)
    lu = [list(row) for row in A]
    perm = list(range(N))
    det = 1
    for k in range(N):
        p = max(range(k, N), key=lambda r: abs(lu[r][k]))
        if lu[p][k] == 0:
            return lu, perm, 0 * det
        if p != k:
            lu[k], lu[p] = lu[p], lu[k]
            perm[k], perm[p] = perm[p], perm[k]
            det = -det
        pivot = lu[k][k]
        det = det * pivot
        top = lu[k]
        columns = [c for c in range(k + 1, N) if not exact_zero(top[c])]  # structural zeros stay exact
        for r in range(k + 1, N):
            if exact_zero(lu[r][k]):
                continue
            f = lu[r][k] / pivot
            lu[r][k] = f
            if f != 0:
                row = lu[r]
                for c in columns:
                    row[c] -= f * top[c]
    return lu, perm, det


def lu_solve(lu: Matrix, perm: list[int], b: list[Any]) -> list[Any]:
    """Solve A x = b with the factors of :func:`lu_factor` (det != 0)."""
    N = len(lu)
    y = [b[perm[r]] for r in range(N)]
    for r in range(N):
        terms = [lu[r][c] * y[c] for c in range(r) if not (exact_zero(lu[r][c]) or exact_zero(y[c]))]
        if terms:
            y[r] = y[r] - sum(terms[1:], terms[0])
    for r in range(N - 1, -1, -1):
        terms = [lu[r][c] * y[c] for c in range(r + 1, N) if not (exact_zero(lu[r][c]) or exact_zero(y[c]))]
        y[r] = (y[r] - sum(terms[1:], terms[0]) if terms else y[r]) / lu[r][r]
    return y
