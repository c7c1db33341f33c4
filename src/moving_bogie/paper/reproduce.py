"""Rebuild the paper's tables and figures into one folder, each shown next to its caption.

``moving-bogie reproduce --out DIR [--quick]`` runs every artifact of :data:`ARTIFACTS` and writes
``DIR/index.html`` and ``DIR/index.md``: per artifact the paper's caption (verbatim, from
:mod:`moving_bogie.paper.captions`), then the rebuilt figure or table, or the reason it is not covered.

Design
------
* A registry of :class:`Artifact` (caption + builder). A builder imports the feature it needs lazily
  (:func:`require`); when the feature is not in this installation the artifact is listed as
  **not covered** with the reason. It never gets a placeholder image.
* A builder that raises anything else is **failed**: its traceback goes to ``DIR/errors/ID.txt``, the
  index says so, and the command exits 1. Table 2 differing from the print also exits 1.
* Quick mode (``--quick``, or ``MOVING_BOGIE_QUICK=1``) uses reduced grids and short time windows
  (closed-form series only) so that the whole run takes well under two minutes; the index names every
  reduction next to the artifact it affects.
* Results shared between artifacts (the induced frequencies of each case) are computed once.
"""

from __future__ import annotations

import datetime
import html
import importlib
import os
import re
import time
import traceback
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from moving_bogie.paper.captions import CAPTIONS, Caption

__all__ = [
    "ARTIFACTS",
    "QUICK_ENV",
    "Artifact",
    "BuildContext",
    "Built",
    "NotCovered",
    "Outcome",
    "Report",
    "quick_from_env",
    "reproduce",
    "require",
]

#: Environment variable that switches notebooks and :func:`reproduce` to reduced grids ("1", "true", "yes").
QUICK_ENV = "MOVING_BOGIE_QUICK"


def quick_from_env(default: bool = False) -> bool:
    """True when :data:`QUICK_ENV` is set to 1/true/yes (False for 0/false/no; `default` when unset)."""
    value = os.environ.get(QUICK_ENV)
    if value is None or not value.strip():
        return default
    return value.strip().lower() in ("1", "true", "yes", "on")


class NotCovered(Exception):
    """The artifact needs a feature this installation does not have; the message says which."""


def require(module: str, *names: str) -> Any:
    """Import ``moving_bogie.<module>`` and return it, or the named attributes of it.

    Raises
    ------
    NotCovered
        When the module itself does not exist or lacks one of `names`. An ImportError raised *inside*
        an existing module is a bug and propagates unchanged.
    """
    full = module if module.split(".")[0] == "moving_bogie" else f"moving_bogie.{module}"
    try:
        mod = importlib.import_module(full)
    except ModuleNotFoundError as exc:
        if exc.name is not None and (full == exc.name or full.startswith(exc.name + ".")):
            raise NotCovered(f"feature missing: module {full} is not in this installation") from None
        raise
    missing = [name for name in names if not hasattr(mod, name)]
    if missing:
        raise NotCovered(f"feature missing: {full} has no {', '.join(missing)}")
    if not names:
        return mod
    values = tuple(getattr(mod, name) for name in names)
    return values[0] if len(values) == 1 else values


@dataclass
class Built:
    """What a builder returns: files written (relative to the output folder), a table, notes."""

    files: list[str] = field(default_factory=list)
    html: str = ""
    markdown: str = ""
    notes: list[str] = field(default_factory=list)
    ok: bool = True  # False: built, but the result disagrees with the paper (e.g. Table 2 mismatch)


@dataclass(frozen=True)
class Artifact:
    """One table or figure of the paper and how to rebuild it.

    `builder` is None for an artifact the software does not compute; `reason` then says why.
    """

    caption: Caption
    kind: str  # "figure" or "table"
    builder: Callable[[BuildContext], Built] | None
    reason: str = ""

    @property
    def id(self) -> str:
        return self.caption.id

    @property
    def label(self) -> str:
        return self.caption.label


@dataclass
class Outcome:
    """The result of one artifact: status "covered", "not covered" or "failed"."""

    artifact: Artifact
    status: str
    built: Built = field(default_factory=Built)
    reason: str = ""
    seconds: float = 0.0

    @property
    def ok(self) -> bool:
        return self.status != "failed" and self.built.ok


