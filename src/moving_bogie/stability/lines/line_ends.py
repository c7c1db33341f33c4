"""Why an instability line ends where it does (Section 3.5; Figures 3, 4, 7, 8).

An instability line is the projection on the (alpha, theta) plane of a curve E_chr(q; alpha, theta) = 0 with
q real. A line drawn in a figure can stop in three kinds of places:

- **the plot's edge** (``alpha_min``, ``alpha_max``, ``theta_zero``, ``theta_max``): the curve goes on
  outside the plotted range;
- **inside the plot**, for a reason recorded by the continuation
  (:mod:`~moving_bogie.stability.lines.continuation`): ``q_max`` (the real root leaves the searched range of
  q;
  :func:`~moving_bogie.stability.lines.instability_lines.instability_lines` then raises q_max automatically,
  so
  this stays only when the cap was reached), ``q_zero`` (the root reaches q = 0), ``cut`` (the continuation
  stalls where a p-root of N is real: the cut of K), ``stalled`` (any other singular point: two lines cross
  or the root is double), ``max_steps``;
- **a fold** (a tip): the line turns back sharply at an extreme value of alpha or theta. At a tip where
  theta is largest, say, the induced frequency followed over alpha at fixed theta only *touches* the real
  q-axis (Im dq/dalpha = 0): just below the tip it crosses the axis twice, just above not at all, so no
  line goes on. Figure 3(e)'s d = 2 line has such a tip at alpha ~ 1.07, eta_M ~ 110.

For the Euler-Bernoulli beam with eta_f > 0 a real q never meets the cut of K (it lies on Im q = eta_f), so
``cut`` is there for models whose cut comes down to the real axis.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from moving_bogie.typing import FloatArray

__all__ = ["EXPLANATIONS", "PLOT_EDGES", "LineEnd", "find_folds", "line_end"]

#: End reasons that are the edge of the plotted range (the line continues outside).
PLOT_EDGES = frozenset({"alpha_min", "alpha_max", "theta_zero", "theta_max", "closed"})

#: One sentence per reason, for the JSON output, the figures and the docs.
EXPLANATIONS = {
    "alpha_min": "leaves the plotted velocity range",
    "alpha_max": "leaves the plotted velocity range",
    "theta_zero": "reaches theta = 0",
    "theta_max": "leaves the plotted parameter range",
    "closed": "closed line",
    "q_max": "the real induced frequency leaves the searched range q <= q_max",
    "q_zero": "the real induced frequency reaches q = 0",
    "stalled": "singular point: two lines cross or the real root is double",
    "cut": "the real root meets the cut of K (a root p of N(p, q) is real there)",
    "max_steps": "continuation stopped after its maximum number of steps",
    "fold": "tip: the line turns back; there the induced frequency only touches the real axis",
}


@dataclass(frozen=True)
class LineEnd:
    """A place where an instability line stops: its reason (a key of :data:`EXPLANATIONS`) and the point."""

    reason: str
    alpha: float
    theta: float
    q: float

    @property
    def inside(self) -> bool:
        """True when the line stops inside the plotted range (it is marked in the figures)."""
        return self.reason not in PLOT_EDGES

    def to_dict(self, parameter: str) -> dict:
        """JSON-ready; ``parameter`` names the vertical axis (the lines' ``parameter``)."""
        return {
            "reason": self.reason,
            "explanation": EXPLANATIONS[self.reason],
            "inside": self.inside,
            "alpha": float(self.alpha),
            parameter: float(self.theta),
            "q": float(self.q),
        }


def line_end(reason: str, alpha: float, theta: float, q: float) -> LineEnd:
    """A :class:`LineEnd` at the point (alpha, theta, q)."""
    return LineEnd(reason, float(alpha), float(theta), float(q))


def find_folds(
    alpha: FloatArray,
    theta: FloatArray,
    q: FloatArray,
    alpha_span: float,
    theta_max: float,
    *,
    reach: float = 0.02,
) -> tuple[LineEnd, ...]:
    """Tips where the line turns back in the (alpha, theta) plane.

    In the plot's scaled coordinates (alpha / alpha_span, theta / theta_max), every local extremum of alpha
    or theta along the line is compared with the points an arclength ``reach`` before and after it: where
    the two directions point back against each other (an angle above 120 degrees) the line has a tip there.
    Extrema closer than ``reach`` to each other are one tip.
    """
    P = np.stack([np.asarray(alpha) / alpha_span, np.asarray(theta) / theta_max], axis=-1)
    if len(P) < 3:
        return ()
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(P, axis=0), axis=-1))])
    extrema: set[int] = set()
    for coordinate in P.T:
        step = np.diff(coordinate)
        extrema |= set((np.nonzero(step[:-1] * step[1:] < 0)[0] + 1).tolist())
    folds: list[LineEnd] = []
    last = -np.inf

    for k in sorted(extrema):
        i = np.searchsorted(s, s[k] - reach, side="right") - 1
        j = np.searchsorted(s, s[k] + reach)
        if i < 0 or j >= len(P) or s[k] - last < reach:
            continue
        u, v = P[k] - P[i], P[j] - P[k]
        c = np.dot(u, v) / (np.linalg.norm(u) * np.linalg.norm(v) + 1e-300)
        if c < -0.5:
            folds.append(line_end("fold", alpha[k], theta[k], q[k]))
            last = s[k]
    return tuple(folds)
