"""The stability margin of every cell of a sleeper map: the smallest Im Omega of its vibrations [1/s].

The D-decomposition of a sleeper map (:mod:`~moving_bogie.stability.maps.sleeper_map`) counts the growing
roots of every cell at once, but says nothing of how fast a stable cell's vibrations decay. The margin of a
cell is that of the strip search at its (v, M) (:func:`~moving_bogie.stability.maps.sleeper_map.search_cell`,
docs/sleepers.md "Decaying roots and the margin"), as the continuous map's margin is the smallest Im q of
its induced frequencies (:mod:`~moving_bogie.stability.maps.column_margin`):

- an unstable cell: the smallest Im Omega of its roots (< 0: minus its growth rate);
- a stable cell: :attr:`~moving_bogie.roots.strip.FloquetResult.margin`, the least-damped root's Im Omega or
  the rail's free waves' when lower; a lower bound (``bound``) when the window stopped below them;
- an undetermined search: NaN.

One search per cell (1-3 s each), spread over ``workers`` processes and kept, cell by cell, under
``checkpoint``: an option of the map (``stability-map --margin``), as ``sweep --margin`` is of a sweep.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable
from dataclasses import replace

import numpy as np

from moving_bogie.checkpoint import Checkpoint, Part, run_parts
from moving_bogie.kernels.bound import BoundModel
from moving_bogie.model.scales import Scales
from moving_bogie.roots.verdict import STABLE, UNSTABLE
from moving_bogie.stability.maps.d_map import keep_freed_memory
from moving_bogie.stability.maps.sleeper_map import SleeperMap, search_cell

__all__ = ["cell_margin", "sleeper_margins", "with_margins"]

#: what sets a stable margin that is a lower bound only (FloquetResult.margin_source)
LOWER_BOUND = "the window's top"


def cell_margin(bound: BoundModel, scales: Scales, v: float, M: float) -> tuple[float, bool]:
    """(the smallest Im Omega [1/s] at (v [m/s], M [kg]), whether it is a lower bound) (module doc)."""
    res = search_cell(bound, scales, v, M)
    state = res.verdict.state
    if state == UNSTABLE:
        return min(r.q.imag for r in res.roots) / scales.t_scale, False
    if state == STABLE and res.margin is not None:
        return res.margin / scales.t_scale, res.margin_source == LOWER_BOUND
    return math.nan, False


def margin_part(task: tuple[BoundModel, Scales, float, float]) -> Part:
    """:func:`cell_margin` of ``task`` = (bound, scales, v, M) as arrays (one process's task)."""
    keep_freed_memory()
    margin, bound = cell_margin(*task)
    return {"margin": np.array(margin), "bound": np.array(bound)}


def sleeper_margins(
    bound: BoundModel,
    scales: Scales,
    velocities: np.ndarray,
    masses: np.ndarray,
    *,
    workers: int | None = None,
    progress: Callable[[float], None] | None = None,
    checkpoint: str | os.PathLike[str] | None = None,
    resume: bool = False,
) -> tuple[np.ndarray, np.ndarray]:
    """(margin [1/s], bound) of every cell ``[j, i]`` at (velocities[i], masses[j]) (module doc);
    ``workers``, ``progress``, ``checkpoint``, ``resume`` as
    :func:`~moving_bogie.stability.maps.sleeper_map.sleeper_map` (a checkpoint keeps every finished cell)."""
    tasks = [(bound, scales, float(v), float(M)) for M in masses for v in velocities]
    kept = None
    if checkpoint is not None:
        job = {"data": repr(bound), "velocities": velocities.tolist(), "mass_axis": masses.tolist()}
        kept = Checkpoint.open(checkpoint, "sleeper-margin", job, resume=resume)
    parts = run_parts(margin_part, tasks, workers=workers, checkpoint=kept, progress=progress, what="cells")
    shape = (len(masses), len(velocities))
    margin = np.array([float(p["margin"]) for p in parts]).reshape(shape)
    lower = np.array([bool(p["bound"]) for p in parts]).reshape(shape)
    if kept is not None:
        kept.remove()
    return margin, lower


def with_margins(
    smap: SleeperMap,
    bound: BoundModel,
    scales: Scales,
    *,
    workers: int | None = None,
    progress: Callable[[float], None] | None = None,
    checkpoint: str | os.PathLike[str] | None = None,
    resume: bool = False,
) -> SleeperMap:
    """``smap`` (of ``bound`` and its ``scales``) with the margin of each of its cells
    (:func:`sleeper_margins`)."""
    margin, lower = sleeper_margins(
        bound, scales, smap.velocities, smap.masses,
        workers=workers, progress=progress, checkpoint=checkpoint, resume=resume,
    )  # fmt: skip
    return replace(smap, margin=margin, margin_bound=lower)