@dataclass
class Report:
    """All outcomes of a run, in registry order."""

    out: Path
    quick: bool
    outcomes: list[Outcome]
    seconds: float

    @property
    def ok(self) -> bool:
        return all(o.ok for o in self.outcomes)

    def count(self, status: str) -> int:
        return sum(o.status == status for o in self.outcomes)


class BuildContext:
    """Passed to every builder: the output folder, the mode, shared results and a progress callback."""

    def __init__(self, out: Path, *, quick: bool, dps: int, progress: Callable[[float], None] | None = None):
        self.out = out
        self.quick = quick
        self.dps = dps
        self._progress = progress
        self._frequencies: dict[int, Any] = {}
        self.table2: Any = None

    def progress(self, fraction: float) -> None:
        """Report the fraction of the current artifact done (0..1)."""
        if self._progress is not None:
            self._progress(max(0.0, min(1.0, fraction)))

    def save_figure(self, fig: Any, name: str, *, dpi: int = 110) -> str:
        """Save a matplotlib Figure as ``figures/<name>.png``, close it, return the relative path."""
        rel = f"figures/{name}.png"
        path = self.out / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        fig.savefig(path, dpi=dpi, bbox_inches="tight")
        _close(fig)
        return rel

    def frequencies(self, case: int) -> Any:
        """Induced frequencies of Table 1 case `case` (bogie), from Table 2 when it was built in this run."""
        if case not in self._frequencies:
            row = next((r for r in self.table2.rows if r.case == case), None) if self.table2 else None
            if row is not None:
                self._frequencies[case] = row.result
            else:
                from moving_bogie.model.cases import table1_case
                from moving_bogie.roots.frequencies import induced_frequencies

                self._frequencies[case] = induced_frequencies(table1_case(case), "bogie", dps=self.dps)
        return self._frequencies[case]


def _close(fig: Any) -> None:
    """Release a figure whether or not pyplot manages it."""
    import sys

    if "matplotlib.pyplot" in sys.modules:
        sys.modules["matplotlib.pyplot"].close(fig)


# --------------------------------------------------------------------------------------------------------
# Tables
# --------------------------------------------------------------------------------------------------------

_TABLE1_COLUMNS = (
    ("eta_f", "η<sub>f</sub>", "$\\eta_f$"),
    ("eta_M", "η<sub>M</sub>", "$\\eta_M$"),
    ("d", "d̃", "$\\tilde{d}$"),
    ("cf1", "cf<sub>1</sub>", "$cf_1$"),
    ("cf2", "cf<sub>2</sub>", "$cf_2$"),
    ("kappa_v", "κ<sub>v</sub>", "$\\kappa_v$"),
    ("eta_v", "η<sub>v</sub>", "$\\eta_v$"),
    ("alpha", "α", "$\\alpha$"),
)


def build_table1(ctx: BuildContext) -> Built:
    """Table 1 from the packaged case data (``moving_bogie/data/table1_cases.csv``)."""
    from moving_bogie.model.cases import TABLE1_CASES, table1_case

    rows = [(n, table1_case(n).to_dict()) for n in TABLE1_CASES]
    head = "".join(f"<th>{h}</th>" for _, h, _ in _TABLE1_COLUMNS)
    body = "\n".join(
        f"<tr><th>Case {n}</th>" + "".join(f"<td>{d[key]}</td>" for key, _, _ in _TABLE1_COLUMNS) + "</tr>"
        for n, d in rows
    )
    table = f'<table class="data">\n<tr><th>Parameter</th>{head}</tr>\n{body}\n</table>'
    md_head = "| Parameter | " + " | ".join(m for _, _, m in _TABLE1_COLUMNS) + " |"
    md_rule = "|" + "---|" * (len(_TABLE1_COLUMNS) + 1)
    md_rows = [f"| Case {n} | " + " | ".join(d[key] for key, _, _ in _TABLE1_COLUMNS) + " |" for n, d in rows]
    ctx.progress(1.0)
    return Built(
        html=table,
        markdown="\n".join([md_head, md_rule, *md_rows]),
        notes=[
            "Read from the packaged data file moving_bogie/data/table1_cases.csv (mu_v, J_b by Eq. (63))."
        ],
    )


