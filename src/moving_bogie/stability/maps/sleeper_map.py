"""The (v, M) stability map of a vehicle on sleepers from its D-decomposition lines (docs/sleepers.md, (S22)).

Each velocity is one column: its crossings (:func:`~moving_bogie.stability.maps.d_lines.d_column`) give the
number of unstable roots in the strip at every wheel mass at once, none at M -> 0 plus the signed
crossings below M. No cell is searched; the count is checked against
:func:`~moving_bogie.roots.strip.floquet_frequencies` (the argument principle, no D-decomposition) at a few
cells: one in each count region of ``verify`` columns. A disagreement, a column whose crossings have not
converged in the harmonics or a sign change not resolved is said in ``notes`` and marks the column
``uncertain``. The columns, then the checks, are spread over ``workers`` processes.
"""

from __future__ import annotations

import csv
import io
import math
import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np

from moving_bogie.checkpoint import Part, run_parts
from moving_bogie.errors import JobInterrupted, ParameterError
from moving_bogie.kernels.bound import BoundModel
from moving_bogie.kernels.hill import VehicleMatrices
from moving_bogie.kernels.mass_pencil import mass_pencil
from moving_bogie.kernels.periodic_track import PeriodicTrack
from moving_bogie.kernels.sleeper_track import SleeperTrack
from moving_bogie.model.params import DimensionlessParams
from moving_bogie.model.scales import Scales
from moving_bogie.roots.strip import FloquetResult, floquet_frequencies
from moving_bogie.stability.maps.d_lines import DColumn, d_column
from moving_bogie.stability.maps.d_map import column_notes, count_columns, keep_freed_memory

__all__ = ["MapCheck", "SleeperMap", "sleeper_map"]


@dataclass(frozen=True)
class MapCheck:
    """A cell counted by floquet_frequencies beside the map's count: (v, M) in SI, both counts, the verdict
    and whether that search converged."""

    v: float
    M: float
    map_count: int
    search_count: int
    verdict: str
    converged: bool

    @property
    def agrees(self) -> bool:
        return self.map_count == self.search_count


