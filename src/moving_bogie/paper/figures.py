"""Recipes of the paper's figures: the stability figures and the time series.

* :class:`StabilityFigure` — Figures 2, 3, 4, 7, 8 and 16, drawn by ``figureN(quick=, progress=)`` of
  :mod:`moving_bogie.stability.figures.plots` (Sections 3.5-3.8).
* :class:`TimeSeriesFigure` — Figures 5, 6, 9-15 and A1-A7: the closed-form vibrations of Eqs. (35)-(43)
  for the cases of Table 1, with the finite-beam overlay of Section 3.4 where the paper shows one
  (full runs only). :data:`SERIES` says, per figure, which cases, panels and time window.
"""

from __future__ import annotations

import inspect
import re
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from moving_bogie.paper.recipe import BuildContext, Built

__all__ = ["SERIES", "STABILITY_FIGURES", "SeriesSpec", "StabilityFigure", "TimeSeriesFigure"]

#: The figures drawn by :mod:`moving_bogie.stability.figures.plots`, by number.
STABILITY_FIGURES = (2, 3, 4, 7, 8, 16)


def _stability_plot(number: int) -> Callable[..., Any]:
    """``moving_bogie.paper.stability_figures.figure<number>`` (imported here: it pulls in matplotlib)."""
    from moving_bogie.paper import stability_figures as plots

    functions = {
        2: plots.figure2,
        3: plots.figure3,
        4: plots.figure4,
        7: plots.figure7,
        8: plots.figure8,
        16: plots.figure16,
    }
    return functions[number]


def _described(func: Callable[..., Any]) -> list[str]:
    """The paragraphs of `func`'s docstring before its numpydoc sections, each on one line."""
    text = inspect.cleandoc(func.__doc__ or "")
    described = re.split(r"\n(?:Parameters|Returns|Raises|Notes|Examples)\n-+", text)[0]
    return [" ".join(paragraph.split()) for paragraph in described.split("\n\n") if paragraph.strip()]


@dataclass(frozen=True)
class StabilityFigure:
    """Recipe of stability Figure `number`: calls ``figure<number>(quick=..., progress=...)``.

    The index notes quote the figure function's own description (its docstring), so the page says what
    the code draws.
    """

    number: int

    def __call__(self, ctx: BuildContext) -> Built:
        func = _stability_plot(self.number)
        fig = func(quick=ctx.quick, progress=ctx.progress)
        notes = [f"Built by {func.__module__}.{func.__qualname__}(quick={ctx.quick})."]
        notes += _described(func)
        if ctx.quick:
            notes.append("Quick mode: reduced grids; rerun without --quick for the full resolution.")
        return Built(files=[ctx.save_figure(fig, f"figure{self.number}")], notes=notes)


@dataclass(frozen=True)
class SeriesSpec:
    """A time-series figure: which cases, which panels, which time window, finite-beam overlay or not.

    The preprint's figures are missing from the received text, so the windows are chosen to show what
    the text says each figure shows (initial stages, or long times where a weak instability wins).
    ``tau_max=None`` (finite-beam figures): the validation's own window, 100 undamped and 200 damped
    (:func:`moving_bogie.validation.compare.default_tau_max`). Quick mode uses ``quick_tau_max``, closed
    form only.
    """

    cases: tuple[int, ...]
    panels: tuple[str, ...]
    tau_max: float | None
    quick_tau_max: float
    finite: bool = False
    colors: tuple[str, ...] = ()
    points: int = 1500


_THREE = ("w_rear", "u", "theta")
_TWO = ("w_rear", "u")

#: Every time-series figure of the paper. Initial stages without a finite beam: tau <= 400 (the periods
#: 2 pi / Re q of Cases 7-13 reach 100); long times: about 3.5 growth times 1/|Im q| of the unstable root
#: of Table 2 (1584 in Case 13 ... 7690 in Case 1), so that it visibly outgrows the decaying ones (x ~30);
#: Figure 15 (Case 6, stable) uses the window of Figure 13 (Case 5) for comparison.
SERIES: dict[str, SeriesSpec] = {
    "figure5": SeriesSpec((1,), _THREE, None, 100, finite=True),
    "figure6": SeriesSpec((1,), _TWO, 27000, 2000, points=20000),
    "figure9": SeriesSpec((2,), _THREE, None, 100, finite=True),
    "figure10": SeriesSpec((3,), _THREE, None, 100, finite=True),
    "figure11": SeriesSpec((4,), _THREE, None, 100, finite=True),
    "figure12": SeriesSpec((5,), _THREE, None, 100, finite=True),
    "figure13": SeriesSpec((5,), ("w_rear",), 7500, 2000, points=20000),
    "figure14": SeriesSpec((6,), _THREE, None, 100, finite=True),
    "figure15": SeriesSpec((6,), ("w_rear",), 7500, 2000, points=20000),
    "figureA1": SeriesSpec((7,), _THREE, None, 100, finite=True),
    "figureA2": SeriesSpec((7, 8, 9, 10), _THREE, 400, 100, colors=("darkviolet", "green", "red", "blue")),
    "figureA3": SeriesSpec((7, 11), _THREE, 400, 100, colors=("darkviolet", "orange")),
    "figureA4": SeriesSpec((12,), _THREE, 400, 100),
    "figureA5": SeriesSpec((12,), _TWO, 7500, 2000, points=20000),
    "figureA6": SeriesSpec((13,), _THREE, 400, 100),
    "figureA7": SeriesSpec((13,), _TWO, 5500, 2000, points=20000),
}