def build_table2(ctx: BuildContext) -> Built:
    """Table 2: every induced frequency with its confirmed digits, beside the printed value."""
    from moving_bogie.roots.table2 import compute_table2, format_table2

    table = compute_table2(dps=ctx.dps, progress=ctx.progress)
    ctx.table2 = table
    (ctx.out / "table2.txt").write_text(format_table2(table) + "\n", encoding="utf-8")
    import json

    (ctx.out / "table2.json").write_text(json.dumps(table.to_dict(), indent=2) + "\n", encoding="utf-8")
    html_rows, md_rows = [], []
    for row in table.rows:
        verdict = "stable" if row.result.stable else "UNSTABLE"
        count = "count ok" if row.result.count_ok else "COUNT MISMATCH"
        match = "" if not row.printed else ("matches print" if row.ok else "DIFFERS FROM PRINT")
        status = ", ".join(x for x in (count, verdict, match) if x)
        n = len(row.result.roots)
        for k, (root, diff) in enumerate(zip(row.result.roots, row.differences)):
            shown = min(6, root.decimals)
            re6, im6 = _round_text(root.re_text, shown), _round_text(root.im_text, shown)
            printed = _printed_for(row.printed, root) if diff is not None else None
            pr = f"±{printed[0]}" if printed else "withheld" if not row.printed else "—"
            pi = printed[1] if printed else ""
            dd = f"{float(diff[0]):+.1e}, {float(diff[1]):+.1e}" if diff is not None else ""
            cls = ' class="unstable"' if root.unstable else ""
            first = (
                f'<th rowspan="{n}">Case {row.case}<br><small>{html.escape(status)}</small></th>'
                if k == 0
                else ""
            )
            html_rows.append(
                f"<tr{cls}>{first}<td>{k + 1}</td><td>±{re6}</td><td>{im6}</td><td>{pr}</td><td>{pi}</td>"
                f'<td>{dd}</td><td class="digits">±{root.re_text}<br>{root.im_text}<br>'
                f"<small>{root.digits} digits confirmed</small></td></tr>"
            )
            md_rows.append(
                f"| {'Case ' + str(row.case) if k == 0 else ''} | {k + 1} | ±{re6} | {im6} | {pr} | {pi} "
                f"| {dd} | "
                f"{root.digits} | {status if k == 0 else ''} |"
            )
    head = (
        "<tr><th>Case</th><th>#</th><th>q<sup>r</sup></th><th>q<sup>i</sup></th>"
        "<th>printed q<sup>r</sup></th>"
        "<th>printed q<sup>i</sup></th><th>computed − printed</th><th>all confirmed digits</th></tr>"
    )
    table_html = f'<table class="data">\n{head}\n' + "\n".join(html_rows) + "\n</table>"
    md = "\n".join(
        [
            "| Case | # | $q^r$ | $q^i$ | printed $q^r$ | printed $q^i$ | computed − printed | digits "
            "| verdict |",
            "|---|---|---|---|---|---|---|---|---|",
            *md_rows,
        ]
    )
    notes = [
        f"Computed at {ctx.dps} digits; every digit shown is confirmed by recomputation at higher precision. "
        "One root of each pair q, −conj(q) is listed (Re q ≥ 0); rows in red are unstable (Im q < 0).",
        "The preprint withholds the printed rows of Cases 7-13: those are computed only.",
        "Also written: table2.txt (the layout of `moving-bogie table2`) and table2.json.",
    ]
    if not table.ok:
        notes.append("MISMATCH: some case differs from the print or has a count mismatch (see table2.txt).")
    return Built(files=["table2.txt", "table2.json"], html=table_html, markdown=md, notes=notes, ok=table.ok)


def _round_text(text: str, decimals: int) -> str:
    from decimal import Decimal

    value = Decimal(text).quantize(Decimal(1).scaleb(-decimals))
    if value == 0:
        value = abs(value)
    return f"{value:.{decimals}f}"


def _printed_for(printed: Sequence[tuple[str, str]], root: Any) -> tuple[str, str]:
    q = complex(root.q)
    return min(printed, key=lambda pr: abs(q - complex(float(pr[0]), float(pr[1]))))


# --------------------------------------------------------------------------------------------------------
# Stability figures (Sections 3.4-3.8): figure functions of the stability feature
# --------------------------------------------------------------------------------------------------------

#: Modules searched, in order, for the stability figure functions ``figureN(quick=...)``.
STABILITY_FIGURE_MODULES = ("plots_stability",)


