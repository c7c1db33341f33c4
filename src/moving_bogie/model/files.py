"""TOML parameter files.

A file names its model (optional; default the paper's) and holds either dimensionless parameters::

    case = 7              # optional: start from a Table 1 case, then override any key below
    [model]
    beam = "tr"           # eb | tr; track = "one-layer"; vehicle = "bogie" | "masses"
    [dimensionless]
    eta_f = 0.05          # the model's groups (moving-bogie models lists them); cf1/cf2 may replace mu_v/J_b
    S = 100
    r = 0.03
    ...

or physical parameters in SI units, with the SI names of the model's parameters and the scales EI, m, k_f, P::

    [physical]
    EI = 6.4e6            # N m^2
    m = 60                # kg/m
    ...

Decimal numbers are read exactly from their text (``0.1`` is 1/10, never a binary float). The keys a
table accepts come from the generated metadata, so a model added in ``derivations/`` is read with no edit.
"""

from __future__ import annotations

import tomllib
from decimal import Decimal
from pathlib import Path
from typing import Any

from moving_bogie.errors import ParameterError, suggestion
from moving_bogie.model.cases import table1_case
from moving_bogie.model.catalogue import DEFAULT_MODEL, contact_spring_vehicle, default_catalogue, get_model
from moving_bogie.model.params import DimensionlessParams
from moving_bogie.model.physical import PhysicalParams

#: The tracks on soil (soil/track.py) and the commands that take their files (cli/soil_cmd.py).
SOIL_TRACKS = ("soil", "ballasted-soil")
SOIL_COMMANDS = (
    "dispersion", "critical-velocity", "moving-load", "frequencies", "instability-lines", "stability-map",
    "sweep",
)  # fmt: skip

__all__ = ["dimensionless_keys", "load_parameters", "load_params_file", "parse_params_toml", "physical_keys"]

_TOP_LEVEL = ("case", "model", "dimensionless", "physical")
_MODEL_KEYS = ("beam", "track", "vehicle")


def dimensionless_keys() -> tuple[str, ...]:
    """Keys of a ``[dimensionless]`` table: every group and alternative of the catalogue (and ``beam``)."""
    catalogue = default_catalogue()
    return (*catalogue.specs, *catalogue.parameters.ALTERNATIVES, "beam")


def physical_keys() -> tuple[str, ...]:
    """Keys of a ``[physical]`` table: the scale parameters and the SI name of every group, on any track.

    A track may name SI parameters its own way (a layered track's railpads ``k_1``, ``c_1``); its model's
    metadata says so, and its names are keys too.
    """
    catalogue = default_catalogue()
    meta = catalogue.parameters
    keys = [*meta.SCALE_PARAMETERS, *(m["si"] for m in meta.PARAMETERS.values())]
    for model in catalogue.models():
        keys += [*model.scale_parameters, *(spec.si for spec in model.specs.values())]
    return tuple(dict.fromkeys(keys))


def load_parameters(path: str | Path) -> tuple[DimensionlessParams, PhysicalParams | None]:
    """Read a TOML parameter file (the files of ``examples/``; ``load_params_file`` is the same function).

    The file has a ``[model]`` table (beam, track, vehicle) and a ``[dimensionless]`` table of the groups
    (optionally on top of ``case = N`` of Table 1) or a ``[physical]`` table of SI parameters.

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

    Examples
    --------
    >>> import pathlib, tempfile
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "case7-faster.toml"
    >>> _ = path.write_text("case = 7\\n[dimensionless]\\nalpha = 0.5\\n")
    >>> params, physical = load_parameters(path)
    >>> float(params.alpha), float(params.eta_M), physical is None
    (0.5, 30.0, True)
    """
    path = Path(path)
    return parse_params_toml(path.read_text(encoding="utf-8"), source=str(path))


#: The former name of :func:`load_parameters`, kept.
load_params_file = load_parameters


def parse_params_toml(
    text: str, *, source: str = "<string>"
) -> tuple[DimensionlessParams, PhysicalParams | None]:
    """Parse the text of a parameter file, named `source` in error messages; see :func:`load_parameters`."""
    try:
        data = tomllib.loads(text, parse_float=Decimal)
    except tomllib.TOMLDecodeError as exc:
        raise ParameterError("file", f"{source}: not a valid TOML file: {exc}") from None
    try:
        return _build(data)
    except ParameterError as exc:
        raise ParameterError(exc.parameter, f"{source}: {exc}") from None


