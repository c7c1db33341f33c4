"""A vehicle on a track on the soil (``frequencies --file``): its parameters and the track it is bound to.

A soil-track file names a vehicle in ``[model]`` (``vehicle = "mass"``) and gives the vehicle's SI values in
``[physical]`` beside the track's, as every ``[physical]`` file does (``examples/soil-mass.toml``). The
vehicle's groups are those of the paper (Eqs. (15)-(17)) with the track's reference stiffness k_ref
(:func:`~.rail_track.reference_stiffness`) in the place of k_f and no foundation damping: the parameters
of the Euler-Bernoulli rail on the Winkler track of k_ref, bound to the soil's own track
(:class:`~.rail_track.SoilRail`) instead of that Winkler track (``moving_bogie.bind``). Given per rail, the
vehicle's masses, inertias, stiffnesses, dampings and loads (the values in kg or N) are doubled like the
track's: the soil carries the whole track and the whole vehicle.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from moving_bogie.errors import ParameterError
from moving_bogie.model.physical import PhysicalParams

from .file import SoilInput, load_soil_file
from .rail_track import SoilRailSpec, reference_stiffness

__all__ = ["SoilVehicle", "load_soil_vehicle", "soil_vehicle"]

#: The beam of the vehicle's scaling (the rail on the soil bends as an Euler-Bernoulli beam, Eq. (S6)).
BEAM = "eb"
#: [physical] keys the soil replaces (the support is the soil's).
SUPPORT_KEYS = ("k_f", "c_f")


@dataclass(frozen=True)
class SoilVehicle:
    """The file's track and soil (``input``), the vehicle's SI parameters scaled with k_ref
    (``physical``) and the track the bound model gets (``rail``)."""

    input: SoilInput
    physical: PhysicalParams
    rail: SoilRailSpec


def _whole(physical: PhysicalParams, values: dict[str, float]) -> dict[str, float]:
    """The values of a per-rail file for the whole track: those in kg or N doubled (module docstring)."""
    units = physical.units()
    return {k: 2 * v if ("kg" in units[k] or "N" in units[k]) else v for k, v in values.items()}


def soil_vehicle(data: SoilInput, *, tol: float = 1e-6) -> SoilVehicle:
    """The vehicle of a read soil-track file on its track (module docstring).

    Raises
    ------
    ParameterError
        When the file names no vehicle or no load P, gives k_f or c_f, or a vehicle value is wrong.
    """
    if data.vehicle is None:
        raise ParameterError(
            "vehicle", 'name the vehicle in [model] (vehicle = "mass", ...) and give its values in [physical]'
        )
    if data.load is None:
        raise ParameterError("P", "P (N, the static load of the vehicle's wheels) is missing from [physical]")
    values = dict(data.vehicle_values)
    for key in SUPPORT_KEYS:
        if key in values:
            raise ParameterError(key, f"{key} does not apply to a track on the soil: the soil is the support")
    k_ref = reference_stiffness(data.track, data.soil)
    track = data.track
    common: dict[str, Any] = {"EI": track.EI, "m": track.m, "k_f": k_ref, "c_f": 0.0, "P": data.load}
    physical = PhysicalParams(beam=BEAM, vehicle=data.vehicle, **(common | values))
    if data.per == "rail":
        physical = PhysicalParams(beam=BEAM, vehicle=data.vehicle, **(common | _whole(physical, values)))
    return SoilVehicle(data, physical, SoilRailSpec(track, data.soil, k_ref, tol))


def load_soil_vehicle(path: str | Path) -> SoilVehicle:
    """Read a soil-track file with a vehicle; errors name the key and the file."""
    data = load_soil_file(path)
    try:
        return soil_vehicle(data)
    except ParameterError as exc:
        raise ParameterError(exc.parameter, f"{path}: {exc}") from None
