"""Figures of the closed-form vibrations in the paper's style (matplotlib, Agg backend, no pyplot state).

* :func:`time_series_figure`: three stacked panels against tau, (a) beam deflection at the rear wheel,
  (b) bar mass-centre displacement, (c) bar rotation (Figures 5, 9-12, 14, A1-A4, A6); for two moving
  masses, the deflections under the rear and the front mass.
* :func:`long_time_figure`: the long-time views of Figures 6, 13, 15, A5, A7: (a) w_rear, (b) u.
* :func:`shape_figure`: the beam deflection w(xi) around the bogie at one time, wheels marked.

Each ``*_figure`` returns a :class:`matplotlib.figure.Figure`; :func:`save_figure` writes it atomically.
"""

from __future__ import annotations

import io

import numpy as np

__all__ = ["long_time_figure", "save_figure", "shape_figure", "time_series_figure"]


def _figure(rows: int, height: float):
    from matplotlib.figure import Figure

    fig = Figure(figsize=(7.0, height), constrained_layout=True)
    axes = fig.subplots(rows, 1, sharex=True, squeeze=False)[:, 0]
    return fig, axes


def _labels(ts) -> dict:
    si = ts.units.get("tau") == "s"
    if si:
        return {
            "tau": "time t [s]",
            "w_rear": "w(0, t) [m]",
            "w_front": "w(d, t) [m]",
            "u": "u(t) [m]",
            "theta": r"$\theta$(t) [rad]",
        }
    # Dimensionless: every quantity as the ratio it is (Eqs. (15)-(17)), w and u over the static deflection.
    return {
        "tau": r"dimensionless time $\tau = t\,\sqrt{k_f/m}$",
        "w_rear": r"$w(0,\tau)\,/\,w_{st}$",
        "w_front": r"$w(\tilde d,\tau)\,/\,w_{st}$",
        "u": r"$u(\tau)\,/\,w_{st}$",
        "theta": r"$\theta(\tau)\,/\,(w_{st}\,\chi)$",
    }


_TITLES = {
    "w_rear": "beam deflection at the rear wheel",
    "w_front": "beam deflection at the front wheel",
    "u": "bogie bar mass centre displacement",
    "theta": "bogie bar rotation",
}


def _panels(ts, names, height, title, steady: bool):
    labels = _labels(ts)
    fig, axes = _figure(len(names), height)
    for k, (ax, name) in enumerate(zip(axes, names)):
        y = getattr(ts, name)
        ax.plot(ts.tau, y, lw=0.9, color="C0")
        if steady:
            level = {
                "w_rear": ts.w_steady_rear,
                "w_front": ts.w_steady_front,
                "u": ts.u_steady,
                "theta": ts.theta_steady,
            }[name]
            if np.isfinite(level):
                ax.axhline(level, color="0.5", lw=0.7, ls="--", label="steady part")
                ax.legend(loc="lower right", fontsize=8, frameon=False)
        ax.set_ylabel(labels[name])
        ax.set_title(f"({chr(97 + k)}) {_TITLES[name]}", loc="left", fontsize=9)
        ax.grid(True, lw=0.3, alpha=0.6)
        ax.margins(x=0)
    axes[-1].set_xlabel(labels["tau"])
    if title:
        fig.suptitle(title, fontsize=10)
    return fig


def _has(ts, name: str) -> bool:
    """Whether the vehicle has this response (the others are NaN, e.g. no bar for two masses)."""
    return not np.all(np.isnan(getattr(ts, name)))


def time_series_figure(ts, *, title: str | None = None, steady: bool = True):
    """Three stacked panels: w_rear, u, theta against tau (a vehicle without a bar: w_rear, w_front)."""
    names = ("w_rear", "u", "theta") if _has(ts, "u") else ("w_rear", "w_front")
    return _panels(ts, names, 2.3 * len(names) + 0.4, title, steady)


def long_time_figure(ts, *, title: str | None = None):
    """Two stacked panels, w_rear and u, for long times (Figures 6, 13, 15, A5, A7)."""
    names = ("w_rear", "u") if _has(ts, "u") else ("w_rear", "w_front")
    return _panels(ts, names, 5.0, title, steady=False)


def shape_figure(xi, w, *, tau: float, d: float, si: bool = False, title: str | None = None):
    """Beam deflection w(xi) at one time, with the rear (xi = 0) and front (xi = d) wheels marked."""
    fig, axes = _figure(1, 3.2)
    ax = axes[0]
    ax.plot(xi, w, lw=1.0, color="C0")
    for x, name in ((0.0, "rear"), (d, "front")):
        ax.axvline(x, color="C3", lw=0.8, ls=":")
        ax.text(
            x,
            0.03,
            f"{name} wheel ",
            transform=ax.get_xaxis_transform(),
            rotation=90,
            fontsize=8,
            ha="right",
            va="bottom",
            color="C3",
        )
    ax.axhline(0.0, color="0.5", lw=0.5)
    if si:
        ax.set_xlabel("position behind (-) / ahead of (+) the rear wheel, r [m]")
        ax.set_ylabel("w(r, t) [m]")
        when = f"t = {tau:g} s"
    else:
        ax.set_xlabel(r"moving coordinate $\xi = \chi\,(x - v t)$ (rear wheel at 0)")
        ax.set_ylabel(r"$w(\xi,\tau)\,/\,w_{st}$")
        when = rf"$\tau$ = {tau:g}"
    ax.set_title(title or f"beam deflection at {when}", fontsize=10)
    ax.grid(True, lw=0.3, alpha=0.6)
    ax.margins(x=0)
    return fig


def save_figure(fig, path, *, dpi: int = 150) -> None:
    """Write the figure (format from the file suffix) atomically."""
    from pathlib import Path

    from moving_bogie.output import atomic_write

    path = Path(path)
    buffer = io.BytesIO()
    fig.savefig(buffer, format=path.suffix.lstrip(".") or "png", dpi=dpi)
    atomic_write(path, buffer.getvalue())
