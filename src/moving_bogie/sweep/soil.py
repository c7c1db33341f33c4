"""A sweep over the values of a soil-track file: the critical velocity of the track on its soil per point.

Each point is the file with the point's values in their place, as ``--set KEY=VALUE`` puts them
(:mod:`moving_bogie.soil.settings`: ``[physical]`` keys of the track, layer keys numbered from 1 at the top),
checked by the file's own checks (the smallest and the largest value of every axis before any computation),
and its critical velocity computed by :func:`~moving_bogie.soil.critical.critical_velocity`: the least phase
velocity of the coupled guided waves and the uncoupled intersection estimate (docs/soil.md). The store's
layout is a sleeper sweep's (:mod:`moving_bogie.sweep.sleeper_store`) with the variables of
:data:`SOIL_VARIABLES`; a point costs seconds, so a block is one point by default.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path
from typing import Any

import numpy as np

from moving_bogie.errors import ParameterError
from moving_bogie.soil.file import SoilInput, soil_input
from moving_bogie.soil.settings import key_unit, settable_keys, with_settings
from moving_bogie.soil.track import LOAD_KEYS, TRACK_KINDS
from moving_bogie.sweep.design import Axis, Block
from moving_bogie.sweep.sleeper_store import (
    PointGrid,
    block_points,
    create_sleeper_store,
    point_axes,
    point_values,
    write_sleeper_block,
)

__all__ = ["SOIL_VARIABLES", "SoilSweepSpec", "SoilTask", "make_soil_spec", "soil_point", "soil_summary"]

#: Data variables of a soil sweep: (name, dtype, fill value, long_name, units).
SOIL_VARIABLES: tuple[tuple[str, str, Any, str, str], ...] = (
    ("v_cr", "float64", np.nan, "least phase velocity of the coupled guided waves (NaN: none found)", "m/s"),
    ("omega_cr", "float64", np.nan, "frequency of v_cr", "rad/s"),
    ("v_cr_uncoupled", "float64", np.nan, "uncoupled intersection estimate (Mezher et al. 2016)", "m/s"),
    ("omega_uncoupled", "float64", np.nan, "frequency of v_cr_uncoupled", "rad/s"),
    ("found", "bool", False, "a guided wave of the coupled track was found (v_cr is finite)", "1"),
    (
        "noted",
        "bool",
        False,
        "critical_velocity noted a doubt (v_cr at a grid point or the range's end)",
        "1",
    ),
    ("computed", "bool", False, "the point's block has been computed and written", "1"),
)
SOIL_ATTRS = {
    "title": "moving-bogie sweep of the critical velocity of a track on the soil",
    "kind": "soil",
    "search": (
        "soil.critical.critical_velocity: the least phase velocity of the coupled guided waves of the "
        "track on its soil, and the uncoupled intersection estimate (docs/soil.md)"
    ),
}


def _input(data: Mapping[str, Any], settings: Mapping[str, float]) -> SoilInput:
    return soil_input(with_settings(data, settings))


@dataclass(frozen=True)
class _Base:
    physical: dict[str, float]


@dataclass(frozen=True)
class SoilSweepSpec(PointGrid):
    """A sweep of a soil-track file: its parsed TOML ``data``, the ``settings`` (``--set``) of the base
    point, the varied keys (``axes``, exact values in their units) and the design ("grid" or "sobol")."""

    data: dict[str, Any]
    source: str
    axes: tuple[Axis, ...]
    settings: dict[str, float] = field(default_factory=dict)
    design: str = "grid"
    block_points: int = 1
    extra: dict[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        _input(self.data, self.settings)  # the base point is checked (its errors name the key)
        for a in self.axes:  # every value is checked as the file's own, before any computation
            for v in sorted({min(a.values), max(a.values)}):
                try:
                    _input(self.data, self.settings | {a.name: float(v)})
                except ParameterError as exc:
                    raise ParameterError("--vary", f"--vary {a.name}: {exc}") from None

    @property
    def base(self) -> _Base:
        """The base point's values (SI): the file's [physical] keys and every layer's h, rho, E, nu, c_s,
        c_p and eta, numbered from 1 at the top (the half-space without h)."""
        data = with_settings(self.data, self.settings)
        values = {k: float(v) for k, v in data.get("physical", {}).items()}
        for i, layer in enumerate(_input(self.data, self.settings).soil.layers, start=1):
            e = 2 * layer.mu * (1 + layer.nu)
            own = {"h": layer.h, "rho": layer.rho, "E": e, "nu": layer.nu, "c_s": layer.c_s, "c_p": layer.c_p}
            values |= {f"{k}{i}": v for k, v in (own | {"eta": layer.eta}).items() if math.isfinite(v)}
        return _Base(values)

    @property
    def model(self) -> str:
        inp = _input(self.data, self.settings)
        return f"{inp.track.kind} track on {len(inp.soil.layers)}-layer soil (per {inp.per})"

    @property
    def units(self) -> dict[str, str]:
        return {a.name: key_unit(a.name) for a in self.axes}

    def describe(self) -> dict[str, Any]:
        """JSON-ready description (stored in the attributes; a resumed sweep must match it)."""
        ranges = self.extra.get("ranges")
        own = self.grid_description("soil", self.model, self.base.physical, self.units, ranges)
        return own | {"chunks": list(self.chunks)}

    def operating_point(self) -> dict[str, float]:
        physical = self.base.physical
        return {a.name: physical[a.name] for a in self.axes if a.name in physical}

    def task(self, block: Block) -> SoilTask:
        names = tuple(a.name for a in self.axes)
        return SoilTask(self.data, self.settings, names, self.block_values(block), self.design)

    def create_store(self, path: Path) -> None:
        create_sleeper_store(path, self, SOIL_VARIABLES, SOIL_ATTRS)

    def write_block(self, path: Path, slices: tuple[slice, ...], arrays: dict[str, np.ndarray]) -> None:
        write_sleeper_block(path, slices, arrays, SOIL_VARIABLES)

    def summary(self, path: Path) -> dict[str, Any]:
        from moving_bogie.sweep.store import open_sweep

        return soil_summary(self, open_sweep(path, dask=False))


@dataclass(frozen=True)
class SoilTask:
    """One block of a soil sweep: ``values[k]`` the block's values along dimension k (grid) or of key k at
    each point (sobol)."""

    data: dict[str, Any]
    settings: dict[str, float]
    names: tuple[str, ...]
    values: tuple[tuple[Fraction, ...], ...]
    design: str

    def evaluate(self) -> dict[str, np.ndarray]:
        shape, points = block_points(self.names, self.values, self.design)
        out = {name: np.full(shape, fill, dtype=dtype) for name, dtype, fill, *_ in SOIL_VARIABLES}
        for index, point in points:
            inp = _input(self.data, self.settings | {n: float(v) for n, v in point.items()})
            for name, value in soil_point(inp).items():
                out[name][index] = value
        out["computed"][...] = True
        return out


def soil_point(inp: SoilInput) -> dict[str, Any]:
    """The stored values of one point: the critical velocities of the track on its soil (docs/soil.md)."""
    from moving_bogie.soil.critical import critical_velocity

    crit = critical_velocity(inp.track, inp.soil)
    return {
        "v_cr": crit.v_cr,
        "omega_cr": crit.omega_cr,
        "v_cr_uncoupled": crit.v_cr_uncoupled,
        "omega_uncoupled": crit.omega_uncoupled,
        "found": bool(np.isfinite(crit.v_cr)),
        "noted": bool(crit.notes) and bool(np.isfinite(crit.v_cr)),
    }


def make_soil_spec(
    data: dict[str, Any],
    source: str,
    vary: Mapping[str, str],
    *,
    settings: Mapping[str, float] | None = None,
    sample: int | None = None,
    block_points: int = 1,
) -> SoilSweepSpec:
    """A :class:`SoilSweepSpec` from ``vary`` = {key: "START:STOP:COUNT" or "V1,V2,..."} (with ``sample=N``:
    {key: "START:STOP"} and N scrambled Sobol points, seed 0); the keys are the track's and the layers'
    (:func:`~moving_bogie.soil.settings.settable_keys`; the load and a vehicle's values do not enter v_cr)."""
    track = TRACK_KINDS.get(data.get("model", {}).get("track"), ())
    layer_keys = [k for k in settable_keys(data) if k[-1].isdigit()]
    known = [*track, *layer_keys]
    for name in vary:
        if name in LOAD_KEYS or (name not in known and name in settable_keys(data)):
            raise ParameterError("--vary", f"--vary {name}: {name} does not enter the critical velocity")
    axes, extra, design = point_axes(vary, known, sample)
    return SoilSweepSpec(data, source, axes, dict(settings or {}), design, block_points, extra)


def soil_summary(spec: SoilSweepSpec, ds: Any) -> dict[str, Any]:
    """The summary of a soil sweep (:data:`~moving_bogie.sweep.plan.SWEEP_KEYS`: a critical velocity is no
    stability verdict, so ``unstable_fraction`` is None, and ``uncertain_points`` counts the points without
    a guided wave or with a note of :func:`~moving_bogie.soil.critical.critical_velocity`), with the least and
    the greatest v_cr and their points (of the points found and not noted)."""
    ds = ds.compute()
    v = np.where(ds.found.values & ~ds.noted.values, ds.v_cr.values, np.nan)
    out: dict[str, Any] = {
        "model": spec.model,
        "unstable_fraction": None,
        "uncertain_points": int((ds.computed.values & (~ds.found.values | ds.noted.values)).sum()),
        "units": spec.units | {"v_cr": "m/s", "v_cr_uncoupled": "m/s"},
    }
    for label, pick in (("v_cr_min", np.nanargmin), ("v_cr_max", np.nanargmax)):
        if not np.isfinite(v).any():
            out[label] = None
            continue
        at = np.unravel_index(int(pick(v)), v.shape)
        out[label] = {"v_cr": float(v[at])} | point_values(ds, "v_cr", at, spec.units)
    return out
