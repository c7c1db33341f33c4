"""The one check of every command's option values, shared by every command (and the sleeper-track twins).

Counts, sizes, worker numbers and real numbers are argparse types: a bad value ends in one line naming the
option and exit status 2 while the command line is parsed, before anything is read or computed. The
``NAME=VALUE`` lists (``--set``, ``--vary``, ``--range``, ``--sel``) go through :func:`named_values`, which
refuses a malformed entry and a name given twice. Numbers must be finite and within the range of double
precision (:data:`~moving_bogie.model.exact.LARGEST`), since the computations run in floats.
"""

from __future__ import annotations

import argparse
from collections.abc import Callable, Iterable
from fractions import Fraction

from moving_bogie.errors import ParameterError
from moving_bogie.model.exact import LARGEST

__all__ = [
    "LARGEST",
    "MAX_WORKERS",
    "count",
    "decimal_number",
    "exact_number",
    "named_values",
    "nonnegative",
    "number",
    "number_list",
    "positive",
    "value_range",
    "workers",
]


#: The most worker processes a command starts.
MAX_WORKERS = 1024


def exact_number(text: str) -> Fraction:
    """The exact value of decimal text ("0.1" is 1/10), finite and within :data:`LARGEST`.

    Raises
    ------
    ValueError
        With the reason, for text that is no number, NaN, an infinity or a number out of range.
    """
    try:
        value = Fraction(text.strip())
    except (ValueError, ZeroDivisionError):
        raise ValueError(f"not a number: {text!r}") from None
    if value != 0 and not 1 / LARGEST <= abs(value) <= LARGEST:
        raise ValueError(f"{text.strip()} is out of range: give a magnitude from 1e-30 to 1e30, or 0")
    return value


def decimal_number(text: str) -> str:
    """argparse type: the text itself (converted exactly later), once it is a number in range."""
    try:
        exact_number(text)
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None
    return text


def number(text: str) -> float:
    """argparse type: a finite float within :data:`LARGEST` (no NaN, no infinity, no overflow)."""
    try:
        return float(exact_number(text))
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def positive(text: str) -> float:
    """argparse type: a :func:`number` > 0 (a largest value, a tolerance)."""
    value = number(text)
    if not value > 0:
        raise argparse.ArgumentTypeError(f"must be positive (got {text.strip()})")
    return value


def nonnegative(text: str) -> float:
    """argparse type: a :func:`number` >= 0 (a velocity)."""
    value = number(text)
    if value < 0:
        raise argparse.ArgumentTypeError(f"must be >= 0 (got {text.strip()})")
    return value


def number_list(text: str) -> list[str]:
    """argparse type: comma-separated numbers, each checked by :func:`decimal_number`."""
    values = [decimal_number(t) for t in text.split(",") if t.strip()]
    if not values:
        raise argparse.ArgumentTypeError(f"expected numbers separated by commas (got {text!r})")
    return values


def count(low: int, high: int, what: str = "") -> Callable[[str], int]:
    """argparse type: an integer from ``low`` to ``high`` (``what`` says what it counts, in the message)."""

    def check(text: str) -> int:
        try:
            value = int(text.strip())
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected an integer (got {text!r})") from None
        if not low <= value <= high:
            unit = f" {what}" if what else ""
            raise argparse.ArgumentTypeError(f"must be from {low} to {high}{unit} (got {value})")
        return value

    check.__name__ = "integer"  # argparse names the type in its messages
    return check


#: argparse type of ``--workers`` in every command: 1 to :data:`MAX_WORKERS` processes.
workers = count(1, MAX_WORKERS, "processes")


def named_values(texts: Iterable[str], option: str, form: str = "NAME=VALUE") -> dict[str, str]:
    """``NAME=VALUE`` texts of a repeatable option as {NAME: VALUE}, in order.

    Raises
    ------
    ParameterError
        Naming ``option`` for an entry without ``=`` or a name, and for a name given twice (no silent
        "last one wins").
    """
    out: dict[str, str] = {}
    for text in texts:
        name, eq, value = text.partition("=")
        name = name.strip()
        if not eq or not name or not value.strip():
            raise ParameterError(option, f"{option} {text!r}: expected {form}")
        if name in out:
            raise ParameterError(
                option,
                f"{option}: {name} is given twice ({name}={out[name]} and {name}={value}); give it once",
            )
        out[name] = value
    return out


def value_range(name: str, spec: str, option: str = "--range") -> tuple[float, float]:
    """``LO:HI`` of ``NAME=LO:HI`` as floats, LO < HI, both numbers in range."""
    parts = spec.split(":")
    try:
        if len(parts) != 2:
            raise ValueError("two numbers")
        lo, hi = (float(exact_number(x)) for x in parts)
    except ValueError:
        raise ParameterError(option, f"{option} {name}={spec}: expected {name}=LO:HI with LO < HI") from None
    if not hi > lo:
        raise ParameterError(option, f"{option} {name}={spec}: expected {name}=LO:HI with LO < HI")
    return lo, hi