_PANEL_LABELS = {
    "w_rear": "beam deflection at the rear mass  w̃(0, τ)",
    "w_front": "beam deflection at the front mass  w̃(d̃, τ)",
    "u": "bogie bar mass center displacement  ũ(τ)",
    "theta": "bogie bar mass center rotation  θ̃(τ)",
}


@dataclass(frozen=True)
class TimeSeriesFigure:
    """Recipe of the time-series figure `id` (a key of :data:`SERIES`)."""

    id: str

    @property
    def spec(self) -> SeriesSpec:
        return SERIES[self.id]

    def __call__(self, ctx: BuildContext) -> Built:
        spec = self.spec
        if spec.finite and not ctx.quick:
            return _validation_figure(ctx, self.id, spec.cases[0])
        tau_max = spec.quick_tau_max if ctx.quick or spec.tau_max is None else spec.tau_max
        points = min(spec.points, 2000) if ctx.quick else spec.points
        curves, notes = [], []
        for k, case in enumerate(spec.cases):
            series = ctx.closed_form(case, tau_max, points)
            curves.append((case, series))
            notes += [f"Case {case}: {note}" for note in series.notes]
            ctx.progress((k + 1) / len(spec.cases))
        fig = _paper_style_figure(spec, curves) or _series_figure(spec, curves)
        if spec.finite and ctx.quick:
            notes.append(
                f"Quick mode: closed form only, τ ≤ {tau_max:g}; the full run overlays the finite beam "
                "(500 modes, moving_bogie.validation.compare)."
            )
        elif ctx.quick:
            notes.append(f"Quick mode: τ ≤ {tau_max:g} (full run: τ ≤ {spec.tau_max:g}).")
        notes.append(
            "Closed form, Eqs. (35)-(43): steady part, residues at every induced frequency of Table 2, "
            "and the branch-cut part where it matters (branch_cut='auto')."
        )
        return Built(files=[ctx.save_figure(fig, self.id)], notes=notes)


def _validation_figure(ctx: BuildContext, fig_id: str, case: int) -> Built:
    """Finite beam (full lines) against the closed form (dashed), with the validation verdict."""
    from moving_bogie.api import validate
    from moving_bogie.model.cases import table1_case
    from moving_bogie.validation.compare import plot_validation
    from moving_bogie.validation.verdict import ValidationResult

    result = validate(table1_case(case), progress=ctx.progress)
    assert isinstance(result, ValidationResult)  # Table 1's cases are on the continuous track
    fig = plot_validation(result, title=f"Case {case}: finite beam (full) vs closed form (dashed)")
    diffs = "; ".join(
        f"{name}: {100 * q.relative:.2g} % of its largest value (tolerance {q.tolerance:.0%})"
        for name, q in result.quantities.items()
    )
    notes = [
        f"Finite beam: L = {result.finite_beam.length:.1f}, {result.finite_beam.n_modes} modes, "
        f"comparison window τ ≤ {result.window[1]:.1f} (dotted line). "
        f"Validation {'agrees' if result.agrees else 'DISAGREES'}: {diffs}.",
        *result.notes,
    ]
    return Built(files=[ctx.save_figure(fig, fig_id)], notes=notes, ok=bool(result.agrees))


def _paper_style_figure(spec: SeriesSpec, curves: list) -> Any:
    """The response feature's own figures where they fit: one case, panels (a)-(c) or (a)-(b)."""
    from moving_bogie.response.plots import long_time_figure, time_series_figure

    if len(curves) != 1 or spec.panels not in (_THREE, _TWO):
        return None
    plot = time_series_figure if spec.panels == _THREE else long_time_figure
    case, series = curves[0]
    return plot(series, title=f"Case {case}: closed form (infinite beam)")


def _series_figure(spec: SeriesSpec, curves: list) -> Any:
    """Stacked panels (a), (b), (c) like the paper, closed form only, one color per case."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(7.5, 2.3 * len(spec.panels) + 0.5), layout="constrained")
    axes = fig.subplots(len(spec.panels), 1, sharex=True, squeeze=False)[:, 0]
    for j, (panel, ax) in enumerate(zip(spec.panels, axes)):
        for k, (case, series) in enumerate(curves):
            color = spec.colors[k] if spec.colors else "C0"
            ax.plot(series.tau, series[panel], "-", color=color, lw=1.0, label=f"Case {case}")
        name, symbol = _PANEL_LABELS[panel].split("  ")
        ax.set_ylabel(symbol)
        ax.set_title(f"({'abc'[j]}) {name}" if len(spec.panels) > 1 else name, loc="left", fontsize=9)
        ax.grid(True, lw=0.3)
        ax.margins(x=0)
        if j == 0 and len(curves) > 1:
            ax.legend(fontsize=8, loc="upper right", ncol=len(curves))
    axes[-1].set_xlabel("τ")
    cases = ", ".join(str(case) for case, _ in curves)
    fig.suptitle(f"Case{'s' if len(curves) > 1 else ''} {cases}: closed form (infinite beam)", fontsize=9)
    return fig
