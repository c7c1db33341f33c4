"""A sweep over the SI parameters of a sleeper-track file: one Floquet strip search per point.

Each point is the file's ``[physical]`` values with the point's values in their place, read and checked by
:func:`~moving_bogie.model.sleeper_input.sleeper_input` exactly as the file's own (the smallest and the
largest value of every axis are checked before any computation), and searched by
:func:`~moving_bogie.roots.strip.floquet_frequencies`: every root in one strip of width Omega_0 up to the
rail's free waves (docs/sleepers.md, Eq. (S14)), converged in the harmonics, and a stable point's margin.
A grid has one dimension per varied parameter, a Sobol design one dimension ``point``; the points are cut
into blocks of ``block_points`` points along the last dimension (one chunk of the store each: a point costs
seconds).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from moving_bogie.errors import ParameterError
from moving_bogie.model.bar import DEFAULT_BAR, check_bar, moves_bar, rule_note
from moving_bogie.model.sleeper_input import SleeperInput, sleeper_input, sleeper_model, sleeper_units
from moving_bogie.roots.verdict import STABLE, UNSTABLE
from moving_bogie.sweep.design import Axis, Block
from moving_bogie.sweep.sleeper_store import (
    SLEEPER_VARIABLES,
    PointGrid,
    block_points,
    create_sleeper_store,
    point_axes,
    point_values,
    write_sleeper_block,
)

if TYPE_CHECKING:
    import xarray

__all__ = [
    "SleeperSweepSpec",
    "SleeperTask",
    "evaluate_sleeper_block",
    "make_sleeper_spec",
    "sleeper_point",
    "sleeper_summary",
]


def _input(
    data: Mapping[str, Any],
    source: str,
    overrides: Mapping[str, float],
    bar: str = DEFAULT_BAR,
    varied: tuple[str, ...] = (),
) -> SleeperInput:
    """The checked input of one point (the bogie's bar moved by ``bar`` along a varied wheel mass,
    :mod:`moving_bogie.model.bar`); a vehicle at rest has no Floquet strip."""
    inp = sleeper_input(data, source, overrides, bar=bar, varied=varied)
    if inp.groups["alpha"] <= 0:
        raise ParameterError("v", "v must be positive on a sleeper track (the strip has width 2 pi v / l)")
    return inp


@dataclass(frozen=True)
class SleeperSweepSpec(PointGrid):
    """A sweep of a sleeper file: its parsed TOML ``data``, the ``settings`` (``--set``) of the base point,
    the varied SI parameters (``axes``, exact values in their units) and the design ("grid" or "sobol")."""

    data: dict[str, Any]
    source: str
    axes: tuple[Axis, ...]
    settings: dict[str, float] = field(default_factory=dict)
    design: str = "grid"
    block_points: int = 1
    extra: dict[str, Any] = field(default_factory=dict)
    bar: str = DEFAULT_BAR

    def __post_init__(self) -> None:
        names = [a.name for a in self.axes]
        if not names:
            raise ParameterError("--vary", "give at least one --vary NAME=...")
        if len(set(names)) != len(names):
            raise ParameterError("--vary", f"--vary: a parameter is varied twice ({', '.join(names)})")
        _ = self.base  # the base point is checked (its errors name the key)
        for a in self.axes:  # every value is checked as the file's own, before any computation
            for v in sorted({min(a.values), max(a.values)}):
                try:
                    _input(self.data, self.source, self.settings | {a.name: float(v)}, self.bar, (a.name,))
                except ParameterError as exc:
                    raise ParameterError("--vary", f"--vary {a.name}: {exc}") from None

    @property
    def base(self) -> SleeperInput:
        """The file's values with the settings: the base point of the sweep."""
        return sleeper_input(self.data, self.source, self.settings)

    @property
    def bar_note(self) -> dict[str, str] | None:
        """The rule of the bogie's bar (:func:`~moving_bogie.model.bar.bar_note`) when an axis moves it."""
        model = sleeper_model(self.data, self.settings)
        names = {a.name for a in self.axes}
        moved = any(spec.si in names and moves_bar(model, g) for g, spec in model.specs.items())
        return rule_note(self.bar) if moved else None

    @property
    def model(self) -> str:
        base = self.base
        return f"{base.beam}/{base.track}/{base.vehicle}"

    @property
    def units(self) -> dict[str, str]:
        """The SI unit of every varied parameter."""
        known = sleeper_units(self.data, self.settings)
        return {a.name: known[a.name] for a in self.axes}

    def describe(self) -> dict[str, Any]:
        """JSON-ready description (stored in the attributes; a resumed sweep must match it)."""
        ranges = self.extra.get("ranges")
        own = self.grid_description("sleepers", self.model, self.base.physical, self.units, ranges)
        return own | ({"bar": note} if (note := self.bar_note) else {}) | {"chunks": list(self.chunks)}

    def operating_point(self) -> dict[str, float]:
        """The base point's value of every varied parameter."""
        physical = self.base.physical
        return {a.name: float(physical[a.name]) for a in self.axes}

    def task(self, block: Block) -> SleeperTask:
        """The worker's task for ``block``: the file's data and only that block's values."""
        names = tuple(a.name for a in self.axes)
        values = self.block_values(block)
        return SleeperTask(self.data, self.source, self.settings, names, values, self.design, self.bar)

    def create_store(self, path: Path) -> None:
        create_sleeper_store(path, self)

    def write_block(self, path: Path, slices: tuple[slice, ...], arrays: dict[str, np.ndarray]) -> None:
        write_sleeper_block(path, slices, arrays)

    def summary(self, path: Path) -> dict[str, Any]:
        from moving_bogie.sweep.store import open_sweep

        return sleeper_summary(self, open_sweep(path, dask=False))