@dataclass(frozen=True)
class SleeperMap:
    """Unstable counts ``count[j, i]`` at (velocities[i] m/s, masses[j] kg), the D-decomposition columns
    (dimensionless, alpha = v / v_ref, eta_M = M / mass_unit, Omega = q / t_scale) and the checks."""

    model: str
    velocities: np.ndarray
    masses: np.ndarray
    v_ref: float
    mass_unit: float
    t_scale: float
    columns: tuple[DColumn, ...]
    count: np.ndarray
    checks: tuple[MapCheck, ...] = ()
    notes: tuple[str, ...] = field(default=())
    params: DimensionlessParams | None = None
    #: the track in words, where the roots are counted, and how (the text output, the figure's title)
    track: str = "rail on sleepers"
    region: str = "in the strip of width 2 pi v / l"
    method: str = "D-decomposition in the wheel mass at each velocity, count 0 at M -> 0 (S19)-(S22)"
    #: the margin of every cell, smallest Im Omega [1/s] (NaN: undetermined), and where it is a lower bound
    #: (:mod:`~moving_bogie.stability.maps.sleeper_margin`); None when not computed
    margin: np.ndarray | None = None
    margin_bound: np.ndarray | None = None

    @property
    def min_decay_rate(self) -> float | None:
        """The smallest margin of the stable cells of certain columns [1/s] (None: no such cell measured)."""
        from moving_bogie.stability.maps.map import min_decay_rate

        return min_decay_rate(self.margin, (self.count == 0) & ~self.uncertain)

    @property
    def uncertain(self) -> np.ndarray:
        """The columns (as a cell mask) whose count is not certain: notes, or a check that disagrees."""
        bad = np.array([bool(c.notes) for c in self.columns])
        for check in self.checks:
            if not check.agrees:
                bad[int(np.argmin(np.abs(self.velocities - check.v)))] = True
        return np.broadcast_to(bad[None, :], self.count.shape)

    def _repr_html_(self) -> str:
        """Jupyter: the verdict over the grid first, then the grid and the checks (as a stability map)."""
        from moving_bogie.html_repr import html_table

        s = self.summary()
        unstable, uncertain = s["unstable_cells"], s["uncertain_columns"]
        if unstable:
            verdict = f"UNSTABLE in {unstable} of {s['cells']} cells"
        else:
            verdict = "STABLE in every certain column" if uncertain else "STABLE in every cell"
        rows = [
            ("model", s["model"]),
            ("v [m/s]", f"{s['v_m_s'][0]:.6g}..{s['v_m_s'][1]:.6g} ({s['v_m_s'][2]})"),
            ("M [kg]", f"{s['M_kg'][0]:.6g}..{s['M_kg'][1]:.6g} ({s['M_kg'][2]})"),
            ("method", s["method"]),
            ("crossings, uncertain columns", f"{s['crossings']}, {s['uncertain_columns']}"),
        ]
        items = [(f"{c.v:.6g}", f"{c.M:.6g}", c.map_count, c.search_count, c.verdict) for c in self.checks]
        header = ("v [m/s]", "M [kg]", "map count", "search count", "verdict")
        return html_table(
            f"stability map, {self.track}", verdict, rows, reasons=list(self.notes), items=(header, items)
        )

    def lines(self) -> list[dict]:
        """Every crossing in SI: v [m/s], M [kg], the real frequency Omega [rad/s] and the change."""
        return [
            {
                "v": float(col.alpha * self.v_ref),
                "M": c.eta_M * self.mass_unit,
                "Omega_rad_s": c.q / self.t_scale,
                "change": c.change,
                "moved": c.moved,
            }
            for col in self.columns
            for c in col.crossings
        ]

    def summary(self) -> dict:
        """Counts, the verdict's limits and the checks (JSON-ready), after the keys of the continuous
        tracks' map with the same meaning (:data:`~moving_bogie.stability.maps.map.MAP_KEYS`: the
        parameters, the vertical axis' group, both axes in groups, the unstable fraction, the uncertain
        cells)."""
        alphas, etas = self.velocities / self.v_ref, self.masses / self.mass_unit
        rows, cols = np.nonzero(self.uncertain)
        shared = {
            "params": None if self.params is None else self.params.to_dict(),
            "parameter": "eta_M",
            "alpha_range": [float(alphas[0]), float(alphas[-1]), len(alphas)],
            "eta_M_range": [float(etas[0]), float(etas[-1]), len(etas)],
            "unstable_fraction": float(np.mean(self.count > 0)),
            "uncertain_cells": int(self.uncertain.sum()),
            "uncertain": [{"alpha": float(alphas[i]), "eta_M": float(etas[j])} for j, i in zip(rows, cols)],
        }
        return shared | {
            "model": self.model,
            "method": self.method,
            "v_m_s": [float(self.velocities[0]), float(self.velocities[-1]), len(self.velocities)],
            "M_kg": [float(self.masses[0]), float(self.masses[-1]), len(self.masses)],
            "unstable_cells": int(np.count_nonzero(self.count > 0)),
            "cells": int(self.count.size),
            "max_count": int(self.count.max(initial=0)),
            "uncertain_columns": int(np.count_nonzero(self.uncertain[0])),
            "crossings": len(self.lines()),
            "checks": [c.__dict__ | {"agrees": c.agrees} for c in self.checks],
            "min_decay_rate_1_s": self.min_decay_rate,
            "notes": list(self.notes),
        }

    def to_dict(self) -> dict:
        """The summary with the lines, the count array and, when computed, the margins [1/s] (NaN: None)."""
        margins = {}
        if self.margin is not None and self.margin_bound is not None:
            values = [[None if math.isnan(x) else float(x) for x in row] for row in self.margin]
            margins = {"margin_1_s": values, "margin_bound": self.margin_bound.tolist()}
        return self.summary() | {
            "velocities_m_s": self.velocities.tolist(),
            "masses_kg": self.masses.tolist(),
            "count": self.count.tolist(),
            "uncertain": self.uncertain[0].tolist(),
            "lines": self.lines(),
            **margins,
        }

    def to_csv(self) -> str:
        """One row per cell: v [m/s], M [kg], count, uncertain (and the margin [1/s] when computed)."""
        out = io.StringIO()
        writer = csv.writer(out, lineterminator="\n")
        margin = self.margin
        writer.writerow(
            ["v_m_s", "M_kg", "unstable_count", "uncertain"] + ([] if margin is None else ["margin_1_s"])
        )
        unc = self.uncertain
        for i, v in enumerate(self.velocities):
            for j, m in enumerate(self.masses):
                row = [f"{v:.10g}", f"{m:.10g}", int(self.count[j, i]), int(unc[j, i])]
                writer.writerow(row + ([] if margin is None else [f"{margin[j, i]:.10g}"]))
        return out.getvalue()


