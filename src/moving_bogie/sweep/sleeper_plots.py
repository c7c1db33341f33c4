"""Views of a sleeper sweep (:mod:`moving_bogie.sweep.sleepers`): the growth rate against one varied
parameter, or the map of stable, unstable and undetermined points over two."""

from __future__ import annotations

import json
from collections.abc import Mapping
from typing import TYPE_CHECKING

import numpy as np

from moving_bogie.stability.figures.plot_units import axis_label, mark_operating_point, unit_suffix
from moving_bogie.sweep.plots import missing_text, select_slice

if TYPE_CHECKING:
    import xarray
    from matplotlib.artist import Artist
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["plot_sleeper_sweep"]

#: colours of the map's classes: stable, unstable, undetermined
_CLASSES = (
    ("stable", "#8fc98f"),
    ("unstable (a root with Im Omega < 0)", "#d9534f"),
    ("undetermined", "0.6"),
)


def plot_sleeper_sweep(
    ds: xarray.Dataset, x: str, y: str | None = None, sel: Mapping[str, float] | None = None
) -> Figure:
    """Figure: with ``y`` None the growth rate ``-Im Omega`` [1/s] of the fastest-growing root against
    ``x`` (stable points on the zero line, undetermined and uncertain points marked); with ``y`` the
    (x, y) map of stable, unstable and undetermined points, uncertain points hatched; points an
    interrupted sweep has not computed are left out and counted in the title. The base point of
    the sweep is marked where it lies on the axes; the title names the model and the fixed parameters."""
    from matplotlib.figure import Figure

    s = select_slice(ds, x, y, sel).compute()
    fig = Figure(figsize=(8.0, 5.0), layout="constrained")
    ax = fig.subplots()
    point = json.loads(ds.attrs.get("operating_point", "{}"))
    patches: list[Artist] = []
    if y is None:
        _growth_line(ax, s, x)
        if x in point and s[x].min() <= point[x] <= s[x].max():
            ax.axvline(point[x], color="0.3", ls=":", lw=1, label="operating point")
    else:
        patches = _class_map(ax, s, x, y)
        xs, ys = s[x].values, s[y].values
        if (
            x in point
            and y in point
            and xs.min() <= point[x] <= xs.max()
            and ys.min() <= point[y] <= ys.max()
        ):
            mark_operating_point(ax, point[x], point[y])
    ax.set_xlabel(axis_label(ds[x]))
    fixed = [f"{k} = {float(s[k].values):.4g}{unit_suffix(ds[k])}" for k in (sel or {})]
    physical = json.loads(ds.attrs.get("physical", "{}"))
    varied = set(map(str, ds.dims))
    fixed += [f"{k} = {v:.4g}" for k, v in physical.items() if k not in varied and k not in (sel or {})]
    heading = "sleeper sweep, " + ("growth rate" if y is None else "Floquet verdict")
    heading += missing_text(~s.computed.values)
    ax.set_title(f"{heading}: {ds.attrs.get('model', '')}\n" + ", ".join(fixed), fontsize=8)
    drawn, _ = ax.get_legend_handles_labels()
    ax.legend(handles=[*drawn, *patches], loc="best", fontsize=8)
    return fig


def _growth_line(ax: Axes, s: xarray.Dataset, x: str) -> None:
    """-Im Omega against x: the growth rate of an unstable point, minus the margin (the least-damped
    vibration's decay rate) of a stable one, joined by a line; the others marked at 0."""
    xs = s[x].values
    margin = s.margin.values if "margin" in s else np.zeros(xs.shape)
    growth = np.where(s.unstable.values, -s.Omega_im.values, np.where(s.stable.values, -margin, np.nan))
    stable, unstable, computed = s.stable.values, s.unstable.values, s.computed.values
    undetermined = ~stable & ~unstable & computed
    ax.plot(xs, np.where(stable | unstable, np.nan_to_num(growth), np.nan), "-", color="0.4", lw=1)
    if unstable.any():
        ax.plot(xs[unstable], growth[unstable], "o", color=_CLASSES[1][1], label="unstable: growth rate")
    if stable.any():
        label = "stable: minus the margin (decay rate)"
        ax.plot(xs[stable], np.nan_to_num(growth[stable]), "s", color=_CLASSES[0][1], label=label)
    if undetermined.any():
        label = "undetermined (no growing root found, the window incomplete)"
        ax.plot(xs[undetermined], np.zeros(undetermined.sum()), "^", color=_CLASSES[2][1], label=label)
    uncertain = ~s.certain.values & computed
    if uncertain.any():
        ax.plot(
            xs[uncertain],
            np.nan_to_num(growth[uncertain]),
            "x",
            color="k",
            label="not converged or a counted root not located",
        )
    ax.axhline(0.0, color="0.7", lw=0.8)
    ax.set_ylabel("growth rate -Im Omega [1/s]")
    if not computed.all():  # the axis spans the points not computed too (left blank)
        pad = 0.03 * (xs.max() - xs.min())
        ax.set_xlim(xs.min() - pad, xs.max() + pad)


def _class_map(ax: Axes, s: xarray.Dataset, x: str, y: str) -> list[Artist]:
    """The classes stable / unstable / undetermined over (x, y), uncertain points hatched, points not
    computed left blank."""
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    stable, unstable, computed = s.stable.values, s.unstable.values, s.computed.values
    classes = np.where(computed, np.where(stable, 0, np.where(unstable, 1, 2)), np.nan)
    cmap = ListedColormap([c for _, c in _CLASSES])
    xs, ys = s[x].values, s[y].values
    ax.pcolormesh(xs, ys, classes, cmap=cmap, vmin=-0.5, vmax=2.5, shading="nearest")
    uncertain = ~s.certain.values & computed
    if uncertain.any():
        ax.contourf(xs, ys, uncertain.astype(float), levels=[0.5, 1.5], hatches=["//"], colors="none")
    present: list[Artist] = [
        Patch(color=c, label=label) for k, (label, c) in enumerate(_CLASSES) if (classes == k).any()
    ]
    if uncertain.any():
        present.append(Patch(facecolor="none", hatch="//", label="not converged or a root not located"))
    if not computed.all():
        present.append(Patch(facecolor="white", edgecolor="0.6", label="not computed (interrupted)"))
    ax.set_ylabel(axis_label(s[y]))
    return present
