"""Sign changes refined by the Illinois method, many brackets at once (the soil's modes, the free waves)."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import numpy.typing as npt

from moving_bogie.typing import FloatArray

IntArray = npt.NDArray[np.intp]

__all__ = ["IntArray", "illinois"]


def illinois(
    f: Callable[[FloatArray, IntArray], FloatArray],
    lo: FloatArray,
    hi: FloatArray,
    *,
    rtol: float | FloatArray = 1e-13,
    iterations: int = 80,
) -> FloatArray:
    """Roots of ``f(x, index)`` in the brackets [lo, hi] (f changes sign in each; ``index`` says which
    bracket each x belongs to, so that f can look up its other arguments): regula falsi that halves the
    value kept at a stale end (Illinois); a step outside the bracket, or a bracket that has not halved in two
    steps (a square-root behaviour near a layer's wave speed), bisects; stops when every bracket is
    below ``rtol`` (one for all, or one per bracket) of its end, or after ``iterations`` steps. Returns
    the end of smaller |f| of each."""
    lo, hi = np.asarray(lo, dtype=float).copy(), np.asarray(hi, dtype=float).copy()
    index = np.arange(lo.size)
    f_lo, f_hi = f(lo, index), f(hi, index)
    side = np.zeros(lo.shape, dtype=int)
    before = [np.abs(hi - lo)] * 2  # the widths two steps back: a bracket that did not halve is bisected
    for _ in range(iterations):
        active = np.abs(hi - lo) > rtol * np.maximum(np.abs(hi), np.abs(lo))
        if not np.any(active):
            break
        a = np.nonzero(active)[0]
        width = hi[a] - lo[a]
        mid = hi[a] - f_hi[a] * width / (f_hi[a] - f_lo[a])
        inside = np.isfinite(mid) & (mid > np.minimum(lo[a], hi[a])) & (mid < np.maximum(lo[a], hi[a]))
        slow = np.abs(width) > 0.5 * before[0][a]
        mid = np.where(inside & ~slow, mid, lo[a] + width / 2)
        before = [before[1], np.abs(hi - lo)]
        f_mid = f(mid, index[a])
        left = np.sign(f_mid) == np.sign(f_lo[a])
        # the end kept twice in a row has its value halved (Illinois)
        f_hi[a] = np.where(left & (side[a] == 1), 0.5 * f_hi[a], f_hi[a])
        f_lo[a] = np.where(~left & (side[a] == -1), 0.5 * f_lo[a], f_lo[a])
        lo[a], f_lo[a] = np.where(left, mid, lo[a]), np.where(left, f_mid, f_lo[a])
        hi[a], f_hi[a] = np.where(left, hi[a], mid), np.where(left, f_hi[a], f_mid)
        side[a] = np.where(left, 1, -1)
    return np.where(np.abs(f_lo) < np.abs(f_hi), lo, hi)
