"""Frequency lines (Figure 2): the induced frequencies followed over the velocity alpha.

Each induced frequency q(alpha) (one member of each pair q, -conj(q)) is a root of E_chr(q; alpha) = 0,
Eq. (48). Starting points come from :func:`~moving_bogie.roots.frequencies.induced_frequencies` (argument
principle, no guesses) at checkpoints spread over the range; between checkpoints every root is followed
by predictor-corrector continuation in double precision (Euler predictor dq/dalpha = -E_alpha / E_q,
Newton corrector at fixed alpha, step control; every line of a stretch in the same evaluations,
:mod:`~moving_bogie.stability.lines.frequency_tracker`).
At the next checkpoint the continued roots are matched with the freshly found ones: a found root that no
line reaches is a line that appeared in between, and is followed backwards to where it appeared; a line
that reaches a checkpoint without a partner is reported.

A line ends where it meets the cut of K (Section 3.1, "their evolution is interrupted when their
imaginary part reaches eta_f"): there a root of N(p, q) crosses the real p-axis, which is detected as a
change of the number of p-roots with Im p > 0 (:meth:`SweepCharacteristic.upper_root_count`), and the end
is located by bisection in alpha.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from fractions import Fraction
from typing import TYPE_CHECKING

import numpy as np

from moving_bogie.kernels.bound import BoundModel
from moving_bogie.kernels.sweep_characteristic import SweepCharacteristic
from moving_bogie.roots.frequencies import induced_frequencies
from moving_bogie.stability.lines.frequency_tracker import FrequencyTracker

if TYPE_CHECKING:
    from moving_bogie.model.params import DimensionlessParams

__all__ = ["FrequencyLine", "FrequencyLines", "frequency_lines"]


@dataclass(frozen=True)
class FrequencyLine:
    """One induced frequency followed over alpha.

    ``start``/``end`` say how the line begins and ends: "range" (edge of the alpha range), "cut" (it
    meets the cut of K), "lost" (continuation failed; reported in the warnings).
    """

    alpha: np.ndarray
    q: np.ndarray
    start: str
    end: str

    def to_dict(self) -> dict:
        return {
            "start": self.start,
            "end": self.end,
            "points": [
                {"alpha": float(a), "re": float(z.real), "im": float(z.imag)}
                for a, z in zip(self.alpha, self.q)
            ],
        }


@dataclass(frozen=True)
class FrequencyLines:
    params: DimensionlessParams
    model: str
    alpha_range: tuple[float, float]
    lines: tuple[FrequencyLine, ...]
    checkpoints: tuple[tuple[float, int, int], ...]  # (alpha, number of roots found, number matched)
    warnings: tuple[str, ...] = field(default=())

    def to_dict(self) -> dict:
        return {
            "params": self.params.to_dict(),
            "model": self.model,
            "alpha_range": list(self.alpha_range),
            "lines": [line.to_dict() for line in self.lines],
            "checkpoints": [{"alpha": a, "found": n, "matched": m} for a, n, m in self.checkpoints],
            "warnings": list(self.warnings),
        }


@dataclass
class _OpenLine:
    """A line being followed: its points so far, how it began, and how it ended (None while it goes on)."""

    alpha: list[float]
    q: list[complex]
    start: str
    end: str | None = None


def frequency_lines(
    bound: BoundModel,
    *,
    alpha_range: tuple[float, float] = (0.0, 1.2),
    checkpoints: int = 13,
    h_max: float = 0.01,
    dps: int = 20,
    match_tol: float = 1e-6,
    progress: Callable[[float], None] | None = None,
) -> FrequencyLines:
    """Induced frequencies of the bound model as functions of alpha (Figure 2 for Case 1).

    Parameters
    ----------
    bound : BoundModel
        Everything except alpha (the vehicle: that of their model).
    alpha_range : (float, float)
    checkpoints : int
        Number of alphas (evenly spaced, ends included) where all roots are found afresh by
        :func:`induced_frequencies` and compared with the continued lines.
    h_max : float
        Largest continuation step in alpha.
    dps : int
        Working precision of :func:`induced_frequencies` at the checkpoints.
    match_tol : float
        A continued root and a found root match when closer than ``match_tol * max(1, |q|)``.
    progress : callable, optional
        Called with the fraction of work done.
    """
    params = bound.params
    a0, a1 = float(alpha_range[0]), float(alpha_range[1])
    tracker = FrequencyTracker(SweepCharacteristic(bound), h_max)
    alphas = np.round(np.linspace(a0, a1, max(2, checkpoints)), 12)
    warnings: list[str] = []
    found = _checkpoint_roots(bound, alphas, dps, warnings, progress)
    finished: list[_OpenLine] = []
    active = [_OpenLine([alphas[0]], [q], "range") for q in found[0]]
    record = [(float(alphas[0]), len(found[0]), len(found[0]))]
    for k in range(len(alphas) - 1):
        a_from, a_to = alphas[k], alphas[k + 1]
        active, matched = _continue_lines(
            tracker, active, found[k + 1], a_from, a_to, match_tol, warnings, finished
        )
        record.append((float(a_to), len(found[k + 1]), matched))
        if progress is not None:
            progress(0.7 + 0.3 * (k + 1) / (len(alphas) - 1))
    for line in active:
        line.end = "range"
        finished.append(line)
    lines = []
    for line in finished:
        assert line.end is not None  # every finished line has been given its end
        order = np.argsort(line.alpha, kind="stable")
        lines.append(
            FrequencyLine(
                np.asarray(line.alpha)[order],
                np.asarray(line.q, dtype=complex)[order],
                line.start,
                line.end,
            )
        )
    lines.sort(key=lambda ln: (ln.alpha[0], -ln.q[0].real))
    return FrequencyLines(params, params.vehicle, (a0, a1), tuple(lines), tuple(record), tuple(warnings))


def _checkpoint_roots(
    bound: BoundModel,
    alphas: np.ndarray,
    dps: int,
    warnings: list[str],
    progress: Callable[[float], None] | None,
) -> list[list[complex]]:
    """Every induced frequency at each checkpoint alpha, found afresh (:func:`induced_frequencies`)."""
    found: list[list[complex]] = []
    for k, a in enumerate(alphas):
        res = induced_frequencies(bound.replace(alpha=Fraction(str(float(a)))), dps=dps)
        if not res.count_ok:
            warnings.append(f"alpha={a:g}: induced_frequencies count check failed: {'; '.join(res.warnings)}")
        found.append([complex(r.q) for r in res.roots])
        if progress is not None:
            progress(0.7 * (k + 1) / len(alphas))
    return found


def _continue_lines(
    tracker: FrequencyTracker,
    active: list[_OpenLine],
    found: list[complex],
    a_from: float,
    a_to: float,
    match_tol: float,
    warnings: list[str],
    finished: list[_OpenLine],
) -> tuple[list[_OpenLine], int]:
    """Continue the active lines from ``a_from`` to the next checkpoint ``a_to`` (all together) and match them
    with the roots ``found`` there; a root found there that no line reaches is a line that appeared in
    between, followed backwards (those together too). Lines that end on the way go to ``finished``.
    Returns the lines still active, the matches."""
    still = []
    followed = tracker.follow_many([(line.alpha[-1], line.q[-1], a_to) for line in active])
    for line, (pa, pq, how) in zip(active, followed):
        line.alpha += pa
        line.q += pq
        if how == "reached":
            still.append(line)
        else:
            line.end = how
            finished.append(line)
            if how == "lost":
                warnings.append(f"a line was lost near alpha={line.alpha[-1]:.6g}, q={line.q[-1]:.6g}")
    targets = list(found)
    matched = 0
    for line in still:
        z = line.q[-1]
        dist = [abs(z - t) for t in targets]
        if dist and min(dist) < match_tol * max(1.0, abs(z)):
            j = int(np.argmin(dist))
            line.q[-1] = targets.pop(j)
            matched += 1
        else:
            warnings.append(f"alpha={a_to:g}: continued root {z:.8g} not among the roots found there")
    # the lines that appeared between the checkpoints: followed backwards
    for t, (pa, pq, how) in zip(targets, tracker.follow_many([(a_to, t, a_from) for t in targets])):
        if how == "reached":
            warnings.append(f"alpha={a_from:g}: root continued back from {t:.8g} was not found there")
        start = "cut" if how == "cut" else ("range" if how == "reached" else "lost")
        still.append(_OpenLine(pa[::-1] + [a_to], pq[::-1] + [t], start))
    return still, matched
