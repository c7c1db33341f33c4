"""The minimum of a real function on an interval by Brent's method (golden sections and parabolic steps;
Forsythe, Malcolm & Moler 1977, ``fmin``), in the form of SciPy's bounded ``minimize_scalar``, step for
step.

The moving load's peak speed (:func:`moving_bogie.soil.moving_load.moving_load`) is refined with it.
SciPy computes the same iterates (a test compares them), but importing ``scipy.optimize`` costs a third
of a second (:mod:`moving_bogie.kernels.brent`).
"""

from __future__ import annotations

import math
from collections.abc import Callable

__all__ = ["fminbound"]

_SQRT_EPS = math.sqrt(2.2e-16)
_GOLDEN = 0.5 * (3.0 - math.sqrt(5.0))


def _parabolic(
    xf: float, fx: float, nfc: float, fnfc: float, fulc: float, ffulc: float
) -> tuple[float, float]:
    """(p, q) of the parabola through the three best points: its step from xf is p / q."""
    r = (xf - nfc) * (fx - ffulc)
    q = (xf - fulc) * (fx - fnfc)
    p = (xf - fulc) * q - (xf - nfc) * r
    q = 2.0 * (q - r)
    if q > 0.0:
        p = -p
    return p, abs(q)


def fminbound(
    f: Callable[[float], float], a: float, b: float, xatol: float, maxfun: int = 500
) -> tuple[float, float]:
    """(x, f(x)): the least value found of ``f`` on [a, b]; the search stops when the bracket of the best
    point lies within 2 (sqrt(eps) |x| + xatol / 3) of it (SciPy's ``minimize_scalar(method="bounded")``)."""
    fulc = nfc = xf = a + _GOLDEN * (b - a)
    rat = e = 0.0
    fx = f(xf)
    num, ffulc, fnfc = 1, fx, fx
    xm = 0.5 * (a + b)
    tol1 = _SQRT_EPS * abs(xf) + xatol / 3.0
    tol2 = 2.0 * tol1
    while abs(xf - xm) > tol2 - 0.5 * (b - a):
        golden = True
        if abs(e) > tol1:  # try a parabolic step
            golden = False
            p, q = _parabolic(xf, fx, nfc, fnfc, fulc, ffulc)
            r, e = e, rat
            if abs(p) < abs(0.5 * q * r) and q * (a - xf) < p < q * (b - xf):
                rat = p / q
                x = xf + rat
                if (x - a) < tol2 or (b - x) < tol2:
                    rat = tol1 * (1.0 if xm >= xf else -1.0)
            else:
                golden = True
        if golden:
            e = (a - xf) if xf >= xm else (b - xf)
            rat = _GOLDEN * e
        x = xf + (1.0 if rat >= 0 else -1.0) * max(abs(rat), tol1)
        fu = f(x)
        num += 1
        if fu <= fx:
            a, b = (xf, b) if x >= xf else (a, xf)
            fulc, ffulc, nfc, fnfc, xf, fx = nfc, fnfc, xf, fx, x, fu
        else:
            a, b = (a, x) if x >= xf else (x, b)
            if fu <= fnfc or nfc == xf:
                fulc, ffulc, nfc, fnfc = nfc, fnfc, x, fu
            elif fu <= ffulc or fulc == xf or fulc == nfc:
                fulc, ffulc = x, fu
        xm = 0.5 * (a + b)
        tol1 = _SQRT_EPS * abs(xf) + xatol / 3.0
        tol2 = 2.0 * tol1
        if num >= maxfun:
            break
    return xf, fx
