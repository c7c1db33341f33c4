"""Quadrature shared by the branch-cut integrals (Eq. (35)) and the Bromwich reference.

Composite 16-point Gauss-Legendre panels (:func:`gauss_panels`, :func:`adapt_panels` and
:func:`adapt_panels_with_values`, :func:`subdivide`), bands of times that double (:func:`by_bands`),
and sum_n G_n e^{i q_n t} for many times t (:func:`fourier_sum`). Used by the Euler-Bernoulli cut (a
horizontal half-line, :mod:`branch_cut`), the traced cut of any model (:mod:`cut_integral`) and
:mod:`bromwich`.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike

__all__ = [
    "PANEL_PHASE",
    "PANEL_XI",
    "adapt_panels",
    "adapt_panels_with_values",
    "band_top",
    "by_bands",
    "cis",
    "equidistribute",
    "fourier_sum",
    "gauss_panels",
    "oscillation_rule",
    "subdivide",
    "uniform_step",
]

GL_X, GL_W = np.polynomial.legendre.leggauss(16)
#: Bands of times: [0, 1/2], (1/2, 1], (1, 2], ...: each band gets its own truncation and panels.
FIRST_BAND = 0.5
#: Phase per panel (radians) at the largest tau of its band; 16 Gauss-Legendre nodes integrate it to ~1e-14.
PANEL_PHASE = 3 * np.pi
#: Radians of e^{i p xi} per panel at the largest |xi| of a shape.
PANEL_XI = 2.0


def gauss_panels(a: ArrayLike, b: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Nodes and weights of the 16-point Gauss-Legendre rule on every panel [a_k, b_k] (flattened)."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    nodes = (0.5 * (b - a)[:, None] * GL_X + 0.5 * (a + b)[:, None]).ravel()
    return nodes, (0.5 * (b - a)[:, None] * GL_W).ravel()


def adapt_panels(
    start: ArrayLike, values: Callable[[np.ndarray], np.ndarray], tol: float, max_splits: int = 40
) -> np.ndarray:
    """Edges refining ``start``: a panel is halved while its integral of ``values`` (nodes -> (n, m))
    differs from the sum over its halves by more than ``tol``; resolves peaks far narrower than a panel."""
    return adapt_panels_with_values(start, values, tol, max_splits)[0]


def adapt_panels_with_values(
    start: ArrayLike,
    values: Callable[[np.ndarray], np.ndarray],
    tol: float,
    max_splits: int = 40,
    checked: int | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """(edges, the values at the Gauss nodes of the final panels, in the order of :func:`gauss_panels`
    of the edges) of :func:`adapt_panels`; only the first ``checked`` columns of ``values`` (all when
    None) enter the test, the others ride along (e.g. q at the nodes).

    Each pass evaluates the halves of the panels still open; a half's integral is the whole of the next
    pass (the halves of a panel are evaluated by the same calls as when every pass evaluated the whole
    too: first all left halves, then all right halves)."""
    start = np.asarray(start, dtype=float)
    n = GL_X.size

    def evaluate(a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        nodes, weights = gauss_panels(a, b)
        f = values(nodes)
        f = f.reshape(a.size, n, -1)
        return f, (f[..., :checked] * weights.reshape(a.size, n, 1)).sum(axis=1)

    lo, hi = start[:-1], start[1:]
    f, whole = evaluate(lo, hi)
    edges, done_lo, done_f = [start], [], []
    for _ in range(max_splits):
        if lo.size == 0:
            break
        mid = 0.5 * (lo + hi)
        f_left, left = evaluate(lo, mid)
        f_right, right = evaluate(mid, hi)
        bad = np.abs(whole - left - right).max(axis=-1) > tol
        edges.append(mid[bad])
        done_lo.append(lo[~bad])
        done_f.append(f[~bad])
        lo, hi = np.concatenate([lo[bad], mid[bad]]), np.concatenate([mid[bad], hi[bad]])
        f, whole = np.concatenate([f_left[bad], f_right[bad]]), np.concatenate([left[bad], right[bad]])
    done_lo.append(lo)  # panels still open after max_splits are final too
    done_f.append(f)
    order = np.argsort(np.concatenate(done_lo), kind="stable")
    return np.unique(np.concatenate(edges)), np.concatenate(done_f)[order].reshape(order.size * n, -1)


def subdivide(edges: np.ndarray, pieces: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Gauss nodes and weights after splitting panel k of ``edges`` into ``pieces[k]`` equal parts."""
    counts = np.maximum(1, np.asarray(pieces)).astype(int)
    k = np.repeat(np.arange(edges.size - 1), counts)
    j = np.arange(k.size) - np.repeat(np.cumsum(counts) - counts, counts)
    width = np.diff(edges) / counts
    lo = edges[:-1][k] + j * width[k]
    # the last part ends at the panel's edge exactly (the nodes of an undivided panel are its own)
    return gauss_panels(lo, np.where(j + 1 == counts[k], edges[1:][k], lo + width[k]))


