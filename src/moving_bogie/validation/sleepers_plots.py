"""The figure of the finite-beam check on sleepers: the contact force and the free vibration's envelope."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from moving_bogie.validation.sleepers_check import SleeperCheck
from moving_bogie.validation.sleepers_fit import period_rms, smooth_steps

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["CheckUnits", "plot_sleeper_check"]


@dataclass(frozen=True)
class CheckUnits:
    """How the check is shown: in SI by the scales of docs/sleepers.md (S2) (time ``t_scale`` [s], force
    ``P / 2`` [N] per unit of the static load 2, deflection ``w_st`` [m]), or dimensionless (all 1)."""

    t_scale: float = 1.0
    force: float = 1.0
    deflection: float = 1.0
    si: bool = False

    def time_label(self) -> str:
        return "t [s]" if self.si else r"$\tau$"

    def rate_text(self, rate: float) -> str:
        """A growth rate d ln(amplitude) / dt: in 1/s, or per unit tau."""
        return f"{rate / self.t_scale:.5g} 1/s" if self.si else f"{rate:.5g}"


def plot_sleeper_check(result: SleeperCheck, *, title: str = "", units: CheckUnits | None = None) -> Figure:
    """(a) The finite rail's contact force over time with the Floquet steady force over the last bay (a
    stable case) or the free vibration's deflection under the wheel (an unstable one); (b) the free
    vibration's RMS per bay-passing period (log scale) with the finite rail's fitted rate and the Floquet
    growth rate ``-Im q`` drawn through the same point. In ``units`` (SI for a sleeper file; dimensionless,
    docs/sleepers.md (S2), by default)."""
    from matplotlib.figure import Figure

    units = units or CheckUnits()
    fig = Figure(figsize=(8, 6.2), layout="constrained")
    ax_f, ax_e = fig.subplots(2, 1)
    if result.loaded is not None and result.steady_force is not None:
        run = result.loaded
        force = smooth_steps(run.force[0]) * units.force
        ax_f.plot(run.tau * units.t_scale, force, color="C0", lw=0.9, label="finite rail, contact force")
        assert result.steady_tau is not None
        ax_f.plot(
            result.steady_tau * units.t_scale,
            result.steady_force * units.force,
            "--",
            color="C3",
            lw=1.4,
            label="Floquet steady force (S17), last bay",
        )
        ax_f.set_ylabel("contact force [N]" if units.si else "contact force (static load 2)")
    else:
        run = result.free
        ax_f.plot(
            run.tau * units.t_scale,
            run.deflection[0] * units.deflection,
            color="C0",
            lw=0.7,
            label="finite rail, free vibration under the wheel",
        )
        ax_f.set_ylabel("deflection under the wheel" + (" [m]" if units.si else " (w_st)"))
    ax_f.set_xlabel(units.time_label())
    ax_f.legend(fontsize=8, loc="upper right")
    ax_f.set_title(
        "(a) " + ("contact force" if result.loaded is not None else "free vibration"), loc="left", fontsize=9
    )
    free = result.free
    period = 2 * np.pi / result.Omega0
    mids, rms = period_rms(free.tau, free.deflection[0], period)
    rms = rms * units.deflection
    shown = mids * units.t_scale
    ax_e.semilogy(shown, rms, "o", ms=3, color="C0", label="finite rail: RMS over each period $T_0$")
    fit = mids >= result.fit_start
    anchor = mids[fit][0], rms[fit][0]
    line = anchor[1] * np.exp(result.rate * (mids - anchor[0]))
    fitted = f"finite rail, fitted rate {units.rate_text(result.rate)}"
    ax_e.semilogy(shown, line, "-", color="C0", lw=1, label=fitted)
    if result.root is not None:
        rate = -result.root.imag
        ax_e.semilogy(
            shown,
            anchor[1] * np.exp(rate * (mids - anchor[0])),
            "--",
            color="C3",
            lw=1.2,
            label=f"Floquet growth rate $-$Im {'Omega' if units.si else 'q'} = {units.rate_text(rate)}",
        )
    ax_e.axvline(result.fit_start * units.t_scale, color="k", ls=":", lw=1, label="start of the fit")
    ax_e.set_xlabel(units.time_label())
    ax_e.set_ylabel("RMS of the deflection" + (" [m]" if units.si else " (w_st)"))
    ax_e.legend(fontsize=8)
    ax_e.set_title("(b) free vibration released from the static deflection", loc="left", fontsize=9)
    verdict = "agree" if result.agrees else "DISAGREE"
    rows = ", ".join(f"{c.quantity} {100 * c.relative:.2g} %" for c in result.comparisons)
    fig.suptitle(f"{title}\nfinite rail vs Floquet: {rows}: {verdict}", fontsize=9)
    return fig
