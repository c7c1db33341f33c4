"""The figure of the steady response on a sleeper track (matplotlib, Agg backend, no pyplot state).

:func:`sleeper_series_figure`: two panels against the rear wheel's position [m] (time on the top axis),
(a) the contact force and (b) the rail deflection under each wheel (docs/sleepers.md, Eqs. (S16)-(S18)),
with the continuous track of the same smeared supports as a dashed line (its force is the static load, its
deflection the steady part of the paper's Eq. (39)), and the supports as dotted vertical lines.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from moving_bogie.response.closed_form import TimeSeries

__all__ = ["sleeper_series_figure"]


def sleeper_series_figure(ts: TimeSeries, *, title: str | None = None) -> Figure:
    """Contact force [kN] and deflection under the wheel [mm] over the bays, per wheel (Eqs. (S16)-(S18)), of
    a series on periodic supports (its ``bay``)."""
    from matplotlib.figure import Figure

    from moving_bogie.errors import ParameterError

    series = ts.bay
    if series is None:
        raise ParameterError("series", "the figure over the bays needs a series on periodic supports")

    fig = Figure(figsize=(7.0, 5.6), constrained_layout=True)
    ax_f, ax_w = fig.subplots(2, 1, sharex=True)
    x = series.position
    colors = [f"C{j % 10}" for j in range(series.wheels)]
    for j, color in enumerate(colors):
        label = f"wheel {j}" + (f" (+{series.wheel_positions[j]:g} m)" if j else "")
        ax_f.plot(x, series.contact_force[j] / 1e3, color=color, lw=1.4, label=label)
        ax_w.plot(x, series.deflection[j] * 1e3, color=color, lw=1.4, label=label)
        ax_f.axhline(series.static_force[j] / 1e3, color=color, ls="--", lw=1.0)
        if series.continuous_deflection is not None:
            ax_w.axhline(series.continuous_deflection[j] * 1e3, color=color, ls="--", lw=1.0)
    supports = np.arange(0.0, x[-1] + 0.5 * series.bay, series.bay)
    for ax in (ax_f, ax_w):
        for s in supports:
            ax.axvline(s, color="0.6", ls=":", lw=0.8)
        ax.grid(True, lw=0.3, alpha=0.6)
        ax.margins(x=0)
    cont = series.continuous_model or "no continuous track with these supports"
    ax_f.set_ylabel("contact force F [kN]")
    ax_w.set_ylabel("deflection under the wheel w [mm]")
    ax_w.set_xlabel("rear wheel's position x = v t from a support [m] (dotted: supports)")
    ax_f.set_title(title or f"steady response on {series.model}", fontsize=10, loc="left")
    ax_w.set_title(f"dashed: continuous track {cont} (force: the static load)", fontsize=9, loc="left")
    v = series.v
    top = ax_f.secondary_xaxis("top", functions=(lambda x: x / v * 1e3, lambda t: t * v / 1e3))
    top.set_xlabel("time t [ms]")
    if series.wheels > 1:
        ax_f.legend(fontsize=8, loc="best")
    return fig