def _stability_figure_function(number: int) -> Callable[..., Any]:
    name = f"figure{number}"
    missing = []
    for module in STABILITY_FIGURE_MODULES:
        try:
            return require(module, name)
        except NotCovered as exc:
            missing.append(str(exc).removeprefix("feature missing: "))
    raise NotCovered(f"feature missing: no {name}() in the stability plots ({'; '.join(missing)})")


def _stability_builder(number: int) -> Callable[[BuildContext], Built]:
    def build(ctx: BuildContext) -> Built:
        func = _stability_figure_function(number)
        kwargs: dict[str, Any] = {"quick": ctx.quick}
        import inspect

        if "progress" in inspect.signature(func).parameters:
            kwargs["progress"] = ctx.progress
        fig = func(**kwargs)
        notes = [f"Built by {func.__module__}.{func.__qualname__}(quick={ctx.quick})."]
        described = re.split(
            r"\n(?:Parameters|Returns|Raises|Notes|Examples)\n-+", inspect.getdoc(func) or ""
        )[0]
        notes += [" ".join(paragraph.split()) for paragraph in described.split("\n\n") if paragraph.strip()]
        if ctx.quick:
            notes.append("Quick mode: reduced grids; rerun without --quick for the full resolution.")
        return Built(files=[ctx.save_figure(fig, f"figure{number}")], notes=notes)

    build.__name__ = f"build_figure{number}"
    return build


# --------------------------------------------------------------------------------------------------------
# Time series (Figures 5, 6, 9-15, A1-A7)
# --------------------------------------------------------------------------------------------------------


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


def _series_builder(fig_id: str) -> Callable[[BuildContext], Built]:
    spec = SERIES[fig_id]

    def build(ctx: BuildContext) -> Built:
        from moving_bogie.model.cases import table1_case

        closed_form_response = require("response", "closed_form_response")
        notes = []
        if spec.finite and not ctx.quick:
            try:
                return _validation_figure(ctx, fig_id, spec.cases[0])
            except NotCovered as exc:
                notes.append(f"No finite-beam overlay ({exc}): closed form only.")
        import numpy as np

        tau_max = spec.quick_tau_max if ctx.quick or spec.tau_max is None else spec.tau_max
        points = min(spec.points, 2000) if ctx.quick else spec.points
        tau = np.linspace(0.0, tau_max, points + 1)
        curves = []
        for k, case in enumerate(spec.cases):
            series = closed_form_response(
                table1_case(case), tau, model="bogie", frequencies=ctx.frequencies(case)
            )
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
        return Built(files=[ctx.save_figure(fig, fig_id)], notes=notes)

    build.__name__ = f"build_{fig_id}"
    return build


def _validation_figure(ctx: BuildContext, fig_id: str, case: int) -> Built:
    """Finite beam (full lines) against the closed form (dashed), with the validation verdict."""
    from moving_bogie.model.cases import table1_case

    validate, plot_validation = require("validation", "validate", "plot_validation")
    result = validate(table1_case(case), progress=ctx.progress)
    fig = plot_validation(result, title=f"Case {case}: finite beam (full) vs closed form (dashed)")
    diffs = "; ".join(
        f"{name}: max diff {q.max_abs_diff:.2g} (tolerance {q.tolerance:.2g})"
        for name, q in result.quantities.items()
    )
    notes = [
        f"Finite beam: L = {result.finite.length:.1f}, {result.finite.n_modes} modes, comparison window "
        f"τ ≤ {result.window[1]:.1f} (dotted line). "
        f"Validation {'agrees' if result.agrees else 'DISAGREES'}: {diffs}.",
        *result.notes,
    ]
    return Built(files=[ctx.save_figure(fig, fig_id)], notes=notes, ok=bool(result.agrees))


def _paper_style_figure(spec: SeriesSpec, curves: list) -> Any:
    """The response feature's own figures where they fit: one case, panels (a)-(c) or (a)-(b)."""
    if len(curves) != 1 or spec.panels not in (_THREE, _TWO):
        return None
    try:
        name = "time_series_figure" if spec.panels == _THREE else "long_time_figure"
        plot = require("plots_timeseries", name)
    except NotCovered:
        return None
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
            ax.plot(series.tau, getattr(series, panel), "-", color=color, lw=1.0, label=f"Case {case}")
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


# --------------------------------------------------------------------------------------------------------
# Registry
# --------------------------------------------------------------------------------------------------------

