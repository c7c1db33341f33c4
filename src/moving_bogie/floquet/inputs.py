"""A vehicle on a sleeper track from a TOML file in SI units (``examples/sleepers.toml``).

The file names the model (``[model]``: beam, track one of ``generated.sleepers.TRACKS``, vehicle) and gives
``[physical]`` SI values per rail: ``EI``, ``m``, the bay ``l``, the support's parameters, the optional
``k_f``, ``c_f``, the vehicle's parameters and ``v``. The groups of docs/sleepers.md (S2) come from the
generated exact scaling; the vehicle's groups from ``generated/parameters.py`` with the smeared stiffness
k_e in the place of k_f. Numbers are floats: the Floquet runtime works in double precision.
"""

from __future__ import annotations

import importlib
import math
import tomllib
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from moving_bogie.errors import ParameterError, suggestion
from moving_bogie.generated import parameters as paper_groups
from moving_bogie.generated import sleepers as generated
from moving_bogie.model.catalogue import contact_spring_vehicle

__all__ = ["SleeperInput", "is_sleeper_file", "load_sleeper_file", "sleeper_input", "sleeper_units"]


@dataclass(frozen=True)
class SleeperInput:
    """The model names, the track's groups, the vehicle's groups and the SI scales of one file."""

    beam: str
    track: str
    vehicle: str
    groups: dict
    vehicle_groups: dict
    physical: dict
    chi: float
    v_ref: float
    t_scale: float
    k_e: float


def is_sleeper_file(path: str | Path) -> bool:
    """True when the file's ``[model]`` table names a sleeper track (read before any other check)."""
    try:
        data = tomllib.loads(Path(path).read_text())
    except (OSError, tomllib.TOMLDecodeError):
        return False
    return isinstance(data.get("model"), dict) and data["model"].get("track") in generated.TRACKS


def _number(si: dict, key: str, path: Path | str) -> float:
    value = si[key]
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise ParameterError(key, f"{key} in {path} must be a number (got {value!r})")
    return float(value)


def load_sleeper_file(path: str | Path, overrides: Mapping[str, float] | None = None) -> SleeperInput:
    """Read and check a sleeper-track file; every error names its key before any computation.

    ``overrides`` replaces or adds ``[physical]`` values (SI, checked as the file's own).
    """
    return sleeper_input(tomllib.loads(Path(path).read_text()), path, overrides)


def _vehicle(data: Mapping[str, Any], overrides: Mapping[str, float] | None = None) -> str:
    """The file's vehicle (``mass`` when it names none), on Hertz contact springs when its ``[physical]``
    table or the overrides set k_H or c_H."""
    physical = data.get("physical", {})
    keys = {*(physical if isinstance(physical, Mapping) else ()), *(overrides or {})}
    return contact_spring_vehicle(data.get("model", {}).get("vehicle", "mass"), keys)


def sleeper_units(data: Mapping[str, Any], overrides: Mapping[str, float] | None = None) -> dict[str, str]:
    """The ``[physical]`` names a sleeper file of this ``[model]`` takes (with `overrides`), with their SI
    units."""
    model = data.get("model", {})
    beam, track, vehicle = model.get("beam", "eb"), model["track"], _vehicle(data, overrides)
    module = importlib.import_module(f"moving_bogie.generated.vehicle_{vehicle}")
    table: dict[str, dict[str, Any]] = generated.PARAMETERS[track][beam]  # type: ignore[assignment]
    ref = generated.TRACKS[track]["reference"]
    paper: dict[str, dict[str, Any]] = paper_groups.PARAMETERS  # type: ignore[assignment]
    units = {"EI": "N m^2", "m": "kg/m", "P": "N", ref[0]: ref[1]}
    units |= {spec["si"]: spec["unit"] for spec in table.values()}
    return units | {paper[g]["si"]: paper[g]["unit"] for g in module.MODEL_PARAMETERS}


