"""Figures of a track on the soil: the dispersion figure (soil modes, track curves, the critical point) and
the moving load's deflection against speed."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from .critical import CriticalVelocity
from .moving_load import MovingLoad
from .rayleigh import SoilModes

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["dispersion_figure", "moving_load_figure"]


def dispersion_figure(modes: SoilModes, critical: CriticalVelocity, title: str) -> Figure:
    """Phase velocity (m/s) against frequency (Hz): the soil's modes (grey, the fundamental black), the
    track's own curve (dashed), the coupled guided waves (blue dots), the critical point and the uncoupled
    estimate."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(7.5, 5.0), layout="constrained")
    ax = fig.add_subplot()
    for j in range(modes.c.shape[1]):
        w, c = modes.mode(j)
        ax.plot(
            w / (2 * np.pi),
            c,
            color="black" if j == 0 else "0.7",
            lw=1.6 if j == 0 else 0.9,
            label="soil: fundamental mode" if j == 0 else ("soil: higher modes" if j == 1 else None),
        )
    waves = critical.waves
    ax.plot(waves.omega / (2 * np.pi), critical.c_track, "--", color="tab:orange", label="track without soil")
    f = np.repeat(waves.omega, waves.c.shape[1]) / (2 * np.pi)
    ax.plot(f, waves.c.ravel(), ".", color="tab:blue", ms=5, label="track on soil: guided waves")
    if np.isfinite(critical.v_cr):
        ax.plot(
            critical.omega_cr / (2 * np.pi),
            critical.v_cr,
            "o",
            ms=10,
            mfc="none",
            mec="tab:red",
            mew=2,
            label=f"critical velocity {critical.v_cr:.1f} m/s",
        )
    if np.isfinite(critical.v_cr_uncoupled):
        ax.plot(
            critical.omega_uncoupled / (2 * np.pi),
            critical.v_cr_uncoupled,
            "x",
            ms=9,
            color="tab:green",
            mew=2,
            label=f"uncoupled estimate {critical.v_cr_uncoupled:.1f} m/s",
        )
    top = np.nanmax(modes.c) if np.isfinite(modes.c).any() else 1.0
    ax.set_ylim(0, 1.1 * top)
    marks = [w for w in (critical.omega_cr, critical.omega_uncoupled) if np.isfinite(w)]
    right = min(waves.omega.max(), 4 * max(marks)) if marks else waves.omega.max()
    ax.set_xlim(0, right / (2 * np.pi))
    ax.set_xlabel("frequency f = omega / 2 pi [Hz]")
    ax.set_ylabel("phase velocity c = omega / k [m/s]")
    ax.set_title(title)
    ax.grid(alpha=0.3)
    ax.legend(loc="upper right", fontsize=8)
    return fig


def moving_load_figure(result: MovingLoad, title: str) -> Figure:
    """Dynamic amplification w(0, v) / w_static against speed, its peak marked."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(7.0, 4.5), layout="constrained")
    ax = fig.add_subplot()
    # the refined peak lies between grid points: the line passes through it
    v = np.append(result.v, result.v_peak)
    order = np.argsort(v)
    daf = np.append(result.daf, result.daf_peak)[order]
    ax.plot(v[order], daf, "-", color="tab:blue", label="deflection under the load / static")
    ax.plot(result.v, result.daf, "o", ms=3, color="tab:blue")
    ax.plot(
        result.v_peak,
        result.daf_peak,
        "o",
        ms=10,
        mfc="none",
        mec="tab:red",
        mew=2,
        label=f"peak {result.daf_peak:.2f} at {result.v_peak:.1f} m/s",
    )
    ax.set_xlabel("speed v [m/s]")
    ax.set_ylabel("dynamic amplification")
    ax.set_title(title)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    return fig
