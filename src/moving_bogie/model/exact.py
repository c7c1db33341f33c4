"""Exact numbers: user input to :class:`~fractions.Fraction`, and Fractions to text and mpmath.

Parameters are stored exactly so that a case read from decimal text ("0.1") reaches mpmath at any
working precision without first passing through a binary float.
"""

from __future__ import annotations

import dataclasses
import math
import numbers
from collections.abc import Callable
from decimal import Decimal
from fractions import Fraction
from typing import Any, TypeAlias

import mpmath
from mpmath.libmp import from_rational, round_nearest

from moving_bogie.errors import ParameterError

__all__ = [
    "LARGEST",
    "NumberLike",
    "dataclass_repr",
    "fraction_to_exact_text",
    "fraction_to_mpf",
    "fraction_to_text",
    "map_fractions",
    "nonnegative",
    "positive",
    "to_fraction",
]

#: What a numeric parameter accepts: exact values, decimal text ("0.1", "3/4", "1e-3") and floats.
NumberLike: TypeAlias = Fraction | int | float | str | Decimal


#: The largest magnitude of a parameter value (and, but for zero, the reciprocal of the smallest): the
#: computations run in double precision (and the exact conversions in binary with bounded exponents), where
#: powers and products of the groups built from values beyond it overflow.
LARGEST = Fraction(10) ** 30


def to_fraction(name: str, value: object) -> Fraction:
    """Convert one parameter value exactly to a :class:`~fractions.Fraction`, within :data:`LARGEST`.

    See :func:`_to_fraction` for the accepted types.

    Raises
    ------
    ParameterError
        For a value :func:`_to_fraction` refuses, or one beyond :data:`LARGEST` (or nearer 0 than its
        reciprocal); the message names `name`.
    """
    x = _to_fraction(name, value)
    if x != 0 and not 1 / LARGEST <= abs(x) <= LARGEST:
        shown = (
            value.strip()
            if isinstance(value, str)
            else mpmath.nstr(mpmath.mpf(x.numerator) / x.denominator, 6)
        )
        raise ParameterError(
            name, f"{name} = {shown} is out of range: give a magnitude from 1e-30 to 1e30, or 0"
        )
    return x


def _to_fraction(name: str, value: object) -> Fraction:
    """Convert one parameter value exactly to a :class:`~fractions.Fraction` (no range check).

    Parameters
    ----------
    name : str
        Parameter name, used in the error message.
    value : Fraction, int, float, str, Decimal or mpmath.mpf
        Decimal text converts exactly (``"0.1"`` is 1/10); a float is read by its shortest decimal text,
        as the command line reads it (``0.1`` is 1/10, not the binary 0.1000000000000000055...); integers
        and Fractions are kept.

    Returns
    -------
    Fraction

    Raises
    ------
    ParameterError
        For a bool, NaN, an infinity, unparsable text or a non-numeric type; the message names `name`.
    """
    if isinstance(value, bool):
        raise ParameterError(name, f"{name} must be a number, not a bool (got {value!r})")
    if isinstance(value, Fraction):
        return value
    if isinstance(value, numbers.Rational):  # int, numpy integers
        return Fraction(int(value.numerator), int(value.denominator))
    if isinstance(value, str):
        try:
            return Fraction(value.strip())
        except (ValueError, ZeroDivisionError):
            raise ParameterError(
                name, f"{name} must be a finite number written as decimal text, e.g. '0.1' (got {value!r})"
            ) from None
    if isinstance(value, Decimal):
        if not value.is_finite():
            raise ParameterError(name, f"{name} must be a finite number (got {value})")
        return Fraction(value)
    if isinstance(value, mpmath.mpf):
        if not mpmath.isfinite(value):
            raise ParameterError(name, f"{name} must be a finite number (got {value})")
        mantissa, exponent = value.man_exp
        return Fraction(int(mantissa)) * Fraction(2) ** int(exponent)
    if isinstance(value, numbers.Real):  # float, numpy floats
        x = float(value)
        if not math.isfinite(x):
            raise ParameterError(name, f"{name} must be a finite number (got {x})")
        return Fraction(repr(x))
    raise ParameterError(
        name, f"{name} must be a real number or decimal text (got {type(value).__name__} {value!r})"
    )


def fraction_to_text(value: Fraction) -> str:
    """Text for a Fraction: its exact decimal expansion when finite, else the repr of the nearest float.

    Examples
    --------
    >>> fraction_to_text(Fraction("0.10")), fraction_to_text(Fraction(20)), fraction_to_text(Fraction(1, 3))
    ('0.1', '20', '0.3333333333333333')
    """
    den = value.denominator
    twos = (den & -den).bit_length() - 1
    fives = 0
    rest = den >> twos
    while rest % 5 == 0:
        rest //= 5
        fives += 1
    if rest != 1:
        return repr(float(value))
    places = max(twos, fives)
    scaled = abs(value.numerator) * 10**places // den
    sign = "-" if value < 0 else ""
    if places == 0:
        return f"{sign}{scaled}"
    digits = str(scaled).rjust(places + 1, "0")
    whole, frac = digits[:-places], digits[-places:].rstrip("0")
    return f"{sign}{whole}.{frac}" if frac else f"{sign}{whole}"


def fraction_to_mpf(value: Fraction) -> mpmath.mpf:
    """Round a Fraction once, correctly, to an mpf at the current ``mpmath.mp`` precision."""
    return mpmath.mp.make_mpf(
        from_rational(value.numerator, value.denominator, mpmath.mp.prec, round_nearest)
    )


def fraction_to_exact_text(value: Fraction) -> str:
    """Exact text that ``Fraction(text)`` reads back: decimal when finite (``'0.05'``), else ``'1/3'``."""
    text = fraction_to_text(value)
    return text if Fraction(text) == value else f"{value.numerator}/{value.denominator}"


def positive(name: str, value: object) -> Fraction:
    """Convert `value` exactly and require it to be > 0, else raise :class:`ParameterError`."""
    x = to_fraction(name, value)
    if x <= 0:
        raise ParameterError(name, f"{name} must be a positive finite number (got {fraction_to_text(x)})")
    return x


def nonnegative(name: str, value: object) -> Fraction:
    """Convert `value` exactly and require it to be >= 0, else raise :class:`ParameterError`."""
    x = to_fraction(name, value)
    if x < 0:
        raise ParameterError(name, f"{name} must be a non-negative finite number (got {fraction_to_text(x)})")
    return x


def dataclass_repr(obj: Any) -> str:
    """Exact, evaluable repr of a parameter dataclass: Fractions shown as exact text (``eta_f='0.05'``)."""
    parts = []
    for field in dataclasses.fields(obj):
        value = getattr(obj, field.name)
        shown = fraction_to_exact_text(value) if isinstance(value, Fraction) else value
        parts.append(f"{field.name}={shown!r}")
    return f"{type(obj).__name__}({', '.join(parts)})"


def map_fractions(obj: Any, func: Callable[[Fraction], Any]) -> dict[str, Any]:
    """Fields of a parameter dataclass by name, `func` applied to the Fractions, other values kept."""
    values = {field.name: getattr(obj, field.name) for field in dataclasses.fields(obj)}
    return {name: func(value) if isinstance(value, Fraction) else value for name, value in values.items()}
