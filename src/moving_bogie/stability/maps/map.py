"""Stability maps: the degree of instability over an (alpha, theta) grid, in vectorised double precision.

Each column (fixed alpha, every theta = eta_M, kappa_v or eta_v at once) is counted and its roots located
by :func:`~moving_bogie.stability.maps.column.stability_column`; the neighbouring column's roots are the first
starting points of Newton's method (continuation in alpha). Cells the column count cannot settle are
settled by a full count at that point (:func:`~moving_bogie.stability.maps.column.settle_cells`), so that
every
cell's verdict is the one :func:`~moving_bogie.roots.frequencies.induced_frequencies` gives; a cell is left
``uncertain`` only when that full count is not certified either. Columns are spread over ``workers``
processes in chunks.
"""

from __future__ import annotations

import json
import os
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import IO, TYPE_CHECKING, Any

import numpy as np

from moving_bogie.checkpoint import Checkpoint, Part, run_parts
from moving_bogie.kernels.bound import BoundModel
from moving_bogie.kernels.sweep_characteristic import SweepCharacteristic
from moving_bogie.stability.maps.column import ColumnResult, settle_cells, stability_column, top_edge

if TYPE_CHECKING:
    import pandas
    import xarray

    from moving_bogie.model.params import DimensionlessParams
    from moving_bogie.stability.figures.plot_units import PlaneUnits

__all__ = [
    "MAP_KEYS",
    "ColumnResult",
    "StabilityMap",
    "map_columns",
    "min_decay_rate",
    "stability_column",
    "stability_map",
]


#: The keys every stability map's summary has, with the same meaning on every track (the continuous
#: tracks' :class:`StabilityMap` and the sleepers'
#: :class:`~moving_bogie.stability.maps.sleeper_map.SleeperMap`), besides the range of the vertical axis'
#: group (``f"{parameter}_range"``): the parameters, that group, the range of alpha, the fraction of
#: unstable cells, the uncertain cells (their number and each by its groups).
MAP_KEYS = ("params", "parameter", "alpha_range", "unstable_fraction", "uncertain_cells", "uncertain")


def min_decay_rate(margin: np.ndarray | None, stable: np.ndarray) -> float | None:
    """The smallest finite margin of the ``stable`` cells (None: no margin, or no such cell measured)."""
    if margin is None:
        return None
    margins = margin[stable]
    margins = margins[np.isfinite(margins)]
    return float(margins.min()) if margins.size else None


