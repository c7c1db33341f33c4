"""Drawing the stability analysis: instability lines, line-end marks, uncertain cells and stability maps.

The paper's figures (2, 3, 4, 7, 8, 16) are recipes built on these in
:mod:`moving_bogie.paper.stability_figures`.
Colours follow the paper's legends: one colour per wheel spacing d.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

import numpy as np

from moving_bogie.stability.figures.margin_plot import hatch_cells
from moving_bogie.stability.figures.plot_units import PlaneUnits

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from matplotlib.lines import Line2D

    from moving_bogie.stability.lines.line_results import InstabilityLines
    from moving_bogie.stability.maps.map import StabilityMap

__all__ = [
    "end_mark_handles",
    "hatch_cells",
    "new_figure",
    "plot_instability_lines",
    "plot_stability_map",
    "spacing_colors",
]


def new_figure(*args: Any, **kwargs: Any) -> Figure:
    """A matplotlib Figure (imported lazily: the library loads matplotlib only when it draws)."""
    from matplotlib.figure import Figure

    return Figure(*args, **kwargs)


def spacing_colors(ds: Iterable[float]) -> dict[float, tuple[float, float, float, float]]:
    """One colour per wheel spacing d (the paper's legends)."""
    import matplotlib

    cmap = matplotlib.colormaps["tab10"]
    return {float(d): cmap(k % 10) for k, d in enumerate(ds)}


#: Marker of a line that stops inside the plot, by kind: a fold (tip) or any other reason.
END_MARKERS: dict[str, dict[str, Any]] = {
    "fold": dict(marker="^", mfc="none", mec="k", ms=6, ls="none"),
    "other": dict(marker="x", color="tab:red", ms=6, ls="none"),
}
END_LABELS = {
    "fold": "tip: the root only touches the real axis",
    "other": "line stops: q range, q = 0, the cut or a singular point",
}


def plot_instability_lines(
    ax: Axes,
    lines: InstabilityLines,
    *,
    colors: dict[float, Any] | None = None,
    linestyle: str = "-",
    scale: float = 1.0,
    label: bool = True,
    lw: float = 1.2,
    units: PlaneUnits | None = None,
) -> set[str]:
    """Draw the branches of an :class:`~moving_bogie.stability.lines.instability_lines.InstabilityLines` on
    ``ax``.

    ``scale`` divides the vertical coordinate (adapted masses of Figure 4); ``units``
    (:class:`~moving_bogie.stability.figures.plot_units.PlaneUnits`) shows the axes and the spacings in SI.
    Where a
    line stops inside the plot it is marked (:data:`END_MARKERS`; the reasons are in
    :mod:`~moving_bogie.stability.lines.line_ends`). Returns the kinds of marks drawn ("fold", "other").
    """
    units = units or PlaneUnits()
    ds = sorted({b.d for b in lines.branches})
    colors = colors or spacing_colors(ds)
    seen: set[tuple[float, str]] = set()
    marked: set[str] = set()
    parameter = lines.parameter
    x, y = (lambda a: units.value("alpha", a)), (lambda t: units.value(parameter, t) / scale)
    for b in lines.branches:
        style = UNDAMPED_STYLES.get(b.kind, {"ls": linestyle})
        key = (b.d, b.kind)
        lab = None
        if label and key not in seen:
            kind = "" if b.kind == "crossing" else f", {UNDAMPED_LABELS[b.kind]}"
            lab = (units.legend("d", b.d) if units.si else f"d = {b.d:g}") + kind
        seen.add(key)
        ax.plot(x(b.alpha), y(b.theta), color=colors[b.d], lw=lw, label=lab, **style)
        for end in b.stops_inside:
            kind = "fold" if end.reason == "fold" else "other"
            ax.plot([x(end.alpha)], [y(end.theta)], **END_MARKERS[kind])
            marked.add(kind)
    return marked


#: Line styles and legend labels of the boundaries drawn for an undamped foundation (:mod:`undamped_lines`).
UNDAMPED_STYLES: dict[str, dict[str, Any]] = {
    "undamped": {"ls": "-", "marker": "."},
    "limit": {"ls": "--", "marker": "."},
}
UNDAMPED_LABELS = {"undamped": "boundary at eta_f = 0", "limit": "boundary as eta_f -> 0+"}


def end_mark_handles(kinds: Iterable[str]) -> list[Line2D]:
    """Legend handles explaining the line-end marks of ``kinds`` (from :func:`plot_instability_lines`)."""
    from matplotlib.lines import Line2D

    return [Line2D([], [], label=END_LABELS[k], **END_MARKERS[k]) for k in sorted(kinds)]


def plot_stability_map(
    smap: StabilityMap,
    lines: InstabilityLines | None = None,
    *,
    vmin_log: float = -6.0,
    units: PlaneUnits | None = None,
) -> Figure:
    """The map coloured by its stability margin (:mod:`~moving_bogie.stability.figures.margin_plot`: decay
    rate where stable, growth rate where unstable, in 1/s for an SI input), with instability lines on top;
    uncertain cells hatched and counted in the title; axes in ``units`` (SI for a ``[physical]`` input,
    :class:`~moving_bogie.stability.figures.plot_units.PlaneUnits`) with the operating point marked, the
    critical velocity drawn where it lies on the axis and noted where it does not. ``vmin_log`` (the
    decades of growth shown) is kept for callers; the growth scale spans at most
    :data:`~moving_bogie.stability.figures.margin_plot.GROWTH_DECADES` decades."""
    from moving_bogie.stability.figures.margin_plot import MarginPlane, draw_margin, plane_title

    units = units or PlaneUnits()
    fig = new_figure(figsize=(8.5, 5.8), layout="constrained")
    ax = fig.subplots()
    xs, ys = units.value("alpha", smap.alphas), units.value(smap.parameter, smap.thetas)
    certain = ~smap.uncertain
    margin = np.where(smap.count > 0, smap.degree, np.nan) if smap.margin is None else smap.margin
    bound = np.zeros(margin.shape, dtype=bool) if smap.margin_bound is None else smap.margin_bound
    plane = MarginPlane(
        xs, ys, units.frequency(margin), bound, certain, certain & (smap.count > 0), "1/s" if units.si else ""
    )
    handles = draw_margin(fig, ax, plane)
    if lines is not None:
        for b in lines.branches:
            ls = UNDAMPED_STYLES.get(b.kind, {}).get("ls", "-")
            x, y = units.value("alpha", b.alpha), units.value(smap.parameter, b.theta)
            ax.plot(x, y, color="tab:cyan", lw=1, ls=ls)
        if lines.branches:
            handles.append(ax.plot([], [], color="tab:cyan", lw=1, label="instability lines")[0])
    ax.set_xlabel(units.label("alpha") if units.si else r"$\alpha$")
    ax.set_ylabel(units.label(smap.parameter))
    ax.set_xlim(xs[0], xs[-1])
    ax.set_ylim(0, ys[-1])
    units.critical(ax, x_range=(xs[0], xs[-1]))
    units.mark(ax, "alpha", smap.parameter)
    heading = "stability margin"
    if lines is not None and lines.statement:
        heading += (
            f" at eta_f = {float(smap.params.eta_f):g}; lines: boundaries at eta_f = 0 (solid), "
            "eta_f -> 0+ (dashed)"
        )
    n_uncertain = int(smap.uncertain.sum())
    if n_uncertain:
        heading += f" ({n_uncertain} uncertain cell(s) hatched)"
    ax.set_title(
        plane_title(heading, smap.params.to_dict(), units.fixed_text(smap.params, smap.parameter, smap.held)),
        fontsize=8,
    )
    drawn, _ = ax.get_legend_handles_labels()
    if drawn or handles:
        ax.legend(handles=[h for h in drawn if h not in handles] + handles, loc="best", fontsize=8)
    return fig