def equidistribute(P: np.ndarray, density: np.ndarray) -> np.ndarray:
    """Edges on [P[0], P[-1]] (a fine grid P) with about unit integral of ``density`` (sampled on P) each."""
    cum = np.concatenate([[0.0], np.cumsum(0.5 * (density[1:] + density[:-1]) * np.diff(P))])
    return np.interp(np.linspace(0.0, cum[-1], max(1, int(np.ceil(cum[-1]))) + 1), cum, P)


def oscillation_rule(edges: np.ndarray, phase: np.ndarray, dp: float) -> tuple[np.ndarray, np.ndarray]:
    """:func:`subdivide` each panel into pieces spanning at most PANEL_PHASE of ``phase`` (its phase s tau
    per panel) and ``dp`` of its own length."""
    return subdivide(edges, np.ceil(np.maximum(np.abs(phase) / PANEL_PHASE, np.diff(edges) / dp)))


def by_bands(tau: ArrayLike, m: int, band: Callable[[float, np.ndarray], np.ndarray]) -> np.ndarray:
    """(1/pi) Re of ``band(lo, ts)`` over the bands of times, shape tau.shape + (m,).

    ``band(lo, ts)`` returns the complex integral (len(ts), m) for the times ``ts`` of one band, whose
    lower end is ``lo`` (0 for the first band).
    """
    tau = np.asarray(tau, dtype=float)
    flat = tau.reshape(-1)
    result = np.zeros((flat.size, m), dtype=complex)
    band_hi = FIRST_BAND * 2.0 ** np.ceil(np.log2(np.maximum(flat, FIRST_BAND) / FIRST_BAND))
    for hi in np.unique(band_hi):
        idx = np.nonzero(band_hi == hi)[0]
        result[idx] = band(0.0 if hi <= FIRST_BAND else hi / 2, flat[idx])
    return (result.real / np.pi).reshape(tau.shape + (m,))


def band_top(lo: float, ts: np.ndarray, rule_tau: ArrayLike | None) -> float:
    """The time that sets the panels of the band of :func:`by_bands` with lower end ``lo``, (lo, 2 lo]
    (``[0, FIRST_BAND]`` when lo = 0): the largest of ``ts`` and of the ``rule_tau`` in that band."""
    top = float(ts.max())
    if rule_tau is None:
        return top
    rule_tau = np.asarray(rule_tau, dtype=float)
    hi = 2 * lo if lo > 0 else FIRST_BAND
    same = rule_tau[(rule_tau > lo) & (rule_tau <= hi)] if lo > 0 else rule_tau[rule_tau <= hi]
    return max(top, float(same.max())) if same.size else top


#: Taylor terms of e^{i q delta} with |q delta| <= 1/4 (remainder below 1e-16 of the sum of |G|).
_TAYLOR_TERMS = 12
_GRID_BLOCK = 256


def cis(x: np.ndarray) -> np.ndarray:
    """e^{i x} for a real array x (cos and sin of real arguments are cheaper than a complex exp)."""
    out = np.empty(x.shape, dtype=complex)
    np.cos(x, out=out.real)
    np.sin(x, out=out.imag)
    return out


def _phases(t: np.ndarray, s: np.ndarray, eta: float | np.ndarray) -> np.ndarray:
    """e^{i (s + i eta) t} for the outer product of times t and real s (sin/cos of real arguments).

    ``eta`` is one number (a cut on a horizontal line) or an array like s (a curved cut).
    """
    out = cis(np.multiply.outer(t, s))
    if np.ndim(eta) == 0:
        out *= np.exp(-eta * t)[:, None]
    else:
        out *= np.exp(-np.multiply.outer(t, eta))
    return out