def _build(data: dict[str, Any]) -> tuple[DimensionlessParams, PhysicalParams | None]:
    if isinstance(data.get("model"), dict) and data["model"].get("track") in SOIL_TRACKS:
        raise ParameterError(
            "track",
            f"track {data['model']['track']!r} (a track on soil) is analysed by the commands "
            f"{', '.join(SOIL_COMMANDS)} with --file (docs/soil.md), not by this one",
        )
    for key in data:
        if key not in _TOP_LEVEL:
            raise ParameterError(
                key, f"unknown top-level key or table {key!r}; {suggestion(key, _TOP_LEVEL)}"
            )
    if "dimensionless" in data and "physical" in data:
        raise ParameterError("physical", "give either a [dimensionless] or a [physical] table, not both")
    model = _table(data, "model", _MODEL_KEYS)
    # k_H or c_H (kappa_H, eta_H) put each wheel of the vehicle on its own contact spring
    vehicle = model.get("vehicle", DEFAULT_MODEL["vehicle"])
    if contact_spring_vehicle(vehicle, _keys(data)) != vehicle:
        model["vehicle"] = contact_spring_vehicle(vehicle, _keys(data))
    if not {"case", "dimensionless", "physical"} & set(data):
        raise ParameterError("file", _no_parameters(model))
    if "physical" in data:
        if "case" in data:
            raise ParameterError(
                "case", "case cannot be combined with a [physical] table (Table 1 is dimensionless)"
            )
        physical = PhysicalParams(**model, **_table(data, "physical", physical_keys()))
        return physical.to_dimensionless(), physical
    values = _table(data, "dimensionless", dimensionless_keys())
    if "beam" in values and "beam" in model:
        raise ParameterError("beam", "give beam in [model] only")
    values |= model
    if "case" not in data:
        return DimensionlessParams.from_mapping(values), None
    case = data["case"]
    if isinstance(case, bool) or not isinstance(case, int):
        raise ParameterError("case", f"case must be an integer (got {_toml_type(case)} {case!r})")
    return table1_case(case).replace(**values), None


def _keys(data: dict[str, Any]) -> set[str]:
    """The keys of the file's parameter tables."""
    tables = (data.get(name) for name in ("physical", "dimensionless"))
    return {key for table in tables if isinstance(table, dict) for key in table}


def _no_parameters(table: dict[str, Any]) -> str:
    """What a file that sets no parameters lacks: the SI names and units of its model's [physical] table."""
    try:
        specs = get_model(**table)
    except ParameterError:
        specs = get_model()
    required = {k: v["unit"] for k, v in specs.scale_parameters.items()}
    required |= {spec.si: spec.unit for spec in specs.specs.values() if spec.default is None}
    names = ", ".join(f"{k} [{unit}]" for k, unit in required.items())
    return (
        f"the file sets no parameters: give a [physical] table in SI units ({names}), or a [dimensionless] "
        "table of the groups, or case = N of Table 1 (moving-bogie models lists the names)"
    )


def _table(data: dict[str, Any], name: str, keys: tuple[str, ...]) -> dict[str, Any]:
    """The table `name` of `data` (empty if absent), with its keys and value types checked."""
    table = data.get(name, {})
    if not isinstance(table, dict):
        raise ParameterError(name, f"{name} must be a table [{name}] (got {type(table).__name__})")
    for key, value in table.items():
        if key not in keys:
            raise ParameterError(key, f"unknown key {key!r} in [{name}]; {suggestion(key, keys)}")
        expected = str if key in _MODEL_KEYS else (int, Decimal)
        if isinstance(value, bool) or not isinstance(value, expected):
            kind = "a string" if key in _MODEL_KEYS else "a number"
            raise ParameterError(key, f"{key} in [{name}] must be {kind} (got {_toml_type(value)} {value!r})")
    return dict(table)


def _toml_type(value: Any) -> str:
    return {bool: "boolean", str: "string", list: "array", dict: "table"}.get(
        type(value), type(value).__name__
    )