_CAPTION = {c.id: c for c in CAPTIONS}


def _artifacts() -> tuple[Artifact, ...]:
    out = []
    for caption in CAPTIONS:
        kind = "table" if caption.id.startswith("table") else "figure"
        if caption.id == "figure1":
            out.append(
                Artifact(
                    caption,
                    kind,
                    None,
                    "a schematic drawing of the model, not a computed result; README.md carries the same "
                    "sketch in text form",
                )
            )
        elif caption.id == "table1":
            out.append(Artifact(caption, kind, build_table1))
        elif caption.id == "table2":
            out.append(Artifact(caption, kind, build_table2))
        elif caption.id in SERIES:
            out.append(Artifact(caption, kind, _series_builder(caption.id)))
        else:
            number = int(caption.id.removeprefix("figure"))
            out.append(Artifact(caption, kind, _stability_builder(number)))
    return tuple(out)


#: Every table and figure of the paper, in the paper's order.
ARTIFACTS: tuple[Artifact, ...] = _artifacts()


def reproduce(
    out: str | os.PathLike[str],
    *,
    quick: bool = False,
    only: Sequence[str] | None = None,
    dps: int | None = None,
    progress: Callable[[float], None] | None = None,
    log: Callable[[str], None] | None = None,
) -> Report:
    """Rebuild the artifacts into `out` and write ``index.html`` and ``index.md``.

    Parameters
    ----------
    out : path
        Output folder (created). Existing files of the same names are replaced.
    quick : bool
        Reduced grids, short time windows, no finite-beam runs (a couple of minutes in all).
    only : sequence of str, optional
        Artifact ids (``"table2"``, ``"figure5"``, ``"figureA3"``) or labels (``"Figure 5"``) to build;
        the others are listed as "not built in this run". The time series reuse the roots of Table 2
        when it is built in the same run (it comes first), and compute them otherwise.
    dps : int, optional
        Working precision of the induced frequencies (default 30, quick 20).
    progress : callable, optional
        Called with the overall fraction done.
    log : callable, optional
        Called with one line per finished artifact.

    Returns
    -------
    Report
    """
    from moving_bogie.errors import ParameterError

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    dps = dps if dps is not None else (20 if quick else 30)
    unknown = sorted(
        {x.strip() for x in only or ()} - {a.id for a in ARTIFACTS} - {a.label for a in ARTIFACTS}
    )
    if unknown:
        known = ", ".join(a.id for a in ARTIFACTS)
        raise ParameterError("only", f"unknown artifact(s) {', '.join(unknown)}; known: {known}")
    selected = _select(only) or {a.id for a in ARTIFACTS}
    start = time.perf_counter()
    todo = [a for a in ARTIFACTS if a.id in selected]
    outcomes: dict[str, Outcome] = {}
    done = 0

    def overall(fraction: float) -> None:
        if progress is not None:
            progress((done + fraction) / max(1, len(todo)))

    ctx = BuildContext(out, quick=quick, dps=dps, progress=overall)
    for artifact in todo:
        outcome = _run(artifact, ctx)
        outcomes[artifact.id] = outcome
        done += 1
        overall(0.0)
        if log is not None:
            extra = outcome.reason if outcome.status != "covered" else ", ".join(outcome.built.files)
            log(
                f"{artifact.label}: {outcome.status} ({outcome.seconds:.1f} s){': ' + extra if extra else ''}"
            )
    for artifact in ARTIFACTS:
        if artifact.id not in outcomes:
            outcomes[artifact.id] = Outcome(artifact, "not built", reason="not selected in this run (--only)")
    report = Report(out, quick, [outcomes[a.id] for a in ARTIFACTS], time.perf_counter() - start)
    write_index(report)
    return report


def _select(only: Sequence[str] | None) -> set[str] | None:
    if not only:
        return None
    wanted = {x.strip() for x in only}
    return {a.id for a in ARTIFACTS if a.id in wanted or a.label in wanted}