#: Fewer times than this take the exponentials of every time (no blocks).
_UNIFORM_MIN = 16
#: Complex entries of the phase tables per chunk of nodes (fits the cache better than ``memory``).
_CACHE_SIZED = 2**18


def uniform_step(ts: np.ndarray) -> float | None:
    """The step h when ``ts[k] = ts[0] + k h`` to rounding (8 ulps of the largest |t|), else None."""
    if ts.size < _UNIFORM_MIN:
        return None
    h = float(ts[-1] - ts[0]) / (ts.size - 1)
    if not h > 0:
        return None
    deviation = float(np.abs(ts - (ts[0] + np.arange(ts.size) * h)).max())
    return h if deviation <= 8 * np.finfo(float).eps * float(np.abs(ts).max()) else None


def _grid_parts(t0: float, h: float, count: int) -> tuple[np.ndarray, np.ndarray]:
    """(coarse, fine): t0 + j h = coarse[j // c] + fine[j % c] for j < count, c ~ sqrt(count) (to
    rounding: :func:`_grid_phases` takes these very numbers, :func:`_uniform_sum` their exact sum)."""
    c = int(np.ceil(np.sqrt(count)))
    return t0 + np.arange(-(-count // c)) * (c * h), np.arange(c) * h


def _grid_phases(t0: float, h: float, count: int, s: np.ndarray, eta: float | np.ndarray) -> np.ndarray:
    """e^{i (s + i eta) (coarse + fine)} of :func:`_grid_parts`, shape (count, len(s)): the products of
    the phases of the coarse and of the fine times, exponentials of 2 sqrt(count) times only (each
    product adds a rounding, far below that of the argument s t of a direct exponential)."""
    coarse, fine = _grid_parts(t0, h, count)
    out = _phases(coarse, s, eta)[:, None, :] * _phases(fine, s, eta)[None, :, :]
    return out.reshape(-1, s.size)[:count]


def _two_sum(a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(a + b rounded, its rounding error): a + b exactly (Knuth's TwoSum)."""
    total = a + b
    b_part = total - a
    return total, (a - (total - b_part)) + (b - b_part)


def _grid_offsets(ts: np.ndarray, h: float, J: int) -> np.ndarray:
    """ts - (the time of :func:`_uniform_sum`'s phases for each t), to about 1e-32 relative: the sum of
    the four grid parts of each time is formed exactly (double-double by :func:`_two_sum`)."""
    k = np.arange(ts.size)
    B = -(-ts.size // J)
    start_coarse, start_fine = _grid_parts(float(ts[0]), J * h, B)
    off_coarse, off_fine = _grid_parts(0.0, h, J)
    b, j = k // J, k % J
    cb, cj = start_fine.size, off_fine.size
    parts = [start_coarse[b // cb], start_fine[b % cb], off_coarse[j // cj], off_fine[j % cj]]
    total, low = parts[0], np.zeros(ts.size)
    for part in parts[1:]:
        total, err = _two_sum(total, part)
        low = low + err
    return (ts - total) - low


def _uniform_sum(
    ts: np.ndarray, h: float, s: np.ndarray, im: float | np.ndarray, G: np.ndarray, memory: int
) -> np.ndarray:
    """sum_k G_k e^{i (s_k + i im_k) t} at times ``ts`` of uniform step h (:func:`uniform_step`), shape
    (len(ts), m).

    With t = T_b + j h + delta (blocks b of J ~ sqrt(n) times; delta, a few ulps of t, what rounding
    left of the uniform grid), e^{i q t} = e^{i q T_b} e^{i q j h} (1 + i q delta): the phases of the B
    block starts and of the J offsets only (:func:`_grid_phases`), and the sum over nodes for each
    response column, and for the column q G_r of the first-order term, a matrix product
    (B x nodes) diag(G_r) (nodes x J).
    """
    n, m = ts.size, G.shape[1]
    J = int(np.ceil(np.sqrt(n)))
    B = -(-n // J)
    delta = _grid_offsets(ts, h, J)
    out = np.zeros((2 * m, B, J), dtype=complex)
    chunk = max(16, int(min(memory, _CACHE_SIZED) // (2 * m * B + B + J)))
    for k in range(0, s.size, chunk):
        sl = slice(k, k + chunk)
        eta = im[sl] if isinstance(im, np.ndarray) and im.ndim else im
        first = _grid_phases(float(ts[0]), J * h, B, s[sl], eta)
        local = _grid_phases(0.0, h, J, s[sl], eta)
        both = np.concatenate([G[sl], (s[sl] + 1j * np.asarray(eta))[:, None] * G[sl]], axis=1)
        weighted = first[None, :, :] * both.T[:, None, :]
        out += (weighted.reshape(2 * m * B, -1) @ local.T).reshape(2 * m, B, J)
    sums = out.reshape(2 * m, B * J)[:, :n].T
    return sums[:, :m] + 1j * delta[:, None] * sums[:, m:]


def fourier_sum(
    ts: np.ndarray,
    nodes: np.ndarray,
    weights: np.ndarray,
    weighted: Callable[[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]],
    m: int,
    q_max: float,
    eta: float | np.ndarray | None,
    *,
    memory: int = 4_000_000,
) -> np.ndarray:
    """sum_n G_n e^{i q_n t} for every t, (q, G) = weighted(nodes, weights): shape (len(ts), m).

    ``eta`` is Im q_n when it is the same for every node (else None: taken from q).

    Few times: the exponentials directly, or, for 16 or more times of a uniform step (:func:`uniform_step`,
    the time series' bands), by blocks of times as matrix products (:func:`_uniform_sum`, exponentials of
    about 2 sqrt(len(ts)) times per node). Many times: on a uniform grid t_g with step h = 1/(2 max|q|),
    e^{i q t} = e^{i q t_g} sum_k (i q delta)^k / k! with delta = t - t_g, |q delta| <= 1/4, and the grid
    phases come by blocks from e^{i q t_0} e^{i q j h}. The cost is (grid points x nodes x terms) whatever
    the number of times.
    """
    node_block = max(16, int(memory // (4 * max(m, 1))))
    h = 0.5 / (q_max + 1.0)
    lo, hi = np.floor(ts.min() / h), np.ceil(ts.max() / h)
    grid_size = int(hi - lo) + 1
    direct = ts.size <= grid_size or m > 64
    acc = np.zeros((ts.size, m), dtype=complex)
    step = uniform_step(ts) if direct else None
    if not direct:
        k = np.rint(ts / h)
        delta = ts - k * h
        row = (k - lo).astype(int)
        moments = np.zeros((grid_size, _TAYLOR_TERMS * m), dtype=complex)
        factorials = np.concatenate([[1.0], np.cumprod(np.arange(1, _TAYLOR_TERMS))])
        steps = np.arange(_GRID_BLOCK) * h
    for start in range(0, nodes.size, node_block):
        q, G = weighted(nodes[start : start + node_block], weights[start : start + node_block])
        s = q.real
        im = q.imag if eta is None else eta
        if direct and step is not None:
            acc += _uniform_sum(ts, step, s, im, G, memory)
            continue
        if direct:
            block = max(1, int(memory // max(1, q.size)))
            for t0 in range(0, ts.size, block):
                t = ts[t0 : t0 + block]
                acc[t0 : t0 + block] += _phases(t, s, im) @ G
            continue
        powers = (1j * q)[:, None] ** np.arange(_TAYLOR_TERMS) / factorials
        B = (powers[:, :, None] * G[:, None, :]).reshape(q.size, -1)
        local = _phases(steps, s, im)
        starts = (lo + np.arange(0, grid_size, _GRID_BLOCK)) * h
        first = _phases(starts, s, im)
        for b, g0 in enumerate(range(0, grid_size, _GRID_BLOCK)):
            n = min(_GRID_BLOCK, grid_size - g0)
            moments[g0 : g0 + n] += (local[:n] * first[b]) @ B
    if not direct:
        sel = moments[row].reshape(ts.size, _TAYLOR_TERMS, m)
        acc = sel[:, -1]
        for j in range(_TAYLOR_TERMS - 2, -1, -1):
            acc = acc * delta[:, None] + sel[:, j]
    return acc
