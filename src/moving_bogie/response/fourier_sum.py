"""sum_n G_n e^{i q_n t} for many times t: the last step of every branch-cut integral (Eq. (35)).

Shared by the Euler-Bernoulli cut (a horizontal half-line, :mod:`branch_cut`) and the traced cut of any
model (:mod:`cut_integral`).
"""

from __future__ import annotations

import numpy as np

__all__ = ["cis", "fourier_sum"]

#: Taylor terms of e^{i q delta} with |q delta| <= 1/4 (remainder below 1e-16 of the sum of |G|).
_TAYLOR_TERMS = 12
_GRID_BLOCK = 256


def cis(x):
    """e^{i x} for a real array x (cos and sin of real arguments are cheaper than a complex exp)."""
    out = np.empty(x.shape, dtype=complex)
    np.cos(x, out=out.real)
    np.sin(x, out=out.imag)
    return out


def _phases(t, s, eta):
    """e^{i (s + i eta) t} for the outer product of times t and real s (sin/cos of real arguments).

    ``eta`` is one number (a cut on a horizontal line) or an array like s (a curved cut).
    """
    out = cis(np.multiply.outer(t, s))
    if np.ndim(eta) == 0:
        out *= np.exp(-eta * t)[:, None]
    else:
        out *= np.exp(-np.multiply.outer(t, eta))
    return out


def fourier_sum(ts, nodes, weights, weighted, m, q_max, eta, *, memory=4_000_000):
    """sum_n G_n e^{i q_n t} for every t, (q, G) = weighted(nodes, weights): shape (len(ts), m).

    ``eta`` is Im q_n when it is the same for every node (else None: taken from q).

    Few times: the exponentials directly. Many times: on a uniform grid t_g with step h = 1/(2 max|q|),
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
