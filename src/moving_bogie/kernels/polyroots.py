"""Batched polynomial roots in double precision (numpy), shared by the kernel, the cut and the sweeps.

The roots of N(p, q) in p are needed at every point of every counting contour, so this is the hot path of
the induced-frequency search: a closed-form quartic with a polishing sweep is several times faster than
companion-matrix eigenvalues and as accurate for simple roots. Any other degree (a layered track gives
N of degree 6 in p) goes through batched companion-matrix eigenvalues polished by Newton's method on the
original polynomial.
"""

from __future__ import annotations

import cmath
from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike

from moving_bogie.typing import Scalar

__all__ = [
    "companion_roots",
    "newton_polish",
    "poly_roots",
    "polyder",
    "polyval",
    "quartic_roots",
    "stack_coefficients",
]


def _resolvent(a: Scalar, b: Scalar, cc: Scalar, d: Scalar) -> tuple[Scalar, Scalar, Scalar, Scalar, Scalar]:
    """Ferrari's reduction of the monic x^4 + a x^3 + b x^2 + cc x + d (arrays or numbers): x = y - a/4
    gives y^4 + p y^2 + q y + r, whose resolvent cubic m^3 + p m^2 + (p^2/4 - r) m - q^2/8 = 0 is depressed
    by m = u - p/3 to u^3 + P3 u + Q3. Returns (a/4, p, q, P3, Q3)."""
    a4 = a / 4
    a2 = a4 * a4
    p = b - 6 * a2
    q = cc - 2 * b * a4 + 8 * a2 * a4
    r = d - cc * a4 + b * a2 - 3 * a2 * a2
    C, D = p * p / 4 - r, -q * q / 8
    P3 = C - p * p / 3
    Q3 = 2 * p**3 / 27 - p * C / 3 + D
    return a4, p, q, P3, Q3


def quartic_roots(c: ArrayLike) -> np.ndarray:
    """Roots of quartics ``c[..., 0] x^4 + ... + c[..., 4]`` (shape ``(..., 4)``), vectorised.

    Ferrari's closed form (the resolvent-cubic root of largest modulus, for stability), then two
    Durand-Kerner sweeps on the original polynomial, which restore full double precision for simple
    roots and do not let two approximations collapse onto one root.
    """
    c = np.asarray(c, dtype=complex)
    if c.shape[:-1] and c[..., 0].size <= _SCALAR_BATCH and np.all(np.isfinite(c)) and np.all(c[..., 0]):
        # a handful of quartics (continuation steps, one point at a time): numpy's per-call cost on
        # arrays this small is ten times the arithmetic; the same formulas on Python complex numbers
        flat = c.reshape(-1, 5).tolist()
        return np.array([_quartic_one(*row) for row in flat], dtype=complex).reshape(c.shape[:-1] + (4,))
    a, b, cc, d = (c[..., k] / c[..., 0] for k in range(1, 5))
    a4, p, q, P3, Q3 = _resolvent(a, b, cc, d)
    disc = np.sqrt(Q3 * Q3 / 4 + P3**3 / 27)
    s1, s2 = -Q3 / 2 + disc, -Q3 / 2 - disc
    u1 = np.where(np.abs(s1) >= np.abs(s2), s1, s2) ** (1 / 3)
    cubic_roots = []
    for k in range(3):
        uk = u1 * np.exp(2j * np.pi * k / 3)
        with np.errstate(all="ignore"):
            cubic_roots.append(np.where(uk != 0, uk - P3 / (3 * np.where(uk != 0, uk, 1)), 0) - p / 3)
    ms = np.stack(cubic_roots, -1)
    m = np.take_along_axis(ms, np.argmax(np.abs(ms), -1)[..., None], -1)[..., 0]
    sm = np.sqrt(2 * m)
    with np.errstate(all="ignore"):
        t = np.where(sm != 0, q / np.where(sm != 0, sm, 1), 0)
    # y^4 + p y^2 + q y + r = (y^2 + sm y + e1)(y^2 - sm y + e2)
    e1, e2 = p / 2 + m - t / 2, p / 2 + m + t / 2
    d1, d2 = np.sqrt(sm * sm - 4 * e1), np.sqrt(sm * sm - 4 * e2)
    z = np.stack([(-sm + d1) / 2, (-sm - d1) / 2, (sm + d2) / 2, (sm - d2) / 2], -1) - a4[..., None]
    a, b, cc, d = a[..., None], b[..., None], cc[..., None], d[..., None]
    for _ in range(2):
        val = (((z + a) * z + b) * z + cc) * z + d
        with np.errstate(all="ignore"):
            step = val / _products_of_differences(z)
        z = np.where(np.isfinite(step), z - step, z)
    return z


