"""The traced cut of K split into the pieces that the branch-cut integral runs over (Eq. (35)).

Each curve q_j(p), p real, of the cut (:func:`moving_bogie.kernels.cut.trace_curves`) is cut where it
crosses Re q = 0; its pieces with Re q >= 0 are kept (:class:`CurvePiece`), their mirror images
-conj q covering the rest of the cut. A piece's end is *far* where Re q grows without bound (it is
truncated at Re q = S, the tail integrated by parts), or a crossing of Re q = 0, an interior point of the
cut. A crossing at q = 0 itself (the pole of the steady part) and a curve that stays bounded in Re q > 0
(a mass layer at alpha = 0) are refused. :func:`roots_along` gives the roots of N(., q) along the nodes
of a quadrature rule.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from moving_bogie.kernels.polyroots import newton_polish, poly_roots, polyder, polyval
from moving_bogie.response.branch_cut import BranchCutUnavailable

if TYPE_CHECKING:
    from moving_bogie.kernels.cut import CutTracer

__all__ = ["CurvePiece", "TracedCurve", "cut_pieces", "roots_along"]

#: Companion eigenvalues at every this-th node of a rule, Newton's method at the others.
SEED_STRIDE = 8


class TracedCurve:
    """One traced curve q(p) (samples ``p`` increasing, ``q``), evaluated exactly by Newton."""

    def __init__(self, tracer: CutTracer, p: np.ndarray, q: np.ndarray) -> None:
        self.tracer, self.p, self.q = tracer, p, q

    def q_at(self, p: ArrayLike) -> np.ndarray:
        p = np.asarray(p, dtype=float)
        guess = np.interp(p, self.p, self.q.real) + 1j * np.interp(p, self.p, self.q.imag)
        return self.tracer.refine(p, guess)

    def crossing(self, level: float, a: ArrayLike, b: ArrayLike) -> np.ndarray:
        """The p in [a, b] where Re q = ``level`` (arrays a, b bracketing it): safeguarded Newton."""
        a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
        xa, xb = self.q_at(a).real, self.q_at(b).real
        p = a + (level - xa) * (b - a) / np.where(xb != xa, xb - xa, 1.0)
        for _ in range(40):
            q = self.q_at(p)
            with np.errstate(all="ignore"):
                step = (q.real - level) / self.tracer.dq_dp(p, q).real
            new = np.clip(np.where(np.isfinite(step), p - step, 0.5 * (a + b)), a, b)
            done = np.all(np.abs(new - p) <= 1e-14 * np.maximum(1.0, np.abs(p)))
            p = new
            if done:
                break
        return p


class CurvePiece:
    """The part p_lo <= p <= p_hi of a curve on which Re q >= 0 (module docstring).

    Each end is either *far* (the curve runs to Re q -> +inf there: it is truncated where Re q = S and
    the tail is integrated by parts) or a crossing of Re q = 0, an interior point of the cut that the
    mirror image of another piece continues (no tail).
    """

    def __init__(self, curve: TracedCurve, p_lo: float, p_hi: float, far_lo: bool, far_hi: bool) -> None:
        self.curve, self.tracer = curve, curve.tracer
        self.p_lo, self.p_hi, self.far = p_lo, p_hi, (far_lo, far_hi)
        inside = (curve.p >= p_lo) & (curve.p <= p_hi)
        self.p = np.concatenate([[p_lo], curve.p[inside], [p_hi]])
        self.q = np.concatenate([curve.q_at([p_lo]), curve.q[inside], curve.q_at([p_hi])])
        self.x_min = float(self.q.real.min())
        self._ends: dict = {}

    def q_at(self, p: ArrayLike) -> np.ndarray:
        return self.curve.q_at(p)

    def p_ends(self, S: float) -> tuple[float, float]:
        """(p_lo, p_hi) of the piece truncated at Re q = S: the outermost crossings at its far ends."""
        if S not in self._ends:
            x = self.q.real
            inside = np.nonzero(x <= S)[0]
            ends = [self.p_lo, self.p_hi]
            k = [inside[0] - 1, inside[-1]]  # the crossing lies in [p_k, p_k+1]
            for side in (0, 1):
                if self.far[side] and 0 <= k[side] < x.size - 1:
                    ends[side] = float(self.curve.crossing(S, self.p[k[side]], self.p[k[side] + 1]))
            self._ends[S] = tuple(ends)
        return self._ends[S]

    def far_ends(self, S: float) -> list[tuple[int, float]]:
        """[(sign, p)] of the truncated ends: sign -1 at the lower end, +1 at the upper one."""
        return [(sign, p) for sign, p, far in zip((-1, 1), self.p_ends(S), self.far) if far]


def roots_along(n: np.ndarray) -> np.ndarray:
    """Roots of the polynomials ``n`` (nodes, degree + 1) at the consecutive nodes of a quadrature rule.

    Companion eigenvalues at every ``SEED_STRIDE``-th node, Newton's method from them at the nodes
    between (the roots move little from node to node); a node where Newton does not end at distinct,
    converged roots gets its eigenvalues. The same roots as :func:`poly_roots`, several times faster.
    """
    k, degree = n.shape[0], n.shape[-1] - 1
    if degree <= 4 or k < 4 * SEED_STRIDE:
        return poly_roots(n)
    guess = np.repeat(poly_roots(n[::SEED_STRIDE]), SEED_STRIDE, axis=0)[:k]
    roots = newton_polish(n, guess, steps=8)
    size = np.maximum(1.0, np.abs(roots))
    with np.errstate(all="ignore"):
        step = np.abs(polyval(n, roots) / polyval(polyder(n), roots))
    gap = np.abs(roots[:, :, None] - roots[:, None, :]) + np.where(np.eye(degree, dtype=bool), np.inf, 0)
    ok = np.all((step <= 1e-13 * size) & (gap.min(axis=-1) > 1e-8 * size), axis=-1)
    if not np.all(ok):
        roots[~ok] = poly_roots(n[~ok])
    return roots


def cut_pieces(tracer: CutTracer, ps: np.ndarray, qs: np.ndarray) -> list[CurvePiece]:
    """The pieces with Re q >= 0 of one traced curve; raises if the curve passes through q = 0.

    An end of the traced range is far when Re q still grows there (at least like |p|: Re q at the end
    is 1.5 times its value at half the end's p or more); a curve whose Re q tends to a positive limit
    (a mass layer's curve at alpha = 0) is refused.
    """
    curve = TracedCurve(tracer, ps, qs)
    x = qs.real
    k = np.nonzero((x[:-1] >= 0) != (x[1:] >= 0))[0]
    zeros = curve.crossing(0.0, ps[k], ps[k + 1]) if k.size else np.zeros(0)
    if zeros.size:
        at = curve.q_at(zeros)
        if np.abs(at).min() <= 1e-9:
            raise BranchCutUnavailable(
                f"the cut of K passes through q = 0 (at p = {zeros[np.argmin(np.abs(at))]:.6g}), the pole of "
                "the steady part: no steady state (an undamped layered track, whose mass layer has waves of "
                "every phase speed, or an undamped track above the critical velocity)"
            )
    bounds = np.concatenate([[ps[0]], zeros, [ps[-1]]])
    half = [np.argmin(np.abs(ps - ps[0] / 2)), np.argmin(np.abs(ps - ps[-1] / 2))]
    far = [bool(x[0] > 1.0 and x[0] >= 1.5 * x[half[0]]), bool(x[-1] > 1.0 and x[-1] >= 1.5 * x[half[1]])]
    if (x[0] > 0 and not far[0]) or (x[-1] > 0 and not far[1]):
        raise BranchCutUnavailable(
            "a curve of the cut of K stays bounded in Re q > 0 as |p| grows (a mass layer at alpha = 0): "
            "the branch-cut integral needs every curve to run to Re q -> infinity"
        )
    out = []
    for j in range(bounds.size - 1):
        mid = 0.5 * (bounds[j] + bounds[j + 1])
        if curve.q_at([mid]).real[0] > 0:
            out.append(
                CurvePiece(
                    curve, bounds[j], bounds[j + 1], far[0] and j == 0, far[1] and j == bounds.size - 2
                )
            )
    return out
