"""A plane coloured by its stability margin: how fast the slowest vibration decays, or how fast it grows.

The margin of a point is the smallest Im q of its induced frequencies (Eq. (35): a vibration behaves like
exp(-Im q tau); :mod:`~moving_bogie.stability.maps.column_margin`), shown as the rate Im omega = Im q /
t_scale [1/s] for an input in SI units. Stable points are coloured by that decay rate (yellow close to
instability, blue far from it), unstable ones by their growth rate -Im q (reds), both on logarithmic
scales, each with its labelled colour bar, drawn only
when such points are on the plane. Stable points whose margin is only a lower bound are dotted, stable
points whose margin is undetermined are grey, points whose verdict is not certified are hatched; the
legend lists only what is drawn. :func:`plane_title` names the model, the track and the fixed parameters.
"""

from __future__ import annotations

import textwrap
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike

if TYPE_CHECKING:
    from matplotlib.artist import Artist
    from matplotlib.axes import Axes
    from matplotlib.collections import QuadMesh
    from matplotlib.colors import LogNorm, Normalize
    from matplotlib.figure import Figure

    from moving_bogie.model.catalogue import Model

__all__ = ["MarginPlane", "draw_margin", "fixed_parameters", "hatch_cells", "plane_title"]

#: Decades of growth rate and of decay rate the logarithmic colour scales span at most (smaller rates
#: take the lowest colour, the colour bar's arrow says so).
GROWTH_DECADES = 6
DECAY_DECADES = 3


def _log_norm(values: np.ndarray, decades: int) -> LogNorm:
    """A logarithmic scale from the smallest positive value (at least one decade below the largest, so
    that nearly equal rates get nearly equal colours; at most ``decades`` below it) to the largest."""
    from matplotlib.colors import LogNorm

    hi = float(np.nanmax(values))
    lo = float(np.nanmin(values[values > 0], initial=hi))
    return LogNorm(max(min(lo, hi / 10), hi * 10.0**-decades), hi)


def _colorbar(fig: Figure, ax: Axes, mesh: QuadMesh, label: str, extend: str) -> None:
    """A colour bar with plain numbers (1, 2, 5 of each decade) instead of powers of ten."""
    from matplotlib.ticker import FuncFormatter

    def minor(v: float, _: Any) -> str:
        lead = round(v / 10 ** np.floor(np.log10(v)))
        return f"{v:g}" if lead in (2, 5) else ""

    bar = fig.colorbar(mesh, ax=ax, label=label, pad=0.01, extend=extend)
    bar.ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    bar.ax.yaxis.set_minor_formatter(FuncFormatter(minor))


def hatch_cells(
    ax: Axes,
    x: ArrayLike,
    y: ArrayLike,
    mask: ArrayLike,
    *,
    label: str = "uncertain (not certified)",
    hatch: str = "////",
    color: str = "tab:blue",
) -> int:
    """Hatch the cells ``mask[j, i]`` of the grid ``x[i], y[j]`` (cell edges halfway between the values).

    Returns the number of hatched cells.
    """
    from matplotlib.collections import PatchCollection
    from matplotlib.patches import Rectangle

    x, y, mask = np.asarray(x, dtype=float), np.asarray(y, dtype=float), np.asarray(mask, dtype=bool)

    def edges(v: np.ndarray) -> np.ndarray:
        if len(v) == 1:
            return np.array([v[0] - 0.5, v[0] + 0.5])
        mid = 0.5 * (v[1:] + v[:-1])
        return np.concatenate([[2 * v[0] - mid[0]], mid, [2 * v[-1] - mid[-1]]])

    ex, ey = edges(x), edges(y)
    rows, cols = np.nonzero(mask)
    patches = [Rectangle((ex[i], ey[j]), ex[i + 1] - ex[i], ey[j + 1] - ey[j]) for j, i in zip(rows, cols)]
    if patches:
        ax.add_collection(
            PatchCollection(patches, facecolor="none", edgecolor=color, hatch=hatch, lw=0.5, label=label)
        )
    return len(patches)


