"""Frequency lines (Figure 2): the induced frequencies followed over the velocity alpha.

Each induced frequency q(alpha) (one member of each pair q, -conj(q)) is a root of E_chr(q; alpha) = 0,
Eq. (48). Starting points come from :func:`~moving_bogie.roots.frequencies.induced_frequencies` (argument
principle, no guesses) at checkpoints spread over the range; between checkpoints every root is followed
by predictor-corrector continuation in double precision (Euler predictor dq/dalpha = -E_alpha / E_q,
Newton corrector at fixed alpha, step control). At the next checkpoint the continued roots are matched
with the freshly found ones: a found root that no line reaches is a line that appeared in between, and
is followed backwards to where it appeared; a line that reaches a checkpoint without a partner is
reported.

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
    tracker = _Tracker(SweepCharacteristic(bound), h_max)
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
    tracker: _Tracker,
    active: list[_OpenLine],
    found: list[complex],
    a_from: float,
    a_to: float,
    match_tol: float,
    warnings: list[str],
    finished: list[_OpenLine],
) -> tuple[list[_OpenLine], int]:
    """Continue the active lines from ``a_from`` to the next checkpoint ``a_to`` and match them with the roots
    ``found`` there; a root found there that no line reaches is a line that appeared in between, followed
    backwards. Lines that end on the way go to ``finished``. Returns the lines still active, the matches."""
    still = []
    for line in active:
        pa, pq, how = tracker.follow(line.alpha[-1], line.q[-1], a_to)
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
    for t in targets:  # a line that appeared between the checkpoints: follow it backwards
        pa, pq, how = tracker.follow(a_to, t, a_from)
        if how == "reached":
            warnings.append(f"alpha={a_from:g}: root continued back from {t:.8g} was not found there")
        start = "cut" if how == "cut" else ("range" if how == "reached" else "lost")
        still.append(_OpenLine(pa[::-1] + [a_to], pq[::-1] + [t], start))
    return still, matched


class _Tracker:
    """Continuation of one root q(alpha) of E_chr in double precision."""

    def __init__(
        self,
        sweep: SweepCharacteristic,
        h_max: float,
        *,
        h_min: float = 1e-9,
        tol: float = 1e-12,
        max_iter: int = 8,
    ) -> None:
        self.sweep, self.h_max, self.h_min, self.tol, self.max_iter = sweep, h_max, h_min, tol, max_iter

    def _side(self, q: complex, a: float) -> int:
        return int(self.sweep.upper_root_count(np.array([q]), np.array([a]))[0])

    def _near_cut(self, q: complex, a: float, tol: float = 1e-5) -> bool:
        """Some p-root of N(p, q) is (nearly) real: q is at the cut of K."""
        P = self.sweep.p_roots(np.array([q]), np.array([a]))[0]
        return bool(np.min(np.abs(P.imag) / np.maximum(1.0, np.abs(P))) < tol)

    def _correct(self, q: complex, a: float) -> tuple[complex, bool]:
        """Newton at fixed alpha; returns (q, converged)."""
        for _ in range(self.max_iter):
            E, E_q = self.sweep.e_and_dq(np.array([q]), np.array([a]))
            step = complex(E[0] / E_q[0])
            if not np.isfinite(step):
                return q, False
            q -= step
            if abs(step) < self.tol * max(1.0, abs(q)):
                return (complex(-q.conjugate()) if q.real < 0 else q), True
        return q, False

    def _slope(self, q: complex, a: float) -> complex:
        E, E_q, E_a, _ = self.sweep.derivatives(np.array([q]), np.array([a]), None)
        return complex(-E_a[0] / E_q[0])

    def follow(self, a: float, q: complex, a_end: float) -> tuple[list[float], list[complex], str]:
        """Follow the root q at alpha=a towards a_end; returns (alphas, qs, how) without the start point.

        ``how`` is "reached", "cut" (the root meets the cut of K) or "lost".
        """
        direction = 1.0 if a_end >= a else -1.0
        side = self._side(q, a)
        h = 0.25 * self.h_max
        out_a: list[float] = []
        out_q: list[complex] = []
        while direction * (a_end - a) > 1e-14:
            step = min(h, direction * (a_end - a))
            a_new = a + direction * step
            slope = self._slope(q, a)
            guess = q + slope * (a_new - a)
            q_new, ok = self._correct(guess, a_new)
            ok = ok and abs(q_new - guess) < 0.05 * max(abs(slope) * step, 1e-3)
            if ok and self._side(q_new, a_new) != side:
                a_cut, q_cut = self._bisect_cut(a, q, a_new, side)
                if a_cut != a:
                    out_a.append(a_cut)
                    out_q.append(q_cut)
                return out_a, out_q, "cut"
            if not ok:
                h *= 0.5
                if h < self.h_min:
                    # Newton stalls where K has its square-root behaviour: at the cut itself
                    return out_a, out_q, ("cut" if self._near_cut(q, a) else "lost")
                continue
            a, q = a_new, q_new
            out_a.append(a)
            out_q.append(q)
            h = min(1.5 * h, self.h_max)
        return out_a, out_q, "reached"

    def _bisect_cut(
        self, a_good: float, q_good: complex, a_bad: float, side: int, tol: float = 1e-9
    ) -> tuple[float, complex]:
        """Last point on the starting side of the cut, to ``tol`` in alpha."""
        while abs(a_bad - a_good) > tol:
            a_mid = 0.5 * (a_good + a_bad)
            guess = q_good + self._slope(q_good, a_good) * (a_mid - a_good)
            q_mid, ok = self._correct(guess, a_mid)
            if ok and self._side(q_mid, a_mid) == side:
                a_good, q_good = a_mid, q_mid
            else:
                a_bad = a_mid
        return a_good, q_good
