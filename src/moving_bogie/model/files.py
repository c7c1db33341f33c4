"""TOML parameter files.

A file holds either dimensionless parameters (Eqs. 15-17, 59, 63)::

    case = 7              # optional: start from a Table 1 case, then override any key below
    [dimensionless]
    eta_f = 0.05          # required without `case`: eta_f eta_M d cf1 cf2 kappa_v eta_v alpha
    eta_M = 30            # (mu_v may replace cf1, J_b may replace cf2)
    ...
    beam = "tr"           # optional: eta_s (default 0), beam ("eb" or "tr"), S and r (for "tr")
    S = 100
    r = 0.03

or physical parameters in SI units, with the field names of :class:`~moving_bogie.PhysicalParams`::

    [physical]
    EI = 6.4e6            # N m^2
    m = 60                # kg/m
    ...

Decimal numbers are read exactly from their text (``0.1`` is 1/10, never a binary float).
"""

from __future__ import annotations

import dataclasses
import tomllib
from decimal import Decimal
from pathlib import Path
from typing import Any

from moving_bogie.errors import ParameterError
from moving_bogie.model.cases import table1_case
from moving_bogie.model.params import DimensionlessParams
from moving_bogie.model.physical import PhysicalParams

__all__ = ["DIMENSIONLESS_KEYS", "PHYSICAL_KEYS", "load_params_file", "parse_params_toml"]

#: Keys of a ``[dimensionless]`` table: the first eight are required without ``case``; ``mu_v`` may
#: replace ``cf1`` and ``J_b`` may replace ``cf2`` (Eq. 63).
DIMENSIONLESS_KEYS = (
    "eta_f",
    "eta_M",
    "d",
    "cf1",
    "cf2",
    "kappa_v",
    "eta_v",
    "alpha",
    "mu_v",
    "J_b",
    "eta_s",
    "beam",
    "S",
    "r",
)
#: Keys of a ``[physical]`` table (the fields of PhysicalParams).
PHYSICAL_KEYS = tuple(field.name for field in dataclasses.fields(PhysicalParams))
_TOP_LEVEL = ("case", "dimensionless", "physical")


def load_params_file(path: str | Path) -> tuple[DimensionlessParams, PhysicalParams | None]:
    """Read a TOML parameter file.

    Returns
    -------
    (DimensionlessParams, PhysicalParams or None)
        The physical parameters are given only for a ``[physical]`` file.

    Raises
    ------
    ParameterError
        For invalid TOML, an unknown table or key, a missing key, a value of the wrong type or out of
        range; the message names the key and the file.
    FileNotFoundError
        If `path` does not exist.
    """
    path = Path(path)
    return parse_params_toml(path.read_text(encoding="utf-8"), source=str(path))


def parse_params_toml(
    text: str, *, source: str = "<string>"
) -> tuple[DimensionlessParams, PhysicalParams | None]:
    """Parse the text of a parameter file, named `source` in error messages; see :func:`load_params_file`."""
    try:
        data = tomllib.loads(text, parse_float=Decimal)
    except tomllib.TOMLDecodeError as exc:
        raise ParameterError("file", f"{source}: not a valid TOML file: {exc}") from None
    try:
        return _build(data)
    except ParameterError as exc:
        raise ParameterError(exc.parameter, f"{source}: {exc}") from None


def _build(data: dict[str, Any]) -> tuple[DimensionlessParams, PhysicalParams | None]:
    for key in data:
        if key not in _TOP_LEVEL:
            raise ParameterError(
                key, f"unknown top-level key or table {key!r}; expected one of {', '.join(_TOP_LEVEL)}"
            )
    if "dimensionless" in data and "physical" in data:
        raise ParameterError("physical", "give either a [dimensionless] or a [physical] table, not both")
    if "physical" in data:
        if "case" in data:
            raise ParameterError(
                "case", "case cannot be combined with a [physical] table (Table 1 is dimensionless)"
            )
        values = _table(data, "physical", PHYSICAL_KEYS)
        for field in dataclasses.fields(PhysicalParams):
            if field.default is dataclasses.MISSING and field.name not in values:
                raise ParameterError(field.name, f"missing key {field.name!r} in [physical]")
        physical = PhysicalParams(**values)
        return physical.to_dimensionless(), physical
    values = _table(data, "dimensionless", DIMENSIONLESS_KEYS)
    if "case" not in data:
        return DimensionlessParams.from_mapping(values), None
    case = data["case"]
    if isinstance(case, bool) or not isinstance(case, int):
        raise ParameterError("case", f"case must be an integer (got {_toml_type(case)} {case!r})")
    return table1_case(case).replace(**values), None


def _table(data: dict[str, Any], name: str, keys: tuple[str, ...]) -> dict[str, Any]:
    """The table `name` of `data` (empty if absent), with its keys and value types checked."""
    table = data.get(name, {})
    if not isinstance(table, dict):
        raise ParameterError(name, f"{name} must be a table [{name}] (got {type(table).__name__})")
    for key, value in table.items():
        if key not in keys:
            raise ParameterError(key, f"unknown key {key!r} in [{name}]; expected one of {', '.join(keys)}")
        expected = str if key == "beam" else (int, Decimal)
        if isinstance(value, bool) or not isinstance(value, expected):
            kind = "a string" if key == "beam" else "a number"
            raise ParameterError(key, f"{key} in [{name}] must be {kind} (got {_toml_type(value)} {value!r})")
    return dict(table)


def _toml_type(value: Any) -> str:
    return {bool: "boolean", str: "string", list: "array", dict: "table"}.get(
        type(value), type(value).__name__
    )