def _products_of_differences(z: np.ndarray) -> np.ndarray:
    """prod_{j != i} (z_i - z_j) for each of the four ``z[..., i]``, the factors in the order j = 0..3 (the
    Durand-Kerner denominators): each difference is computed once and its negative reused (exact)."""
    z0, z1, z2, z3 = (z[..., k] for k in range(4))
    d01, d02, d03, d12, d13, d23 = z0 - z1, z0 - z2, z0 - z3, z1 - z2, z1 - z3, z2 - z3
    out = np.empty_like(z)
    out[..., 0] = d01 * d02 * d03
    out[..., 1] = -d01 * d12 * d13
    out[..., 2] = -d02 * -d12 * d23
    out[..., 3] = -d03 * -d13 * -d23
    return out


#: Batches of at most this many quartics go through :func:`_quartic_one` (Python complex arithmetic).
_SCALAR_BATCH = 8


def _quartic_one(c0: complex, c1: complex, c2: complex, c3: complex, c4: complex) -> list[complex]:
    """:func:`quartic_roots` of one quartic (finite coefficients, c0 != 0), the same steps on Python
    complex numbers: the roots agree with the batched ones to rounding (about 1e-16 relative)."""
    a, b, cc, d = c1 / c0, c2 / c0, c3 / c0, c4 / c0
    a4, p, q, P3, Q3 = _resolvent(a, b, cc, d)
    disc = cmath.sqrt(Q3 * Q3 / 4 + P3**3 / 27)
    s1, s2 = -Q3 / 2 + disc, -Q3 / 2 - disc
    u1 = (s1 if abs(s1) >= abs(s2) else s2) ** (1 / 3)
    ms: list[complex] = []
    for k in range(3):
        uk = u1 * cmath.exp(2j * cmath.pi * k / 3)
        ms.append((uk - P3 / (3 * uk) if uk != 0 else 0) - p / 3)
    m = max(ms, key=abs)
    sm = cmath.sqrt(2 * m)
    t = q / sm if sm != 0 else 0
    e1, e2 = p / 2 + m - t / 2, p / 2 + m + t / 2
    d1, d2 = cmath.sqrt(sm * sm - 4 * e1), cmath.sqrt(sm * sm - 4 * e2)
    z = [(-sm + d1) / 2 - a4, (-sm - d1) / 2 - a4, (sm + d2) / 2 - a4, (sm - d2) / 2 - a4]
    for _ in range(2):
        steps = []
        for i, zi in enumerate(z):
            val = (((zi + a) * zi + b) * zi + cc) * zi + d
            den = 1
            for j, zj in enumerate(z):
                if j != i:
                    den *= zi - zj
            step = val / den if den != 0 else 0  # no step where the batched one is not finite either
            steps.append(step if cmath.isfinite(step) else 0)
        z = [zi - st for zi, st in zip(z, steps)]
    return z


