"""The generated coefficients of N(p, q) and Q(p, q) (Eq. (24), a layered track's Cramer's rule) for one
parameter set, as matrices of their monomials: evaluated on many points by a short Horner scheme.

Each generated function (``n_coeffs``, ``n_coeffs_dq``, ``q_coeffs``, ``q_coeffs_dq`` in q; ``n_coeffs_in_q``
in p) returns the coefficients of a polynomial in one variable whose own coefficients are polynomials in
the other. Evaluated once on the variable itself as a polynomial object (:class:`_Poly`, coefficients
lowest power first), the same generated arithmetic yields the matrix ``M[k, j]``: the coefficient of x^j
in coefficient k. The model knowledge stays in the generated code; only its evaluation changes: on a
batch of x, ``M`` costs one multiply-add per power of x (Horner's scheme), where the generated code makes
hundreds of array operations (a three-layer N in q: 150 shared subexpressions). The monomials are the
generated code's own (it is expanded in q and in p), so Horner's scheme has the same rounding-error bound,
sum |M[k, j]| |x|^j times a few units in the last place.

A generated function that is not a polynomial in its first argument (a division by it, a function of it)
raises on :class:`_Poly` or disagrees with itself at three probe points: it is then evaluated directly.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["CoefficientMatrix", "Coefficients"]

#: Largest disagreement accepted at the probe points, relative to the rounding bound of each coefficient.
_PROBE_TOLERANCE = 1e-9
_PROBES = (0.37 + 0.61j, -1.3 + 0.2j, 2.9 - 1.7j)


class _Poly:
    """A polynomial in one variable, complex coefficients lowest power first (only what the generated
    arithmetic uses: +, -, *, integer powers, division by a number)."""

    __slots__ = ("c",)
    __array_ufunc__ = None  # numpy scalars and arrays defer to the methods below

    def __init__(self, c: ArrayLike) -> None:
        self.c = np.asarray(c, dtype=complex)

    @staticmethod
    def _coef(other: object) -> Any:
        if isinstance(other, _Poly):
            return other.c
        if isinstance(other, (int, float, complex)):
            return np.array([other], dtype=complex)
        return NotImplemented

    def __add__(self, other: object) -> Any:
        o = self._coef(other)
        if o is NotImplemented:
            return o
        n = max(self.c.size, o.size)
        out = np.zeros(n, dtype=complex)
        out[: self.c.size] += self.c
        out[: o.size] += o
        return _Poly(out)

    __radd__ = __add__

    def __neg__(self) -> _Poly:
        return _Poly(-self.c)

    def __sub__(self, other: object) -> Any:
        o = self._coef(other)
        return o if o is NotImplemented else self + _Poly(-o)

    def __rsub__(self, other: object) -> Any:
        return (-self) + other

    def __mul__(self, other: object) -> Any:
        if isinstance(other, _Poly):
            return _Poly(np.convolve(self.c, other.c))
        if isinstance(other, (int, float, complex)):
            return _Poly(self.c * other)
        return NotImplemented

    __rmul__ = __mul__

    def __truediv__(self, other: object) -> Any:
        if isinstance(other, (int, float, complex)):
            return _Poly(self.c / other)
        return NotImplemented

    def __pow__(self, k: object) -> Any:
        if not isinstance(k, int) or k < 0:
            return NotImplemented
        out = _Poly([1.0])
        for _ in range(k):
            out = out * self
        return out


class CoefficientMatrix:
    """One generated coefficient function at fixed parameters, evaluated through its monomial matrix.

    ``matrix`` (shape (terms, powers), None when the function is not polynomial in its argument).
    """

    def __init__(self, func: Callable[..., Any], args: dict) -> None:
        self.func, self.args = func, args
        self.matrix = _matrix(func, args)
        self._by_power = None if self.matrix is None else np.ascontiguousarray(self.matrix.T)

    def __call__(self, x: ArrayLike) -> np.ndarray:
        """The coefficients at every point of ``x``: shape ``x.shape + (terms,)``."""
        x = np.asarray(x)
        rows = self._by_power  # rows[j]: the coefficients of x^j, contiguous (None: not polynomial)
        if rows is None:
            return _direct(self.func, x, self.args)
        out = np.empty(x.shape + (rows.shape[1],), dtype=complex)
        out[...] = rows[-1]
        xs = x[..., None]
        for j in range(rows.shape[0] - 2, -1, -1):  # Horner's scheme in x
            out *= xs
            out += rows[j]
        return out


class Coefficients:
    """The coefficient functions of one generated module at fixed parameters, each turned into a
    :class:`CoefficientMatrix` on first use (``coefficients(module.n_coeffs, q)``)."""

    def __init__(self, args: dict) -> None:
        self.args = args
        self._built: dict = {}

    def __call__(self, func: Callable[..., Any], x: ArrayLike) -> np.ndarray:
        built = self._built.get(func)
        if built is None:
            built = self._built[func] = CoefficientMatrix(func, self.args)
        return built(x)


def _direct(func: Callable[..., Any], x: np.ndarray, args: dict) -> np.ndarray:
    coeffs = func(x, **args)
    out = np.empty(x.shape + (len(coeffs),), dtype=complex)
    for k, c in enumerate(coeffs):
        out[..., k] = c
    return out


def _matrix(func: Callable[..., Any], args: dict) -> np.ndarray | None:
    """The monomial matrix of ``func`` (see the module docstring), or None if it is not polynomial."""
    try:
        with np.errstate(all="ignore"):
            terms = func(_Poly([0.0, 1.0]), **args)
    except (TypeError, ZeroDivisionError, OverflowError, ValueError):
        return None
    rows = [t.c if isinstance(t, _Poly) else np.array([t], dtype=complex) for t in terms]
    width = max(r.size for r in rows)
    m = np.zeros((len(rows), width), dtype=complex)
    for k, r in enumerate(rows):
        m[k, : r.size] = r
    if not np.all(np.isfinite(m)):
        return None
    probes = np.array(_PROBES)
    powers = probes[:, None] ** np.arange(width)
    from_matrix = powers @ m.T
    bound = np.abs(powers) @ np.abs(m).T
    try:
        with np.errstate(all="ignore"):
            direct = _direct(func, probes, args)
    except (ZeroDivisionError, OverflowError, ValueError):
        return None
    if not np.all(np.abs(from_matrix - direct) <= _PROBE_TOLERANCE * np.maximum(bound, 1e-300)):
        return None
    return m
