"""Tracing the curves q_j(p) of the cut of K: N(p, q) = 0 for real p (see :mod:`~moving_bogie.kernels.cut`).

For every real p, N(p, .) is a polynomial in q (generated ``n_coeffs_in_q``); its roots q_j(p) are followed
on an adaptive grid of real p: each step is checked against its linear prediction from dq/dp = -N_p/N_q
(implicit-function theorem) and halved until the prediction error is below a tenth of the distance to the
nearest other root, so that no two curves are confused and no turn of a curve is skipped at the resolution
of the grid. Turning points of Re q (folds and cusps) are located by root-finding on Re dq/dp. The p-range
reaches until every curve has left the strip of interest or settled at its limit (:func:`far_range`).
"""

from __future__ import annotations

import cmath
from collections.abc import Sequence
from dataclasses import dataclass
from types import ModuleType
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from moving_bogie.kernels.brent import brentq
from moving_bogie.kernels.coefficient_matrix import Coefficients
from moving_bogie.kernels.polynomial import horner
from moving_bogie.kernels.polyroots import (
    companion_roots,
    newton_polish,
    poly_roots,
    polyder,
    polyval,
)

__all__ = ["CutTracer", "Fold", "far_range", "split_at_turns", "trace_curves"]

_MAX_REFINE = 30
_P_MAX = 2.0**40  # largest p-range traced (a curve drifting out slower than this is cut off there)
_SETTLED = 1e-9  # relative move of a curve's end, when |p| doubles, below which it sits at its limit
_PREDICTION = 0.1  # accepted prediction error, relative to the distance to the nearest other root


class CutTracer:
    """The roots q_j(p) of N(p, .) for real p, their p-derivative and Newton refinement (one model)."""

    def __init__(self, module: ModuleType, args: dict[str, Any]) -> None:
        self.module = module
        self.args = args
        self._coeffs = Coefficients(args)

    def q_roots(self, ps: ArrayLike) -> np.ndarray:
        """All roots in q at real ``ps``, shape ``ps.shape + (DEGREE_N_IN_Q,)``.

        Polished by Newton's method on N(p, .): at large |p| the roots of the rail (|q| ~ p^2) and of a
        mass layer (|q| bounded) differ by many orders, and the closed form alone then loses the small ones'
        digits.
        """
        ps = np.asarray(ps, dtype=float)
        c = self._coeffs(self.module.n_coeffs_in_q, ps)
        z = newton_polish(c, poly_roots(c), steps=2)
        with np.errstate(all="ignore"):
            residual = np.abs(polyval(c, z)) / polyval(np.abs(c), np.abs(z))
        bad = ~np.all(residual <= 1e-11, axis=-1) & np.all(np.isfinite(c), axis=-1) & (c[..., 0] != 0)
        if np.any(bad):  # companion eigenvalues where the closed form lost digits
            z[bad] = companion_roots(c[bad])
        return z

    def dq_dp(self, p: ArrayLike, q: ArrayLike) -> np.ndarray:
        """dq/dp = -N_p / N_q along a curve N(p, q) = 0 (implicit-function theorem)."""
        p, q = np.broadcast_arrays(np.asarray(p, dtype=float), np.asarray(q, dtype=complex))
        n = self._coeffs(self.module.n_coeffs, q)
        nq = self._coeffs(self.module.n_coeffs_dq, q)
        x = p[..., None].astype(complex)
        Np = polyval(polyder(n), x)[..., 0]
        Nq = polyval(nq, x)[..., 0]
        return -Np / Nq

    def refine(self, p: ArrayLike, q: ArrayLike, steps: int = 4) -> np.ndarray:
        """Newton's method on N(p, .) = 0 in q from ``q`` (arrays), at fixed real p.

        A handful of points (the tilings ask for one or a few at a time) take the same steps, with the same
        arithmetic, on Python complex numbers, without numpy's per-call overhead.
        """
        p = np.asarray(p, dtype=float)
        c = self._coeffs(self.module.n_coeffs_in_q, p)
        dc = polyder(c)
        z = np.asarray(q, dtype=complex).copy()
        if z.size <= _SCALAR_REFINE and c.ndim == 1 + z.ndim and c.shape[:-1] == z.shape:
            rows, drows = c.reshape(-1, c.shape[-1]).tolist(), dc.reshape(-1, dc.shape[-1]).tolist()
            flat = [_newton_one(r, dr, zk, steps) for r, dr, zk in zip(rows, drows, z.ravel().tolist())]
            return np.array(flat, dtype=complex).reshape(z.shape)
        for _ in range(steps):
            with np.errstate(all="ignore"):
                step = polyval(c, z[..., None])[..., 0] / polyval(dc, z[..., None])[..., 0]
            z = np.where(np.isfinite(step), z - step, z)
        return z