def track_at(bound: BoundModel, alpha: float) -> SleeperTrack:
    """The sleeper track of the bound model at the velocity ratio ``alpha`` (its track's own rail)."""
    track = bound.replace(alpha=alpha).track
    if not isinstance(track, PeriodicTrack):
        raise ParameterError("track", f"{bound.name}: a sleeper map needs a track on periodic supports")
    return track.sleepers


def column_at(bound: BoundModel, scales: Scales, v: float, eta_max: float, N: int, samples: int) -> DColumn:
    """The D-decomposition column at velocity v [m/s] (one process's task)."""
    track = track_at(bound, v / scales.v_ref)
    pencil = mass_pencil(track, bound.vehicle, bound.vehicle_values(bound.floats), N)
    return d_column(pencil, eta_max=eta_max, samples=samples)


def search_cell(bound: BoundModel, scales: Scales, v: float, M: float) -> FloquetResult:
    """floquet_frequencies (the argument principle in one strip) at (v [m/s], M [kg])."""
    module = bound.vehicle
    track = track_at(bound, v / scales.v_ref)
    wheel = {module.WHEEL_MASS: M / scales.mass}
    vehicle = VehicleMatrices.from_module(module, bound.vehicle_values(bound.floats) | wheel)
    return floquet_frequencies(track, vehicle)


def check_cell(bound: BoundModel, scales: Scales, v: float, M: float, map_count: int) -> MapCheck:
    """floquet_frequencies at (v, M): its count beside the map's."""
    res = search_cell(bound, scales, v, M)
    return MapCheck(v, M, map_count, res.unstable_count, res.verdict.state, res.converged)


def check_part(task: tuple[BoundModel, Scales, float, float, int]) -> Part:
    """:func:`check_cell` of ``task`` = (bound, scales, v, M, map_count) as arrays (one worker's task)."""
    keep_freed_memory()
    c = check_cell(*task)
    counts = np.array([c.map_count, c.search_count, int(c.converged)])
    return {"cell": np.array([c.v, c.M]), "counts": counts, "verdict": np.array(c.verdict)}


def part_check(part: Part) -> MapCheck:
    """The check of :func:`check_part`, read back exactly."""
    (v, M), (map_count, search_count, converged) = part["cell"], part["counts"]
    return MapCheck(
        float(v), float(M), int(map_count), int(search_count), str(part["verdict"]), bool(converged)
    )


