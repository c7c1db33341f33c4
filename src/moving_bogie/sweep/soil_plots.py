"""The view of a soil sweep (:mod:`moving_bogie.sweep.soil`): the critical velocity against a varied key."""

from __future__ import annotations

import json
from collections.abc import Mapping
from typing import TYPE_CHECKING

import numpy as np

from moving_bogie.stability.figures.plot_units import axis_label, unit_suffix
from moving_bogie.sweep.plots import missing_text, select_slice

if TYPE_CHECKING:
    import xarray
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["plot_soil_sweep"]


def plot_soil_sweep(
    ds: xarray.Dataset, x: str, y: str | None = None, sel: Mapping[str, float] | None = None
) -> Figure:
    """Figure: v_cr (coupled, solid) and the uncoupled estimate (dashed) against ``x``; with ``y`` one pair
    of lines per value of ``y`` (at most 10 shown). Points without a guided wave and points an interrupted
    sweep has not computed are left out and counted in the title; the base point of the sweep is marked."""
    from matplotlib.figure import Figure

    s = select_slice(ds, x, y, sel).compute()
    fig = Figure(figsize=(8.0, 5.0), layout="constrained")
    ax = fig.subplots()
    if y is None:
        _lines(ax, s, x, "", "C0")
    else:
        values = s[y].values
        shown = np.unique(np.linspace(0, len(values) - 1, min(10, len(values))).round().astype(int))
        for k, i in enumerate(shown):
            label = f"{y} = {float(values[i]):.4g}{unit_suffix(ds[y])}: "
            _lines(ax, s.isel({y: int(i)}), x, label, f"C{k % 10}")
    point = json.loads(ds.attrs.get("operating_point", "{}"))
    if x in point and float(s[x].min()) <= point[x] <= float(s[x].max()):
        ax.axvline(point[x], color="0.3", ls=":", lw=1, label="the file's value")
    ax.set_xlabel(axis_label(ds[x]))
    ax.set_ylabel("critical velocity [m/s]")
    fixed = [f"{k} = {float(s[k].values):.4g}{unit_suffix(ds[k])}" for k in (sel or {})]
    lost = int((s.computed.values & ~s.found.values).sum())
    heading = "critical velocity of the track on its soil" + missing_text(~s.computed.values)
    if lost:
        heading += f" ({lost} points without a guided wave, left out)"
    ax.set_title(
        f"{heading}\n{ds.attrs.get('model', '')}" + ("; " + ", ".join(fixed) if fixed else ""), fontsize=9
    )
    ax.legend(loc="best", fontsize=8)
    ax.grid(True, color="0.9")
    return fig


def _lines(ax: Axes, s: xarray.Dataset, x: str, label: str, color: str) -> None:
    """v_cr (solid, dots; a noted point crossed, off the line) and v_cr_uncoupled (dashed) of a 1-D slice
    against ``x``."""
    xs = s[x].values
    found = s.found.values & s.computed.values
    noted = found & s.noted.values
    sure = found & ~noted
    ax.plot(xs, np.where(sure, s.v_cr.values, np.nan), "o-", color=color, label=f"{label}v_cr (coupled)")
    if noted.any():
        doubt = f"{label}v_cr doubtful (at a grid point or the range's end: critical-velocity --set says why)"
        ax.plot(xs[noted], s.v_cr.values[noted], "x", color=color, ms=9, mew=2, label=doubt)
    uncoupled = np.where(s.computed.values, s.v_cr_uncoupled.values, np.nan)
    ax.plot(xs, uncoupled, "--", color=color, alpha=0.7, label=f"{label}v_cr uncoupled (estimate)")