#: |Re dq/dp| below this times |dq/dp| is a vertical tangent to rounding (no turn of Re q there).
_FLAT = 1e-13
#: At most this many points take the scalar Newton steps of :meth:`CutTracer.refine`.
_SCALAR_REFINE = 4


def _newton_one(coeffs: Sequence[complex], dcoeffs: Sequence[complex], z: complex, steps: int) -> complex:
    """Newton steps on one polynomial and its derivative (Python complex coefficients, highest first) from
    ``z``: a step that is not finite (N_q = 0, overflow) is not taken, as in the batched path."""
    for _ in range(steps):
        try:
            step = horner(coeffs, z) / horner(dcoeffs, z)
        except (ZeroDivisionError, OverflowError):
            continue
        if cmath.isfinite(step):
            z = z - step
    return z


@dataclass(frozen=True)
class Fold:
    """A turning point of Re q along a curve: ``cusp`` when dq/dp = 0 there (a branch point of K).

    ``end``: not a turning point but the end of a curve that stays bounded as |p| -> infinity (its limit
    q_inf; ``cusp`` is then True: K is singular there too, and ``opens`` is 0).
    """

    p: float
    q: complex
    cusp: bool
    opens: int  # +1: the two arms leave towards larger Re q, -1 towards smaller
    end: bool = False


