"""A vehicle on a sleeper track in SI units as the Floquet runtime takes it (``examples/sleepers.toml``).

A sleeper-track file is a parameter file like any other: ``[model]`` names the beam, a track on periodic
supports and the vehicle, ``[physical]`` gives the SI values per rail, and
:func:`~moving_bogie.model.files.load_parameters` reads it into the one catalogue's parameters
(:mod:`moving_bogie.model.periodic`: the groups of docs/sleepers.md (S2), exact). :class:`SleeperInput`
holds them as the Floquet runtime works with them, in double precision: the track's groups, the vehicle's
groups, the SI values and the scales (:func:`sleeper_input_of`).
"""

from __future__ import annotations

import math
import tomllib
from collections.abc import Collection, Mapping
from dataclasses import dataclass
from pathlib import Path
from types import ModuleType
from typing import TYPE_CHECKING, Any, cast

from moving_bogie.errors import ParameterError
from moving_bogie.generated import parameters as paper_groups
from moving_bogie.model.bar import follow_bar
from moving_bogie.model.catalogue import DEFAULT_MODEL, contact_spring_vehicle, get_model
from moving_bogie.model.physical import PhysicalParams

if TYPE_CHECKING:
    from moving_bogie.model.params import DimensionlessParams
    from moving_bogie.model.periodic import PeriodicFoundation

__all__ = [
    "SleeperInput",
    "load_sleeper_file",
    "sleeper_input",
    "sleeper_input_of",
    "sleeper_model",
    "sleeper_units",
]


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

    def si_units(self) -> tuple[float, float]:
        """(newtons per unit force, metres per unit deflection): ``P / 2`` and ``w_st = P chi / (2 k_e)``
        (docs/sleepers.md (S2); the generated scaling of Eq. (16) with ``k_e`` for ``k_f``).

        Raises
        ------
        ParameterError
            Naming ``P`` when the file gives no static wheel load.
        """
        si = self.physical
        if "P" not in si:
            raise ParameterError("P", "P (the static wheel load, N) is required for the steady response")
        w_st = paper_groups.scales(math.sqrt, si["EI"], si["m"], self.k_e, si["P"])[2]
        return si["P"] / 2, float(w_st)

    @property
    def foundation(self) -> PeriodicFoundation:
        """The generated functions of the beam on its periodic supports, from the catalogue."""
        return cast("PeriodicFoundation", get_model(self.beam, self.track, self.vehicle).foundation)

    @property
    def vehicle_kernels(self) -> ModuleType:
        """The vehicle's generated module, from the catalogue."""
        return get_model(self.beam, self.track, self.vehicle).vehicle_kernels


def sleeper_input_of(params: DimensionlessParams, physical: PhysicalParams | None) -> SleeperInput:
    """The :class:`SleeperInput` of parameters of the one catalogue on periodic supports (as read by
    :func:`~moving_bogie.model.files.load_parameters`, ``--set`` applied): their groups and SI values as
    floats, the scales of (S2).

    Raises
    ------
    ParameterError
        Naming ``file`` when there are no SI parameters (a sleeper track is given in a [physical] table).
    """
    model = params.model
    if physical is None:
        raise ParameterError("file", f"{model.name}: a sleeper track takes a [physical] table in SI units")
    groups = {name: float(getattr(params, name)) for name in model.foundation.MODEL_PARAMETERS}
    vehicle_groups = {name: float(getattr(params, name)) for name in model.vehicle_kernels.MODEL_PARAMETERS}
    si = {name: float(value) for name, value in physical.values().items()}
    scales = physical.scales()
    k_e = float(model.foundation.smeared_stiffness(si, math.sqrt))
    return SleeperInput(
        model.beam, model.track, model.vehicle, groups, vehicle_groups, si, scales.chi, scales.v_ref,
        scales.t_scale, k_e,
    )  # fmt: skip


def load_sleeper_file(path: str | Path, overrides: Mapping[str, float] | None = None) -> SleeperInput:
    """Read and check a sleeper-track file; every error names its key before any computation.

    ``overrides`` replaces or adds ``[physical]`` values (SI, checked as the file's own).
    """
    return sleeper_input(tomllib.loads(Path(path).read_text()), path, overrides)


def sleeper_units(data: Mapping[str, Any], overrides: Mapping[str, float] | None = None) -> dict[str, str]:
    """The ``[physical]`` names a sleeper file of this ``[model]`` takes (with `overrides`), with their SI
    units."""
    model = sleeper_model(data, overrides)
    units = {name: meta["unit"] for name, meta in model.scale_parameters.items()}
    return units | {spec.si: spec.unit for spec in model.specs.values()}


def sleeper_model(data: Mapping[str, Any], overrides: Mapping[str, float] | None = None) -> Any:
    """The file's model; k_H or c_H in ``[physical]`` or the overrides put its wheels on contact springs."""
    names = data.get("model", {})
    physical = data.get("physical", {})
    keys = {*(physical if isinstance(physical, Mapping) else ()), *(overrides or {})}
    vehicle = contact_spring_vehicle(names.get("vehicle", DEFAULT_MODEL["vehicle"]), keys)
    return get_model(names.get("beam"), names.get("track"), vehicle)


def sleeper_input(
    data: Mapping[str, Any],
    path: str | Path,
    overrides: Mapping[str, float] | None = None,
    *,
    bar: str = "fixed",
    varied: Collection[str] = (),
) -> SleeperInput:
    """:func:`load_sleeper_file` of the file's parsed TOML ``data`` (``path`` names it in the messages).

    A point of a sweep: ``varied`` names the SI values of ``overrides`` that the sweep varies, the others
    being its base point's; ``bar`` is the rule of :mod:`moving_bogie.model.bar` for the bogie's bar along a
    varied wheel mass (``"fixed"``: M_b and J_b as given)."""
    try:
        model = sleeper_model(data, overrides)
        if "physical" not in data:
            raise ParameterError("physical", "a sleeper track takes a [physical] table in SI units")
        physical = PhysicalParams(model=model, **{**data["physical"], **(overrides or {})})
        params = physical.to_dimensionless()
        if bar != "fixed" and varied:
            base = {k: v for k, v in (overrides or {}).items() if k not in varied}
            base_params = PhysicalParams(model=model, **{**data["physical"], **base}).to_dimensionless()
            groups = {g for g, spec in model.specs.items() if spec.si in varied}
            moved = follow_bar(base_params, params, bar, groups)
            changed = [g for g in model.specs if getattr(moved, g) != getattr(params, g)]
            if changed:  # the bar's SI values (M_b, J_b) from its moved groups
                si = {model.specs[g].si: float(getattr(moved, g)) * physical.si_factor(g) for g in changed}
                physical = PhysicalParams(model=model, **{**data["physical"], **(overrides or {}), **si})
                params = physical.to_dimensionless()
        return sleeper_input_of(params, physical)
    except ParameterError as exc:
        raise ParameterError(exc.parameter, f"{path}: {exc}") from None
