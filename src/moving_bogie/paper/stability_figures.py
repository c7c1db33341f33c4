"""The paper's stability figures: Figures 2, 3, 4, 7, 8 and 16, each a recipe on the stability tools.

Every ``figureN(quick=False, progress=None)`` returns a matplotlib Figure; ``quick=True`` uses coarser
grids (a few seconds per panel) for CI and previews. ``progress`` is called with the fraction done.
Colours follow the paper's legends: one colour per wheel spacing d, full and dashed lines for the two
variants compared in a panel, a black dotted line at the critical velocity.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import TYPE_CHECKING, Any

import numpy as np

from moving_bogie.api import critical_stiffness, frequency_lines, instability_lines_many, stability_map
from moving_bogie.model.cases import table1_case
from moving_bogie.model.catalogue import get_model
from moving_bogie.model.params import DimensionlessParams
from moving_bogie.stability.figures.plots import (
    end_mark_handles,
    new_figure,
    plot_instability_lines,
    spacing_colors,
)
from moving_bogie.stability.velocity.critical_velocity import critical_velocity

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["figure2", "figure3", "figure4", "figure7", "figure8", "figure16"]

SPACINGS = (1.0, 1.25, 1.5, 1.75, 2.0, 2.25)
ETA_F = ("0.05", "0.1", "0.15", "0.2", "0.25", "0.3")


def _grid(quick: bool) -> dict[str, Any]:
    """The step sizes of the instability lines (the keyword arguments of :func:`instability_lines`)."""
    return (
        dict(alpha_step=0.02, q_step=0.008, h_max=0.02)
        if quick
        else dict(alpha_step=0.01, q_step=0.004, h_max=0.01)
    )


class _Progress:
    """Split one progress callback over n equal parts."""

    def __init__(self, progress: Callable[[float], None] | None, n: int) -> None:
        self.progress, self.n, self.k = progress, max(1, n), 0

    def part(self) -> Callable[[float], None] | None:
        k = self.k
        self.k += 1
        progress = self.progress
        if progress is None:
            return None
        return lambda x: progress((k + min(1.0, x)) / self.n)


def _legend(
    fig: Figure,
    ds: Iterable[float],
    styles: Iterable[tuple[str, str]] = (),
    marks: Iterable[str] = (),
) -> None:
    """One legend for the figure: a colour per spacing, then the line styles and the line-end marks."""
    from matplotlib.lines import Line2D

    colors = spacing_colors(SPACINGS)
    handles = [Line2D([], [], color=colors[float(d)], label=f"d = {d:g}") for d in ds]
    handles += [Line2D([], [], color="k", ls=ls, label=text) for ls, text in styles]
    handles += end_mark_handles(marks)
    fig.legend(handles=handles, loc="outside right center", fontsize=8)


def _decorate(
    ax: Axes,
    title: str,
    alpha_max: float,
    theta_max: float = 200.0,
    ylabel: str = r"$\eta_M$",
    critical: float = 1.0,
) -> None:
    ax.axvline(critical, color="k", ls=":", lw=1)
    ax.set_xlim(0, alpha_max)
    ax.set_ylim(0, theta_max)
    ax.set_xlabel(r"$\alpha$")
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=9)


def _base(eta_f: str = "0.05", **kw: Any) -> DimensionlessParams:
    values = dict(eta_f=eta_f, eta_M=20, d=1, cf1="1.7", cf2="0.01", kappa_v="0.02", eta_v=0, alpha="0.5")
    values.update(kw)
    return DimensionlessParams.from_coefficients(**values)


def figure16_params() -> DimensionlessParams:
    """Stand-in for the data of ref. [48] (two-axle vehicle, wheel distance 15 m), chosen here.

    Track (per rail): EI = 6.4 MN m^2, m = 60 kg/m, k_f = 100 MN/m^2, so chi = 1.406 /m; Timoshenko-Rayleigh
    with G Abar = 250 MN and radius of gyration 0.063 m, giving S = 4.9 ~ 5 and r = 0.09 (Eq. (59));
    foundation damping eta_f = 0.05. Vehicle (per rail): wheel mass M = 750 kg (eta_M = 17.6 ~ 18),
    wheel distance 15 m (d = 21), half the car body M_b = 20 t on it (cf1 = M_b / M ~ 27) with the inertia
    of a uniform bar of length d, J_b = M_b d^2 / 12 (cf2 = cf1 / 12 = 2.25), no suspension damping.
    """
    return DimensionlessParams.from_coefficients(
        eta_f="0.05",
        eta_M=18,
        d=21,
        cf1=27,
        cf2="2.25",
        kappa_v="0.05",
        eta_v=0,
        alpha="1.2",
        beam="tr",
        S=5,
        r="0.09",
    )


def figure2(quick: bool = False, progress: Callable[[float], None] | None = None) -> Figure:
    """Figure 2: real (blue) and imaginary (orange) parts of the induced frequencies of Case 1 over alpha.

    One root of each pair is shown, one panel per frequency line (they are far apart); a line ends where
    it meets the cut of K (Im q = eta_f, dashed).
    """
    p = table1_case(1)
    res = frequency_lines(p, checkpoints=5 if quick else 13, h_max=0.02 if quick else 0.01, progress=progress)
    n = len(res.lines)
    fig = new_figure(figsize=(7, 1.9 * n + 0.6), layout="constrained")
    axs = fig.subplots(n, 1, sharex=True, squeeze=False)[:, 0]
    eta_f = float(p.eta_f)
    for k, (ax, line) in enumerate(zip(axs, res.lines)):
        ax.plot(line.alpha, line.q.real, color="tab:blue", lw=1.3)
        ax.set_ylabel(r"Re $q$", color="tab:blue")
        ax2 = ax.twinx()
        ax2.plot(line.alpha, line.q.imag, color="tab:orange", lw=1.3)
        ax2.axhline(0, color="tab:orange", lw=0.5, alpha=0.5)
        if np.max(line.q.imag) > 0.5 * eta_f:
            ax2.axhline(eta_f, color="tab:orange", ls="--", lw=0.8)
        ax2.set_ylabel(r"Im $q$", color="tab:orange")
        ax.set_title(f"line {k + 1}: starts at {line.start}, ends at {line.end}", fontsize=8)
        ax.axvline(1.0, color="k", ls=":", lw=0.8)
    axs[-1].set_xlabel(r"$\alpha$")
    axs[-1].set_xlim(*res.alpha_range)
    fig.suptitle("Figure 2: induced frequencies of Case 1 over the velocity", fontsize=10)
    return fig


def figure3(quick: bool = False, progress: Callable[[float], None] | None = None) -> Figure:
    """Figure 3: instability lines of two moving masses, d = 1:0.25:2.25, panels eta_f = 0.05:0.05:0.3."""
    fig = new_figure(figsize=(12, 7.5), layout="constrained")
    axs = fig.subplots(2, 3).ravel()
    colors = spacing_colors(SPACINGS)
    split = _Progress(progress, len(ETA_F))
    marks: set[str] = set()
    panels = instability_lines_many(
        [
            (
                _base(eta_f).replace(vehicle="masses"),
                dict(spacings=SPACINGS, progress=split.part(), **_grid(quick)),
            )
            for eta_f in ETA_F
        ]
    )  # the six panels traced together
    for ax, eta_f, tag, lines in zip(axs, ETA_F, "abcdef", panels):
        marks |= plot_instability_lines(ax, lines, colors=colors)
        _decorate(ax, rf"({tag}) $\eta_f$ = {eta_f}", 1.2)
    _legend(fig, SPACINGS, marks=marks)
    fig.suptitle("Figure 3: instability lines of two moving masses", fontsize=10)
    return fig


def figure4(quick: bool = False, progress: Callable[[float], None] | None = None) -> Figure:
    """Figure 4: bogie (full; cf1 = 1.7, cf2 = 0.01, kappa_v = 0.02, eta_v = 0) against two masses of the
    same total mass (dashed, 'a': 2 eta_M' = 2 eta_M + mu_v, i.e. eta_M' = eta_M (1 + cf1/2)), up to
    alpha = 1."""
    fig = new_figure(figsize=(12, 7.5), layout="constrained")
    axs = fig.subplots(2, 3).ravel()
    colors = spacing_colors(SPACINGS)
    adapt = 1 + 1.7 / 2
    split = _Progress(progress, 2 * len(ETA_F))
    marks: set[str] = set()
    requests = []
    for eta_f in ETA_F:
        p = _base(eta_f)
        requests.append(
            (p, dict(spacings=SPACINGS, alpha_range=(0, 1), progress=split.part(), **_grid(quick)))
        )
        same_mass = dict(spacings=SPACINGS, alpha_range=(0, 1), theta_max=200 * adapt, progress=split.part())
        requests.append((p.replace(vehicle="masses"), same_mass | _grid(quick)))
    panels = instability_lines_many(requests)  # all twelve traced together
    for ax, eta_f, tag, bogie, masses in zip(axs, ETA_F, "abcdef", panels[::2], panels[1::2]):
        marks |= plot_instability_lines(ax, bogie, colors=colors)
        marks |= plot_instability_lines(ax, masses, colors=colors, linestyle="--", scale=adapt, label=False)
        _decorate(ax, rf"({tag}) $\eta_f$ = {eta_f}", 1.0)
    _legend(fig, SPACINGS, (("-", "bogie"), ("--", "masses 'a'")), marks)
    fig.suptitle("Figure 4: instability lines, bogie against two masses of the same total mass", fontsize=10)
    return fig


def figure7(quick: bool = False, progress: Callable[[float], None] | None = None) -> Figure:
    """Figure 7: bogie, kappa_v = 0.2, eta_f = 0.05, cf1 = 1.7, d = 1:0.25:2; eta_v = 0 (full) and 0.05
    (dashed); (a) cf2 = 0.1, (b) cf2 = 0.01."""
    ds = SPACINGS[:-1]
    fig = new_figure(figsize=(11, 4.6), layout="constrained")
    axs = fig.subplots(1, 2)
    colors = spacing_colors(SPACINGS)
    split = _Progress(progress, 4)
    marks: set[str] = set()
    variants = [(cf2, eta_v) for cf2 in ("0.1", "0.01") for eta_v in ("0", "0.05")]
    panels = iter(
        instability_lines_many(
            [
                (
                    _base("0.05", cf2=cf2, kappa_v="0.2", eta_v=eta_v),
                    dict(spacings=ds, alpha_range=(0, 1), progress=split.part(), **_grid(quick)),
                )
                for cf2, eta_v in variants
            ]
        )
    )  # the four sets of lines traced together
    for ax, cf2, tag in zip(axs, ("0.1", "0.01"), "ab"):
        for style in ("-", "--"):
            marks |= plot_instability_lines(
                ax, next(panels), colors=colors, linestyle=style, label=style == "-"
            )
        _decorate(ax, rf"({tag}) $cf_2$ = {cf2}", 1.0)
    _legend(fig, ds, (("-", r"$\eta_v$ = 0"), ("--", r"$\eta_v$ = 0.05")), marks)
    fig.suptitle("Figure 7: effect of the suspension damping", fontsize=10)
    return fig


def figure8(quick: bool = False, progress: Callable[[float], None] | None = None) -> Figure:
    """Figure 8: Euler-Bernoulli (full) against Timoshenko-Rayleigh (dashed); cf1 = 1.7, cf2 = 0.1,
    eta_f = 0.05, kappa_v = 0.2, eta_v = 0; (a) S = 100, r = 0.03, (b) S = 10, r = 0.09."""
    fig = new_figure(figsize=(11, 4.6), layout="constrained")
    axs = fig.subplots(1, 2)
    colors = spacing_colors(SPACINGS)
    split = _Progress(progress, 3)
    marks: set[str] = set()
    eb = _base("0.05", cf2="0.1", kappa_v="0.2")

    beams = (("100", "0.03"), ("10", "0.09"))
    options = dict(spacings=SPACINGS, alpha_range=(0, 1), **_grid(quick))
    # the same Euler-Bernoulli lines in both panels; the three sets traced together
    eb_lines, *tr_lines = instability_lines_many(
        [
            (p, options | dict(progress=split.part()))
            for p in [eb, *(eb.replace(beam="tr", S=S, r=r) for S, r in beams)]
        ]
    )
    for ax, (S, r), tag, tr in zip(axs, beams, "ab", tr_lines):
        a_cr = float(critical_velocity(get_model(beam="tr"), S=S, r=r).alpha_cr)
        for lines, style in ((eb_lines, "-"), (tr, "--")):
            marks |= plot_instability_lines(ax, lines, colors=colors, linestyle=style, label=style == "-")
        _decorate(ax, rf"({tag}) $\tilde S$ = {S}, $\tilde r$ = {r}", 1.0)
        ax.axvline(a_cr, color="grey", ls=":", lw=1)
    _legend(fig, SPACINGS, (("-", "Euler-Bernoulli"), ("--", "Timoshenko-Rayleigh")), marks)
    fig.suptitle(
        "Figure 8: effect of the beam theory (grey dotted: TR critical velocity, Eq. (66))", fontsize=10
    )
    return fig


def figure16(quick: bool = False, progress: Callable[[float], None] | None = None) -> Figure:
    """Figure 16 (stand-in): critical primary-suspension stiffness in the (alpha, kappa_v) plane.

    (a) the parameter set of :func:`figure16_params`, chosen
    to resemble
    the two-axle vehicle of ref. [48] (its data are not given in full); (b) the bogie of Case 5, where the
    critical stiffnesses lie in the subcritical range. Shading: number of unstable induced frequencies
    (argument principle); black dots: stable/unstable boundaries (D-decomposition).
    """
    from matplotlib.colors import BoundaryNorm

    fig = new_figure(figsize=(11, 4.6), layout="constrained")
    axs = fig.subplots(1, 2)
    sets = (
        ("(a) stand-in for ref. [48]: TR, d = 21", figure16_params(), (0.5, 2.0), 1.0, 4.0),
        ("(b) bogie of Case 5: EB, d = 1.5", table1_case(5), (0.3, 1.1), 0.6, 1.5),
    )
    # quick: coarser grids, and 6 instead of 40 argument-principle counts per alpha checking the dots
    n_map, n_line, checks = (16, 6, 6) if quick else (120, 60, 40)
    split = _Progress(progress, 4)
    for ax, (title, p, (a0, a1), kmax, q_max) in zip(axs, sets):
        alphas = np.linspace(a0, a1, n_map)
        kappas = np.linspace(kmax / n_map, kmax, n_map)
        m = stability_map(p, parameter="kappa_v", alphas=alphas, thetas=kappas, progress=split.part())
        norm = BoundaryNorm(np.arange(-0.5, 6.5), 256)
        mesh = ax.pcolormesh(
            alphas, kappas, np.minimum(m.count, 6), shading="nearest", cmap="Greys", norm=norm, alpha=0.6
        )
        cs = critical_stiffness(
            p,
            np.linspace(a0, a1, n_line),
            kappa_max=kmax,
            q_max=q_max,
            check_points=checks,
            progress=split.part(),
        )
        for a, crit in zip(cs.alphas, cs.critical):
            ax.plot([a] * len(crit), crit, "k.", ms=3)
        ax.set_xlim(a0, a1)
        ax.set_ylim(0, kmax)
        ax.set_xlabel(r"$\alpha$")
        ax.set_ylabel(r"$\kappa_v$")
        ax.set_title(title, fontsize=9)
        fig.colorbar(mesh, ax=ax, label="unstable induced frequencies", ticks=range(7))
    fig.suptitle("Figure 16 (stand-in): critical stiffness of the primary suspension", fontsize=10)
    return fig
