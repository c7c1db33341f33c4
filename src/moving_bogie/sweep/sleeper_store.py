"""The zarr store of a sleeper sweep (:mod:`moving_bogie.sweep.sleepers`), in SI units.

Layout: one dimension per varied SI parameter (``v`` in m/s, ``l`` in m, ... float64 with ``units`` and
the exact decimal values in ``exact``), or one dimension ``point`` on a Sobol design (each parameter a
coordinate along it); the data variables of :data:`SLEEPER_VARIABLES`,
chunked like the blocks. The safety rules are those of :mod:`moving_bogie.sweep.store`: the store is
created under a temporary name and renamed into place, and ``computed`` is written last.
"""

from __future__ import annotations

import json
import math
import os
import shutil
from collections.abc import Collection, Mapping
from fractions import Fraction
from pathlib import Path
from typing import Any, Protocol

import numpy as np

from moving_bogie.model.exact import fraction_to_text
from moving_bogie.sweep.design import Axis, Block, grid_blocks
from moving_bogie.sweep.store import (
    StorePath,
    consolidate,
    package_version,
    store_array,
    store_group,
    write_coordinate,
)

__all__ = [
    "PointGrid",
    "block_points",
    "point_axes",
    "point_values",
    "SLEEPER_ATTRS",
    "SLEEPER_VARIABLES",
    "SleeperLayout",
    "create_sleeper_store",
    "write_sleeper_block",
]

#: Data variables of a sleeper sweep: (name, dtype, fill value, long_name, units).
SLEEPER_VARIABLES: tuple[tuple[str, str, Any, str, str], ...] = (
    (
        "n_roots",
        "int16",
        -1,
        "roots counted in the strip up to the rail's free waves (-1: not searched)",
        "1",
    ),
    ("stable", "bool", False, "verdict STABLE: every root found decays, the window complete", "1"),
    ("unstable", "bool", False, "verdict UNSTABLE: a root with Im Omega < 0", "1"),
    ("certain", "bool", False, "converged in the harmonics and every counted root located", "1"),
    ("Omega_im", "float64", np.nan, "most negative Im Omega (-Im Omega: growth rate); NaN: no root", "1/s"),
    ("margin", "float64", np.nan, "STABLE: decay rate of the least-damped vibration; else NaN", "1/s"),
    ("Omega_re", "float64", np.nan, "Re Omega of that root", "rad/s"),
    ("harmonics", "int16", -1, "harmonics used: N of n = -N-1..N", "1"),
    ("Omega0", "float64", np.nan, "sleeper-passing frequency Omega_0 = 2 pi v / l", "rad/s"),
    ("computed", "bool", False, "the point's block has been computed and written", "1"),
)


class PointGrid:
    """The points of a sweep whose every point costs seconds (a sleeper or a soil sweep): a grid with one
    dimension per axis, or one dimension ``point`` on a Sobol design, cut into blocks of ``block_points``
    points along the last dimension (one chunk of the store each). The class gives ``axes``, ``design``
    and ``block_points``."""

    axes: tuple[Axis, ...]
    design: str
    block_points: int

    @property
    def dims(self) -> tuple[str, ...]:
        return ("point",) if self.design == "sobol" else tuple(a.name for a in self.axes)

    @property
    def shape(self) -> tuple[int, ...]:
        if self.design == "sobol":
            return (len(self.axes[0].values),)
        return tuple(len(a.values) for a in self.axes)

    @property
    def size(self) -> int:
        return math.prod(self.shape)

    @property
    def chunks(self) -> tuple[int, ...]:
        """One value of every dimension but the last, ``block_points`` values of the last."""
        return (*(1 for _ in self.shape[:-1]), min(self.shape[-1], self.block_points))

    def blocks(self) -> list[Block]:
        """Every block, in a fixed order (its index is its place in that order)."""
        return grid_blocks(self.shape, self.chunks)

    def grid_description(
        self, kind: str, label: str, physical: dict[str, float], units: dict[str, str], ranges: Any
    ) -> dict[str, Any]:
        """The JSON-ready description of the sweep (stored in the attributes; a resumed sweep must match
        it): its ``kind``, the ``label`` of its model, the varied values exactly, or the ranges of a Sobol
        design (``ranges``)."""
        return {
            "kind": kind,
            "model": label,
            "physical": physical,
            "design": self.design,
            "varied": ranges or {a.name: [fraction_to_text(v) for v in a.values] for a in self.axes},
            "units": units,
            "points": self.size,
        }

    def block_values(self, block: Block) -> tuple[tuple[Fraction, ...], ...]:
        """The block's values along each dimension (grid), or of each axis at each point (sobol)."""
        if self.design == "sobol":
            return tuple(a.values[block.slices[0]] for a in self.axes)
        return tuple(a.values[s] for a, s in zip(self.axes, block.slices))


def point_axes(
    vary: Mapping[str, str], known: Collection[str], sample: int | None
) -> tuple[tuple[Axis, ...], dict[str, Any], str]:
    """(axes, extra, design) of ``vary`` = {name: "START:STOP:COUNT" or "V1,V2,..."} over the names
    ``known`` (with ``sample=N``: {name: "START:STOP"} and N scrambled Sobol points, seed 0)."""
    from moving_bogie.sweep.design import parse_vary, sobol_axes

    if sample is None:
        return tuple(Axis(*parse_vary(f"{n}={s}", known)) for n, s in vary.items()), {}, "grid"
    ranges = dict(parse_vary(f"{n}={s}", known, needs_count=False) for n, s in vary.items())
    extra = {"ranges": {k: [str(v) for v in r] for k, r in ranges.items()}, "n": sample, "seed": 0}
    return sobol_axes(ranges, sample), extra, "sobol"


