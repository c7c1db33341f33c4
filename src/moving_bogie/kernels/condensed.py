"""E_chr of a vehicle on n wheels with its internal DOFs eliminated first (the block system of Eq. (38)
condensed to its wheels), and dE_chr/dq by Jacobi's formula (Eq. (40)), at one q, for the mpmath
backend (computed in gmpy2, the library under mpmath, and returned as mpmath numbers).

The block system of :mod:`moving_bogie.kernels.coupling` is [[pi I + 2 Kmat D_cc, 2 Kmat D_ci], [D_ic, D_ii]]
(c: the n wheels, i: the vehicle's internal DOFs). D_ii, the vehicle with its wheels held, does not involve
the track, so its Schur complement is an n x n system, and an evaluation costs a small elimination of
D_ii and one of the wheel system instead of one of the whole block system. The wheel system is the same
coupling of the condensed vehicle S to the track (no internal DOFs left): D, the wheel system and its
derivative are those of :mod:`moving_bogie.kernels.coupling`, in gmpy2 numbers.
"""

from __future__ import annotations

from collections.abc import Sequence

import gmpy2
import mpmath

from moving_bogie.kernels.arithmetic import Rows
from moving_bogie.kernels.coupling import (
    Dynamic,
    coupled_derivative,
    coupled_system,
    dynamic_coefficients,
    dynamic_stiffness,
    kernel_matrix,
)
from moving_bogie.kernels.elimination import exact_zero, lu_factor, lu_solve
from moving_bogie.typing import Matrix, Mpc, Scalar


def binary_matrices(*matrices: Matrix) -> Dynamic:
    """The vehicle's matrices (lists of rows of mpmath numbers at the working precision, exact 0 where
    nothing couples) in gmpy2, exactly, as the coefficients of D(q) (exact too: a sign and a factor i)."""
    with gmpy2.context(gmpy2.get_context(), precision=mpmath.mp.prec + 64):
        binary = tuple([[to_binary(x) for x in row] for row in matrix] for matrix in matrices)
        return dynamic_coefficients(binary, _arithmetic())


def to_binary(x: Scalar) -> Scalar:
    """An mpmath number (or int, float) as the gmpy2 number of the same value; an exact 0 stays 0. Exact
    when the gmpy2 context holds at least the number's bits (the callers' contexts do)."""
    if exact_zero(x):
        return 0
    if isinstance(x, mpmath.mpc):
        return gmpy2.mpc(_mpfr(x.real._mpf_), _mpfr(x.imag._mpf_))
    if isinstance(x, mpmath.mpf):
        return gmpy2.mpc(_mpfr(x._mpf_), 0)
    return gmpy2.mpc(x)


def _mpfr(parts: tuple[int, int, int, int]) -> Scalar:
    """mpmath's (sign, mantissa, exponent, bits) of a real as the gmpy2 mpfr of the same value."""
    sign, man, exp, _ = parts
    value = gmpy2.mul_2exp(gmpy2.mpfr(man), exp)
    return -value if sign else value


def _to_mp(z: Scalar) -> Mpc:
    """A gmpy2 number as an mpmath number, exactly (the caller rounds it to the working precision)."""
    if exact_zero(z):
        return mpmath.mpc(0)
    parts = []
    for x in (z.real, z.imag):
        man, exp = x.as_mantissa_exp()
        parts.append(mpmath.mpf((int(man), int(exp))))
    return mpmath.mpc(*parts)


