"""A track on the soil from a TOML file (``examples/soil-ballasted.toml``), every value checked first.

::

    [model]
    track = "ballasted-soil"   # or "soil" (a beam directly on the soil)
    per = "track"              # or "rail": EI, m, k_pad, c_pad, m_s, A_b and P are then per rail
    [physical]
    EI = 1.29e7                # N m^2 ... (the keys of soil.track.TRACK_KINDS), P (N) for a moving load
    [[soil]]                   # layers, top first; the last one is the half-space (soil.profile)
    ...

The analysis runs on the whole track: a file given per rail has those values doubled (the strip, b, is
the whole track's); deflections are the same either way, and outputs say which the file gave.
"""

from __future__ import annotations

import math
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from moving_bogie.errors import ParameterError, suggestion

from .profile import SoilProfile, soil_profile
from .track import LOAD_KEYS, TRACK_KINDS, UNITS, SoilTrack

__all__ = ["SoilInput", "is_soil_file", "load_soil_file", "soil_input"]

#: Values given per rail that the whole track has twice of (b is the whole track's half-width).
PER_RAIL = ("EI", "m", "k_pad", "c_pad", "m_s", "A_b", "P")
#: The keys of [model]: the track, per track or per rail, and a vehicle (``frequencies --file``).
MODEL_KEYS = ("track", "per", "vehicle")
#: Keys that may be zero.
MAY_BE_ZERO = ("c_pad", "m_s")


@dataclass(frozen=True)
class SoilInput:
    """A soil-track file: the track and the load per track, the soil, and how the file gave them."""

    track: SoilTrack
    soil: SoilProfile
    per: str
    load: float | None
    vehicle: str | None = None
    vehicle_values: tuple[tuple[str, float], ...] = ()

    @property
    def rail_factor(self) -> float:
        """Whole-track values over the file's (2 per rail, 1 per track)."""
        return 2.0 if self.per == "rail" else 1.0


def is_soil_file(path: str | Path) -> bool:
    """True when the file's ``[model]`` names a track on soil (read before any other check)."""
    try:
        data = tomllib.loads(Path(path).read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError):
        return False
    return isinstance(data.get("model"), dict) and data["model"].get("track") in TRACK_KINDS


def load_soil_file(path: str | Path, settings: Mapping[str, float] | None = None) -> SoilInput:
    """Read and check a soil-track file; errors name the key (and the layer) and the file.

    ``settings`` (key -> SI value, ``--set``; :mod:`.settings`) change the file's values: the file is
    checked as written first, then as changed, and an error of the changed file names ``--set``.
    """
    from .settings import with_settings

    path = Path(path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except tomllib.TOMLDecodeError as exc:
        raise ParameterError("file", f"{path}: not a valid TOML file: {exc}") from None
    try:
        loaded = soil_input(data)
    except ParameterError as exc:
        raise ParameterError(exc.parameter, f"{path}: {exc}") from None
    if not settings:
        return loaded
    try:
        return soil_input(with_settings(data, settings))
    except ParameterError as exc:
        raise ParameterError("--set", f"--set: {exc}") from None


def _value(table: dict[str, Any], key: str) -> float:
    value = table[key]
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise ParameterError(key, f"{key} in [physical] must be a number (got {value!r})")
    number = float(value)
    if not math.isfinite(number):
        raise ParameterError(key, f"{key} in [physical] must be finite (got {value!r})")
    if key == "P":
        if number == 0:
            raise ParameterError(key, "P must be nonzero (N, downwards positive)")
    elif number < 0 or (number == 0 and key not in MAY_BE_ZERO):
        raise ParameterError(key, f"{key} must be positive (got {number:g} {UNITS[key]})")
    return number


def soil_input(data: dict[str, Any]) -> SoilInput:
    """The checked contents of a parsed soil-track file (see :func:`load_soil_file`)."""
    for key in data:
        if key not in ("model", "physical", "soil"):
            raise ParameterError(
                key, f"unknown table {key!r}; {suggestion(key, ('model', 'physical', 'soil'))}"
            )
    model = data.get("model", {})
    for key in model:
        if key not in MODEL_KEYS:
            raise ParameterError(key, f"unknown key {key!r} in [model]; {suggestion(key, MODEL_KEYS)}")
    vehicle = model.get("vehicle")
    if vehicle is not None and not isinstance(vehicle, str):
        raise ParameterError("vehicle", f"vehicle must be a vehicle's name (got {vehicle!r})")
    kind = model.get("track")
    if kind not in TRACK_KINDS:
        raise ParameterError("track", f"track must be one of {', '.join(TRACK_KINDS)} (got {kind!r})")
    per = model.get("per", "track")
    if per not in ("track", "rail"):
        raise ParameterError("per", f'per must be "track" or "rail" (got {per!r})')
    physical = data.get("physical", {})
    if not isinstance(physical, dict):
        raise ParameterError("physical", "physical must be a table [physical]")
    needed = TRACK_KINDS[kind]
    known = (*needed, *LOAD_KEYS)
    # with a vehicle, the other keys are the vehicle's: model/ checks them (soil.vehicle)
    others = tuple((key, value) for key, value in physical.items() if key not in known)
    for key in physical if vehicle is None else ():
        if key not in known:
            raise ParameterError(
                key, f"unknown key {key!r} in [physical] of track {kind!r}; {suggestion(key, known)}"
            )
    for key in needed:
        if key not in physical:
            raise ParameterError(key, f"{key} ({UNITS[key]}) is missing from [physical] of track {kind!r}")
    values = {key: _value(physical, key) for key in physical if key in known}
    if "soil" not in data:
        raise ParameterError("soil", "soil is missing: give the layers as [[soil]] tables, top first")
    soil = soil_profile(data["soil"])
    factor = 2.0 if per == "rail" else 1.0
    whole = {key: value * factor if key in PER_RAIL else value for key, value in values.items()}
    load = whole.pop("P", None)
    track = SoilTrack(kind=kind, **whole)
    return SoilInput(track=track, soil=soil, per=per, load=load, vehicle=vehicle, vehicle_values=others)
