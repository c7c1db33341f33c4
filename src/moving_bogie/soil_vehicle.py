"""A vehicle on a track on the soil (docs/soil.md), read from a soil-track file.

The file names a vehicle in ``[model]`` (``vehicle = "mass"``) and gives its SI values in ``[physical]``
beside the track's (:func:`load_soil_vehicle`): the vehicle's groups are the paper's (Eqs. (15)-(17)) with
the track's reference stiffness k_ref (:func:`~moving_bogie.soil.rail_track.reference_stiffness`) in the
place of k_f and no foundation damping, the parameters of the rail (:data:`RAIL_BEAM`) on the Winkler
track of k_ref, which :func:`~moving_bogie.api.bind` binds to the soil's own track
(:class:`~moving_bogie.soil.rail_track.SoilRail`). Given per rail, the vehicle's masses, inertias,
stiffnesses, dampings and loads (the values in kg or N) are doubled like the track's: the soil carries the
whole track and the whole vehicle. Its threshold mass (:func:`threshold_mass`, bound here once as
:func:`~moving_bogie.api.bind` would) is the D-decomposition in the wheel mass along real Omega, in SI.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from moving_bogie.errors import ParameterError
from moving_bogie.model.physical import PhysicalParams

if TYPE_CHECKING:
    from moving_bogie.soil.file import SoilInput
    from moving_bogie.soil.rail_track import SoilRailSpec

__all__ = [
    "RAIL_BEAM",
    "SUPPORT_KEYS",
    "SoilVehicle",
    "ThresholdMass",
    "load_soil_vehicle",
    "soil_vehicle",
    "threshold_mass",
]

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

    @property
    def mass_unit(self) -> float:
        """kg of the wheel mass, as the file gives it (per rail or per track), per unit of its group."""
        name = self.physical.to_dimensionless().model.wheel_mass
        return float(self.physical.si_factor(name)) / self.input.rail_factor

    @property
    def wheel_mass(self) -> float:
        """The file's wheel mass in kg, as the file gives it (per rail or per track)."""
        params = self.physical.to_dimensionless()
        return float(getattr(params, params.model.wheel_mass)) * self.mass_unit


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


#: The lightest mass of a threshold search: the heaviest over this (the lighter the mass, the higher its
#: frequencies and the wider the scan).
LIGHTEST = 64


@dataclass(frozen=True)
class ThresholdMass:
    """The D-decomposition of a vehicle on the soil in its wheel mass along real Omega, in SI (docs/soil.md,
    "The threshold mass"): the masses at which a root crosses the real axis, the direction of each
    crossing, and the threshold (the least mass with a growing root), for masses in [M_min, M_max] and
    0 < Omega <= Omega_max. Masses in kg as the file gives them (per rail or per track)."""

    crossings: tuple[dict[str, float], ...]  # Omega_rad_s, M (kg), change (+1: a root enters Im < 0), moved
    threshold: dict[str, float] | None  # M, Omega_rad_s, moved of the first crossing that makes a root grow
    M_max: float
    M_min: float
    Omega_max_rad_s: float
    samples: int
    notes: tuple[str, ...]
    column: Any  # the dimensionless column (stability/maps/real_axis.py), for counts
    kg_per_group: float

    @classmethod
    def from_column(cls, col: Any, M_max: float, omega_0: float, unit: float) -> ThresholdMass:
        """In SI: ``col`` the dimensionless column of
        :func:`~moving_bogie.stability.maps.real_axis.window_column`, ``omega_0`` rad/s per unit of q,
        ``unit`` kg per unit of the wheel-mass group."""
        crossings = tuple(
            {"Omega_rad_s": c.q * omega_0, "M": c.eta_M * unit, "change": c.change, "moved": c.moved}
            for c in col.crossings
        )
        t = col.threshold
        first = None if t is None else {"M": t.eta_M * unit, "Omega_rad_s": t.q * omega_0, "moved": t.moved}
        top = col.q_max * omega_0
        return cls(crossings, first, M_max, M_max / LIGHTEST, top, col.samples, tuple(col.notes), col, unit)

    def count_at(self, M: float) -> int:
        """The growing roots at the wheel mass ``M`` (kg): the signed crossings below it."""
        return int(self.column.counts([M / self.kg_per_group])[0])

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: every field but the column."""
        keys = ("Omega_max_rad_s", "samples", "M_max", "M_min", "crossings", "threshold", "notes")
        return {k: list(v) if isinstance(v, tuple) else v for k, v in ((k, getattr(self, k)) for k in keys)}


def threshold_mass(
    vehicle: SoilVehicle, M_max: float, *, progress: Callable[[float], None] | None = None
) -> ThresholdMass:
    """The threshold mass of ``vehicle`` at its speed (:class:`ThresholdMass`),
    masses up to ``M_max`` (kg, as the file gives them) down to M_max /
    :data:`LIGHTEST`
    (:func:`~moving_bogie.stability.maps.real_axis.window_column`: the real axis sampled beyond every real
    root of those masses, the Winkler equivalent's far field).

    Examples
    --------
    >>> import moving_bogie as mb
    >>> vehicle = mb.load_soil_vehicle("examples/soil-unstable.toml")
    >>> found = mb.threshold_mass(vehicle, M_max=240e3)  # doctest: +SKIP
    >>> round(found.threshold["M"])  # doctest: +SKIP
    27552
    """
    from moving_bogie.kernels.bound import BoundModel
    from moving_bogie.stability.maps.real_axis import window_column

    if not M_max > 0:
        raise ParameterError("M_max", f"M_max must be a positive mass in kg (got {M_max!r})")
    unit = vehicle.mass_unit
    bound = BoundModel(
        vehicle.physical.to_dimensionless(), track=vehicle.rail
    )  # bound once, as api.bind does
    col = window_column(
        bound,
        equivalent=BoundModel(bound.params),
        eta_max=M_max / unit,
        eta_min=M_max / unit / LIGHTEST,
        progress=progress,
    )
    omega_0 = float(bound.track.omega_0)  # type: ignore[attr-defined]
    return ThresholdMass.from_column(col, M_max, omega_0, unit)
