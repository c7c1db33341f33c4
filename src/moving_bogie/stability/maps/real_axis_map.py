"""The (v, M) stability map of a vehicle on a track given by its receptance (a rail on the soil), column by
column from the D-decomposition along the real axis (:mod:`~moving_bogie.stability.maps.real_axis`).

Each velocity is one column, a bound model of its own: its crossings on 0 < q <= S (S beyond every real
root of the masses of the axis, :func:`~moving_bogie.stability.maps.real_axis.window_column`) at masses
from the axis' first give the number of growing roots at every wheel mass at once, none at M -> 0 plus the
signed crossings below M, as on sleepers
(:mod:`~moving_bogie.stability.maps.sleeper_map`, whose map and figure it shares, and whose columns'
workers and checkpoint, :mod:`~moving_bogie.stability.maps.d_map`). No cell is
searched. A column whose crossings carry a note is ``uncertain``. The columns are spread over ``workers``
processes and kept, one by one, under ``checkpoint``.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING

import numpy as np

from moving_bogie.stability.maps.d_lines import DColumn
from moving_bogie.stability.maps.d_map import column_notes, count_columns
from moving_bogie.stability.maps.real_axis import window_column
from moving_bogie.stability.maps.sleeper_map import SleeperMap

if TYPE_CHECKING:
    from moving_bogie.kernels.bound import BoundModel

__all__ = ["real_axis_map"]

#: What the map's text and JSON say it counts, and how.
REGION = "with Re Omega >= 0 and Im Omega < 0"
METHOD = "D-decomposition in the wheel mass along real Omega at each velocity, count 0 at M -> 0"


def _column(
    bound: BoundModel, equivalent: BoundModel, eta_max: float, eta_min: float, samples: int
) -> DColumn:
    """The column of one velocity (:func:`~moving_bogie.stability.maps.real_axis.window_column`); the strip
    width of a sleeper column holds the radius S scanned."""
    col = window_column(bound, equivalent=equivalent, eta_max=eta_max, eta_min=eta_min, samples=samples)
    return DColumn(col.alpha, col.q_max, col.crossings, 0, col.samples, col.evaluations, col.notes)


def real_axis_map(
    bounds: Sequence[tuple[BoundModel, BoundModel]],
    velocities: Sequence[float] | np.ndarray,
    masses: Sequence[float] | np.ndarray,
    *,
    scales: tuple[float, float, float],
    name: str,
    track: str,
    identity: str,
    samples: int = 64,
    workers: int | None = None,
    progress: Callable[[float], None] | None = None,
    checkpoint: str | os.PathLike[str] | None = None,
    resume: bool = False,
) -> SleeperMap:
    """Growing-root counts over velocities [m/s] x masses [kg] (module docstring).

    Parameters
    ----------
    bounds : sequence of (BoundModel, BoundModel)
        The vehicle on its track at each velocity (the columns), and on the continuous track of the same
        parameters (its far field, :func:`~moving_bogie.stability.maps.real_axis.window_column`).
    scales : (float, float, float)
        (v_ref, mass_unit, t_scale): m/s per alpha, kg per eta_M, and Omega = q / t_scale (rad/s).
    name, track, identity : str
        The map's model in words, the track in words, and what identifies the job of a kept checkpoint.
    samples : int
        Samples of the real axis of each column.
    workers, progress, checkpoint, resume
        As :func:`~moving_bogie.stability.maps.sleeper_map.sleeper_map`.
    """
    vs, ms = np.asarray(velocities, dtype=float), np.asarray(masses, dtype=float)
    v_ref, unit, t_scale = scales
    eta_max, eta_min = float(ms.max()) / unit, float(ms.min()) / unit
    tasks = [(_column, (bound, equivalent, eta_max, eta_min, samples)) for bound, equivalent in bounds]
    job = {"identity": identity, "velocities": vs.tolist(), "eta_max": eta_max, "samples": samples}
    columns, count, kept = count_columns(
        tasks, ms / unit, kind="real-axis-map", job=job, workers=workers, progress=progress,
        checkpoint=checkpoint, resume=resume,
    )  # fmt: skip
    if kept is not None:
        kept.remove()
    notes = column_notes(columns, v_ref)
    return SleeperMap(
        name, vs, ms, v_ref, unit, t_scale, tuple(columns), count, (), tuple(notes),
        track=track, region=REGION, method=METHOD,
    )  # fmt: skip
