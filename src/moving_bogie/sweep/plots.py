"""Slices of a sweep: the degree of instability over two varied parameters, with the stability boundary."""

from __future__ import annotations

import json

import numpy as np

from moving_bogie.errors import ParameterError
from moving_bogie.stability.figures.plot_units import axis_label, mark_operating_point, unit_suffix
from moving_bogie.stability.figures.plots import hatch_cells

__all__ = ["plot_sweep_slice", "select_slice"]


def select_slice(ds, x: str, y: str, sel: dict | None = None):
    """The 2-D slice (y, x) of a grid sweep, other dimensions fixed by ``sel`` (nearest values).

    Raises
    ------
    ParameterError
        Naming ``--x``, ``--y`` or ``--sel`` when a name is not a dimension or a dimension is left free.
    """
    sel = dict(sel or {})
    if "point" in ds.dims:
        raise ParameterError(
            "store", "a quasi-random (Sobol) sweep has no grid to slice; use xarray directly"
        )
    for option, name in (("--x", x), ("--y", y)):
        if name not in ds.dims:
            raise ParameterError(
                option, f"{option} {name}: not a dimension of the store ({', '.join(ds.dims)})"
            )
    if x == y:
        raise ParameterError("--y", "--x and --y must differ")
    for name in sel:
        if name not in ds.dims or name in (x, y):
            raise ParameterError("--sel", f"--sel {name}: not one of the other dimensions")
    free = [d for d in ds.dims if d not in (x, y, "root") and d not in sel]
    if free:
        raise ParameterError("--sel", f"--sel: fix {', '.join(free)} (e.g. --sel {free[0]}=VALUE)")
    return ds.sel(sel, method="nearest").transpose(y, x, ...)


def plot_sweep_slice(ds, x: str, y: str, sel: dict | None = None, *, vmin_log: float = -6.0):
    """Figure: log10 |degree of instability| (white where stable), the boundary between stable and unstable
    points (contour of n_unstable > 0 at 1/2), uncertain points hatched, the axes in the store's units
    (SI for a sweep of a ``[physical]`` input) and the base point of the sweep marked where the store
    records it (``operating_point``)."""
    from matplotlib.figure import Figure

    s = select_slice(ds, x, y, sel).compute()
    xs, ys = s[x].values, s[y].values
    deg = -s.degree_of_instability.values
    certain = s.certain.values
    with np.errstate(divide="ignore", invalid="ignore"):
        z = np.where(certain & (deg > 0), np.log10(np.maximum(deg, 10.0**vmin_log)), np.nan)
    fig = Figure(figsize=(7.5, 5.5), layout="constrained")
    ax = fig.subplots()
    mesh = ax.pcolormesh(
        xs,
        ys,
        z,
        shading="nearest",
        cmap="magma_r",
        vmin=vmin_log,
        vmax=max(vmin_log + 1, float(np.nanmax(z)) if np.isfinite(z).any() else 0),
    )
    fig.colorbar(mesh, ax=ax, label=r"$\log_{10}\,|\min \mathrm{Im}\, q|$ (unstable points)")
    unstable = np.where(certain, (s.n_unstable.values > 0).astype(float), np.nan)
    if len(xs) > 1 and len(ys) > 1 and np.nanmin(unstable) < 0.5 < np.nanmax(unstable):
        ax.contour(xs, ys, unstable, levels=[0.5], colors="tab:cyan", linewidths=1.2)
        ax.plot([], [], color="tab:cyan", label="stability boundary")
    n = hatch_cells(ax, xs, ys, ~certain)
    ax.set_xlabel(axis_label(ds[x]))
    ax.set_ylabel(axis_label(ds[y]))
    point = json.loads(ds.attrs.get("operating_point", "{}"))
    inside = x in point and y in point and min(xs) <= point[x] <= max(xs) and min(ys) <= point[y] <= max(ys)
    if inside:  # the base point, where it lies on the slice's axes
        mark_operating_point(ax, point[x], point[y])
    fixed = ", ".join(f"{k} = {float(s[k].values):.4g}{unit_suffix(ds[k])}" for k in (sel or {}))
    title = f"sweep: degree of instability ({ds.attrs.get('model', '')})" + (f"; {fixed}" if fixed else "")
    if n:
        title += f"; {n} uncertain point(s) hatched"
    ax.set_title(title, fontsize=9)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(loc="upper left", fontsize=8)
    return fig
