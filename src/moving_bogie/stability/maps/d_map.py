"""The columns of a (v, M) map by D-decomposition, one per velocity, spread over processes and kept.

A column (:class:`~moving_bogie.stability.maps.d_lines.DColumn`) is the D-decomposition in the wheel mass at
one velocity: its crossings give the number of growing roots at every mass at once, none at M -> 0 plus the
signed crossings below M. The maps of every track whose crossings run along a real axis share this:
on sleepers (:mod:`~moving_bogie.stability.maps.sleeper_map`, the strip of one harmonic system) and on a
track given by its receptance (:mod:`~moving_bogie.stability.maps.real_axis_map`, the soil). Each builds its
columns with its own function; :func:`count_columns` runs them in ``workers`` processes (:func:`column_part`,
one task per velocity), keeps each under a checkpoint as it finishes and counts every cell.
"""

from __future__ import annotations

import ctypes
import multiprocessing
import os
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from moving_bogie.checkpoint import Checkpoint, Part, run_parts
from moving_bogie.stability.maps.d_lines import DColumn, DCrossing

__all__ = ["column_notes", "column_part", "count_columns", "keep_freed_memory"]

#: one column's task: the function that builds it and its arguments (module-level: sent to a process)
ColumnTask = tuple[Callable[..., DColumn], tuple[Any, ...]]


#: glibc's mallopt parameters, and the values a worker process sets (bytes)
_M_TRIM_THRESHOLD, _M_MMAP_THRESHOLD = -1, -3
_WORKER_HEAP = {_M_MMAP_THRESHOLD: 1 << 26, _M_TRIM_THRESHOLD: 1 << 27}


def keep_freed_memory() -> bool:
    """In a worker process on glibc: arrays below 64 MB from the heap, which keeps up to 128 MB of freed
    memory instead of giving it back to the system at once. The receptance's quadrature makes and frees
    arrays of a few MB at every panel round; by default glibc maps each anew or trims the heap after it,
    and the worker spends a fifth of its time in the page faults of fresh memory. Only in workers (the
    caller's own process is left as it is); True when set. Cheap: called at every task."""
    if multiprocessing.parent_process() is None:
        return False
    try:
        mallopt = ctypes.CDLL("libc.so.6").mallopt
    except (OSError, AttributeError):  # not glibc
        return False
    return all(mallopt(option, value) == 1 for option, value in _WORKER_HEAP.items())


def column_part(task: ColumnTask) -> Part:
    """The column ``function(*arguments)`` of ``task`` = (function, arguments) as arrays (one process's
    task, a checkpoint's part)."""
    keep_freed_memory()
    column, arguments = task
    return column_arrays(column(*arguments))


def column_arrays(col: DColumn) -> Part:
    """A column as arrays (a checkpoint's part), read back exactly by :func:`part_column`."""
    crossings = col.crossings
    return {
        "alpha": np.array(col.alpha),
        "Omega0": np.array(col.Omega0),
        "sizes": np.array([col.harmonics, col.samples, col.evaluations]),
        "q": np.array([c.q for c in crossings], dtype=float),
        "theta": np.array([c.eta_M for c in crossings], dtype=float),  # the vertical axis
        "change": np.array([c.change for c in crossings], dtype=int),
        "moved": np.array([c.moved for c in crossings], dtype=float),
        "notes": np.array(col.notes, dtype=str),
    }


def part_column(part: Part) -> DColumn:
    """The column of :func:`column_part`, read back exactly."""
    crossings = tuple(
        DCrossing(float(q), float(e), int(c), float(m))
        for q, e, c, m in zip(part["q"], part["theta"], part["change"], part["moved"])
    )
    harmonics, samples, evaluations = (int(x) for x in part["sizes"])
    notes = tuple(str(n) for n in part["notes"])
    return DColumn(
        float(part["alpha"]), float(part["Omega0"]), crossings, harmonics, samples, evaluations, notes
    )


def count_columns(
    tasks: Sequence[ColumnTask],
    etas: np.ndarray,
    *,
    kind: str,
    job: dict[str, Any],
    workers: int | None = None,
    progress: Callable[[float], None] | None = None,
    checkpoint: str | os.PathLike[str] | None = None,
    resume: bool = False,
) -> tuple[list[DColumn], np.ndarray, Checkpoint | None]:
    """The columns of ``tasks`` (:func:`column_part`) and their counts ``count[j, i]`` at the masses
    ``etas[j]`` (in the columns' units) of column i, with the checkpoint that kept them (None without
    ``checkpoint``; the caller removes it when the whole job is done).

    ``kind`` and ``job`` identify the job of a kept checkpoint (a checkpoint of another job is not read back);
    ``workers``, ``progress``, ``checkpoint``, ``resume`` as
    :func:`~moving_bogie.stability.maps.sleeper_map.sleeper_map`.
    """
    kept = None if checkpoint is None else Checkpoint.open(checkpoint, kind, job, resume=resume)
    parts = run_parts(column_part, tasks, workers=workers, checkpoint=kept, progress=progress, what="columns")
    columns = [part_column(p) for p in parts]
    return columns, np.stack([col.counts(etas) for col in columns], axis=1), kept


def column_notes(columns: Sequence[DColumn], v_ref: float) -> list[str]:
    """Every column's notes, each with its velocity v = alpha v_ref [m/s]."""
    return [f"v = {col.alpha * v_ref:.6g} m/s: {note}" for col in columns for note in col.notes]