@dataclass(frozen=True)
class StabilityMap:
    """Degree of instability ``degree[j, i]`` at (alphas[i], thetas[j]) and the unstable count.

    ``settled`` marks the cells decided by a full count, ``uncertain`` those still not certified.
    ``margin[j, i]`` is the smallest Im q of the induced frequencies: the degree where unstable, the
    smallest decay rate where stable (:mod:`~moving_bogie.stability.maps.column_margin`), NaN where
    undetermined, a lower bound where ``margin_bound``.
    """

    params: DimensionlessParams
    model: str
    parameter: str
    alphas: np.ndarray
    thetas: np.ndarray
    degree: np.ndarray
    count: np.ndarray
    uncertain: np.ndarray
    settled: np.ndarray | None = None
    margin: np.ndarray | None = None
    margin_bound: np.ndarray | None = None
    held: tuple[str, ...] = ()  # groups held instead of following the vertical axis (model/bar.py)
    units: PlaneUnits | None = None  # SI units of a [physical] input (v, M, rates in 1/s), else the groups

    def save_npz(self, path: str | os.PathLike[str] | IO[bytes]) -> None:
        """Write the arrays (and the parameters as JSON text) to ``path``: a name or a binary file (.npz)."""
        arrays: dict[str, Any] = {
            "alphas": self.alphas,
            "thetas": self.thetas,
            "degree": self.degree,
            "count": self.count,
            "uncertain": self.uncertain,
            "settled": self.settled_cells,
        }
        if self.margin is not None:
            arrays |= {"margin": self.margin, "margin_bound": self.margin_bound}
        arrays |= {
            "params": json.dumps(self.params.to_dict()),
            "model": self.model,
            "parameter": self.parameter,
        }
        np.savez_compressed(path, **arrays)

    @property
    def settled_cells(self) -> np.ndarray:
        return np.zeros(self.count.shape, dtype=bool) if self.settled is None else self.settled

    def uncertain_list(self) -> list[dict]:
        """The uncertain cells as ``{"alpha": ..., parameter: ...}`` (row-major order)."""
        rows, cols = np.nonzero(self.uncertain)
        return [
            {"alpha": float(self.alphas[i]), self.parameter: float(self.thetas[j])}
            for j, i in zip(rows, cols)
        ]

    @property
    def min_decay_rate(self) -> float | None:
        """The smallest margin of the stable, certain cells (min Im q; None: no such cell measured)."""
        return min_decay_rate(self.margin, (self.count == 0) & ~self.uncertain)

    def _repr_html_(self) -> str:
        """Jupyter: the verdict over the grid first, then its axes, margin and uncertain cells (in SI for a
        map of SI parameters, :attr:`units`)."""
        from moving_bogie.html_repr import html_table
        from moving_bogie.presentation import GroupUnits, quantity_text

        units = self.units or GroupUnits()
        unstable, uncertain = int((self.count > 0).sum()), int(self.uncertain.sum())
        if unstable:
            verdict = f"UNSTABLE in {unstable} of {self.count.size} cells"
        else:
            verdict = "STABLE in every certified cell" if uncertain else "STABLE in every cell"
        im, rate = ("Im omega", "1/s") if units.si else ("Im q", "1")

        def axis(group: str, values: np.ndarray) -> tuple[str, str]:
            lo, hi = (
                quantity_text(units.value(group, v), units.unit(group)) for v in (values[0], values[-1])
            )
            return units.name(group), f"{lo}..{hi}, {len(values)} points"

        decay = self.min_decay_rate
        rows = [
            ("model", f"{self.params.beam} beam, {self.params.track} track, {self.model}"),
            axis("alpha", self.alphas),
            axis(self.parameter, self.thetas),
            (
                f"largest growth rate, -min {im}",
                quantity_text(units.frequency(-float(self.degree.min())), rate) if unstable else "none",
            ),
            (
                f"smallest decay rate of the stable cells, min {im}",
                quantity_text(None if decay is None else units.frequency(decay), rate),
            ),
            ("cells settled by a full count / uncertain", f"{int(self.settled_cells.sum())} / {uncertain}"),
        ]
        return html_table("stability map", verdict, rows)

    def to_xarray(self) -> xarray.Dataset:
        """The map as an xarray Dataset over its two axes with CF ``units`` (v [m/s], M [kg], rates [1/s] for
        SI parameters): :func:`moving_bogie.export.map_dataset`."""
        from moving_bogie.export import map_dataset

        return map_dataset(self)

    def to_dataframe(self) -> pandas.DataFrame:
        """The map as a pandas DataFrame, one row per cell, the units in ``attrs["units"]``."""
        from moving_bogie.export import to_dataframe

        return to_dataframe(self.to_xarray())

    def summary(self) -> dict:
        return {
            "params": self.params.to_dict(),
            "model": self.model,
            "parameter": self.parameter,
            "alpha_range": [float(self.alphas[0]), float(self.alphas[-1]), len(self.alphas)],
            # named after the vertical axis (eta_M_range by default; theta_range before, not kept)
            f"{self.parameter}_range": [float(self.thetas[0]), float(self.thetas[-1]), len(self.thetas)],
            "unstable_fraction": float(np.mean(self.count > 0)),
            "max_degree": float(-self.degree.min()) if self.degree.size else 0.0,
            "min_decay_rate": self.min_decay_rate,
            "settled_cells": int(self.settled_cells.sum()),
            "uncertain_cells": int(self.uncertain.sum()),
            "uncertain": self.uncertain_list(),
        }


def map_columns(
    bound: BoundModel,
    parameter: str | None,
    alphas: Sequence[float | Fraction] | np.ndarray,
    thetas: Sequence[float | Fraction] | np.ndarray,
    options: dict[str, Any] | None = None,
    settle: bool = True,
    held: Iterable[str] = (),
) -> list[ColumnResult]:
    """Columns at ``alphas`` (continuation from each column to the next), uncertain cells settled.

    ``alphas`` and ``thetas`` may be exact (Fractions): the columns run on their floats and the full
    counts of :func:`~moving_bogie.stability.maps.column.settle_cells` on the exact values. ``held``: groups
    that keep their values instead of following ``parameter`` (mu_v, J_b in a sweep in SI units;
    :class:`~moving_bogie.kernels.sweep_characteristic.SweepCharacteristic`).
    """
    options = dict(options or {})
    floats = np.array([float(a) for a in alphas])
    if "top" not in options:
        options["top"] = top_edge(bound, floats)
    theta_floats = np.array([float(t) for t in thetas])
    sweep = SweepCharacteristic(bound, parameter, held=held)
    out: list[ColumnResult] = []
    for a, a_float in zip(alphas, floats):
        guesses = out[-1].roots if out else None
        col = stability_column(sweep, a_float, theta_floats, guesses=guesses, **options)
        if settle:
            exact_thetas = None if isinstance(thetas, np.ndarray) else list(thetas)
            exact_alpha = None if isinstance(a, float | np.floating) else a
            col = settle_cells(
                bound, sweep.parameter, col, alpha=exact_alpha, thetas=exact_thetas, held=sweep.held
            )
        out.append(col)
    return out


