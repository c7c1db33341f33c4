"""Paper-style overlay of a finite-beam validation (Figures 5, 9-14, A1-A7): finite beam vs closed form."""

from __future__ import annotations

from os import PathLike
from typing import TYPE_CHECKING, BinaryIO

from moving_bogie.validation.verdict import ValidationResult, beam_title, quantity_labels, series

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from moving_bogie.model.params import DimensionlessParams
    from moving_bogie.model.physical import PhysicalParams

__all__ = ["check_figure", "plot_validation"]


def plot_validation(
    result: ValidationResult, path: str | PathLike[str] | BinaryIO | None = None, *, title: str | None = None
) -> Figure:
    """Paper-style figure (Figures 5, 9-12, 14, A1): finite beam solid, closed form dashed.

    One stacked panel for the rail under the rear wheel and one for every body DOF of the vehicle, labelled
    from its generated ``DOFS`` and ``UNITS`` (the bogie: (a) ``w_rear``, (b) bar bounce ``u``, (c) bar pitch
    ``theta``; the two masses: ``w_rear`` only). The comparison window's
    end is marked by a dotted line, the time after it shaded; the strict reflection-free
    ``tau_valid`` by a thin dotted grey line when it is earlier. Builds a bare
    :class:`matplotlib.figure.Figure` (no pyplot, no GUI backend).

    Parameters
    ----------
    result : ValidationResult
    path : path-like, optional
        Save the figure there (PNG, PDF, SVG by extension).
    title : str, optional
        First line of the figure title (default "bogie: finite beam (solid) vs closed form
        (dashed)"); a second line gives modes, beam, window and verdict.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from matplotlib.figure import Figure

    # the rear wheel and every internal degree of freedom
    names = list(result.quantities)
    panels = [names[0], *names[result.finite_beam.contacts :]]
    # labels from the vehicle's generated DOFS and UNITS (ValidationResult.labels)
    labels = result.labels or quantity_labels(names, {}, result.finite_beam.contacts)
    fig = Figure(figsize=(7.5, 2.3 * len(panels) + 0.9), layout="constrained")
    axes = fig.subplots(len(panels), 1, sharex=True, squeeze=False)[:, 0]
    tau = result.tau
    tau_w = result.window[1]
    correction = " + static correction" if result.finite_beam.static_correction else ""
    for letter, (ax, name) in zip("abcdefghijklmnop", zip(axes, panels)):
        attr = name
        curves = (
            (result.finite_beam, "-", "C0", f"finite beam, {result.finite_beam.n_modes} modes{correction}"),
            (result.closed_form, "--", "C3", "closed form (infinite beam)"),
        )
        for source, style, color, label in curves:
            ax.plot(tau, series(source, attr, tau.size), style, color=color, lw=1.2, label=label)
        if tau_w < tau[-1]:
            ax.axvspan(tau_w, tau[-1], color="0.88", zorder=0, label="after the window")
        ax.axvline(tau_w, color="k", ls=":", lw=1.0, label="window end")
        if result.finite_beam.tau_valid < tau_w:
            ax.axvline(
                result.finite_beam.tau_valid,
                color="0.55",
                ls=(0, (1, 3)),
                lw=0.9,
                label="strict reflection-free end",
            )
        q = result.quantities[name]
        ax.set_ylabel(labels[name])
        ax.set_title(
            f"({letter})  max |difference| in the window {q.max_abs_diff:.2g} = {100 * q.relative:.2g} % of "
            f"max |closed form| (tolerance {q.tolerance:.0%})",
            loc="left",
            fontsize=8,
        )
        ax.margins(x=0)
    axes[-1].set_xlabel(r"$\tau$")
    fig.legend(
        *axes[0].get_legend_handles_labels(), loc="outside lower center", fontsize=8, ncol=3, frameon=False
    )
    fig.suptitle(_suptitle(result, title), fontsize=9)
    if path is not None:
        fig.savefig(path, dpi=150)
    return fig


def _suptitle(result: ValidationResult, title: str | None) -> str:
    """The figure's title: `title` (default: the vehicle and its beam), then the run and the verdict."""
    finite, tau_w = result.finite_beam, result.window[1]
    verdict = "agree" if result.agrees else "DISAGREE"
    if title is None:
        vehicle = result.model
        title = f"{vehicle} ({beam_title(result.params)}): finite beam (solid) vs closed form (dashed)"
    return (
        f"{title}\n{finite.n_modes} modes, "
        f"L = {finite.length:.1f}, k_max = {finite.k_max:.2f}; window [0, {tau_w:.1f}], "
        f"tau_valid = {finite.tau_valid:.1f}: {verdict}"
    )


def check_figure(
    result: ValidationResult, params: DimensionlessParams | PhysicalParams, *, title: str
) -> Figure:
    """The figure of a check on any track: :func:`plot_validation` titled ``title``, or on periodic supports
    the finite rail's (:func:`~moving_bogie.validation.sleepers_plots.plot_sleeper_check`), titled by the
    model and its speed (in m/s for SI ``params``)."""
    if result.supports is None:
        return plot_validation(result, title=title)
    from moving_bogie.validation.sleepers_plots import plot_sleeper_check

    check = result.supports
    speed = f"v = {float(params.v):g} m/s" if check.scales is not None else f"alpha = {float(params.alpha):g}"
    return plot_sleeper_check(check, title=f"{check.model}, {speed}")
