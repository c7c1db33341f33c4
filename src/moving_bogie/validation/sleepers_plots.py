"""The figure of the finite-beam check on sleepers: the contact force and the free vibration's envelope."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from moving_bogie.validation.sleeper_verdict import SleeperCheck
from moving_bogie.validation.sleepers_fit import period_rms, smooth_steps

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["plot_sleeper_check"]


def _time_axis(result: SleeperCheck) -> tuple[float, str, str]:
    """(seconds per unit tau or 1, the time label, the rate unit): SI when the check knows its time scale."""
    if result.time_scale is None:
        return 1.0, r"$\tau$", "per unit $\\tau$"
    return result.time_scale, "time [s]", "1/s"


def _envelope_panel(ax: Axes, result: SleeperCheck, w_st: float | None) -> None:
    """The RMS over each period of the free vibration under the rear wheel, the fitted modes' RMS, the
    dominant mode alone and the Floquet rate drawn from the dominant mode at the window's start; in m when
    ``w_st`` (metres per unit deflection) is given."""
    scale, label, unit = _time_axis(result)
    size = 1.0 if w_st is None else w_st
    fit, free = result.fit, result.free
    period = fit.period
    mids, rms = period_rms(free.tau, free.deflection[0], period)
    ax.semilogy(
        mids * scale, rms * size, "o", ms=3, color="C0", label="finite rail: RMS over each period $T_0$"
    )
    k = np.arange(fit.samples)
    centres = (fit.window[0] + (k + 0.5) * period) * scale
    fitted = fit.period_rms(k) * size
    ax.semilogy(centres, fitted, "-", color="k", lw=0.9, label=f"fitted modes (rank {fit.rank})")
    dominant = fit.period_rms(k, [fit.dominant]) * size
    extrapolated = "" if result.coarse is None else f" ({result.rate / scale:.6g} at dt -> 0)"
    ax.semilogy(
        centres,
        dominant,
        "-",
        color="C0",
        lw=1.2,
        label=f"its dominant mode: rate {fit.rate / scale:.6g} {unit}" + extrapolated,
    )
    if result.root is not None:
        rate = -result.root.imag
        ax.semilogy(
            centres,
            dominant[0] * np.exp(rate * k * period),
            "--",
            color="C3",
            lw=1.2,
            label=f"Floquet growth rate $-$Im q = {rate / scale:.6g} {unit}",
        )
    ax.axvline(fit.window[0] * scale, color="k", ls=":", lw=1, label="start of the fit")
    ax.set_xlabel(label)
    ax.set_ylabel(r"RMS of the deflection / $w_{st}$" if w_st is None else "RMS of the deflection [m]")
    ax.legend(fontsize=8)
    ax.set_title("(b) free vibration released from the static deflection", loc="left", fontsize=9)


def plot_sleeper_check(
    result: SleeperCheck, *, title: str = "", newtons: float | None = None, metres: float | None = None
) -> Figure:
    """(a) The finite rail's contact force over time with the Floquet steady force over the last bay (a
    stable case) or the free vibration's deflection under the wheel (an unstable one); (b) the free
    vibration's RMS per bay-passing period (log scale) with the fitted modes, the dominant one and the
    Floquet growth rate ``-Im q`` drawn from it. Times in s and rates in 1/s when the check has its time
    scale, else dimensionless; deflections over ``w_st = P chi / (2 k_e)``, forces over half the static
    load (docs/sleepers.md (S2)), unless ``newtons`` (per unit force, P / 2: forces in N) and ``metres``
    (per unit deflection, w_st: deflections in m) are given, or the check has its SI scales
    (``result.scales``: ``load`` and ``w_st``)."""
    from matplotlib.figure import Figure

    if result.scales is not None:
        newtons = result.scales.load if newtons is None else newtons
        metres = result.scales.w_st if metres is None else metres

    scale, label, _ = _time_axis(result)
    force_unit = 1.0 if newtons is None else newtons
    length_unit = 1.0 if metres is None else metres
    fig = Figure(figsize=(8, 6.2), layout="constrained")
    ax_f, ax_e = fig.subplots(2, 1)
    if result.loaded is not None and result.steady_force is not None:
        run = result.loaded
        force = smooth_steps(run.force[0])
        ax_f.plot(run.tau * scale, force * force_unit, color="C0", lw=0.9, label="finite rail, contact force")
        assert result.steady_tau is not None
        ax_f.plot(
            result.steady_tau * scale,
            np.asarray(result.steady_force) * force_unit,
            "--",
            color="C3",
            lw=1.4,
            label="Floquet steady force (S17), last bay",
        )
        if result.limit_force is not None:
            ax_f.plot(
                result.steady_tau * scale,
                np.asarray(result.limit_force) * force_unit,
                ":",
                color="k",
                lw=1.4,
                label="finite rail's periodic limit (fixed point of the stroboscopic map)",
            )
        ax_f.set_ylabel("contact force (static load 2)" if newtons is None else "contact force [N]")
    else:
        run = result.free
        ax_f.plot(
            run.tau * scale,
            run.deflection[0] * length_unit,
            color="C0",
            lw=0.7,
            label="finite rail, free vibration under the wheel",
        )
        ax_f.set_ylabel(r"deflection under the wheel / $w_{st}$" if metres is None else "deflection [m]")
    ax_f.set_xlabel(label)
    ax_f.legend(fontsize=8, loc="upper left")
    ax_f.set_title(
        "(a) " + ("contact force" if result.loaded is not None else "free vibration"), loc="left", fontsize=9
    )
    _envelope_panel(ax_e, result, metres)
    verdict = "agree" if result.agrees else "DISAGREE"
    rows = ", ".join(f"{c.quantity} {c.relative:.3%}" for c in result.comparisons)
    fig.suptitle(f"{title}\nfinite rail vs Floquet: {rows}: {verdict}", fontsize=9)
    return fig