@dataclass(frozen=True)
class SleeperTask:
    """One block of a sleeper sweep: ``values[k]`` the block's values along dimension k (grid) or of
    parameter k at each point (sobol)."""

    data: dict[str, Any]
    source: str
    settings: dict[str, float]
    names: tuple[str, ...]
    values: tuple[tuple[Fraction, ...], ...]
    design: str
    bar: str = DEFAULT_BAR

    def evaluate(self) -> dict[str, np.ndarray]:
        return evaluate_sleeper_block(self)


def sleeper_point(inp: SleeperInput) -> dict[str, Any]:
    """The stored values of one point (docs/sweeps.md): the strip search of Eq. (S14) in SI units."""
    from moving_bogie.kernels.hill import VehicleMatrices
    from moving_bogie.kernels.sleeper_track import SleeperTrack
    from moving_bogie.roots.strip import floquet_frequencies

    module = inp.vehicle_kernels
    result = floquet_frequencies(
        SleeperTrack(inp.foundation, inp.groups), VehicleMatrices.from_module(module, inp.vehicle_groups)
    )
    lowest = min((r.q for r in result.roots), key=lambda q: q.imag, default=complex(np.nan, np.nan))
    return {
        "n_roots": result.count,
        "stable": result.verdict.state == STABLE,
        "unstable": result.verdict.state == UNSTABLE,
        "certain": result.converged and result.count == len(result.roots),
        "Omega_im": lowest.imag / inp.t_scale,
        "margin": np.nan if result.margin is None else result.margin / inp.t_scale,
        "Omega_re": lowest.real / inp.t_scale,
        "harmonics": result.harmonics,
        "Omega0": result.Omega0 / inp.t_scale,
    }


def evaluate_sleeper_block(task: SleeperTask) -> dict[str, np.ndarray]:
    """The arrays of one block (shape of the block), one Floquet strip search per point."""
    shape, points = block_points(task.names, task.values, task.design)
    out = {name: np.full(shape, fill, dtype=dtype) for name, dtype, fill, *_ in SLEEPER_VARIABLES}
    for index, point in points:
        overrides = task.settings | {n: float(v) for n, v in point.items()}
        inp = _input(task.data, task.source, overrides, task.bar, task.names)
        for name, value in sleeper_point(inp).items():
            out[name][index] = value
    out["computed"][...] = True
    return out


def make_sleeper_spec(
    data: dict[str, Any],
    source: str,
    vary: Mapping[str, str],
    *,
    settings: Mapping[str, float] | None = None,
    sample: int | None = None,
    block_points: int = 1,
    bar: str = DEFAULT_BAR,
) -> SleeperSweepSpec:
    """A :class:`SleeperSweepSpec` from ``vary`` = {SI name: "START:STOP:COUNT" or "V1,V2,..."} (with
    ``sample=N``: {SI name: "START:STOP"} and N scrambled Sobol points, seed 0)."""
    known = [name for name in sleeper_units(data, settings) if name != "P"]  # P does not enter the roots
    axes, extra, design = point_axes(vary, known, sample)
    return SleeperSweepSpec(
        data, source, axes, dict(settings or {}), design, block_points, extra, check_bar(bar)
    )


def sleeper_summary(spec: SleeperSweepSpec, ds: xarray.Dataset) -> dict[str, Any]:
    """The verdicts of a sleeper sweep for the summary (:data:`~moving_bogie.sweep.plan.SWEEP_KEYS`): the
    counts of points and the fastest growth."""
    ds = ds.compute()
    growth = np.where(ds.unstable.values, -ds.Omega_im.values, np.nan)
    fastest = None
    if np.isfinite(growth).any():
        at = np.unravel_index(int(np.nanargmax(growth)), growth.shape)
        fastest = {"growth_rate_1_s": float(growth[at])} | point_values(ds, "unstable", at, spec.units)
    return {
        "model": spec.model,
        "unstable_fraction": float(ds.unstable.values.mean()),
        "stable_points": int(ds.stable.sum()),
        "unstable_points": int(ds.unstable.sum()),
        "undetermined_points": int((~ds.stable & ~ds.unstable).sum()),
        "uncertain_points": int((~ds.certain).sum()),
        "fastest_growth": fastest,
        "units": spec.units,
        **({"bar": note} if (note := spec.bar_note) else {}),
    }
