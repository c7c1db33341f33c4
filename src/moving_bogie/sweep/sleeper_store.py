"""The zarr store of a sleeper sweep (:mod:`moving_bogie.sweep.sleepers`), in SI units.

Layout: one dimension per varied SI parameter (``v`` in m/s, ``l`` in m, ... float64 with ``units`` and
the exact decimal values in ``exact``), or one dimension ``point`` on a Sobol design (each parameter a
coordinate along it); the data variables of :data:`SLEEPER_VARIABLES`,
chunked like the blocks. The safety rules are those of :mod:`moving_bogie.sweep.store`: the store is
created under a temporary name and renamed into place, and ``computed`` is written last.
"""

from __future__ import annotations

import json
import os
import shutil
from pathlib import Path
from typing import Any, Protocol

import numpy as np

from moving_bogie.sweep.design import Axis
from moving_bogie.sweep.store import (
    StorePath,
    consolidate,
    package_version,
    store_array,
    store_group,
    write_coordinate,
)

__all__ = ["SLEEPER_VARIABLES", "SleeperLayout", "create_sleeper_store", "write_sleeper_block"]

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


def create_sleeper_store(path: StorePath, spec: SleeperLayout) -> None:
    """Write the metadata and coordinates of an empty store at ``path`` (replacing what is there)."""
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
        attrs = {"units": units[axis.name], "long_name": axis.name}
        own = ("point",) if sobol else (axis.name,)
        write_coordinate(g, axis.name, own, axis.floats, attrs, axis.values)
    for name, dtype, fill, long_name, unit in SLEEPER_VARIABLES:
        arr = g.create_array(
            name, shape=shape, chunks=chunks, dtype=dtype, fill_value=fill, dimension_names=dims
        )
        arr.attrs.update(long_name=long_name, units=unit)
        if sobol:
            arr.attrs["coordinates"] = " ".join(a.name for a in spec.axes)
    g.attrs.update(
        title="moving-bogie parameter sweep on a sleeper track (Floquet strip search per point)",
        kind="sleepers",
        model=spec.model,
        physical=json.dumps(spec.base.physical),
        sweep=json.dumps(spec.describe()),
        package_version=package_version(),
        units="si",
        time_factor="exp(i Omega t): a root with Im Omega < 0 grows at the rate -Im Omega",
        search=(
            "roots.strip.floquet_frequencies: the roots in one strip of width Omega_0 up to the rail's "
            "free waves, counted by the argument principle and converged in the harmonics (docs/sleepers.md)"
        ),
        operating_point=json.dumps(spec.operating_point()),
    )
    consolidate(tmp)
    if path.exists():
        shutil.rmtree(path)
    os.replace(tmp, path)


def write_sleeper_block(path: StorePath, slices: tuple[slice, ...], arrays: dict[str, np.ndarray]) -> None:
    """Write one block's arrays into its chunk of every variable, ``computed`` last."""

    g = store_group(path, "r+")
    for name, *_ in SLEEPER_VARIABLES:  # computed is the last of them
        store_array(g, name)[slices] = arrays[name]