def _run(artifact: Artifact, ctx: BuildContext) -> Outcome:
    if artifact.builder is None:
        return Outcome(artifact, "not covered", reason=artifact.reason)
    ctx.progress(0.0)
    start = time.perf_counter()
    try:
        built = artifact.builder(ctx)
    except NotCovered as exc:
        return Outcome(artifact, "not covered", reason=str(exc), seconds=time.perf_counter() - start)
    except Exception as exc:  # a bug or a numerical failure: record it, keep building the others
        rel = f"errors/{artifact.id}.txt"
        path = ctx.out / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(traceback.format_exc(), encoding="utf-8")
        return Outcome(
            artifact,
            "failed",
            Built(files=[rel]),
            reason=f"{type(exc).__name__}: {exc}",
            seconds=time.perf_counter() - start,
        )
    return Outcome(artifact, "covered", built, seconds=time.perf_counter() - start)


# --------------------------------------------------------------------------------------------------------
# Index pages
# --------------------------------------------------------------------------------------------------------

_TEX = [
    (r"\\tilde\{(\w)\}", lambda m: m.group(1) + "\u0303"),
    (r"\\eta", lambda m: "η"),
    (r"\\kappa", lambda m: "κ"),
    (r"\\alpha", lambda m: "α"),
    (r"_(\w)", lambda m: f"<sub>{m.group(1)}</sub>"),
]


def caption_html(text: str) -> str:
    """The caption text with its bold markers and inline TeX rendered as plain HTML (no JavaScript)."""
    parts = re.split(r"(\$[^$]*\$)", text)
    out = []
    for part in parts:
        if part.startswith("$") and part.endswith("$") and len(part) > 1:
            tex = html.escape(part[1:-1].strip())
            for pattern, repl in _TEX:
                tex = re.sub(pattern, repl, tex)
            out.append(f"<i>{tex}</i>")
        else:
            out.append(re.sub(r"\*\*(.+?)\*\*", r"<strong>\1</strong>", html.escape(part)))
    return "".join(out)


_CSS = """
body { font-family: system-ui, sans-serif; max-width: 1000px; margin: 2em auto; padding: 0 1em; color: #222; }
section { border-top: 1px solid #ccc; padding: 1em 0; }
.caption { background: #f6f6f2; padding: .6em .8em; border-left: 4px solid #999; }
.status { font-size: .85em; padding: .1em .5em; border-radius: 3px; }
.covered { background: #d9f2d9; } .notcovered { background: #eee; } .failed { background: #f8d0d0; }
.notbuilt { background: #f2f2d9; }
table.data { border-collapse: collapse; font-size: .85em; margin: .8em 0; }
table.data td, table.data th { border: 1px solid #ccc; padding: .2em .5em; text-align: right; }
table.data tr.unstable td { color: #b00; }
td.digits { font-family: monospace; font-size: .8em; text-align: left; }
img { max-width: 100%; }
ul.notes { font-size: .85em; color: #444; }
table.toc td { padding: .1em .6em; }
"""


def write_index(report: Report) -> None:
    """Write ``index.html`` and ``index.md`` for `report` into its output folder."""
    (report.out / "index.html").write_text(_index_html(report), encoding="utf-8")
    (report.out / "index.md").write_text(_index_md(report), encoding="utf-8")


def _header_facts(report: Report) -> tuple[str, str]:
    from moving_bogie import __version__

    mode = "quick (reduced grids and time windows)" if report.quick else "full"
    when = datetime.datetime.now(datetime.UTC).strftime("%Y-%m-%d %H:%M UTC")
    summary = (
        f"{report.count('covered')} covered, {report.count('not covered')} not covered, "
        f"{report.count('failed')} failed"
        + (f", {report.count('not built')} not built in this run" if report.count("not built") else "")
    )
    facts = f"moving-bogie {__version__}, mode: {mode}, {when}, {report.seconds:.0f} s"
    return facts, summary


