"""Slices of a sweep: the stability margin over two varied parameters, with the stability boundary."""

from __future__ import annotations

import json
from collections.abc import Mapping
from typing import TYPE_CHECKING

import numpy as np

from moving_bogie.errors import ParameterError
from moving_bogie.stability.figures.plot_units import axis_label, mark_operating_point, unit_suffix

if TYPE_CHECKING:
    import xarray
    from matplotlib.figure import Figure

__all__ = ["missing_text", "plot_sweep_slice", "select_slice"]


def select_slice(
    ds: xarray.Dataset, x: str, y: str | None, sel: Mapping[str, float] | None = None
) -> xarray.Dataset:
    """The slice (x) or (y, x) of a grid sweep, other dimensions (but a store's ``root``) fixed by ``sel``
    (nearest values).

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
    shown = [d for d in (x, y) if d is not None]
    for option, name in zip(("--x", "--y"), shown):
        if name not in ds.dims:
            raise ParameterError(
                option, f"{option} {name}: not a dimension of the store ({', '.join(map(str, ds.dims))})"
            )
    if x == y:
        raise ParameterError("--y", "--x and --y must differ")
    for name in sel:
        if name not in ds.dims or name in shown:
            raise ParameterError("--sel", f"--sel {name}: not one of the other dimensions")
    free = [d for d in ds.dims if d not in (*shown, "root") and d not in sel]
    if free:
        raise ParameterError("--sel", f"--sel: fix {', '.join(map(str, free))} (e.g. --sel {free[0]}=VALUE)")
    return ds.sel(sel, method="nearest").transpose(*shown[::-1], ...)


def plot_sweep_slice(
    ds: xarray.Dataset,
    x: str,
    y: str,
    sel: Mapping[str, float] | None = None,
    *,
    vmin_log: float = -6.0,
) -> Figure:
    """Figure: the slice coloured by its stability margin (decay rate where stable, growth rate where
    unstable, in 1/s in a sweep in SI units; :mod:`~moving_bogie.stability.figures.margin_plot`), the
    boundary between stable and unstable points, uncertain points hatched, the axes in the store's units
    and the base point of the sweep marked where the store records it (``operating_point``); the title
    names the model and the fixed parameters. Points an interrupted sweep has not computed are left blank
    and counted in the title. A store without a ``margin`` (written by an earlier version) shows its
    stable points grey and says so. ``vmin_log`` is kept for callers."""
    from matplotlib.figure import Figure

    from moving_bogie.stability.figures.margin_plot import MarginPlane, draw_margin, plane_title

    s = select_slice(ds, x, y, sel).compute()
    xs, ys = s[x].values, s[y].values
    missing = ~s.computed.values
    certain = s.certain.values & ~missing
    unstable = certain & (s.n_unstable.values > 0)
    si = ds.attrs.get("units") == "si"
    if "margin" in s:
        margin, bound = s.margin.values, s.margin_bound.values
    else:  # the growth rate from the degree; no margin of the stable points
        t_scale = ds.degree_of_instability.attrs.get("t_scale_s", 1.0) if si else 1.0
        margin = np.where(unstable, s.degree_of_instability.values / t_scale, np.nan)
        bound = np.zeros(margin.shape, dtype=bool)
    fig = Figure(figsize=(8.5, 5.8), layout="constrained")
    ax = fig.subplots()
    plane = MarginPlane(xs, ys, margin, bound, certain, unstable, "1/s" if si else "", missing)
    handles = draw_margin(fig, ax, plane)
    ax.set_xlabel(axis_label(ds[x]))
    ax.set_ylabel(axis_label(ds[y]))
    point = json.loads(ds.attrs.get("operating_point", "{}"))
    inside = x in point and y in point and min(xs) <= point[x] <= max(xs) and min(ys) <= point[y] <= max(ys)
    if inside:  # the base point, where it lies on the slice's axes
        mark_operating_point(ax, point[x], point[y])
    heading = "sweep, stability margin"
    if "margin" not in s:
        heading += " (not in this store: run the sweep again to store it)"
    if (~certain & ~missing).any():
        heading += f" ({int((~certain & ~missing).sum())} uncertain point(s) hatched)"
    heading += missing_text(missing)
    ax.set_title(
        plane_title(heading, json.loads(ds.attrs.get("params", "{}")), _fixed(ds, s, x, y, sel)), fontsize=8
    )
    drawn, _ = ax.get_legend_handles_labels()
    if drawn or handles:
        ax.legend(handles=[h for h in drawn if h not in handles] + handles, loc="upper left", fontsize=8)
    return fig


def missing_text(missing: np.ndarray) -> str:
    """The title's note of the points an interrupted sweep has not computed (empty: none)."""
    n = int(missing.sum())
    return f" ({n} of {missing.size} points not computed, left blank: the sweep was interrupted)" if n else ""


def _fixed(
    ds: xarray.Dataset, s: xarray.Dataset, x: str, y: str, sel: Mapping[str, float] | None
) -> dict[str, str]:
    """The fixed parameters of a slice as title text: the selected values of the other dimensions, then
    the store's base point (SI in a sweep in SI units) without the varied parameters."""
    from moving_bogie.model.catalogue import get_model
    from moving_bogie.stability.figures.margin_plot import fixed_parameters

    out = {k: f"{float(s[k].values):.4g}{unit_suffix(ds[k])}" for k in (sel or {})}
    params = json.loads(ds.attrs.get("params", "{}"))
    try:
        model = get_model(params.get("beam"), params.get("track"), params.get("vehicle"))
    except ParameterError:
        return out
    si = ds.attrs.get("units") == "si"
    base = json.loads(ds.attrs["physical"]) if si and "physical" in ds.attrs else params
    varied = set(ds.dims) | {str(c) for c in ds.coords}
    follow: dict[str, str] = {}
    # the rule of the store's attribute bar (model/bar.py); a store without one: an SI sweep held
    # the bar, a dimensionless sweep and a map let it follow
    old_rule = "follows" if not si or "vertical_axis" in ds.attrs else "fixed"
    if json.loads(ds.attrs.get("bar", "{}")).get("rule", old_rule) == "follows":
        for name, meta in model.alternatives.items():
            for axis in (x, y, *(sel or {})):
                group = ds[axis].attrs.get("group", axis)
                if group in meta["depends"]:
                    spec = model.specs[meta["sets"]]
                    follow[spec.si if si else meta["sets"]] = (
                        f"follows {axis} ({name} = {float(params[name]):.4g})"
                    )
    return out | fixed_parameters(model, base, varied, si=si, follow=follow)
