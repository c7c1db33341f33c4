"""The figure of a sleeper map: the parametric zones and D-decomposition lines in (v, M), and the continuous
track of the same smeared support beside them in the same axes (docs/sleepers.md, (S22))."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from moving_bogie.stability.maps.sleeper_map import SleeperMap

if TYPE_CHECKING:
    from matplotlib.artist import Artist
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from moving_bogie.stability.maps.map import StabilityMap

__all__ = ["sleeper_map_figure"]


def _counts(ax: Axes, v: np.ndarray, M: np.ndarray, count: np.ndarray, vmax: int) -> None:
    """The unstable count as cells: white where stable, darker reds for more unstable roots."""
    from matplotlib.colors import ListedColormap

    colors = ["white", "#f4a582", "#d6604d", "#b2182b", "#67001f"][: vmax + 1]
    ax.pcolormesh(v, M, count, cmap=ListedColormap(colors), vmin=-0.5, vmax=vmax + 0.5, shading="nearest")


def _zone_bars(ax: Axes, smap: SleeperMap, top: float) -> bool:
    """Each column's unstable M-intervals between its crossings (S21)-(S22), as bars one column wide: a zone
    narrower than a cell of the grid still shows as a band across the columns it spans. True if any."""
    lines = smap.lines()
    width = float(np.min(np.diff(smap.velocities))) if len(smap.velocities) > 1 else 1.0
    bars = []
    for v in sorted({p["v"] for p in lines}):
        count, start = 0, 0.0
        for p in sorted((p for p in lines if p["v"] == v), key=lambda p: p["M"]):
            if count > 0 and start < top:
                bars.append((v, min(p["M"], top) - start, start))
            count, start = count + int(p["change"]), float(p["M"])
        if count > 0 and start < top:
            bars.append((v, top - start, start))
    for v, height, bottom in bars:
        ax.bar(v, height, width, bottom=bottom, color="#d6604d", lw=0, zorder=2)
    return bool(bars)


def _margins(fig: Figure, ax: Axes, smap: SleeperMap) -> list:
    """The cells coloured by their margin [1/s] as the continuous map's
    (:func:`~moving_bogie.stability.figures.margin_plot.draw_margin`: decay rates of the stable cells, growth
    rates of the unstable ones); the legend handles of what is drawn beside the colours."""
    from moving_bogie.stability.figures.margin_plot import MarginPlane, draw_margin

    assert smap.margin is not None and smap.margin_bound is not None
    unstable = smap.count > 0
    plane = MarginPlane(
        smap.velocities, smap.masses, smap.margin, smap.margin_bound, ~smap.uncertain, unstable, unit="1/s"
    )
    return draw_margin(fig, ax, plane)


def _stable_note(ax: Axes, stable: bool) -> None:
    """Say so on a panel that shows nothing unstable nor uncertain (else it would be blank)."""
    if stable:
        ax.text(0.5, 0.5, "stable on the whole grid", transform=ax.transAxes, ha="center")


def sleeper_map_figure(
    smap: SleeperMap,
    continuous: StabilityMap | None = None,
    *,
    operating: tuple[float, float] | None = None,
    continuous_label: str = "",
) -> Figure:
    """Left: the sleeper track's unstable counts (cells), its crossings (red: the count rises with M, blue:
    it falls), uncertain columns hatched; right (when given): the continuous track's counts on the same grid
    in the same axes. ``operating`` (v, M) is marked on both."""
    from matplotlib.figure import Figure
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    panels = 2 if continuous is not None else 1
    fig = Figure(figsize=(5.2 * panels + 0.6, 4.6), layout="constrained")
    axs = fig.subplots(1, panels, sharex=True, sharey=True, squeeze=False)[0]
    vmax = int(max(1, smap.count.max(initial=0), 0 if continuous is None else continuous.count.max()))
    handles: list[Artist] = []  # only what is drawn
    if smap.margin is not None and smap.margin_bound is not None:
        handles += _margins(fig, axs[0], smap)
    else:
        _counts(axs[0], smap.velocities, smap.masses, smap.count, vmax)
        if smap.count.any():
            handles.append(Patch(fc="#f4a582", ec="k", lw=0.5, label="unstable cell of the grid"))
    # with margins the unstable cells show their growth rate: no zone bars over them (the D-lines remain)
    zones = smap.margin is None and _zone_bars(axs[0], smap, float(smap.masses[-1]))
    if zones:
        handles.append(Patch(fc="#d6604d", lw=0, label="unstable between the D-lines (one column wide)"))
    lines = smap.lines()
    for change, color in ((1, "tab:red"), (-1, "tab:blue")):
        pts = np.array([(p["v"], p["M"]) for p in lines if p["change"] == change]).reshape(-1, 2)
        if len(pts):
            axs[0].plot(pts[:, 0], pts[:, 1], ".", ms=3, color=color, zorder=3)
            label = f"D-line: count {change:+d} as M grows"
            handles.append(Line2D([], [], ls="", marker=".", color=color, label=label))
    unc = smap.uncertain[0]
    if unc.any():
        axs[0].fill_between(
            smap.velocities, smap.masses[0], smap.masses[-1], where=unc, step="mid", hatch="///", fc="none"
        )
        handles.append(Patch(fc="none", hatch="///", label="uncertain column"))
    axs[0].set_title(f"{smap.track} ({smap.model})", fontsize=9)
    _stable_note(axs[0], smap.margin is None and not (smap.count.any() or zones or unc.any()))
    if continuous is not None:
        _counts(axs[1], smap.velocities, smap.masses, continuous.count, vmax)
        axs[1].set_title(continuous_label or "continuous track, same smeared support", fontsize=9)
        _stable_note(axs[1], not continuous.count.any())
    for ax in axs:
        if operating is not None:
            ax.plot(*operating, marker="*", ms=11, color="gold", mec="k", ls="")
        ax.set_xlabel("v [m/s]")
    if operating is not None:
        handles.append(Line2D([], [], ls="", marker="*", color="gold", mec="k", label="the file's (v, M)"))
    axs[0].set_ylabel("M [kg]")
    axs[0].legend(handles=handles, fontsize=7, loc="upper right")
    return fig