def _index_html(report: Report) -> str:
    facts, summary = _header_facts(report)
    toc = []
    sections = []
    for o in report.outcomes:
        a = o.artifact
        cls = o.status.replace(" ", "")
        toc.append(
            f'<tr><td><a href="#{a.id}">{a.label}</a></td>'
            f'<td><span class="status {cls}">{o.status}</span></td>'
            f"<td>{html.escape(o.reason if o.status != 'covered' else '')}</td></tr>"
        )
        printed = (
            f" <small>(printed as “{html.escape(a.caption.printed_label)}.”)</small>"
            if a.caption.printed_label
            else ""
        )
        body = [
            f'<section id="{a.id}">',
            f'<h2>{a.label} <span class="status {cls}">{o.status}</span></h2>',
            f'<p class="caption"><strong>{a.label}.</strong>{printed} {caption_html(a.caption.text)}</p>',
        ]
        if o.status == "covered":
            for rel in o.built.files:
                if rel.endswith(".png"):
                    body.append(f'<p><img src="{html.escape(rel)}" alt="{a.label}"></p>')
            if o.built.html:
                body.append(o.built.html)
            others = [rel for rel in o.built.files if not rel.endswith(".png")]
            if others:
                links = ", ".join(f'<a href="{html.escape(r)}">{html.escape(r)}</a>' for r in others)
                body.append(f"<p>Files: {links}</p>")
        elif o.status == "failed":
            link = f' (<a href="{html.escape(o.built.files[0])}">traceback</a>)' if o.built.files else ""
            body.append(f"<p><strong>Failed:</strong> {html.escape(o.reason)}{link}</p>")
        else:
            body.append(f"<p><strong>{o.status.capitalize()}:</strong> {html.escape(o.reason)}</p>")
        notes = list(o.built.notes)
        if o.seconds:
            notes.append(f"Built in {o.seconds:.1f} s.")
        if notes:
            body.append('<ul class="notes">' + "".join(f"<li>{html.escape(n)}</li>" for n in notes) + "</ul>")
        body.append("</section>")
        sections.append("\n".join(body))
    return (
        '<!DOCTYPE html>\n<html lang="en">\n<head>\n<meta charset="utf-8">\n'
        "<title>moving-bogie: the paper's tables and figures, rebuilt</title>\n"
        f"<style>{_CSS}</style>\n</head>\n<body>\n"
        "<h1>The paper's tables and figures, rebuilt</h1>\n"
        "<p>Z. Dimitrovová, <em>Instability of a Moving Bogie: Analysis of Vibrations and Possibility of "
        "Instability in Subcritical Velocity Range</em>, preprint doi 10.20944/preprints202501.1517.v1 "
        "(2025). "
        "Each artifact is shown under the paper's caption, quoted verbatim.</p>\n"
        f"<p>{html.escape(facts)}.<br><strong>{html.escape(summary)}.</strong></p>\n"
        f'<table class="toc">\n{"".join(toc)}\n</table>\n' + "\n".join(sections) + "\n</body>\n</html>\n"
    )


def _index_md(report: Report) -> str:
    facts, summary = _header_facts(report)
    lines = [
        "# The paper's tables and figures, rebuilt",
        "",
        "Z. Dimitrovová, *Instability of a Moving Bogie: Analysis of Vibrations and Possibility of "
        "Instability in Subcritical Velocity Range*, preprint doi 10.20944/preprints202501.1517.v1 (2025). "
        "Each artifact is "
        "shown under the paper's caption, quoted verbatim.",
        "",
        f"{facts}. **{summary}.**",
        "",
        "| artifact | status | reason |",
        "|---|---|---|",
    ]
    for o in report.outcomes:
        reason = o.reason.replace("|", "\\|") if o.status != "covered" else ""
        lines.append(f"| [{o.artifact.label}](#{o.artifact.id}) | {o.status} | {reason} |")
    for o in report.outcomes:
        a = o.artifact
        printed = f' (printed as "{a.caption.printed_label}.")' if a.caption.printed_label else ""
        lines += [
            "",
            f'<a id="{a.id}"></a>',
            "",
            f"## {a.label} — {o.status}",
            "",
            f"> **{a.label}.**{printed} {a.caption.text}",
            "",
        ]
        if o.status == "covered":
            for rel in o.built.files:
                if rel.endswith(".png"):
                    lines += [f"![{a.label}]({rel})", ""]
            if o.built.markdown:
                lines += [o.built.markdown, ""]
            others = [rel for rel in o.built.files if not rel.endswith(".png")]
            if others:
                lines += ["Files: " + ", ".join(f"[{r}]({r})" for r in others), ""]
        elif o.status == "failed":
            lines += [
                f"**Failed:** {o.reason}" + (f" ([traceback]({o.built.files[0]}))" if o.built.files else ""),
                "",
            ]
        else:
            lines += [f"**{o.status.capitalize()}:** {o.reason}", ""]
        notes = list(o.built.notes) + ([f"Built in {o.seconds:.1f} s."] if o.seconds else [])
        lines += [f"- {n}" for n in notes]
    return "\n".join(lines).rstrip() + "\n"
