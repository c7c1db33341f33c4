"""Rebuild the paper's tables and figures into one folder, each shown next to its caption.

``moving-bogie reproduce --out DIR [--quick]`` runs the recipe of every artefact of
:data:`~moving_bogie.paper.registry.ARTIFACTS` and writes ``DIR/index.html`` and ``DIR/index.md``
(:mod:`moving_bogie.paper.index_page`): per artefact the paper's caption (verbatim, from
:mod:`moving_bogie.paper.captions`), then the rebuilt figure or table, or the reason it is not computed.

Design
------
* Each artefact declares its recipe in the registry (:mod:`moving_bogie.paper.registry`); a recipe
  imports what it uses directly, so a missing module or function is a failure, never a silent gap.
* A recipe that raises is **failed**: its traceback goes to ``DIR/errors/ID.txt``, the index says so,
  and the command exits 1. Table 2 differing from the print, or a finite-beam validation disagreeing,
  also exits 1.
* Quick mode (``--quick``, or ``MOVING_BOGIE_QUICK=1``) uses reduced grids and short time windows
  (closed-form series only) so that the whole run takes well under two minutes; the index names every
  reduction next to the artefact it affects.
* Results shared between artefacts (the induced frequencies of each case) are computed once
  (:class:`~moving_bogie.paper.recipe.BuildContext`).
"""

from __future__ import annotations

import os
import time
import traceback
from collections.abc import Callable, Sequence
from pathlib import Path

from moving_bogie.errors import ParameterError
from moving_bogie.paper.index_page import write_index
from moving_bogie.paper.recipe import BuildContext, Built
from moving_bogie.paper.registry import ARTIFACTS, Artifact, select
from moving_bogie.paper.report import Outcome, Report

__all__ = ["QUICK_ENV", "build_artifact", "quick_from_env", "reproduce"]

#: Environment variable that switches notebooks and :func:`reproduce` to reduced grids ("1", "true", "yes").
QUICK_ENV = "MOVING_BOGIE_QUICK"


def quick_from_env(default: bool = False) -> bool:
    """True when :data:`QUICK_ENV` is set to 1/true/yes (False for 0/false/no; `default` when unset)."""
    value = os.environ.get(QUICK_ENV)
    if value is None or not value.strip():
        return default
    return value.strip().lower() in ("1", "true", "yes", "on")


def reproduce(
    out: str | os.PathLike[str],
    *,
    quick: bool = False,
    only: Sequence[str] | None = None,
    dps: int | None = None,
    progress: Callable[[float], None] | None = None,
    log: Callable[[str], None] | None = None,
    artifact_progress: Callable[[str, float], None] | None = None,
) -> Report:
    """Rebuild the artefacts into `out` and write ``index.html`` and ``index.md``.

    Parameters
    ----------
    out : path
        Output folder (created). Existing files of the same names are replaced.
    quick : bool
        Reduced grids, short time windows, no finite-beam runs (a couple of minutes in all).
    only : sequence of str, optional
        Artefact ids (``"table2"``, ``"figure5"``, ``"figureA3"``) or labels (``"Figure 5"``) to build;
        the others are listed as "not built in this run". The time series reuse the roots of Table 2
        when it is built in the same run (it comes first), and compute them otherwise.
    dps : int, optional
        Working precision of the induced frequencies (default 30, quick 20).
    progress : callable, optional
        Called with the overall fraction done.
    log : callable, optional
        Called with one line per finished artefact.
    artifact_progress : callable, optional
        Called as ``artifact_progress(label, fraction)`` with the fraction done of the artefact being
        built (a long recipe, Figure 16 takes minutes, moves it while the overall fraction barely moves).

    Returns
    -------
    Report

    Raises
    ------
    ParameterError
        When `only` names an unknown artefact (before anything is built).
    """
    todo = _selected(only)
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    dps = dps if dps is not None else (20 if quick else 30)
    start = time.perf_counter()
    outcomes: dict[str, Outcome] = {}
    tracker = _Progress(len(todo), progress, artifact_progress)
    ctx = BuildContext(out, quick=quick, dps=dps, progress=tracker.overall)
    for artifact in todo:
        tracker.current = artifact.label
        outcome = build_artifact(artifact, ctx)
        outcomes[artifact.id] = outcome
        tracker.finished()
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


def _selected(only: Sequence[str] | None) -> list[Artifact]:
    """The artefacts to build: those `only` names, every one without it (an unknown name is an error)."""
    if not only:
        return list(ARTIFACTS)
    todo, unknown = select(only)
    if unknown:
        known = ", ".join(a.id for a in ARTIFACTS)
        raise ParameterError("only", f"unknown artifact(s) {', '.join(unknown)}; known: {known}")
    return todo


class _Progress:
    """The overall fraction done (artefacts finished plus the fraction of the one being built) and the
    fraction of the current artefact, each to its callback."""

    def __init__(
        self,
        total: int,
        progress: Callable[[float], None] | None,
        artifact_progress: Callable[[str, float], None] | None,
    ) -> None:
        self.total, self.progress, self.artifact_progress = total, progress, artifact_progress
        self.done = 0
        self.current = ""

    def overall(self, fraction: float) -> None:
        if self.progress is not None:
            self.progress((self.done + fraction) / max(1, self.total))
        if self.artifact_progress is not None and self.current:
            self.artifact_progress(self.current, fraction)

    def finished(self) -> None:
        self.done += 1
        self.current = ""
        self.overall(0.0)


def build_artifact(artifact: Artifact, ctx: BuildContext) -> Outcome:
    """Run the recipe of `artifact`; an exception makes it "failed" with its traceback in ``errors/``."""
    if artifact.recipe is None:
        return Outcome(artifact, "not covered", reason=artifact.reason)
    ctx.progress(0.0)
    start = time.perf_counter()
    try:
        built = artifact.recipe(ctx)
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
