"""The results of the instability lines (Figures 3, 4, 7, 8): one branch, and all lines of a parameter set.

Shared by :mod:`~moving_bogie.stability.lines.instability_lines` (the real induced frequencies traced on a
damped
foundation) and :mod:`~moving_bogie.stability.lines.undamped_lines` (boundaries located by root counts when
eta_f = 0 or nearly so), so that neither imports the other.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from moving_bogie.stability.maps.undamped import regime, statement

if TYPE_CHECKING:
    from moving_bogie.model.params import DimensionlessParams

__all__ = ["InstabilityBranch", "InstabilityLines"]


@dataclass(frozen=True)
class InstabilityBranch:
    """One connected piece of an instability line.

    Attributes
    ----------
    d : float
        Wheel spacing.
    alpha, theta, q : ndarray
        Points of the line: velocity, parameter value (eta_M unless stated), and the real induced
        frequency there.
    unstable_above : ndarray of bool
        At each point, True if increasing theta at fixed alpha makes the real root unstable.
    residual : ndarray
        |E_chr / E_chr'| at each point: distance in q to the exact real root (double precision).
    kind : str
        "crossing" (a real induced frequency, eta_f > 0); on an undamped foundation "undamped" or "limit"
        (boundaries located by counts, :mod:`undamped_lines`: ``q`` and ``residual`` are nan, ``verified``
        holds the counts at the ends of the middle point's bisection bracket, ``mechanism`` what changes
        at each point).
    """

    d: float
    alpha: np.ndarray
    theta: np.ndarray
    q: np.ndarray
    unstable_above: np.ndarray
    residual: np.ndarray
    verified: tuple | None = None  # (alpha, eta below, count, eta above, count) by induced_frequencies
    ends: tuple = ()  # (start, end) LineEnd: why the line stops at each end
    folds: tuple = ()  # LineEnd("fold") at every tip where the line turns back
    kind: str = "crossing"
    mechanism: tuple = ()  # undamped kinds: per point, a key of undamped.MECHANISMS

    @property
    def stops_inside(self) -> tuple:
        """The ends and folds that lie inside the plotted range (marked in the figures)."""
        return tuple(e for e in (*self.ends, *self.folds) if e.inside)

    @property
    def unstable_side(self) -> str:
        """ "above" (larger theta) or "below" at fixed alpha along the whole branch, else "mixed"."""
        if np.all(self.unstable_above):
            return "above"
        if not np.any(self.unstable_above):
            return "below"
        return "mixed"

    def to_dict(self, parameter: str) -> dict:
        """JSON-ready; ``parameter`` names the vertical axis (the lines' ``parameter``)."""
        return {
            "d": self.d,
            "kind": self.kind,
            "unstable_side": self.unstable_side,
            "verified": None
            if self.verified is None
            else dict(
                zip(("alpha", "theta_below", "count_below", "theta_above", "count_above"), self.verified)
            ),
            "ends": [e.to_dict(parameter) for e in self.ends],
            "folds": [e.to_dict(parameter) for e in self.folds],
            "points": [
                {
                    "alpha": float(a),
                    parameter: float(t),
                    "q": float(q) if np.isfinite(q) else None,
                    "unstable_above": bool(u),
                    **({"mechanism": m} if m else {}),
                }
                for a, t, q, u, m in zip(
                    self.alpha, self.theta, self.q, self.unstable_above, self.mechanism or [""] * len(self.q)
                )
            ],
        }


@dataclass(frozen=True)
class InstabilityLines:
    """All instability lines of one parameter set (for one or several wheel spacings)."""

    params: DimensionlessParams
    model: str
    parameter: str
    alpha_range: tuple
    theta_max: float
    branches: tuple
    warnings: tuple = field(default=())
    q_max: float | None = None  # the searched range of real q actually used (raised automatically)
    method: str = "real induced frequencies traced by continuation"

    @property
    def regime(self) -> str:
        """ "damped", "undamped" (eta_f = 0) or "near-undamped" (:func:`~.undamped.regime`)."""
        return regime(self.params.eta_f)

    @property
    def statement(self) -> str:
        """What the lines are, in one sentence (empty for the ordinary lines of a damped foundation)."""
        return statement(self.params.eta_f)

    def for_spacing(self, d: float) -> tuple:
        return tuple(b for b in self.branches if abs(b.d - d) < 1e-12)

    def to_dict(self) -> dict:
        return {
            "params": self.params.to_dict(),
            "model": self.model,
            "parameter": self.parameter,
            "alpha_range": list(self.alpha_range),
            f"{self.parameter}_max": self.theta_max,  # as the option (--eta-M-max); theta_max before
            "q_max": self.q_max,
            "regime": self.regime,
            "method": self.method,
            "statement": self.statement,
            "branches": [b.to_dict(self.parameter) for b in self.branches],
            "warnings": list(self.warnings),
        }