def condensed_characteristic(
    q: Mpc,
    matrices: Dynamic,
    K: Sequence[Mpc],
    index: Sequence[Sequence[int]],
    dK: Sequence[Mpc] | None = None,
) -> tuple[Mpc, Mpc | None] | None:
    """(E_chr, dE_chr/dq or None) of the block system with the internal DOFs eliminated first, or None.

    ``q`` an mpmath number, ``matrices`` the coefficients of D(q) from :func:`binary_matrices` (N x N,
    wheels first), ``K`` (``dK``, or None) the kernel values at the distinct offsets and ``index[i][j]`` the
    offset of xi_i - xi_j. With D(q) = -q^2 M + i q C + K, S = D_cc - D_ci D_ii^-1 D_ic (the vehicle's
    dynamic stiffness condensed to its wheels) and B = pi I + 2 Kmat S, det A = det D_ii det B exactly. With
    X = D_ii^-1 D_ic, Jacobi's formula gives dE/dq = E (tr(D_ii^-1 dD_ii) + tr(B^-1 dB)),
    dB = 2 dKmat S + 2 Kmat dS, dS = dD_cc - dD_ci X - D_ci D_ii^-1 (dD_ic - dD_ii X).

    The arithmetic is gmpy2's (MPC: correctly rounded, a tenth of mpmath's cost per operation here): D at
    the working precision (rounded as mpmath rounds it), the elimination at the working precision plus
    guard bits; the result is rounded back to mpmath at the working precision. Near a
    zero of det D_ii (a resonance of the held vehicle) S is large and the elimination loses about log2 of
    the ratio of the largest to the smallest pivot of D_ii in bits: the guard is that many bits plus 17 (at
    least 34, about 10 digits), so that E keeps the accuracy of the elimination of the whole system. None
    where D_ii or B is singular to working precision: the caller then eliminates the whole system.
    """
    n, N = len(index), len(matrices.coefficients[0])
    m = N - n
    bits, guard = mpmath.mp.prec, 34
    while True:
        with gmpy2.context(gmpy2.get_context(), precision=bits):  # D rounded as mpmath rounds it
            D, dD = dynamic_stiffness(to_binary(q), matrices, _arithmetic(), dK is not None)
        with gmpy2.context(gmpy2.get_context(), precision=bits + guard):
            factors: tuple[Matrix | None, list[int] | None, Scalar] = (None, None, 1)
            loss = 0
            if m:
                lu, perm, det = lu_factor([row[n:] for row in D[n:]])
                if det == 0:
                    return None
                factors = (lu, perm, det)
                pivots = [abs(lu[k][k]) for k in range(m)]
                loss = max(0, int(gmpy2.log2(max(pivots) / min(pivots))))
            if loss + 17 <= guard:
                ops = _arithmetic()
                Kmat = kernel_matrix([to_binary(k) for k in K], index, ops)
                dKmat = None if dK is None else kernel_matrix([to_binary(k) for k in dK], index, ops)
                out = _wheel_system(D, dD, factors, Kmat, dKmat)
                break
        guard = loss + 34
    if out is None:
        return None
    E, dE = out
    return +_to_mp(E), None if dE is None else +_to_mp(dE)


def _arithmetic() -> Rows:
    """gmpy2's arithmetic of :mod:`moving_bogie.kernels.coupling`, pi at the precision of the context."""
    return Rows(gmpy2.const_pi(), gmpy2.mpc(0, 1))


def _wheel_system(
    D: Matrix,
    dD: Matrix | None,
    factors: tuple[Matrix | None, list[int] | None, Scalar],
    Kmat: Matrix,
    dKmat: Matrix | None,
) -> tuple[Scalar, Scalar | None] | None:
    """(det D_ii det B, its q-derivative or None) from the factors of D_ii (see condensed_characteristic)."""
    n, N = len(Kmat), len(D)
    m = N - n
    lu, perm, d = factors

    def product(P: Matrix, Q: Matrix, rows: range, cols: range, inner: range) -> Matrix:
        """sum_k P[r][k] Q[k][c] over ``inner``, skipping exact zeros."""
        out = []
        for r in rows:
            line = []
            for c in cols:
                terms = [P[r][k] * Q[k][c] for k in inner if not (exact_zero(P[r][k]) or exact_zero(Q[k][c]))]
                line.append(sum(terms[1:], terms[0]) if terms else 0)
            out.append(line)
        return out

    wheels, inside = range(n), range(n, N)
    if m:
        assert lu is not None and perm is not None  # D_ii is factored when there is one
        # X[a][c] = (D_ii^-1 D_ic)[a][c], a internal (indexed n..N-1 in the products below)
        cols = [lu_solve(lu, perm, [D[n + a][c] for a in range(m)]) for c in wheels]
        X = [[0] * n for _ in range(n)] + [[cols[c][a] for c in wheels] for a in range(m)]
        DX = product(D, X, wheels, wheels, inside)
        S = [[D[r][c] - DX[r][c] for c in wheels] for r in wheels]
    else:
        S = [[D[r][c] for c in wheels] for r in wheels]
    ops = _arithmetic()
    B = coupled_system(S, Kmat, ops).A
    luB, permB, b = lu_factor(B)
    E = d * b
    if dKmat is None:
        return E, None
    if b == 0:
        return None
    assert dD is not None  # dKmat given: the derivative was asked for
    trace = 0
    if m:
        assert lu is not None and perm is not None
        for a in range(m):
            column = [dD[n + r][n + a] for r in range(m)]
            if any(not exact_zero(x) for x in column):
                trace += lu_solve(lu, perm, column)[a]
        # R = dD_ic - dD_ii X, then dX = D_ii^-1 R
        dDX = product(dD, X, inside, wheels, inside)
        R = [[dD[n + a][c] - dDX[a][c] for c in wheels] for a in range(m)]
        dcols = [lu_solve(lu, perm, [R[a][c] for a in range(m)]) for c in wheels]
        dX = [[0] * n for _ in range(n)] + [[dcols[c][a] for c in wheels] for a in range(m)]
        first, second = product(dD, X, wheels, wheels, inside), product(D, dX, wheels, wheels, inside)
        dS = [[dD[r][c] - first[r][c] - second[r][c] for c in wheels] for r in wheels]
    else:
        dS = [[dD[r][c] for c in wheels] for r in wheels]
    dB = coupled_derivative(S, Kmat, ops, dD=dS, dG=dKmat)
    for c in wheels:
        trace += lu_solve(luB, permB, [dB[r][c] for r in wheels])[c]
    return E, E * trace
