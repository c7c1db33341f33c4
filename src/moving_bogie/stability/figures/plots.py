"""Drawing the stability analysis: instability lines, line-end marks, uncertain cells and stability maps.

The paper's figures (2, 3, 4, 7, 8, 16) are recipes built on these in
:mod:`moving_bogie.paper.stability_figures`.
Colours follow the paper's legends: one colour per wheel spacing d.
"""

from __future__ import annotations

import numpy as np

from moving_bogie.stability.figures.plot_units import PlaneUnits

__all__ = [
    "end_mark_handles",
    "hatch_cells",
    "new_figure",
    "plot_instability_lines",
    "plot_stability_map",
    "spacing_colors",
]


def new_figure(*args, **kwargs):
    """A matplotlib Figure (imported lazily: the library loads matplotlib only when it draws)."""
    from matplotlib.figure import Figure

    return Figure(*args, **kwargs)


def spacing_colors(ds) -> dict:
    """One colour per wheel spacing d (the paper's legends)."""
    import matplotlib

    cmap = matplotlib.colormaps["tab10"]
    return {float(d): cmap(k % 10) for k, d in enumerate(ds)}


#: Marker of a line that stops inside the plot, by kind: a fold (tip) or any other reason.
END_MARKERS = {
    "fold": dict(marker="^", mfc="none", mec="k", ms=6, ls="none"),
    "other": dict(marker="x", color="tab:red", ms=6, ls="none"),
}
END_LABELS = {
    "fold": "tip: the root only touches the real axis",
    "other": "line stops: q range, q = 0, the cut or a singular point",
}


def plot_instability_lines(
    ax,
    lines,
    *,
    colors=None,
    linestyle: str = "-",
    scale: float = 1.0,
    label: bool = True,
    lw: float = 1.2,
    units=None,
) -> set:
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
    seen = set()
    marked = set()
    parameter = getattr(lines, "parameter", "eta_M")
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
UNDAMPED_STYLES = {"undamped": {"ls": "-", "marker": "."}, "limit": {"ls": "--", "marker": "."}}
UNDAMPED_LABELS = {"undamped": "boundary at eta_f = 0", "limit": "boundary as eta_f -> 0+"}


def end_mark_handles(kinds) -> list:
    """Legend handles explaining the line-end marks of ``kinds`` (from :func:`plot_instability_lines`)."""
    from matplotlib.lines import Line2D

    return [Line2D([], [], label=END_LABELS[k], **END_MARKERS[k]) for k in sorted(kinds)]


def hatch_cells(ax, x, y, mask, *, label: str = "uncertain (not certified)") -> int:
    """Hatch the cells ``mask[j, i]`` of the grid ``x[i], y[j]`` (cell edges halfway between the values).

    Returns the number of hatched cells.
    """
    from matplotlib.collections import PatchCollection
    from matplotlib.patches import Rectangle

    x, y, mask = np.asarray(x, dtype=float), np.asarray(y, dtype=float), np.asarray(mask, dtype=bool)

    def edges(v):
        if len(v) == 1:
            return np.array([v[0] - 0.5, v[0] + 0.5])
        mid = 0.5 * (v[1:] + v[:-1])
        return np.concatenate([[2 * v[0] - mid[0]], mid, [2 * v[-1] - mid[-1]]])

    ex, ey = edges(x), edges(y)
    rows, cols = np.nonzero(mask)
    patches = [Rectangle((ex[i], ey[j]), ex[i + 1] - ex[i], ey[j + 1] - ey[j]) for j, i in zip(rows, cols)]
    if patches:
        ax.add_collection(
            PatchCollection(
                patches, facecolor="none", edgecolor="tab:blue", hatch="////", lw=0.5, label=label
            )
        )
    return len(patches)


def plot_stability_map(smap, lines=None, *, vmin_log: float = -6.0, units=None):
    """Heat map of log10 |degree of instability| (white where stable) with instability lines on top;
    uncertain cells (if any) hatched and counted in the title; axes in ``units`` (SI for a ``[physical]``
    input, :class:`~moving_bogie.stability.figures.plot_units.PlaneUnits`) with the operating point marked."""
    units = units or PlaneUnits()
    fig = new_figure(figsize=(7.5, 5.5), layout="constrained")
    ax = fig.subplots()
    deg = -smap.degree
    with np.errstate(divide="ignore"):
        z = np.where((deg > 0) & ~smap.uncertain, np.log10(np.maximum(deg, 10.0**vmin_log)), np.nan)
    xs, ys = units.value("alpha", smap.alphas), units.value(smap.parameter, smap.thetas)
    mesh = ax.pcolormesh(
        xs,
        ys,
        z,
        shading="nearest",
        cmap="magma_r",
        vmin=vmin_log,
        vmax=max(vmin_log + 1, float(np.nanmax(z)) if np.isfinite(z).any() else 0),
    )
    fig.colorbar(mesh, ax=ax, label=r"$\log_{10}\,|\min \mathrm{Im}\, q|$ (unstable cells)")
    if lines is not None:
        for b in lines.branches:
            ls = UNDAMPED_STYLES.get(b.kind, {}).get("ls", "-")
            x, y = units.value("alpha", b.alpha), units.value(smap.parameter, b.theta)
            ax.plot(x, y, color="tab:cyan", lw=1, ls=ls)
    n_uncertain = hatch_cells(ax, xs, ys, smap.uncertain)
    ax.set_xlabel(units.label("alpha") if units.si else r"$\alpha$")
    ax.set_ylabel(units.label(smap.parameter))
    ax.set_xlim(xs[0], xs[-1])
    ax.set_ylim(0, ys[-1])
    units.critical(ax)
    marked = units.mark(ax, "alpha", smap.parameter) or units.alpha_cr is not None
    title = f"degree of instability, {smap.model}; lines: instability lines"
    if lines is not None and lines.statement:
        title = (
            f"degree of instability at eta_f = {float(smap.params.eta_f):g}, {smap.model}; lines: boundaries "
            "at eta_f = 0 (solid), eta_f -> 0+ (dashed)"
        )
    if n_uncertain:
        title += f"; hatched: {n_uncertain} uncertain cell(s)"
    if n_uncertain or marked:
        ax.legend(loc="upper left", fontsize=8)
    ax.set_title(title, fontsize=9)
    return fig
