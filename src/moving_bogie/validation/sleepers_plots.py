"""The figure of the finite-beam check on sleepers: the contact force and the free vibration's envelope."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from moving_bogie.validation.sleepers_check import SleeperCheck
from moving_bogie.validation.sleepers_fit import period_rms, smooth_steps

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["plot_sleeper_check"]


def plot_sleeper_check(result: SleeperCheck, *, title: str = "") -> Figure:
    """(a) The finite rail's contact force over time with the Floquet steady force over the last bay (a
    stable case) or the free vibration's deflection under the wheel (an unstable one); (b) the free
    vibration's RMS per bay-passing period (log scale) with the finite rail's fitted rate and the Floquet
    growth rate ``-Im q`` drawn through the same point. Dimensionless (docs/sleepers.md (S2))."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(8, 6.2), layout="constrained")
    ax_f, ax_e = fig.subplots(2, 1)
    if result.loaded is not None and result.steady_force is not None:
        run = result.loaded
        ax_f.plot(run.tau, smooth_steps(run.force[0]), color="C0", lw=0.9, label="finite rail, contact force")
        assert result.steady_tau is not None
        ax_f.plot(
            result.steady_tau,
            result.steady_force,
            "--",
            color="C3",
            lw=1.4,
            label="Floquet steady force (S17), last bay",
        )
        ax_f.set_ylabel("contact force (static load 2)")
    else:
        run = result.free
        ax_f.plot(
            run.tau,
            run.deflection[0],
            color="C0",
            lw=0.7,
            label="finite rail, free vibration under the wheel",
        )
        ax_f.set_ylabel("deflection under the wheel")
    ax_f.set_xlabel(r"$\tau$")
    ax_f.legend(fontsize=8, loc="upper right")
    ax_f.set_title(
        "(a) " + ("contact force" if result.loaded is not None else "free vibration"), loc="left", fontsize=9
    )
    free = result.free
    period = 2 * np.pi / result.Omega0
    mids, rms = period_rms(free.tau, free.deflection[0], period)
    ax_e.semilogy(mids, rms, "o", ms=3, color="C0", label="finite rail: RMS over each period $T_0$")
    fit = mids >= result.fit_start
    anchor = mids[fit][0], rms[fit][0]
    line = anchor[1] * np.exp(result.rate * (mids - anchor[0]))
    ax_e.semilogy(mids, line, "-", color="C0", lw=1, label=f"finite rail, fitted rate {result.rate:.5g}")
    if result.root is not None:
        rate = -result.root.imag
        ax_e.semilogy(
            mids,
            anchor[1] * np.exp(rate * (mids - anchor[0])),
            "--",
            color="C3",
            lw=1.2,
            label=f"Floquet growth rate $-$Im q = {rate:.5g}",
        )
    ax_e.axvline(result.fit_start, color="k", ls=":", lw=1, label="start of the fit")
    ax_e.set_xlabel(r"$\tau$")
    ax_e.set_ylabel("RMS of the deflection")
    ax_e.legend(fontsize=8)
    ax_e.set_title("(b) free vibration released from the static deflection", loc="left", fontsize=9)
    verdict = "agree" if result.agrees else "DISAGREE"
    rows = ", ".join(f"{c.quantity} {100 * c.relative:.2g} %" for c in result.comparisons)
    fig.suptitle(f"{title}\nfinite rail vs Floquet: {rows}: {verdict}", fontsize=9)
    return fig
