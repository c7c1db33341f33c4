"""A stability map written as a 2-D sweep store (alpha, parameter), in the layout of :mod:`store`, so that
``sweep-plot`` and xarray read a map and a sweep alike."""

from __future__ import annotations

from fractions import Fraction
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from moving_bogie.sweep.design import SweepSpec
from moving_bogie.sweep.store import StorePath, consolidate, prepare_store, store_group, write_block

if TYPE_CHECKING:
    from moving_bogie.kernels.bound import BoundModel
    from moving_bogie.model.physical import PhysicalParams
    from moving_bogie.stability.maps.map import StabilityMap

__all__ = ["write_map"]


def write_map(
    path: StorePath,
    smap: StabilityMap,
    bound: BoundModel,
    *,
    overwrite: bool = False,
    physical: PhysicalParams | None = None,
) -> Path:
    """Write a :class:`~moving_bogie.stability.maps.map.StabilityMap` as a 2-D sweep store (alpha, parameter);
    ``bound`` is the bound model the map was computed with.

    With ``physical`` (the SI parameters of the map's base point) the store is in SI units, as a sweep of
    a ``[physical]`` input: dimensions ``v``, ``M``, ... (each SI value the group times
    :meth:`~moving_bogie.model.physical.PhysicalParams.si_factor`, read by its shortest decimal text), the
    groups beside them. Along the map's vertical axis the groups that Eq. (63) ties to it follow it, or
    are held (``smap.held``, :mod:`~moving_bogie.model.bar`), as the attributes ``vertical_axis``
    and ``bar`` say.
    """
    from moving_bogie.stability.maps.column import exact
    from moving_bogie.sweep.design import Axis

    def axis(name: str, values: np.ndarray) -> Axis:
        exact_values = tuple(exact(v) for v in values)
        if physical is None:
            return Axis(name, exact_values)
        spec = smap.params.model.specs[name]
        factor = physical.si_factor(name)
        si_values = tuple(Fraction(repr(float(v) * factor)) for v in values)
        return Axis(name, exact_values, si=spec.si, unit=spec.unit, si_values=si_values)

    axes = (axis("alpha", smap.alphas), axis(smap.parameter, smap.thetas))
    bar = "fixed" if smap.held else "follows"
    margin = smap.margin is not None  # the map's margin is stored as a sweep's with --margin
    spec = SweepSpec(bound, smap.model, axes, check=0, physical=physical, bar=bar, margin=margin)
    path = prepare_store(path, spec, overwrite=overwrite)
    certain = ~smap.uncertain.T
    n = np.where(certain, smap.count.T, -1).astype(np.int16)
    arrays = {
        "stable": certain & (n == 0),
        "n_unstable": n,
        "degree_of_instability": np.where(certain, smap.degree.T, np.nan),
        "margin": _map_margin(smap, certain),
        "margin_bound": (
            np.zeros(n.shape, dtype=bool)
            if smap.margin is None or smap.margin_bound is None
            else smap.margin_bound.T
        ),
        "certain": certain,
        "settled": smap.settled_cells.T,
        "checked": np.zeros(n.shape, dtype=np.int8),
        "computed": np.ones(n.shape, dtype=bool),
    }
    write_block(path, spec, (slice(None), slice(None)), arrays)
    follow = [
        f"{meta['sets']} = {name} x {smap.parameter}" + (" x d^2" if "d" in meta["depends"] else "")
        for name, meta in smap.params.model.alternatives.items()
        if smap.parameter in meta["depends"]
    ]
    if follow:
        text = (
            f"held at the base point's values ({', '.join(smap.held)})"
            if smap.held
            else ", ".join(follow) + " follow it (Eq. (63))"
        )
        store_group(path, "r+").attrs["vertical_axis"] = f"a stability map: along {smap.parameter} {text}"
        consolidate(path)
    return path


def _map_margin(smap: StabilityMap, certain: np.ndarray) -> np.ndarray:
    """The map's margin (alpha first), NaN where not certain or not measured."""
    if smap.margin is None:
        return np.full(certain.shape, np.nan)
    return np.where(certain, smap.margin.T, np.nan)
