"""Instability lines of one vehicle on two tracks side by side (the one-layer track and a layered one).

The instability lines (Section 3.7, Figures 3-8) of a vehicle depend on the track only through K(xi, q);
a layered track (docs/layered_tracks.md) changes K and so moves the lines. :func:`compare_tracks` computes
the lines of the same vehicle on the base parameters' track and on another track with its extra groups,
with the critical velocity of each track (the smallest local minimum of the phase speed,
:mod:`moving_bogie.stability.velocity.critical_velocity`); :func:`figure_track_comparison` draws them in two
panels with the same axes.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from moving_bogie.kernels.bound import BoundModel
from moving_bogie.stability.lines.instability_lines import InstabilityLines, instability_lines
from moving_bogie.stability.velocity.critical_velocity import critical_velocity

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from moving_bogie.stability.figures.plot_units import PlaneUnits

__all__ = ["TrackComparison", "compare_tracks", "figure_track_comparison"]


@dataclass(frozen=True)
class TrackComparison:
    """The instability lines and critical velocity of one vehicle on each of two tracks."""

    lines: tuple[InstabilityLines, InstabilityLines]
    alpha_cr: tuple[float, float]
    spacings: tuple[float, ...]
    alpha_range: tuple[float, float]
    theta_max: float

    def to_dict(self) -> dict:
        return {
            "tracks": [
                {"track": lines.params.track, "alpha_cr": a, "lines": lines.to_dict()}
                for lines, a in zip(self.lines, self.alpha_cr)
            ],
            "spacings": list(self.spacings),
            "alpha_range": list(self.alpha_range),
            "eta_M_max": self.theta_max,  # as the option --eta-M-max (theta_max before)
        }


def compare_tracks(
    bound: BoundModel,
    track: str,
    groups: Mapping[str, Any],
    *,
    spacings: Sequence[float] = (1.0, 1.5, 2.0),
    alpha_range: tuple[float, float] = (0.0, 1.2),
    theta_max: float = 200.0,
    quick: bool = False,
    progress: Callable[[float], None] | None = None,
) -> TrackComparison:
    """Instability lines (in the plane alpha, eta_M) of the vehicle of `bound` on its track and on `track`.

    Parameters
    ----------
    bound : BoundModel
        The vehicle and the base track (usually the paper's one-layer track).
    track : str
        The other track (``moving-bogie models`` lists them), e.g. ``"two-layer"``.
    groups : mapping
        The groups the other track adds (``mu_2``, ``kappa_2``, ``eta_2`` for two layers). Every group of
        the vehicle and of the base track (the pads' ``eta_f``) is shared.
    spacings, alpha_range, theta_max
        As in :func:`~moving_bogie.stability.lines.instability_lines.instability_lines`.
    quick : bool
        Coarser continuation steps (for previews and tests).
    """
    other = bound.replace(track=track, **dict(groups))
    alpha_step, q_step, h_max = (0.02, 0.008, 0.02) if quick else (0.01, 0.004, 0.01)

    def track_lines(k: int, p: BoundModel) -> InstabilityLines:
        part = None if progress is None else (lambda x: progress((k + x) / 2))
        return instability_lines(
            p,
            spacings=spacings,
            alpha_range=alpha_range,
            theta_max=theta_max,
            progress=part,
            alpha_step=alpha_step,
            q_step=q_step,
            h_max=h_max,
        )

    base_lines = track_lines(0, bound)
    base_cr = float(critical_velocity(bound).alpha_cr)
    other_lines = track_lines(1, other)
    other_cr = float(critical_velocity(other).alpha_cr)
    return TrackComparison(
        (base_lines, other_lines),
        (base_cr, other_cr),
        tuple(spacings),
        (alpha_range[0], alpha_range[1]),
        theta_max,
    )


def figure_track_comparison(comparison: TrackComparison, units: PlaneUnits | None = None) -> Figure:
    """Two panels with the same axes: the instability lines on each track, its critical velocity dotted;
    in SI with ``units`` (:class:`~moving_bogie.stability.figures.plot_units.PlaneUnits`), operating point
    marked."""
    import matplotlib
    from matplotlib.figure import Figure

    from moving_bogie.stability.figures.plot_units import PlaneUnits
    from moving_bogie.stability.figures.plots import plot_instability_lines

    units = units or PlaneUnits()
    fig = Figure(figsize=(11, 4.6), layout="constrained")
    axs = fig.subplots(1, 2, sharey=True)
    cmap = matplotlib.colormaps["tab10"]
    colors = {float(d): cmap(k % 10) for k, d in enumerate(comparison.spacings)}
    parameter = comparison.lines[0].parameter
    for ax, lines, a_cr in zip(axs, comparison.lines, comparison.alpha_cr):
        plot_instability_lines(ax, lines, colors=colors, units=units)
        ax.axvline(units.value("alpha", a_cr), color="k", ls=":", lw=1)
        ax.set_xlim(*(units.value("alpha", a) for a in comparison.alpha_range))
        ax.set_ylim(0, units.value(parameter, comparison.theta_max))
        ax.set_xlabel(units.label("alpha") if units.si else r"$\alpha$")
        ax.set_ylabel(units.label(parameter) if units.si else r"$\eta_M$")
        critical = (
            f"v_cr = {units.value('alpha', a_cr):.4g} {units.unit('alpha')}"
            if units.si
            else rf"$\alpha_{{cr}}$ = {a_cr:.4f}"
        )
        ax.set_title(f"{lines.params.beam} on the {lines.params.track} track, {critical}")
    axs[0].legend(fontsize=8, title="d")
    if units.mark(axs[1], "alpha", parameter):
        axs[1].legend(fontsize=8)
    return fig
