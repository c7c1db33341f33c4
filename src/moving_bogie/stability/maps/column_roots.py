"""Locating the unstable roots of a column once their number is known (:mod:`column_count`).

Newton's method on E_chr (Eq. (38)) is started, in turn, from the neighbouring column's roots
(continuation in alpha), from the places on the real axis where a root just below (or above) it shows
(|E| dips, the refinement of the count went deep), from the neighbouring theta's roots, and from the
Delves-Lyness roots of a rectangle: the power sums s_m = (1/2 pi i) contour-integral of q^m E'/E dq over
its boundary (Gauss-Legendre panels on the right half, the left half from E(-conj q) = conj E(q)) are the
power sums of the roots inside, which are then the zeros of a polynomial (Newton's identities).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np

from moving_bogie.kernels.sweep_characteristic import SweepCharacteristic
from moving_bogie.stability.maps.column_count import BoxCount, horner_rows
from moving_bogie.typing import ComplexArray, FloatArray

__all__ = [
    "delves_lyness",
    "dip_candidates",
    "from_power_sums",
    "locate_roots",
    "located",
    "polish_roots",
    "rectangle_sums",
]


def rectangle_sums(
    coeffs: Callable[[ComplexArray], tuple[ComplexArray, ComplexArray]],
    t: FloatArray,
    X: float,
    Y: float,
    top: float,
    *,
    panel: float = 0.05,
    nodes: int = 16,
    adaptive: bool = False,
) -> Callable[[int, int], complex]:
    """``s(j, m)``: the power sum s_m = (1/2 pi i) contour-integral of q^m E'/E dq of the roots inside
    -X..X x -Y..top for the j-th t (Gauss-Legendre panels on the right half, the left half from
    E(-conj q) = conj E(q)); s(j, 0) is the argument principle's count.

    ``coeffs(z)`` returns the coefficients in t of E and of dE/dq at the points z. With ``adaptive`` a
    panel is halved until E'/E is resolved on it (:func:`_resolved_panels`): a root at the distance d from
    a panel of width w limits the rule's accuracy to about rho^(-2 nodes), rho = a + sqrt(a^2 + 1),
    a = 2 d / w (the Bernstein ellipse through the pole), so a root near an edge needs narrow panels there.
    """
    x, w = np.polynomial.legendre.leggauss(nodes)
    ends = []
    for a, b in (
        (complex(0, -Y), complex(X, -Y)),
        (complex(X, -Y), complex(X, top)),
        (complex(X, top), complex(0, top)),
    ):
        n = max(1, int(np.ceil(abs(b - a) / panel)))
        ends += [(a + (b - a) * k / n, a + (b - a) * (k + 1) / n) for k in range(n)]
    z, wz, g = _resolved_panels(coeffs, t, np.array(ends), x, w, levels=16 if adaptive else 0)

    sums: dict[int, ComplexArray] = {}  # power m -> s_m of every t, computed on the first call for m

    def s(j: int, m: int) -> complex:
        if m not in sums:
            right = np.sum(z**m * g * wz, axis=-1)
            left = np.sum((-np.conj(z)) ** m * (-np.conj(g)) * np.conj(wz), axis=-1)
            sums[m] = (right + left) / (2j * np.pi)
        return complex(sums[m][j])

    return s


def _resolved_panels(
    coeffs: Callable[[ComplexArray], tuple[ComplexArray, ComplexArray]],
    t: FloatArray,
    ends: ComplexArray,
    x: FloatArray,
    w: FloatArray,
    levels: int,
    tol: float = 1e-5,
) -> tuple[ComplexArray, ComplexArray, ComplexArray]:
    """Nodes, weights and E'/E (one row per t) of Gauss-Legendre panels from ``ends`` (pairs of complex
    ends), each halved, up to ``levels`` times, while the last two Legendre coefficients of E'/E on it,
    times its half-width, exceed ``tol`` for some t (the rule's error is about their square)."""
    tail = np.linalg.inv(np.polynomial.legendre.legvander(x, len(x) - 1))[-2:]
    zs, ws, gs = [], [], []
    for level in range(levels + 1):
        a, b = ends[:, 0:1], ends[:, 1:2]
        z, wz = a + (b - a) * (x + 1) / 2, (b - a) / 2 * w
        c, dc = coeffs(z.ravel())
        g = (horner_rows(dc, t[:, None]) / horner_rows(c, t[:, None])).reshape(len(t), *z.shape)
        size = np.abs(np.einsum("kn,jpn->jpk", tail, g)).max(axis=(0, 2)) * np.abs(b - a)[:, 0] / 2
        split = ~(size <= tol) if level < levels else np.zeros(len(ends), dtype=bool)
        zs.append(z[~split].ravel())
        ws.append(wz[~split].ravel())
        gs.append(g[:, ~split].reshape(len(t), -1))
        if not split.any():
            break
        mid = ends[split].mean(axis=1)
        halves = (np.stack([ends[split, 0], mid], axis=1), np.stack([mid, ends[split, 1]], axis=1))
        ends = np.concatenate(halves)
    return np.concatenate(zs), np.concatenate(ws), np.concatenate(gs, axis=1)


def delves_lyness(
    coeffs: Callable[[ComplexArray], tuple[ComplexArray, ComplexArray]],
    t: FloatArray,
    X: float,
    Y: float,
    top: float,
    *,
    panel: float = 0.05,
    nodes: int = 16,
    max_roots: int = 8,
) -> list[list[complex]]:
    """Roots inside -X..X x -Y..top for each t (Delves-Lyness, :func:`rectangle_sums`), or an empty list
    where that fails.

    ``coeffs(z)`` returns the coefficients in t of E and of dE/dq at the points z; a failure is a count
    that is not an integer, or more than ``max_roots`` roots.
    """
    s = rectangle_sums(coeffs, t, X, Y, top, panel=panel, nodes=nodes)
    out: list[list[complex]] = []
    for j in range(len(t)):
        inside = s(j, 0).real
        if abs(inside - round(inside)) > 1e-3 or not 0 < round(inside) <= max_roots:
            out.append([])
            continue
        out.append(located(s, j, int(round(inside))))
    return out


def located(s: Callable[[int, int], complex], j: int, n: int) -> list[complex]:
    """The n roots whose power sums are s(j, 1..n) (:func:`from_power_sums`)."""
    return list(from_power_sums(np.array([s(j, m) for m in range(1, n + 1)])))


def from_power_sums(s: ComplexArray) -> np.ndarray:
    """Roots of the monic polynomial whose roots have power sums s[0..n-1] (Newton's identities)."""
    n = len(s)
    e = [1.0 + 0j]
    for k in range(1, n + 1):
        e.append(sum((-1) ** (i - 1) * e[k - i] * s[i - 1] for i in range(1, k + 1)) / k)
    coeffs = [(-1) ** k * e[k] for k in range(n + 1)]
    return np.roots(coeffs) if n > 0 else np.zeros(0, dtype=complex)


def dip_candidates(box: BoxCount, j: int, limit: int = 10) -> list[complex]:
    """Starting points below the places of the top edge where a root near the real axis shows."""
    zr = box.path[box.n_outer :]
    mag = np.abs(box.E[j, box.n_outer :])
    inner = np.nonzero((mag[1:-1] < mag[:-2]) & (mag[1:-1] < mag[2:]))[0] + 1
    chosen: list[complex] = []
    out: list[complex] = []
    for z_ in list(zr[inner[np.argsort(mag[inner])][:limit]]) + box.near_axis[j][::-1]:
        if len(chosen) >= limit:
            break
        if all(abs(z_ - c) > 0.002 for c in chosen):
            chosen.append(z_)
            out += [z_ - 0.002j, z_ - 0.01j, z_ - 1e-4j]
    return out


def locate_roots(
    sweep: SweepCharacteristic,
    alpha: float,
    thetas: FloatArray,
    cands: Sequence[Sequence[complex]],
    count: np.ndarray,
    steps: int,
    spread: bool = True,
) -> list[ComplexArray]:
    """Polish the candidates of every cell at once; with ``spread``, cells still short of roots then
    borrow the roots of the nearest complete cell (continuation in theta), front by front."""
    roots = [np.zeros(0, dtype=complex) for _ in thetas]
    tried: dict[int, set[int]] = {}
    for _ in range(len(thetas) + 1):
        owner = np.concatenate([np.full(len(c), j) for j, c in enumerate(cands)]).astype(int)
        flat = np.array([x for c in cands for x in c], dtype=complex)
        if flat.size:
            flat = polish_roots(sweep, flat, alpha, thetas[owner], steps)
        for j in set(owner.tolist()):
            r = list(roots[j]) + [x for x in flat[owner == j] if np.isfinite(x) and x.imag < 0]
            keep: list[complex] = []
            for x in r:
                x = -np.conj(x) if x.real < 0 else x
                if all(abs(x - y) > 1e-7 * max(1.0, abs(x)) for y in keep):
                    keep.append(x)
            roots[j] = np.array(sorted(keep, key=lambda x: x.imag), dtype=complex)
        complete = np.array([len(r) >= c for r, c in zip(roots, count)])
        spread_to: list[list[complex]] = [[] for _ in thetas]
        for j in np.nonzero(~complete)[0].tolist():
            for nb in (j - 1, j + 1):
                if 0 <= nb < len(thetas) and complete[nb] and count[nb] > 0 and nb not in tried.get(j, ()):
                    spread_to[j] += list(roots[nb])
                    tried.setdefault(j, set()).add(nb)
        cands = spread_to
        if not spread or not any(cands):
            break
    return roots


def polish_roots(
    sweep: SweepCharacteristic,
    q: ComplexArray,
    alpha: float,
    thetas: FloatArray,
    steps: int,
    tol: float = 1e-11,
) -> ComplexArray:
    """Newton on E_chr for every (q, theta) pair; non-converged entries come back as nan."""
    q = q.astype(complex)
    done = np.zeros(q.shape, dtype=bool)
    for _ in range(steps):
        todo = ~done & np.isfinite(q)
        if not np.any(todo):
            break
        E, dE = sweep.e_and_dq(q[todo], np.full(int(todo.sum()), alpha), thetas[todo])
        with np.errstate(all="ignore"):
            step = E / dE
        ok = np.isfinite(step) & (np.abs(step) < 0.1)
        qt = np.where(ok, q[todo] - step, np.nan)
        q[todo] = qt
        done[todo] = ok & (np.abs(step) < tol * np.maximum(1.0, np.abs(qt)))
    return np.where(done, q, np.nan)
