"""The right ray of a cut that is a straight half-line (:mod:`branch_cut`, its module text): the point
q(p) = alpha p + i c + sqrt(R(p))/2 of the real root p of N(., q), Re q = s(p) convex with its minimum q_c
at p_c, and the inverse p(s) on p > p_c."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from moving_bogie.kernels.brent import brentq

__all__ = ["RightRay"]


class RightRay:
    """The geometry of the right ray, for :class:`~moving_bogie.response.branch_cut.BranchCut`, which sets
    ``alpha``, ``eta_f`` (c), ``p_c`` and the radicand R (``_radicand``) and R'/4 (``_radicand_dp``)."""

    alpha: float
    eta_f: float
    p_c: float
    _radicand: np.ndarray
    _radicand_dp: np.ndarray

    def _R(self, p: np.ndarray | float) -> np.ndarray:
        return np.sqrt(np.polyval(self._radicand, p))

    def s(self, p: np.ndarray | float) -> np.ndarray:
        """Re q of the cut point of the real root p (right ray)."""
        return self.alpha * p + 0.5 * self._R(p)

    def ds(self, p: np.ndarray | float) -> np.ndarray:
        """ds/dp (>= 0 for p >= p_c)."""
        return self.alpha + np.polyval(self._radicand_dp, p) / self._R(p)

    def _minimum(self) -> float:
        if self.alpha == 0:
            return 0.0
        lo = -1.0
        while self.ds(lo) >= 0:
            lo *= 2
        return brentq(lambda p: float(self.ds(p)), lo, 0.0, xtol=1e-15, rtol=1e-15)

    def p_of_s(self, s: ArrayLike) -> np.ndarray:
        """The real root p > p_c with s(p) = s (s >= q_c); Newton from the right (s is convex)."""
        s = np.asarray(s, dtype=float)
        p = np.sqrt(2 * np.maximum(s, 0.0)) + 1.0 + abs(self.p_c)
        for _ in range(100):
            step = (self.s(p) - s) / self.ds(p)
            p = p - step
            if np.all(np.abs(step) <= 1e-15 * np.maximum(1.0, np.abs(p))):
                break
        return p

    def q(self, p: np.ndarray | float) -> np.ndarray:
        """The cut point q(p) = s(p) + i eta_f."""
        return self.s(p) + 1j * self.eta_f