def point_values(ds: Any, variable: str, at: tuple[Any, ...], names: Collection[str]) -> dict[str, float]:
    """The value of the parameters ``names`` at the index ``at`` of the data variable ``variable`` of a
    finished store ``ds`` (each parameter a coordinate along one of its dimensions)."""
    dims = list(ds[variable].dims)
    return {name: float(ds[name].values[at[dims.index(ds[name].dims[0])]]) for name in names}


def block_points(
    names: tuple[str, ...], values: tuple[tuple[Fraction, ...], ...], design: str
) -> tuple[tuple[int, ...], list[tuple[tuple[int, ...], dict[str, Fraction]]]]:
    """The shape of a block of :meth:`PointGrid.block_values` ``values`` and its points: (index in the
    block, {name: value})."""
    if design == "sobol":
        shape: tuple[int, ...] = (len(values[0]),)
        return shape, [((i,), {n: v[i] for n, v in zip(names, values)}) for i in range(shape[0])]
    shape = tuple(len(v) for v in values)
    return shape, [(i, {n: v[k] for n, v, k in zip(names, values, i)}) for i in np.ndindex(shape)]


class _Base(Protocol):
    """The base point's checked input: its SI values."""

    @property
    def physical(self) -> dict[str, float]: ...


class SleeperLayout(Protocol):
    """What the store needs of a sleeper sweep (:class:`~moving_bogie.sweep.sleepers.SleeperSweepSpec`)."""

    @property
    def axes(self) -> tuple[Axis, ...]: ...

    @property
    def design(self) -> str: ...

    @property
    def base(self) -> _Base: ...

    @property
    def model(self) -> str: ...

    @property
    def units(self) -> dict[str, str]: ...

    @property
    def dims(self) -> tuple[str, ...]: ...

    @property
    def shape(self) -> tuple[int, ...]: ...

    @property
    def chunks(self) -> tuple[int, ...]: ...

    def describe(self) -> dict[str, Any]: ...

    def operating_point(self) -> dict[str, float]: ...


#: The store attributes of a sleeper sweep that another sweep of this layout (``sweep/soil.py``) replaces.
SLEEPER_ATTRS = {
    "title": "moving-bogie parameter sweep on a sleeper track (Floquet strip search per point)",
    "kind": "sleepers",
    "time_factor": "exp(i Omega t): a root with Im Omega < 0 grows at the rate -Im Omega",
    "search": (
        "roots.strip.floquet_frequencies: the roots in one strip of width Omega_0 up to the rail's "
        "free waves, counted by the argument principle and converged in the harmonics (docs/sleepers.md)"
    ),
}

Variables = tuple[tuple[str, str, Any, str, str], ...]


def create_sleeper_store(
    path: StorePath,
    spec: SleeperLayout,
    variables: Variables = SLEEPER_VARIABLES,
    attrs: dict[str, str] | None = None,
) -> None:
    """Write the metadata and coordinates of an empty store at ``path`` (replacing what is there): the
    data variables ``variables`` (:data:`SLEEPER_VARIABLES`) and the attributes ``attrs``
    (:data:`SLEEPER_ATTRS`) of a sweep of this layout."""
    import zarr

    path = Path(path)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    shutil.rmtree(tmp, ignore_errors=True)
    g = zarr.open_group(str(tmp), mode="w")
    dims, shape, chunks, units = spec.dims, spec.shape, spec.chunks, spec.units
    sobol = spec.design == "sobol"
    if sobol:
        point = g.create_array("point", shape=shape, chunks=shape, dtype="int64", dimension_names=("point",))
        point[:] = np.arange(shape[0])
        point.attrs.update(long_name="point of the quasi-random design", units="1")
    for axis in spec.axes:
        coord = {"units": units[axis.name], "long_name": axis.name}
        own = ("point",) if sobol else (axis.name,)
        write_coordinate(g, axis.name, own, axis.floats, coord, axis.values)
    for name, dtype, fill, long_name, unit in variables:
        arr = g.create_array(
            name, shape=shape, chunks=chunks, dtype=dtype, fill_value=fill, dimension_names=dims
        )
        arr.attrs.update(long_name=long_name, units=unit)
        if sobol:
            arr.attrs["coordinates"] = " ".join(a.name for a in spec.axes)
    g.attrs.update(
        **(attrs or SLEEPER_ATTRS),
        model=spec.model,
        physical=json.dumps(spec.base.physical),
        sweep=json.dumps(spec.describe()),
        package_version=package_version(),
        units="si",
        operating_point=json.dumps(spec.operating_point()),
    )
    consolidate(tmp)
    if path.exists():
        shutil.rmtree(path)
    os.replace(tmp, path)


def write_sleeper_block(
    path: StorePath,
    slices: tuple[slice, ...],
    arrays: dict[str, np.ndarray],
    variables: Variables = SLEEPER_VARIABLES,
) -> None:
    """Write one block's arrays into its chunk of every variable, ``computed`` last."""

    g = store_group(path, "r+")
    for name, *_ in variables:  # computed is the last of them
        store_array(g, name)[slices] = arrays[name]
