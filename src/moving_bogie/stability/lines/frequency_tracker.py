"""Continuation of induced frequencies q(alpha) over the velocity, several lines in lockstep (Figure 2).

Each line is a root of E_chr(q; alpha) = 0 (Eq. (48)) followed from a start (alpha, q) towards an end
alpha by predictor-corrector continuation in double precision: an Euler predictor dq/dalpha =
-E_alpha / E_q, Newton's method at fixed alpha as corrector, and step control (the step grows by 1.5 after
a success, halves after a failure). A line ends "reached" at its end alpha, "cut" where a root of N(p, q)
crosses the real p-axis (the number of p-roots with Im p > 0 changes: the root meets the cut of K; that
end is located by bisection in alpha), or "lost" when the step falls below ``h_min`` away from the cut.

:meth:`FrequencyTracker.follow_many` advances every line one step per round, and each stage of a round
(the slopes, every Newton iteration, the side of the cut) is one evaluation of E_chr for all the lines
that are in it. The evaluations are elementwise, so each line takes the very steps it takes when it is
followed alone (:meth:`FrequencyTracker.follow`, the same function on one line).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from moving_bogie.kernels.sweep_characteristic import SweepCharacteristic

__all__ = ["FrequencyTracker"]

#: A followed line: (the alphas, the q's, without the start point; how it ended).
_Followed = tuple[list[float], list[complex], str]


@dataclass
class _Line:
    """The state of one line being followed."""

    a: float
    q: complex
    a_end: float
    direction: float
    side: int
    h: float
    out_a: list[float] = field(default_factory=list)
    out_q: list[complex] = field(default_factory=list)
    how: str | None = None

    def open(self) -> bool:
        return self.how is None and self.direction * (self.a_end - self.a) > 1e-14


class FrequencyTracker:
    """Continuation of roots q(alpha) of E_chr in double precision (module docstring)."""

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

    def _sides(self, q: np.ndarray, a: np.ndarray) -> np.ndarray:
        return self.sweep.upper_root_count(q, a).astype(int)

    def _near_cut(self, q: complex, a: float, tol: float = 1e-5) -> bool:
        """Some p-root of N(p, q) is (nearly) real: q is at the cut of K."""
        P = self.sweep.p_roots(np.array([q]), np.array([a]))[0]
        return bool(np.min(np.abs(P.imag) / np.maximum(1.0, np.abs(P))) < tol)

    def _correct(self, q: np.ndarray, a: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Newton at fixed alpha for every start at once; returns (q, converged), each entry as if alone."""
        q = np.array(q, dtype=complex)
        converged = np.zeros(q.shape, dtype=bool)
        going = np.ones(q.shape, dtype=bool)
        for _ in range(self.max_iter):
            k = np.flatnonzero(going)
            if not k.size:
                break
            E, E_q = self.sweep.e_and_dq(q[k], a[k])
            with np.errstate(all="ignore"):
                step = E / E_q
            finite = np.isfinite(step)
            going[k[~finite]] = False  # a non-finite step: not converged, q as it was
            k, step = k[finite], step[finite]
            q[k] -= step
            done = np.abs(step) < self.tol * np.maximum(1.0, np.abs(q[k]))
            converged[k[done]] = True
            going[k[done]] = False
        # a converged root on the left half-plane is reported as its mirror -conj(q) (one of each pair)
        fold = converged & (q.real < 0)
        q[fold] = -np.conj(q[fold])
        return q, converged

    def _slopes(self, q: np.ndarray, a: np.ndarray) -> np.ndarray:
        E, E_q, E_a, _ = self.sweep.derivatives(q, a, None)
        return -E_a / E_q

    def follow(self, a: float, q: complex, a_end: float) -> _Followed:
        """Follow the root q at alpha=a towards a_end; returns (alphas, qs, how) without the start point.

        ``how`` is "reached", "cut" (the root meets the cut of K) or "lost"."""
        return self.follow_many([(a, q, a_end)])[0]

    def follow_many(self, starts: list[tuple[float, complex, float]]) -> list[_Followed]:
        """:meth:`follow` for every (a, q, a_end) of ``starts``, all lines advanced together (module
        docstring)."""
        if not starts:
            return []
        sides = self._sides(np.array([q for _, q, _ in starts]), np.array([a for a, _, _ in starts]))
        lines = [
            _Line(a, q, a_end, 1.0 if a_end >= a else -1.0, int(side), 0.25 * self.h_max)
            for (a, q, a_end), side in zip(starts, sides)
        ]
        while True:
            live = [line for line in lines if line.open()]
            if not live:
                break
            self._advance(live)
        return [(line.out_a, line.out_q, line.how or "reached") for line in lines]

    def _advance(self, live: list[_Line]) -> None:
        """One predictor-corrector step of every live line (each with its own step size)."""
        a = np.array([line.a for line in live])
        q = np.array([line.q for line in live], dtype=complex)
        step = np.array([min(line.h, line.direction * (line.a_end - line.a)) for line in live])
        a_new = a + np.array([line.direction for line in live]) * step
        slope = self._slopes(q, a)
        guess = q + slope * (a_new - a)
        q_new, ok = self._correct(guess, a_new)
        ok &= np.abs(q_new - guess) < 0.05 * np.maximum(np.abs(slope) * step, 1e-3)
        side_new = np.zeros(len(live), dtype=int)
        if np.any(ok):
            side_new[ok] = self._sides(q_new[ok], a_new[ok])
        for k, line in enumerate(live):
            if ok[k] and side_new[k] != line.side:
                a_cut, q_cut = self._bisect_cut(line.a, line.q, float(a_new[k]), line.side)
                if a_cut != line.a:
                    line.out_a.append(a_cut)
                    line.out_q.append(q_cut)
                line.how = "cut"
            elif not ok[k]:
                line.h *= 0.5
                if line.h < self.h_min:
                    # Newton stalls where K has its square-root behaviour: at the cut itself
                    line.how = "cut" if self._near_cut(line.q, line.a) else "lost"
            else:
                line.a, line.q = float(a_new[k]), complex(q_new[k])
                line.out_a.append(line.a)
                line.out_q.append(line.q)
                line.h = min(1.5 * line.h, self.h_max)

    def _bisect_cut(
        self, a_good: float, q_good: complex, a_bad: float, side: int, tol: float = 1e-9
    ) -> tuple[float, complex]:
        """Last point on the starting side of the cut, to ``tol`` in alpha."""
        while abs(a_bad - a_good) > tol:
            a_mid = 0.5 * (a_good + a_bad)
            one_a, one_q = np.array([a_good]), np.array([q_good])
            guess = q_good + complex(self._slopes(one_q, one_a)[0]) * (a_mid - a_good)
            q_mid, ok = self._correct(np.array([guess]), np.array([a_mid]))
            if ok[0] and self._sides(q_mid, np.array([a_mid]))[0] == side:
                a_good, q_good = a_mid, complex(q_mid[0])
            else:
                a_bad = a_mid
        return a_good, q_good
