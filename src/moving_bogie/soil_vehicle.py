"""A vehicle on a track on the soil (docs/soil.md), read from a soil-track file.

The file names a vehicle in ``[model]`` (``vehicle = "mass"``) and gives its SI values in ``[physical]``
beside the track's (:func:`load_soil_vehicle`): the vehicle's groups are the paper's (Eqs. (15)-(17)) with
the track's reference stiffness k_ref (:func:`~moving_bogie.soil.rail_track.reference_stiffness`) in the
place of k_f and no foundation damping, the parameters of the rail (:data:`RAIL_BEAM`) on the Winkler
track of k_ref, which :func:`~moving_bogie.api.bind` binds to the soil's own track
(:class:`~moving_bogie.soil.rail_track.SoilRail`). Given per rail, the vehicle's masses, inertias,
stiffnesses, dampings and loads (the values in kg or N) are doubled like the track's: the soil carries the
whole track and the whole vehicle.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from moving_bogie.errors import ParameterError
from moving_bogie.model.physical import PhysicalParams

if TYPE_CHECKING:
    from moving_bogie.soil.file import SoilInput
    from moving_bogie.soil.rail_track import SoilRailSpec

__all__ = ["RAIL_BEAM", "SUPPORT_KEYS", "SoilVehicle", "load_soil_vehicle", "soil_vehicle"]

#: The beam of the vehicle's scaling: the rails of every track on the soil bend as Euler-Bernoulli beams,
#: EI k1^4 - m omega^2 in the rail's dynamic stiffness (:mod:`moving_bogie.soil.track`, Eq. (S6)).
RAIL_BEAM = "eb"
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
    """The vehicle of a read soil-track file on its track (the module's docstring).

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
    from moving_bogie.soil.rail_track import SoilRailSpec, reference_stiffness

    k_ref = reference_stiffness(data.track, data.soil)
    track = data.track
    common: dict[str, Any] = {"EI": track.EI, "m": track.m, "k_f": k_ref, "c_f": 0.0, "P": data.load}
    physical = PhysicalParams(beam=RAIL_BEAM, vehicle=data.vehicle, **(common | values))
    if data.per == "rail":
        physical = PhysicalParams(beam=RAIL_BEAM, vehicle=data.vehicle, **(common | _whole(physical, values)))
    return SoilVehicle(data, physical, SoilRailSpec(track, data.soil, k_ref, tol))


def load_soil_vehicle(path: str | Path, settings: Mapping[str, float] | None = None) -> SoilVehicle:
    """Read a soil-track file with a vehicle (:func:`soil_vehicle`), its values changed by ``settings``
    (key -> SI value, ``--set``: :func:`~moving_bogie.soil.file.load_soil_file`); errors name the key and
    the file, or ``--set`` when the key is one of the settings."""
    from moving_bogie.soil.file import load_soil_file

    data = load_soil_file(path, settings)
    try:
        return soil_vehicle(data)
    except ParameterError as exc:
        where = "--set" if settings and exc.parameter in settings else str(path)
        raise ParameterError(exc.parameter, f"{where}: {exc}") from None