def poly_roots(coeffs: ArrayLike) -> np.ndarray:
    """Roots of polynomials given by ``coeffs[..., :]`` (highest first), batched.

    Degree 2: the stable quadratic formula; 4: :func:`quartic_roots`; others: companion eigenvalues.
    Where the leading coefficient is exactly zero the degree drops: the roots of the lower-degree
    polynomial and a root at infinity (a nan entry, which callers discard). Non-finite coefficients give
    nan entries only.
    """
    coeffs = np.asarray(coeffs, dtype=complex)
    deg = coeffs.shape[-1] - 1
    finite = np.all(np.isfinite(coeffs), axis=-1)
    drop = (coeffs[..., 0] == 0) & finite & np.any(coeffs[..., 1:] != 0, axis=-1)
    if deg > 1 and np.any(drop):
        # the degree drops where the leading coefficient vanishes (e.g. alpha = 0 on a layered track):
        # the roots of the lower-degree polynomial, and one root at infinity (nan)
        roots = poly_roots(np.where(drop[..., None], 1.0, coeffs))
        low = poly_roots(coeffs[drop][..., 1:])
        roots[drop] = np.concatenate([low, np.full(low.shape[:-1] + (1,), np.nan + 0j)], axis=-1)
        return roots
    with np.errstate(divide="ignore", invalid="ignore"):
        monic = coeffs[..., 1:] / coeffs[..., :1]
    bad = ~np.all(np.isfinite(monic), axis=-1)
    monic = np.where(bad[..., None], 0, monic)
    if deg == 1:
        roots = -monic
    elif deg == 2:
        b, c = monic[..., 0], monic[..., 1]
        s = np.sqrt(b * b - 4 * c)
        r1 = np.where(np.real(np.conj(b) * s) >= 0, -(b + s) / 2, -(b - s) / 2)
        with np.errstate(divide="ignore", invalid="ignore"):
            r2 = np.where(r1 != 0, c / np.where(r1 != 0, r1, 1), -b - r1)
        roots = np.stack([r1, r2], axis=-1)
    elif deg == 4:
        roots = quartic_roots(np.concatenate([np.ones(monic.shape[:-1] + (1,)), monic], axis=-1))
    else:
        roots = _companion(coeffs, monic)
    return np.where(bad[..., None], np.nan, roots)


def companion_roots(coeffs: ArrayLike) -> np.ndarray:
    """Roots by (balanced) companion-matrix eigenvalues polished by Newton's method, any degree, batched.

    Slower than :func:`quartic_roots` but backward stable, also when the roots differ by many orders of
    magnitude (where the closed form loses the small ones). Leading coefficients must not vanish.
    """
    coeffs = np.asarray(coeffs, dtype=complex)
    return _companion(coeffs, coeffs[..., 1:] / coeffs[..., :1])


#: Batches larger than this are solved in levels (contour points come in order, neighbours have nearby
#: roots): companion eigenvalues at every ``_LEVELS[0]``-th polynomial of the batch (flattened order), then
#: Aberth's iteration at every ``_LEVELS[1]``-th, then at all the others, each started from the roots of
#: the nearest rows already solved on either side (interpolated linearly when both match one to one).
_ANCHOR_BATCH = 64
_LEVELS = (32, 8, 1)
_ABERTH_STEPS = 16
_BACKWARD = 4e-15


def _companion(coeffs: np.ndarray, monic: np.ndarray) -> np.ndarray:
    """Companion eigenvalues (polished), in levels for a large batch (:func:`_anchored`)."""
    if monic.ndim > 1 and monic[..., 0].size > _ANCHOR_BATCH:
        return _anchored(coeffs, monic)
    return _eigen(coeffs, monic)