def _match(
    prev: np.ndarray, pred: np.ndarray, new: np.ndarray, back: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """Index of the root of ``new`` nearest to each prediction, and whether the step is acceptable.

    A step is accepted when the forward prediction (and, with ``back``, the backward prediction from the
    new roots, ordered like ``new``) lands within a tenth of the distance to the nearest other root.
    """
    d = np.abs(new[:, None, :] - pred[:, :, None])  # (k, j prev, i new)
    order = np.argmin(d, axis=-1)
    ok = np.all(np.sort(order, axis=-1) == np.arange(order.shape[-1]), axis=-1)
    err = np.abs(np.take_along_axis(new, order, axis=-1) - pred)
    if back is not None:
        err = np.maximum(err, np.abs(np.take_along_axis(back, order, axis=-1) - prev))
    sep = np.abs(prev[:, :, None] - prev[:, None, :])
    sep = sep + np.where(np.eye(prev.shape[-1], dtype=bool), np.inf, 0)
    ok &= np.all((err <= _PREDICTION * sep.min(axis=-1)) & np.isfinite(err), axis=-1)
    return order, ok


def trace_curves(
    tracer: CutTracer, p_lo: float, p_hi: float, n: int = 2001, grid: ArrayLike | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """(ps, Q): the curves q_j(p) on an adaptive grid of [p_lo, p_hi] (or refined from ``grid``);
    column j is one continuous curve. Steps are halved until both the forward and the backward linear
    predictions (from dq/dp at either end) land within a tenth of the distance to the nearest other root."""
    ps = np.linspace(p_lo, p_hi, n) if grid is None else np.asarray(grid, dtype=float)
    for _ in range(_MAX_REFINE):
        Q = tracer.q_roots(ps)
        D = tracer.dq_dp(ps[:, None], Q)
        h = np.diff(ps)[:, None]
        pred = Q[:-1] + D[:-1] * h
        order, ok = _match(Q[:-1], pred, Q[1:], Q[1:] - D[1:] * h)
        if np.all(ok) or np.diff(ps).min() < 1e-9:
            break
        ps = np.sort(np.concatenate([ps, 0.5 * (ps[:-1] + ps[1:])[~ok]]))
    out = np.empty_like(Q)
    out[0] = Q[0]
    idx = np.arange(Q.shape[1])
    for k in range(order.shape[0]):
        idx = order[k][idx]
        out[k + 1] = Q[k + 1][idx]
    return ps, out


def _turn_brackets(xd: np.ndarray) -> list[tuple[int, int]]:
    """(a, b) index pairs between which Re dq/dp changes sign: b = a + 1 (a root inside), or b > a + 1 when
    the samples between are exact zeros (a turn on a sample, e.g. p = 0 of an even curve at alpha = 0)."""
    sign = np.sign(xd)
    nz = np.nonzero(sign)[0]
    return [(a, b) for a, b in zip(nz[:-1], nz[1:]) if sign[a] * sign[b] < 0]


def split_at_turns(
    tracer: CutTracer, ps: np.ndarray, qs: np.ndarray
) -> tuple[list[tuple[np.ndarray, np.ndarray]], list[Fold]]:
    """Arms (p, q samples) and folds of one curve: cut where Re dq/dp changes sign."""
    d_all = tracer.dq_dp(ps, qs)
    # Re dq/dp at rounding level is 0: a curve on Re q = 0 (alpha = 0, a mirror-symmetric cut) has
    # Re dq/dp ~ 1e-60 of either sign along it, which is no turn
    xd = np.where(np.abs(d_all.real) <= _FLAT * np.abs(d_all), 0.0, d_all.real)
    folds, cuts = [], []
    for k, b in _turn_brackets(xd):
        if b > k + 1:  # the turn sits on a sample
            m = (k + b) // 2
            pt, qt, end, nxt = float(ps[m]), complex(qs[m]), m, m + 1
        else:

            def slope(p: float, k: int = k) -> float:
                q = tracer.refine(
                    np.array([p]), np.array([qs[k] + (p - ps[k]) * (qs[k + 1] - qs[k]) / (ps[k + 1] - ps[k])])
                )
                return float(tracer.dq_dp(np.array([p]), q).real[0])

            fa, fb = slope(ps[k]), slope(ps[k + 1])
            if fa * fb < 0:
                pt = brentq(slope, ps[k], ps[k + 1], xtol=1e-15, rtol=1e-15)
                qt = complex(tracer.refine(np.array([pt]), np.array([qs[k]]))[0])
                end = nxt = k + 1
            else:  # the change of sign was at rounding level (a turn on or next to a sample, e.g. at p = 0
                # of a curve even in p at alpha = 0): the turn is the sample with the smaller slope
                m = k if abs(fa) <= abs(fb) else k + 1
                pt, qt, end, nxt = float(ps[m]), complex(qs[m]), m, m + 1
        d = tracer.dq_dp(np.array([pt]), np.array([qt]))[0]
        scale = max(1.0, float(np.abs(tracer.dq_dp(ps[k : b + 1], qs[k : b + 1])).max()))
        opens = 1 if xd[b] > 0 else -1
        folds.append(Fold(float(pt), qt, bool(abs(d) < 1e-6 * scale), opens))
        cuts.append((end, pt, qt, nxt))
    arms = []
    start_p: list[float] = []
    start_q: list[complex] = []
    first = 0
    for end, pt, qt, nxt in cuts:
        arms.append(
            (
                np.concatenate([start_p, ps[first:end], [pt]]),
                np.concatenate([start_q, qs[first:end], [qt]]),
            )
        )
        start_p, start_q, first = [pt], [qt], nxt
    arms.append((np.concatenate([start_p, ps[first:]]), np.concatenate([start_q, qs[first:]])))
    return arms, folds


def far_range(tracer: CutTracer, reach: float) -> float:
    """A p-range P beyond which no curve q_j(p) (|p| > P) comes back into |Re q| <= reach except as its limit.

    Every end q_j(+-P) either lies beyond the strip (the rail's curves, |q| ~ p^2, and a mass layer's for
    alpha > 0, q ~ alpha p + s_inf) or has settled at a finite limit q_inf: with t = 1/p, t^deg N(1/t, q)
    is a polynomial in t whose value at t = 0 vanishes at q_inf (the leading coefficient of N in p; for a
    mass layer at alpha = 0, its own resonance), so such a curve converges like a power of 1/p. Settled
    means: the end moved by at most 1e-9 (relative) when |p| doubled, and by at most half as much as in the
    doubling before (a curve drifting linearly, q ~ alpha p with alpha tiny, is not settled).
    """
    P = 4.0
    prev = tracer.q_roots(np.array([-P, P]))
    moved_before = np.full(prev.shape, np.inf)
    while P < _P_MAX:
        P *= 2
        cur = tracer.q_roots(np.array([-P, P]))
        moved = np.min(np.abs(cur[..., :, None] - prev[..., None, :]), axis=-1)
        settled = (moved <= _SETTLED * (1 + np.abs(cur))) & (moved <= 0.5 * moved_before)
        if np.all((np.abs(cur.real) > reach) | settled):
            break
        prev, moved_before = cur, moved
    return P
