"""Degree of a vehicle's E_chr in each of its parameters, from the block system (Eq. (38) for n wheels).

The stability tools sweep one vehicle parameter theta at fixed (q, alpha) by interpolating E_chr exactly in
theta (``kernels/sweep_characteristic.py``): E_chr = det [[pi I + 2 Kmat D_cc, 2 Kmat D_ci], [D_ic, D_ii]]
is a polynomial in theta because every entry of D = -q^2 M + i q C + K is linear in the vehicle's groups (the
alternatives of Eq. (63), mu_v = cf1 eta_M and J_b = cf2 eta_M d^2, held). Its degree is that of the
determinant with every other quantity (q, the kernel values at the distinct contact offsets, pi, the other
groups, cf1, cf2) replaced by fixed pseudo-random complex rationals: a generic point, at which the leading
coefficient (a nonzero polynomial in those quantities) does not vanish. The result is exact rational
arithmetic, so the degree is never under-estimated by rounding; a degree below the generic one would need
the random point to lie on an algebraic set of measure zero.

A group that moves a contact point (d, L_c) also moves K(xi_i - xi_j, q) and is not swept this way.

``follow=False`` gives the degrees with the groups an alternative sets held fixed instead (mu_v and J_b do not
follow eta_M: a sweep in SI units over the wheel mass M keeps the frame's M_b and J_b), every group then an
independent constant (``FIXED_POLYNOMIAL_DEGREES``).
"""

import random

import sympy as sp
from sympy.polys.matrices import DomainMatrix

from . import symbols as s

SEED = 21  # fixed, so that regeneration is reproducible


def block_degrees(matrices, follow: bool = True) -> dict:
    """``{group: degree of E_chr in it}`` for every group that places no contact and (with ``follow``, the
    alternatives of Eq. (63) substituted) that no alternative sets; without ``follow`` every group that places
    no contact, the others held fixed."""
    rng = random.Random(SEED)

    def number():
        return sp.Rational(rng.randint(1, 997), rng.randint(1, 997)) + sp.I * sp.Rational(
            rng.randint(1, 997), rng.randint(1, 997)
        )

    held = {group: expr for group, expr, _ in s.ALTERNATIVES.values() if group in matrices.parameters}
    moving = set()
    for x in matrices.positions:
        moving |= sp.sympify(x).free_symbols
    n, total = matrices.contacts, len(matrices.dofs)
    offsets = {}
    Kmat = sp.zeros(n, n)
    for i in range(n):
        for j in range(n):
            key = sp.expand(matrices.positions[i] - matrices.positions[j])
            if key not in offsets:
                offsets[key] = number()
            Kmat[i, j] = offsets[key]
    D = matrices.dynamic_stiffness()
    if follow:
        D = D.subs(held)
    else:
        held = {}
    alternatives = sorted(
        {c for expr in held.values() for c in expr.free_symbols} - set(matrices.parameters), key=str
    )
    values = {x: number() for x in (s.q, *matrices.parameters, *alternatives)}
    pi = number()
    out = {}
    for par in matrices.parameters:
        if par in moving or par in held:
            continue
        theta = sp.Symbol("theta")
        # numbers for symbols, all at once (xreplace): the same as one after the other
        Dp = D.xreplace({x: v for x, v in values.items() if x != par} | {par: theta})
        A = sp.zeros(total, total)
        A[:n, :] = 2 * Kmat * Dp[:n, :]
        A[:n, :n] += pi * sp.eye(n)
        A[n:, :] = Dp[n:, :]
        out[str(par)] = _degree(A, theta)

    return out


def _degree(A, theta) -> int:
    """Degree in ``theta`` of det A (entries polynomial in theta, Gaussian-rational coefficients), exactly.

    det A has degree at most ``bound``, the sum over the rows of their largest entry degree. Its values at
    theta = 0, 1, ..., bound (determinants of Gaussian-rational matrices, exact) determine it, and its degree
    is the largest k whose divided difference f[0, ..., k] (the coefficient of the Newton basis polynomial of
    degree k) is not zero. Many small exact determinants cost far less than one in QQ_I[theta]."""
    ring = sp.QQ_I[theta]
    n = A.shape[0]
    rows = [[ring.from_sympy(A[i, j]) for j in range(n)] for i in range(n)]
    bound = sum(max((e.degree() for e in row if e), default=0) for row in rows)
    values = []
    for x in range(bound + 1):
        at = [[e(x) if e else sp.QQ_I.zero for e in row] for row in rows]
        values.append(DomainMatrix(at, (n, n), sp.QQ_I).det())
    differences = list(values)
    for k in range(1, bound + 1):  # in place: differences[i] becomes f[i-k, ..., i]
        for i in range(bound, k - 1, -1):
            differences[i] = (differences[i] - differences[i - 1]) / sp.QQ_I(k)
    degree = max((k for k, c in enumerate(differences) if c), default=None)
    if degree is None:
        raise ValueError("E_chr vanishes identically in this parameter at the generic point")
    return degree