#: The arrays of a map, one value per cell (theta rows, alpha columns).
CELL_ARRAYS = ("degree", "count", "uncertain", "settled", "margin", "margin_bound")


def _column_task(args: tuple[Any, ...]) -> Part:
    """One chunk of columns (the arguments of :func:`map_columns`), in a worker process: its cells'
    arrays, one column per alpha."""
    columns = map_columns(*args)
    return {name: np.stack([getattr(c, name) for c in columns], axis=1) for name in CELL_ARRAYS}


def stability_map(
    bound: BoundModel,
    *,
    parameter: str | None = None,
    alphas: Sequence[float] | None = None,
    thetas: Sequence[float] | None = None,
    workers: int | None = None,
    chunk: int = 8,
    settle: bool = True,
    progress: Callable[[float], None] | None = None,
    held: tuple[str, ...] = (),
    checkpoint: str | os.PathLike[str] | None = None,
    resume: bool = False,
    **options: Any,
) -> StabilityMap:
    """Degree of instability over the grid ``alphas x thetas`` (beyond the paper).

    Parameters
    ----------
    bound : BoundModel
        Everything but alpha and ``parameter`` (cf1, cf2 kept fixed when the parameter is eta_M); the
        vehicle is that of their model.
    parameter : str, optional
        The vertical axis (eta_M, kappa_v, eta_v, ...; default the wheel mass, ``Model.wheel_mass``).
    alphas, thetas : sequence of float
        Grid (default 0..1.2 and 1..200 in 200 steps each, theta > 0).
    workers : int, optional
        Processes (default: the number of CPUs); 1 runs in-process.
    chunk : int
        Columns per task (the continuation in alpha starts again at each chunk).
    settle : bool
        Settle the cells the column count leaves uncertain by a full count (default True).
    progress : callable, optional
        Called with the fraction of columns done.
    held : tuple of str
        Groups held instead of following ``parameter`` (mu_v, J_b: :mod:`~moving_bogie.model.bar`).
    checkpoint : path, optional
        A folder in which each finished chunk is kept (:class:`~moving_bogie.checkpoint.Checkpoint`):
        Ctrl-C raises :class:`~moving_bogie.errors.JobInterrupted`, and the same map with
        ``resume=True`` computes only the chunks missing, its cells equal to an uninterrupted map's.
    resume : bool
        Read back the chunks kept under ``checkpoint`` (else they are computed anew).
    **options
        Passed to :func:`~moving_bogie.stability.maps.column.stability_column`.
    """
    params = bound.params
    parameter = parameter or params.model.wheel_mass
    alpha_grid = np.asarray(np.linspace(0.0, 1.2, 200) if alphas is None else alphas, dtype=float)
    theta_grid = np.asarray(np.linspace(1.0, 200.0, 200) if thetas is None else thetas, dtype=float)
    if "top" not in options:
        options["top"] = top_edge(bound, alpha_grid)
    chunks = [alpha_grid[i : i + chunk] for i in range(0, len(alpha_grid), chunk)]
    tasks = [(bound, parameter, c, theta_grid, options, settle, held) for c in chunks]
    kept = None
    if checkpoint is not None:
        track = bound.foundation_model  # a track model beside the parameters' own is another map
        job = {
            "params": params.to_dict(),
            "track": [track.module.__name__, track.values, getattr(bound.track_factory, "__qualname__", "")],
            "parameter": parameter,
            "held": list(held),
            "alphas": alpha_grid.tolist(),
            "thetas": theta_grid.tolist(),
            "options": options,
            "chunk": chunk,
            "settle": settle,
        }
        kept = Checkpoint.open(checkpoint, "stability-map", job, resume=resume)
    what = f"chunks of {chunk} columns"
    parts = run_parts(_column_task, tasks, workers=workers, checkpoint=kept, progress=progress, what=what)
    cells: dict[str, Any] = {name: np.concatenate([p[name] for p in parts], axis=1) for name in CELL_ARRAYS}
    if kept is not None:
        kept.remove()
    return StabilityMap(params, params.vehicle, parameter, alpha_grid, theta_grid, **cells, held=held)