def _verify_cells(
    smap_count: np.ndarray, columns: Sequence[DColumn], masses: np.ndarray, verify: int
) -> list:
    """(i, j) cells to check: in ``verify`` evenly spread columns, the middle cell of each count region."""
    n = len(columns)
    picks = sorted({int(round(x)) for x in np.linspace(0, n - 1, verify)}) if verify > 0 else []
    cells = []
    for i in picks:
        col = smap_count[:, i]
        edges = [0] + [j for j in range(1, len(col)) if col[j] != col[j - 1]] + [len(col)]
        cells += [(i, (lo + hi - 1) // 2) for lo, hi in zip(edges[:-1], edges[1:])]
    return cells


def _check_plane(bound: BoundModel, scales: Scales, vs: np.ndarray) -> None:
    """A track on periodic supports, damped along the rail, and positive velocities, else a ParameterError
    naming what is wrong (before any computation)."""
    if not (getattr(bound.floats, "eta_f", None) or 0.0) > 0:
        raise ParameterError(
            "c_f", "the D-decomposition runs along the real axis: it needs c_f > 0 (docs/sleepers.md, S15)"
        )
    if vs.min() <= 0:
        raise ParameterError("v", "the velocities of a sleeper map must be positive")
    track_at(bound, float(vs[0]) / scales.v_ref)  # a track on periodic supports, else refused here


def _notes(columns: Sequence[DColumn], checks: Sequence[MapCheck], v_ref: float) -> list[str]:
    """The columns' notes and every check that disagrees with the map, with their (v, M) in SI."""
    return column_notes(columns, v_ref) + [
        f"v = {c.v:.6g} m/s, M = {c.M:.6g} kg: the map counts {c.map_count} unstable root(s), "
        f"floquet_frequencies {c.search_count} ({c.verdict.upper()})"
        for c in checks
        if not c.agrees
    ]


def sleeper_map(
    bound: BoundModel,
    scales: Scales,
    velocities: Sequence[float] | np.ndarray,
    masses: Sequence[float] | np.ndarray,
    *,
    N: int = 2,
    samples: int = 32,
    verify: int = 2,
    workers: int | None = None,
    progress: Callable[[float], None] | None = None,
    checkpoint: str | os.PathLike[str] | None = None,
    resume: bool = False,
) -> SleeperMap:
    """Unstable counts over velocities [m/s] x masses [kg] (module docstring).

    Parameters
    ----------
    bound : BoundModel
        Parameters on periodic supports bound to their track (``moving_bogie.bind``); the map moves their
        velocity and wheel mass.
    scales : Scales
        Their SI scales (``PhysicalParams.scales()``): v = alpha v_ref, the wheel mass in units of
        ``scales.mass``, Omega = q / t_scale.
    N : int
        Harmonics -N-1..N of the D-decomposition (each crossing is checked with N + 1).
    samples : int
        Samples of the real axis of the strip (a multiple of 4).
    verify : int
        Columns whose count regions are each checked by floquet_frequencies at one cell.
    workers : int, optional
        Processes (default: the number of CPUs); 1 runs in-process.
    progress : callable, optional
        Called with the fraction done (the columns, then the checks).
    checkpoint : path, optional
        A folder in which each finished column is kept (:class:`~moving_bogie.checkpoint.Checkpoint`):
        Ctrl-C raises :class:`~moving_bogie.errors.JobInterrupted`, and the same map with
        ``resume=True`` computes only the columns missing.
    resume : bool
        Read back the columns kept under ``checkpoint`` (else they are computed anew).
    """
    vs, ms = np.asarray(velocities, dtype=float), np.asarray(masses, dtype=float)
    _check_plane(bound, scales, vs)
    unit = scales.mass
    eta_max = float(ms.max()) / unit
    tasks = [(column_at, (bound, scales, float(v), eta_max, N, samples)) for v in vs]
    job = {"data": repr(bound), "velocities": vs.tolist(), "eta_max": eta_max, "N": N, "samples": samples}
    share = len(tasks) / (len(tasks) + 16 * verify)  # about 2 checks per verified column, 8 columns each
    part = None if progress is None else (lambda x: progress(share * x))
    columns, count, kept = count_columns(
        tasks, ms / unit, kind="sleeper-map", job=job, workers=workers, progress=part,
        checkpoint=checkpoint, resume=resume,
    )  # fmt: skip
    cells = _verify_cells(count, columns, ms, verify)
    checked = [(bound, scales, float(vs[i]), float(ms[j]), int(count[j, i])) for i, j in cells]
    part = None if progress is None else (lambda x: progress(share + (1 - share) * x))
    try:
        done = run_parts(check_part, checked, workers=workers, progress=part, what="checks")
    except JobInterrupted:  # the columns are kept: a resumed map computes the checks only
        folder = None if kept is None else kept.folder
        raise JobInterrupted(len(tasks), len(tasks), folder, "columns") from None
    checks = [part_check(p) for p in done]
    if kept is not None:
        kept.remove()
    notes = _notes(columns, checks, scales.v_ref)
    return SleeperMap(
        bound.name,
        vs,
        ms,
        scales.v_ref,
        unit,
        scales.t_scale,
        tuple(columns),
        count,
        tuple(checks),
        tuple(notes),
        bound.params,
    )
