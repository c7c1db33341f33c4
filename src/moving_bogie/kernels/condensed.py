"""E_chr of a vehicle on n wheels with its internal DOFs eliminated first (the block system of Eq. (38)
condensed to its wheels), and dE_chr/dq by Jacobi's formula (Eq. (40)), at one q in mpmath.

The block system of :mod:`moving_bogie.kernels.vehicle` is [[pi I + 2 Kmat D_cc, 2 Kmat D_ci], [D_ic, D_ii]]
(c: the n wheels, i: the vehicle's internal DOFs). D_ii, the vehicle with its wheels held, does not involve
the track, so its Schur complement is an n x n system, and an evaluation costs a small elimination of
D_ii and one of the wheel system instead of one of the whole block system.
"""

from __future__ import annotations

import mpmath

from moving_bogie.kernels.elimination import exact_zero, lu_factor, lu_solve


def condensed_characteristic(D, dD, Kmat, dKmat=None):
    """(E_chr, dE_chr/dq or None) of the block system with the internal DOFs eliminated first, or None.

    ``D``, ``dD`` (or None) are D(q) = -q^2 M + i q C + K and dD/dq (N x N, wheels first), ``Kmat``, ``dKmat``
    (or None) the n x n kernel matrices K(xi_i - xi_j, q) and dK/dq. With S = D_cc - D_ci D_ii^-1 D_ic (the
    vehicle's dynamic stiffness condensed to its wheels) and B = pi I + 2 Kmat S, det A = det D_ii det B
    exactly. With X = D_ii^-1 D_ic, Jacobi's formula gives dE/dq = E (tr(D_ii^-1 dD_ii) + tr(B^-1 dB)),
    dB = 2 dKmat S + 2 Kmat dS, dS = dD_cc - dD_ci X - D_ci D_ii^-1 (dD_ic - dD_ii X).

    Near a zero of det D_ii (a resonance of the held vehicle) S is large and the elimination loses about
    log10 of the ratio of the largest to the smallest pivot of D_ii in digits: it runs with that many guard
    digits plus 5 (at least 10), so that E keeps the accuracy of the elimination of the whole system. None
    where D_ii or B is singular to working precision: the caller then eliminates the whole system.
    """
    n, N = len(Kmat), len(D)
    m = N - n
    dps, guard, factors = mpmath.mp.dps, 10, (None, None, 1)
    while m:
        with mpmath.workdps(dps + guard):
            factors = lu_factor([row[n:] for row in D[n:]])
            if factors[2] == 0:
                return None
            pivots = [abs(factors[0][k][k]) for k in range(m)]
            loss = max(0, int(mpmath.log10(max(pivots) / min(pivots))))
        if loss + 5 <= guard:
            break
        guard = loss + 10
    with mpmath.workdps(dps + guard):
        out = _wheel_system(D, dD, factors, Kmat, dKmat)
    return None if out is None else tuple(None if x is None else +x for x in out)


def _wheel_system(D, dD, factors, Kmat, dKmat):
    """(det D_ii det B, its q-derivative or None) from the factors of D_ii (see condensed_characteristic)."""
    n, N = len(Kmat), len(D)
    m = N - n
    lu, perm, d = factors

    def product(P, Q, rows, cols, inner):  # sum_k P[r][k] Q[k][c], skipping exact zeros
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
        # X[a][c] = (D_ii^-1 D_ic)[a][c], a internal (indexed n..N-1 in the products below)
        cols = [lu_solve(lu, perm, [D[n + a][c] for a in range(m)]) for c in wheels]
        X = [[0] * n for _ in range(n)] + [[cols[c][a] for c in wheels] for a in range(m)]
        DX = product(D, X, wheels, wheels, inside)
        S = [[D[r][c] - DX[r][c] for c in wheels] for r in wheels]
    else:
        S = [[D[r][c] for c in wheels] for r in wheels]
    B = product(Kmat, S, wheels, wheels, wheels)
    B = [[2 * B[r][c] + (mpmath.pi if r == c else 0) for c in wheels] for r in wheels]
    luB, permB, b = lu_factor(B)
    E = d * b
    if dKmat is None:
        return E, None
    if b == 0:
        return None
    trace = 0
    if m:
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
    left, right = product(dKmat, S, wheels, wheels, wheels), product(Kmat, dS, wheels, wheels, wheels)
    dB = [[2 * (left[r][c] + right[r][c]) for c in wheels] for r in wheels]
    for c in wheels:
        trace += lu_solve(luB, permB, [dB[r][c] for r in wheels])[c]
    return E, E * trace