def sleeper_input(
    data: Mapping[str, Any], path: str | Path, overrides: Mapping[str, float] | None = None
) -> SleeperInput:
    """:func:`load_sleeper_file` of the file's parsed TOML ``data`` (``path`` names it in the messages)."""
    model = data.get("model", {})
    beam, track, vehicle = model.get("beam", "eb"), model["track"], _vehicle(data, overrides)
    if beam not in generated.BEAMS:
        raise ParameterError(
            "beam", f"no beam {beam!r}; {suggestion(beam, list(generated.BEAMS), listing='one of')}"
        )
    from moving_bogie.generated import DECLARED_VEHICLES

    if vehicle not in DECLARED_VEHICLES:
        hint = suggestion(vehicle, list(DECLARED_VEHICLES), listing="one of")
        raise ParameterError("vehicle", f"no vehicle {vehicle!r}; {hint}")
    if "physical" not in data:
        raise ParameterError("physical", f"{path}: a sleeper track takes a [physical] table in SI units")
    module = importlib.import_module(f"moving_bogie.generated.vehicle_{vehicle}")
    table: dict[str, dict[str, Any]] = generated.PARAMETERS[track][beam]  # type: ignore[assignment]
    ref: str = generated.TRACKS[track]["reference"][0]
    paper: dict[str, dict[str, Any]] = paper_groups.PARAMETERS  # type: ignore[assignment]
    vehicle_si = {paper[g]["si"]: g for g in module.MODEL_PARAMETERS}
    known = set(sleeper_units(data, overrides))
    si = {**data["physical"], **(overrides or {})}
    for key in si:
        if key not in known:
            raise ParameterError(
                key, f"unknown key {key!r} in {path}; {suggestion(key, sorted(known), listing='one of')}"
            )
    values = {key: _number(si, key, path) for key in si}
    optional = {spec["si"]: float(spec["default"]) for spec in table.values() if spec["default"] is not None}
    for key, group in vehicle_si.items():
        if paper[group]["default"] is not None:
            optional[key] = float(paper[group]["default"])
    nonnegative = {"v"} | {key for key, g in vehicle_si.items() if paper[g]["constraint"] != "positive"}
    for key in ("EI", "m", ref, *(s["si"] for s in table.values()), *vehicle_si):
        if key not in values and key not in optional:
            raise ParameterError(key, f"{path} has no {key!r} (required on {beam}/{track}/{vehicle})")
        if key in nonnegative and values.get(key, 0.0) < 0:
            raise ParameterError(key, f"{key} must not be negative (got {values[key]:g})")
        if key in values and key not in optional and key not in nonnegative and values[key] <= 0:
            raise ParameterError(key, f"{key} must be positive (got {values[key]:g})")
    for key, default in optional.items():
        values.setdefault(key, default)
    for spec in table.values():
        if values[spec["si"]] < 0:
            raise ParameterError(
                spec["si"], f"{spec['si']} must not be negative (got {values[spec['si']]:g})"
            )
    tag = track.replace("-", "_")
    chi, v_ref, t_scale, k_e = getattr(generated, f"scales_{tag}")(
        math.sqrt, values["EI"], values["m"], values[ref], values["l"]
    )
    groups = {}
    for name in table:
        fn = getattr(generated, f"dimensionless_{tag}_{name}", None)
        if fn is None:  # a group of the rail itself (S, r, eta_N): the paper's scaling with k_e for k_f
            groups[name] = float(_call(getattr(paper_groups, f"dimensionless_{name}"), values, k_e))
        else:
            groups[name] = float(_call(fn, values))
    vehicle_groups = {
        g: float(_call(getattr(paper_groups, f"dimensionless_{g}"), values, k_e))
        for g in module.MODEL_PARAMETERS
    }
    return SleeperInput(beam, track, vehicle, groups, vehicle_groups, values, chi, v_ref, t_scale, k_e)


def _call(fn: Callable[..., Any], values: dict, reference: float | None = None) -> float:
    """Call a generated scaling function with its SI arguments; with ``reference``, a function of the
    paper's scaling, whose k_f is the reference stiffness: k_e here."""
    names = fn.__code__.co_varnames[: fn.__code__.co_argcount]
    args = {n: math.sqrt if n == "sqrt" else values[n] for n in names if n != "k_f" or reference is None}
    if reference is not None and "k_f" in names:
        args["k_f"] = reference
    return fn(**args)
