"""Numbers as a reader sees them: ``1.22 1/s``, never a Python repr, never ``-0.0``.

Every result shows its numbers through these helpers, in the terminal (:func:`field_lines`), in JSON
(:func:`quantity`, :func:`json_clean`) and in Jupyter (:mod:`moving_bogie.html_repr`). A quantity in JSON is
the object ``{"value": number, "unit": text}``; the unit ``"1"`` marks a dimensionless number.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from numbers import Real
from typing import Any

__all__ = [
    "GroupUnits",
    "field_lines",
    "json_clean",
    "number_text",
    "quantity",
    "quantity_text",
    "value_text",
]


def _is_number(x: object) -> bool:
    return isinstance(x, Real) and not isinstance(x, bool)


def clean_zero(x: float) -> float:
    """``x`` with a negative zero made positive (``-0.0`` reads as a sign that is not there)."""
    return 0.0 if x == 0 else x


def number_text(x: object, digits: int = 6) -> str:
    """A number in at most ``digits`` significant digits (``n/a`` for None; no ``-0``)."""
    if x is None:
        return "n/a"
    if isinstance(x, bool) or not _is_number(x):
        return str(x)
    if isinstance(x, int):
        return str(x)
    value = float(x)  # type: ignore[arg-type]
    if not math.isfinite(value):
        return str(value)
    text = f"{clean_zero(value):.{digits}g}"
    return "0" if text in ("-0", "0") else text


def quantity(value: float | None, unit: str) -> dict[str, Any]:
    """The JSON of a quantity: ``{"value": value, "unit": unit}`` (value None when not defined)."""
    return {"value": None if value is None else clean_zero(float(value)), "unit": unit}


def quantity_text(value: object, unit: str, digits: int = 6) -> str:
    """``1.22 1/s``: the number and its unit (the number alone for the unit ``1`` or none)."""
    text = number_text(value, digits)
    return text if value is None or unit in ("", "1") else f"{text} {unit}"


def _is_quantity(value: object) -> bool:
    return (
        isinstance(value, Mapping)
        and set(value) >= {"value", "unit"}
        and set(value) <= {"value", "unit", "name"}
    )


def value_text(value: object, digits: int = 6) -> str:
    """Any JSON value as text for the terminal: a quantity as ``1.22 1/s``, a list as ``a, b, c``, an
    object as ``key value; key value``, a number by :func:`number_text`."""
    if _is_quantity(value):
        assert isinstance(value, Mapping)
        text = quantity_text(value["value"], str(value["unit"]), digits)
        return f"{value['name']} = {text}" if "name" in value else text
    if isinstance(value, Mapping):
        return "; ".join(f"{k} {value_text(v, digits)}" for k, v in value.items())
    if isinstance(value, list | tuple):
        return ", ".join(value_text(v, digits) for v in value)
    return number_text(value, digits)


def field_lines(fields: Mapping[str, Any], *, skip: Iterable[str] = (), width: int = 18) -> list[str]:
    """One line per field, ``name  value`` with the value as :func:`value_text` writes it."""
    left_out = set(skip)
    return [f"{k:{width}s} {value_text(v)}" for k, v in fields.items() if k not in left_out]


def json_clean(data: Any) -> Any:
    """JSON ``data`` with every negative zero made ``0.0`` (lists, tuples and objects walked through)."""
    if isinstance(data, float):
        return clean_zero(data)
    if isinstance(data, Mapping):
        return {k: json_clean(v) for k, v in data.items()}
    if isinstance(data, list | tuple):
        return [json_clean(v) for v in data]
    return data


class GroupUnits:
    """A plane shown in its own dimensionless groups: the units of a result that has no SI units.

    It answers as :class:`~moving_bogie.stability.figures.plot_units.PlaneUnits` does for the groups (the
    same methods), so that a result shows itself through either without importing the figures.
    """

    si = False

    def name(self, group: str) -> str:
        return group

    def unit(self, group: str) -> str:
        return "1"

    def value(self, group: str, x: Any) -> Any:
        return x

    def frequency(self, q: Any) -> Any:
        return q