def _extend(values: np.ndarray, norm: Normalize) -> str:
    """``"min"`` when some finite value lies below the colour scale (shown in its lowest colour)."""
    lowest = norm.vmin * (1 - 1e-12)  # type: ignore[operator]  # every norm here is built with vmin (typed float | None)
    return "min" if np.nanmin(values[values > 0], initial=np.inf) < lowest else "neither"


@dataclass(frozen=True)
class MarginPlane:
    """What :func:`draw_margin` draws, every array indexed ``[j, i]`` at (x[i], y[j]).

    ``margin`` is the smallest Im q, or Im omega [1/s] with ``unit`` "1/s" (NaN: undetermined);
    ``bound`` marks a lower bound; ``certain`` a certified verdict; ``unstable`` a certified unstable one;
    ``missing`` the points not computed (an interrupted sweep), drawn blank and neither certain nor not.
    """

    x: np.ndarray
    y: np.ndarray
    margin: np.ndarray
    bound: np.ndarray
    certain: np.ndarray
    unstable: np.ndarray
    unit: str = ""
    missing: np.ndarray | None = None

    @property
    def stable(self) -> np.ndarray:
        return self.certain & ~self.unstable


def _rate(kind: str, unit: str) -> str:
    """Colour-bar label: what the colour is, and its unit."""
    if unit:
        symbol = r"$\min\,\mathrm{Im}\,\omega$" if kind == "decay" else r"$-\min\,\mathrm{Im}\,\omega$"
        return f"{kind} rate {symbol} [{unit}]" + (" (stable)" if kind == "decay" else " (unstable)")
    symbol = r"$\min\,\mathrm{Im}\,q$" if kind == "decay" else r"$-\min\,\mathrm{Im}\,q$"
    return f"{kind} rate {symbol} (dimensionless)" + (" (stable)" if kind == "decay" else " (unstable)")


def _closest(ax: Axes, plane: MarginPlane, decay: np.ndarray) -> Artist:
    """Mark the stable cell closest to instability (the smallest decay rate) and name its rate: the number a
    plane of nearly one colour would hide."""
    j, i = np.unravel_index(int(np.nanargmin(decay)), decay.shape)
    unit = plane.unit or "(dimensionless)"
    label = f"smallest decay rate {decay[j, i]:.3g} {unit}" + (" (lower bound)" if plane.bound[j, i] else "")
    (marker,) = ax.plot(
        plane.x[i],
        plane.y[j],
        ls="none",
        marker="v",
        ms=8,
        mfc="white",
        mec="k",
        label=label,
        zorder=5,
        clip_on=False,  # whole on the edge of the plane too, where the closest cell often lies
    )
    return marker


