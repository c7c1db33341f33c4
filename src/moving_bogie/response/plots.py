"""Figures of the closed-form vibrations in the paper's style (matplotlib, Agg backend, no pyplot state).

* :func:`time_series_figure`: three stacked panels against tau, (a) beam deflection at the rear wheel,
  (b) bounce and (c) pitch of the vehicle's first body (the bogie's bar: Figures 5, 9-12, 14, A1-A4, A6);
  for a vehicle without a body (two moving masses), the deflections under the rear and the front wheel.
* :func:`long_time_figure`: the long-time views of Figures 6, 13, 15, A5, A7: (a) the rear wheel's
  deflection, (b) the first body's bounce.

The panels are chosen from the vehicle's DOFs (``TimeSeries.responses``, the wheels first); the paper's
bogie keeps the paper's axis labels and titles, any other DOF is labelled by its name and unit.
* :func:`shape_figure`: the beam deflection w(xi) around the bogie at one time, wheels marked.

Each ``*_figure`` returns a :class:`matplotlib.figure.Figure`; :func:`save_figure` writes it atomically.
"""

from __future__ import annotations

import io
from collections.abc import Sequence
from os import PathLike
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from moving_bogie.response.closed_form import TimeSeries

__all__ = ["long_time_figure", "save_figure", "shape_figure", "time_series_figure"]


def _figure(rows: int, height: float) -> tuple[Figure, np.ndarray]:
    """A figure of `rows` stacked panels sharing the x axis, and its axes (an array of ``Axes``)."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(7.0, height), constrained_layout=True)
    axes = fig.subplots(rows, 1, sharex=True, squeeze=False)[:, 0]
    return fig, axes


def _labels(ts: TimeSeries) -> dict[str, str]:
    si = ts.units.get("tau") == "s"
    if si:
        known = {
            "tau": "time t [s]",
            "w_rear": "w(0, t) [m]",
            "w_front": "w(d, t) [m]",
            "u": "u(t) [m]",
            "theta": r"$\theta$(t) [rad]",
        }
    else:
        # Dimensionless: every quantity as the ratio it is (Eqs. (15)-(17)), w and u over the static
        # deflection.
        known = {
            "tau": r"dimensionless time $\tau = t\,\sqrt{k_f/m}$",
            "w_rear": r"$w(0,\tau)\,/\,w_{st}$",
            "w_front": r"$w(\tilde d,\tau)\,/\,w_{st}$",
            "u": r"$u(\tau)\,/\,w_{st}$",
            "theta": r"$\theta(\tau)\,/\,(w_{st}\,\chi)$",
        }
    return {name: known.get(name, f"{name} [{unit}]") for name, unit in ts.response_units.items()} | {
        "tau": known["tau"]
    }


#: The paper's titles of the bogie's panels; any other DOF is titled by what it is (:func:`_title`).
_TITLES = {
    "w_rear": "beam deflection at the rear wheel",
    "w_front": "beam deflection at the front wheel",
    "u": "bogie bar mass centre displacement",
    "theta": "bogie bar rotation",
}


def _title(ts: TimeSeries, name: str) -> str:
    if name in _TITLES:
        return _TITLES[name]
    k = ts.names.index(name)
    if k < ts.contacts:
        return f"beam deflection under wheel {k + 1} of {ts.contacts}"
    return f"{name}, {'pitch' if ts.response_units[name] in ('rad', 'w_st chi') else 'bounce'}"


def _panels(ts: TimeSeries, names: Sequence[str], height: float, title: str | None, steady: bool) -> Figure:
    labels = _labels(ts)
    fig, axes = _figure(len(names), height)
    for k, (ax, name) in enumerate(zip(axes, names)):
        ax.plot(ts.tau, ts[name], lw=0.9, color="C0")
        if steady:
            level = ts.steady[name]
            if np.isfinite(level):
                ax.axhline(level, color="0.5", lw=0.7, ls="--", label="steady part")
                ax.legend(loc="lower right", fontsize=8, frameon=False)
        ax.set_ylabel(labels[name])
        ax.set_title(f"({chr(97 + k)}) {_title(ts, name)}", loc="left", fontsize=9)
        ax.grid(True, lw=0.3, alpha=0.6)
        ax.margins(x=0)
    axes[-1].set_xlabel(labels["tau"])
    if title:
        fig.suptitle(title, fontsize=10)
    return fig


def _wheels_and_bodies(ts: TimeSeries) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """The DOFs of the rail under the wheels (rear first) and those of the vehicle's bodies."""
    return ts.names[: ts.contacts], ts.names[ts.contacts :]


def time_series_figure(ts: TimeSeries, *, title: str | None = None, steady: bool = True) -> Figure:
    """Three stacked panels: the rear wheel, the first body's bounce and pitch against tau (the bogie:
    w_rear, u, theta); a vehicle without a body: the rear and the front wheel."""
    wheels, bodies = _wheels_and_bodies(ts)
    names = (wheels[0], *bodies[:2]) if bodies else (wheels[0], wheels[-1])
    return _panels(ts, names, 2.3 * len(names) + 0.4, title, steady)


def series_figure(ts: TimeSeries, label: str) -> Figure:
    """The figure of a series on any track, titled by ``label`` (the case, file or model): the closed form's
    panels (:func:`time_series_figure`), or on periodic supports the contact force and the deflection over
    the bays (:func:`~moving_bogie.response.sleeper_plots.sleeper_series_figure`)."""
    if ts.bay is not None:
        from moving_bogie.response.sleeper_plots import sleeper_series_figure

        return sleeper_series_figure(ts, title=label)
    return time_series_figure(ts, title=f"{label}: closed-form time series")


def long_time_figure(ts: TimeSeries, *, title: str | None = None) -> Figure:
    """Two stacked panels, the rear wheel and the first body's bounce (the bogie: w_rear, u), for long
    times (Figures 6, 13, 15, A5, A7); a vehicle without a body: the rear and the front wheel."""
    wheels, bodies = _wheels_and_bodies(ts)
    names = (wheels[0], bodies[0]) if bodies else (wheels[0], wheels[-1])
    return _panels(ts, names, 5.0, title, steady=False)


def shape_figure(
    xi: ArrayLike, w: ArrayLike, *, tau: float, d: float, si: bool = False, title: str | None = None
) -> Figure:
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


def save_figure(fig: Figure, path: str | PathLike[str], *, dpi: int = 150) -> None:
    """Write the figure (format from the file suffix) atomically."""
    from pathlib import Path

    from moving_bogie.output import atomic_write

    path = Path(path)
    buffer = io.BytesIO()
    fig.savefig(buffer, format=path.suffix.lstrip(".") or "png", dpi=dpi)
    atomic_write(path, buffer.getvalue())