def _anchored(coeffs: np.ndarray, monic: np.ndarray) -> np.ndarray:
    """Eigenvalues at every ``_LEVELS[0]``-th polynomial of the batch, Aberth's simultaneous iteration from
    the solved neighbours for the rest, level by level (:data:`_LEVELS`). A row is done when every root has
    converged (relative step 1e-14) or has a backward error at rounding level (``_BACKWARD``: |P(z)|
    against sum |c_k| |z|^k, the accuracy the eigenvalues reach; ill-conditioned roots, a near coalescence,
    never reach the relative step), and its roots add up to -c_1 (Vieta: no root reached twice while
    another is missed); any other row (a start too far from its roots) gets its own eigenvalues."""
    shape = monic.shape
    deg = shape[-1]
    flat_c = coeffs.reshape(-1, deg + 1)
    flat_m = monic.reshape(-1, deg)
    n = flat_m.shape[0]
    solved = np.zeros(n, dtype=bool)  # the rows solved so far (a mask: no set operations on indices)
    solved[:: _LEVELS[0]] = solved[n - 1] = True
    known = np.flatnonzero(solved)
    roots = np.empty((n, deg), dtype=complex)
    roots[known] = _eigen(flat_c[known], flat_m[known])
    for every in _LEVELS[1:]:
        rows = np.arange(0, n, every)
        rows = rows[~solved[rows]]
        if not rows.size:
            continue
        mc = np.concatenate([np.ones((rows.size, 1)), flat_m[rows]], axis=-1)
        z, done = _aberth(mc, _starts(roots, known, rows))
        roots[rows[done]] = z[done]
        failed = rows[~done]
        if failed.size:
            roots[failed] = _eigen(flat_c[failed], flat_m[failed])
        solved[rows] = True
        known = np.flatnonzero(solved)
    return roots.reshape(shape)


def _starts(roots: np.ndarray, known: np.ndarray, rows: np.ndarray) -> np.ndarray:
    """Starting roots for ``rows``: those of the nearest solved row before it, moved linearly towards those
    of the nearest solved row after it where the two sets match one to one (nearest neighbours)."""
    pos = np.searchsorted(known, rows) - 1  # rows are not in known: known[pos] < row < known[pos + 1]
    a, b = known[pos], known[np.minimum(pos + 1, known.size - 1)]
    za, zb = roots[a], roots[b]
    order = np.argmin(np.abs(za[:, :, None] - zb[:, None, :]), axis=-1)
    match = np.all(np.sort(order, axis=-1) == np.arange(za.shape[1]), axis=-1) & (b > rows)
    t = ((rows - a) / np.maximum(b - a, 1))[:, None]
    moved = za + t * (np.take_along_axis(zb, order, axis=-1) - za)
    with np.errstate(invalid="ignore"):
        return np.where(match[:, None] & np.isfinite(moved), moved, za)