def draw_margin(fig: Figure, ax: Axes, plane: MarginPlane) -> list:
    """Colour ``ax`` by the margin of ``plane`` (module text); returns the legend handles of what is drawn
    beside the colours (dotted bounds, grey undetermined margins, hatched uncertain points, the boundary)."""
    from matplotlib import colormaps
    from matplotlib.colors import ListedColormap, Normalize
    from matplotlib.patches import Patch

    x, y, m = plane.x, plane.y, plane.margin
    handles: list[Artist] = []
    decay = np.where(plane.stable & np.isfinite(m), m, np.nan)
    if np.isfinite(decay).any():
        hi = float(np.nanmax(decay))
        norm = _log_norm(decay, DECAY_DECADES) if hi > 0 else Normalize(0.0, 1.0)
        mesh = ax.pcolormesh(x, y, decay, shading="nearest", cmap="YlGnBu", norm=norm)
        _colorbar(fig, ax, mesh, _rate("decay", plane.unit), _extend(decay, norm))
        handles.append(_closest(ax, plane, decay))
    growth = np.where(plane.unstable & np.isfinite(m), -m, np.nan)
    if np.isfinite(growth).any():
        norm = _log_norm(growth, GROWTH_DECADES)
        reds = ListedColormap(colormaps["Reds"](np.linspace(0.25, 1.0, 192)))  # the least growth still pink
        shown = np.where(growth > 0, growth, np.nan)
        mesh = ax.pcolormesh(x, y, shown, shading="nearest", cmap=reds, norm=norm)
        _colorbar(fig, ax, mesh, _rate("growth", plane.unit), _extend(growth, norm))
    unknown = plane.stable & ~np.isfinite(m)
    if unknown.any():
        ax.pcolormesh(x, y, np.where(unknown, 1.0, np.nan), shading="nearest", cmap="Greys", vmin=0, vmax=4)
        handles.append(Patch(facecolor="0.8", label="stable, margin undetermined"))
    bound = plane.stable & plane.bound & np.isfinite(m)
    if bound.any():
        hatch_cells(ax, x, y, bound, hatch="..", color="0.3", label="_lower bound")  # _: in handles only
        handles.append(Patch(facecolor="none", edgecolor="0.3", hatch="..", label="margin: a lower bound"))
    missing = np.zeros(m.shape, dtype=bool) if plane.missing is None else plane.missing
    if hatch_cells(ax, x, y, ~plane.certain & ~missing, label="_not certified"):
        handles.append(Patch(facecolor="none", edgecolor="tab:blue", hatch="////", label="not certified"))
    if missing.any():  # left blank: no colour, no hatch
        handles.append(Patch(facecolor="white", edgecolor="0.6", label="not computed (interrupted)"))
    flag = np.where(plane.certain, plane.unstable.astype(float), np.nan)
    if len(x) > 1 and len(y) > 1 and np.nanmin(flag, initial=1) < 0.5 < np.nanmax(flag, initial=0):
        ax.contour(x, y, flag, levels=[0.5], colors="k", linewidths=1.0)
        handles.append(ax.plot([], [], color="k", lw=1.0, label="stability boundary")[0])
    return handles


def plane_title(heading: str, model: dict, fixed: dict, *, width: int = 110) -> str:
    """``heading`` with the model (vehicle, beam, track) and the fixed parameters, wrapped to ``width``.

    ``model`` holds ``beam``, ``track`` and ``vehicle``; ``fixed`` maps a shown name to its text with
    unit (``{"c_f": "1.2e+04 N s/m^2"}``).
    """
    what = f"{model.get('vehicle', '')}, {model.get('beam', '')} beam, {model.get('track', '')} track"
    text = f"{heading}: {what}"
    if fixed:
        text += "; fixed: " + ", ".join(
            f"{k} {v}" if v.startswith("follows") else f"{k} = {v}" for k, v in fixed.items()
        )
    return "\n".join(textwrap.wrap(text, width))


def fixed_parameters(model: Model, values: dict, shown: set, *, si: bool, follow: dict | None = None) -> dict:
    """The parameters a plane holds fixed, as title text: ``{name: "value unit"}``.

    ``model`` is the :class:`~moving_bogie.model.catalogue.Model`; ``values`` its parameters by name (the
    SI values of a ``[physical]`` input with ``si``, else the groups), as ``to_dict`` writes them;
    ``shown``: the names on the axes (left out); ``follow``: names that follow an axis, with the text
    that says how (``{"M_b": "follows M (cf1 = 2.6)"}``).
    """
    units = {spec.si: spec.unit for spec in model.specs.values()} if si else {}
    units |= {name: meta["unit"] for name, meta in model.scale_parameters.items()} if si else {}
    follow = follow or {}
    skip = {"beam", "track", "vehicle", *shown}
    if not si:
        skip |= set(model.alternatives)  # cf1, cf2: their groups are listed
    out = {}
    for name, text in values.items():
        if name in skip or text is None:
            continue
        if name in follow:
            out[name] = follow[name]
            continue
        value = float(text)
        unit = units.get(name, "")
        out[name] = f"{value:.4g}" + (f" {unit}" if unit and unit != "1" else "")
    return out
