"""Brent's method for a root of a real function bracketed by a sign change (Brent 1973, "Algorithms for
Minimization without Derivatives", ch. 4), in the form of SciPy's ``brentq``, step for step.

The cut tracing (:mod:`moving_bogie.kernels.cut_curves`) and the search columns
(:mod:`moving_bogie.roots.search.search_columns`) find a turn of a cut curve and the crossing of two arms
with it. SciPy's ``brentq`` computes the same iterates (a test compares them bit for bit), but importing
``scipy.optimize`` costs a third of a second, more than all the calls of a search.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

__all__ = ["brentq"]

#: The smallest relative tolerance allowed (four units of roundoff, as SciPy's).
RTOL_MIN = 4 * 2.220446049250313e-16


def brentq(
    f: Callable[..., float],
    a: float,
    b: float,
    args: tuple[Any, ...] = (),
    xtol: float = 2e-12,
    rtol: float = RTOL_MIN,
    maxiter: int = 100,
) -> float:
    """A root of ``f(x, *args)`` in [a, b], where f(a) and f(b) differ in sign, to within
    ``xtol + rtol |x|``: inverse quadratic interpolation or the secant step where it falls well inside the
    bracket, bisection otherwise.

    Raises
    ------
    ValueError
        If f(a) and f(b) have the same sign, a tolerance is too small, or f returns NaN.
    RuntimeError
        If ``maxiter`` iterations do not converge.
    """
    if not xtol > 0 or not rtol >= RTOL_MIN:
        raise ValueError(f"xtol must be > 0 and rtol >= {RTOL_MIN} (got {xtol}, {rtol})")

    def value(x: float) -> float:
        y = float(f(x, *args))
        if math.isnan(y):
            raise ValueError(f"the function is NaN at x = {x}")
        return y

    xpre, xcur = float(a), float(b)
    fpre, fcur = value(xpre), value(xcur)
    if fpre == 0:
        return xpre
    if fcur == 0:
        return xcur
    if math.copysign(1.0, fpre) == math.copysign(1.0, fcur):
        raise ValueError("f(a) and f(b) must have different signs")
    xblk = fblk = spre = scur = 0.0
    for _ in range(maxiter):
        if fpre != 0 and fcur != 0 and math.copysign(1.0, fpre) != math.copysign(1.0, fcur):
            xblk, fblk = xpre, fpre
            spre = scur = xcur - xpre
        if abs(fblk) < abs(fcur):  # the best estimate in xcur, the bracket's other end in xblk
            xpre, xcur, xblk = xcur, xblk, xcur
            fpre, fcur, fblk = fcur, fblk, fcur
        delta = (xtol + rtol * abs(xcur)) / 2
        sbis = (xblk - xcur) / 2
        if fcur == 0 or abs(sbis) < delta:
            return xcur
        spre, scur = _step(xpre, xcur, xblk, fpre, fcur, fblk, spre, scur, sbis, delta)
        xpre, fpre = xcur, fcur
        xcur += scur if abs(scur) > delta else (delta if sbis > 0 else -delta)
        fcur = value(xcur)
    raise RuntimeError(f"brentq: no convergence in {maxiter} iterations (last x = {xcur})")


def _step(
    xpre: float,
    xcur: float,
    xblk: float,
    fpre: float,
    fcur: float,
    fblk: float,
    spre: float,
    scur: float,
    sbis: float,
    delta: float,
) -> tuple[float, float]:
    """The next (previous step, step): interpolation (secant, or inverse quadratic through the three
    points) when it is short enough, else bisection."""
    if abs(spre) > delta and abs(fcur) < abs(fpre):
        if xpre == xblk:  # interpolate
            stry = -fcur * (xcur - xpre) / (fcur - fpre)
        else:  # extrapolate
            dpre = (fpre - fcur) / (xpre - xcur)
            dblk = (fblk - fcur) / (xblk - xcur)
            stry = -fcur * (fblk * dblk - fpre * dpre) / (dblk * dpre * (fblk - fpre))
        if 2 * abs(stry) < min(abs(spre), 3 * abs(sbis) - delta):  # a good short step
            return scur, stry
    return sbis, sbis