def _aberth(mc: np.ndarray, z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Aberth's iteration on the monic polynomials ``mc`` from ``z``; (roots, rows accepted)."""
    dc = polyder(mc)
    bound_c = np.abs(mc)
    active = np.arange(z.shape[0])
    done = np.zeros(z.shape[0], dtype=bool)
    with np.errstate(all="ignore"):
        for _ in range(_ABERTH_STEPS):
            za, ca, da = z[active], mc[active], dc[active]
            val = polyval(ca, za)
            ratio = val / polyval(da, za)
            w = ratio / (1.0 - ratio * inverse_distances(za))
            small = (np.abs(w) <= 1e-14 * np.maximum(1.0, np.abs(za))) | (
                np.abs(val) <= _BACKWARD * polyval(bound_c[active], np.abs(za)).real
            )
            za = za - w
            z[active] = za
            total = np.abs(za.sum(axis=-1) + ca[:, 1])
            vieta = total <= 1e-10 * np.maximum(1.0, np.abs(za).sum(axis=-1))
            ok = np.all(np.isfinite(za) & small, axis=-1) & vieta
            done[active[ok]] = True
            active = active[~ok]
            if not active.size:
                break
    return z, done


def inverse_distances(z: np.ndarray) -> np.ndarray:
    """sum over j != i of 1 / (z_i - z_j), for every root z_i of every row of ``z`` (n, deg): the repulsion
    term of Aberth's iteration. One column j at a time over contiguous (n, deg) arrays, its own term i = j
    set to 0, summed in a fixed order: four partial sums over the columns j = 0, 1, 2, 3 (mod 4) of the
    first multiple of four, (s_0 + s_1) + (s_2 + s_3), then the remaining columns in turn (fewer than
    four columns: in turn). That is numpy's pairwise order along a row of at most 64 entries, so the
    (n, deg, deg) matrix of distances summed along its rows gives the same values, bit for bit."""
    deg = z.shape[-1]
    with np.errstate(divide="ignore", invalid="ignore"):
        columns = [1.0 / (z - z[:, j : j + 1]) for j in range(deg)]
    for j, column in enumerate(columns):
        column[:, j] = 0
    if deg < 4:
        total = columns[0]
        for column in columns[1:]:
            total += column
        return total
    four = deg - deg % 4
    partial = columns[:4]  # summed into in place (each column is a new array)
    for i in range(4, four, 4):
        for k in range(4):
            partial[k] += columns[i + k]
    total = partial[0] + partial[1]
    total += partial[2] + partial[3]
    for column in columns[four:]:
        total += column
    return total


def _eigen(coeffs: np.ndarray, monic: np.ndarray) -> np.ndarray:
    """Eigenvalues of the companion matrices of ``monic``, polished on ``coeffs`` (:func:`newton_polish`)."""
    deg = coeffs.shape[-1] - 1
    comp = np.zeros(coeffs.shape[:-1] + (deg, deg), dtype=complex)
    comp[..., 0, :] = -monic
    idx = np.arange(deg - 1)
    comp[..., idx + 1, idx] = 1
    return newton_polish(coeffs, np.linalg.eigvals(comp))


def newton_polish(coeffs: np.ndarray, roots: np.ndarray, steps: int = 2) -> np.ndarray:
    """A few batched Newton steps on every root (``coeffs (..., n+1)``, ``roots (..., n)``).

    Companion eigenvalues carry a backward error of order machine epsilon times the norm of the
    companion matrix; two Newton steps on the original polynomial restore full relative precision for
    simple roots. A step that is not finite or that does not decrease |P| is not taken.
    """
    deriv = polyder(coeffs)
    z = roots
    for _ in range(steps):
        with np.errstate(all="ignore"):
            val = polyval(coeffs, z)
            step = val / polyval(deriv, z)
            new = z - step
            better = np.isfinite(new) & (np.abs(polyval(coeffs, new)) <= np.abs(val))
        z = np.where(better, new, z)
    return z


def stack_coefficients(coeffs: Sequence[Scalar], shape: Sequence[int]) -> np.ndarray:
    """Generated coefficient tuples (scalars or arrays) -> complex array ``shape + (n+1,)``, highest first."""
    out = np.empty(tuple(shape) + (len(coeffs),), dtype=complex)
    for k, c in enumerate(coeffs):
        out[..., k] = c
    return out


def polyval(coeffs: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Batched Horner (the steps of :func:`moving_bogie.kernels.polynomial.horner`, on arrays, in place):
    coeffs ``(..., n+1)`` highest first, x ``(..., k)`` -> ``(..., k)``; complex unless both are real (the
    bounds sum |c_j| |x|^j of the backward-error tests)."""
    dtype = complex if np.iscomplexobj(coeffs) or np.iscomplexobj(x) else float
    n = coeffs.shape[-1]
    if n == 1:
        return np.multiply(coeffs[..., :1], np.ones_like(x, dtype=dtype), dtype=dtype)
    # c0 x + c1 first (it allocates the broadcast result), then the same Horner steps in place: the same
    # roundings as from acc = c0, without the shape computation (this is called ~10^4 times per search)
    acc = np.multiply(coeffs[..., :1], x, dtype=dtype)
    acc += coeffs[..., 1:2]
    for j in range(2, n):
        acc *= x
        acc += coeffs[..., j : j + 1]
    return acc


def polyder(coeffs: np.ndarray) -> np.ndarray:
    """Batched derivative of coefficient arrays ``(..., n+1)`` (highest first)."""
    n = coeffs.shape[-1] - 1
    if n == 0:
        return np.zeros_like(coeffs)
    return coeffs[..., :-1] * np.arange(n, 0, -1)
