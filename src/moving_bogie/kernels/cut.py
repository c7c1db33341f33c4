"""The cut locus of K(xi, q) in the q-plane: where a root of N(p, q) crosses the real p-axis.

K of Eq. (29) is analytic in q except where N(p, q) = 0 has a real root p; there the set of roots used by
the residue sum changes and K jumps (the branch cuts of Eq. (35)). For every real p, N(p, .) is a
polynomial in q (generated ``n_coeffs_in_q``), so the cut is the union of the explicit curves q_j(p),
p real, j = 1..DEGREE_N_IN_Q. For the Euler-Bernoulli beam (eta_f < 1)

    q = alpha p + i eta_f +- sqrt((p^4 + 4 eta_s p^2 + 4)/4 - eta_f^2),

two half-lines on Im q = eta_f meeting at a cusp q_c (a double real root p: the branch point of K).
For Timoshenko-Rayleigh the curve through q_c is a fold (Re q turns, Im q does not): a thin lens below
eta_f opens to the right of q_c, and a second curve runs near the real axis beyond |Re q| ~ sqrt(S)/r.

Tracing (:mod:`~moving_bogie.kernels.cut_curves`): the curves are followed on an adaptive grid of
real p, and split at their turning points of Re q (folds and cusps). Every point used later (contour
edges, ``CutArm.q_at``) is then recomputed exactly by Newton's method on N(p, .) = 0, never interpolated.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import mpmath
import numpy as np
from numpy.typing import ArrayLike

from moving_bogie.kernels.cut_curves import CutTracer, Fold, far_range, split_at_turns, trace_curves

if TYPE_CHECKING:
    from moving_bogie.kernels.bound import BoundModel

__all__ = [
    "CutArm",
    "CutLocus",
    "CutTracer",
    "Fold",
    "arms_p_at",
    "arms_y_at",
    "clearance",
    "cut_loci",
    "cut_locus",
    "far_range",
    "side_of_cut",
    "trace_curves",
]


@dataclass(eq=False)
class CutArm:
    """A piece of one curve q_j(p) on which Re q is strictly monotone in p: a graph over Re q.

    ``p`` (increasing) and ``q`` are samples; :meth:`q_at` and :meth:`p_at` are exact (Newton).
    """

    p: np.ndarray
    q: np.ndarray
    tracer: CutTracer = field(repr=False)
    _known: dict = field(default_factory=dict, repr=False)  # x -> p already solved (cells share edges)

    @property
    def x_lo(self) -> float:
        return float(self.q.real.min())

    @property
    def x_hi(self) -> float:
        return float(self.q.real.max())

    @property
    def increasing(self) -> bool:
        return bool(self.q.real[-1] > self.q.real[0])

    def guess(self, p: np.ndarray | float) -> np.ndarray:
        """The arm's q at p (clipped to its range) interpolated from its samples (a start for Newton)."""
        return np.interp(p, self.p, self.q.real) + 1j * np.interp(p, self.p, self.q.imag)

    def q_at(self, p: np.ndarray | float) -> np.ndarray:
        """The cut point of the arm at real p (in its p-range), exact to rounding."""
        p = np.clip(np.asarray(p, dtype=float), self.p[0], self.p[-1])
        return self.tracer.refine(p, self.guess(p))

    def p_at(self, x: ArrayLike) -> np.ndarray:
        """The p of the arm where Re q = x (x within the arm's range), by safeguarded Newton.

        Solutions are remembered: the cells of a tiling share their corners and edges.
        """
        x = np.asarray(x, dtype=float)
        return arms_p_at([self], x.ravel())[0].reshape(x.shape)

    def y_at(self, x: ArrayLike) -> np.ndarray:
        """Im q of the arm at Re q = x."""
        return self.q_at(self.p_at(x)).imag

    def offset(self, p: np.ndarray | float, side: int, delta: float) -> np.ndarray:
        """q(p) + side * d * n(p), n the unit normal pointing to larger Im q (side +1: above the arm), d the
        :func:`clearance` of ``delta`` at p."""
        q = self.q_at(p)
        t = self.tracer.dq_dp(p, q)
        t = np.where(t.real >= 0, t, -t)  # orient along increasing Re q
        return q + side * clearance(p, t, delta) * 1j * t / np.abs(t)

    def clearance(self, x: ArrayLike, delta: float) -> float:
        """The largest :func:`clearance` of ``delta`` at the arm's points over Re q = ``x`` (an array)."""
        p = self.p_at(np.asarray(x, dtype=float))
        return float(np.max(clearance(p, self.tracer.dq_dp(p, self.q_at(p)), delta)))


#: The offset of a contour from the cut, relative to |dq/dp| max(1, |p|), is at least this. Where q moves
#: fast with p (|dq/dp| ~ 1e4-1e5 next to an avoided crossing of two curves q_j(p), light intermediate
#: layers), q(p) from N(p, q) = 0 in double precision is only good to about 1e-15 |dq/dp| (N's q-derivative
#: is small there), and the p-root of a point beside the cut has Im p ~ distance / |dq/dp|: both must stay
#: far from rounding.
CLEARANCE = 1e-13


def clearance(p: ArrayLike, t: ArrayLike, delta: float) -> np.ndarray:
    """The distance from the cut at which an offset point passes: ``delta``, or CLEARANCE |t| max(1, |p|)
    where that is more (t = dq/dp at the arm's point q(p))."""
    return np.maximum(delta, CLEARANCE * np.abs(t) * np.maximum(1.0, np.abs(p)))


def arms_p_at(arms: Sequence[CutArm], x: ArrayLike) -> list:
    """:meth:`CutArm.p_at` of several arms (one tracer) at the same Re q values ``x`` (1-d), in one batch."""
    x = np.asarray(x, dtype=float)
    values = x.tolist()
    outs, todo = [], []
    for k, arm in enumerate(arms):
        out = np.array([arm._known.get(v, np.nan) for v in values])
        outs.append(out)
        new = np.isnan(out)
        if np.any(new):
            todo.append((k, new))
    if todo:
        solved = _solve_p([arms[k] for k, _ in todo], [x[new] for _, new in todo])
        for (k, new), p in zip(todo, solved):
            outs[k][new] = p
            arms[k]._known.update(zip(x[new].tolist(), p.tolist()))
    return outs


def arms_y_at(arms: Sequence[CutArm], x: ArrayLike) -> np.ndarray:
    """Im q of several arms at Re q = ``x`` (1-d), shape (len(arms), len(x)), with one Newton batch."""
    ps = arms_p_at(arms, x)
    guess = np.concatenate([arm.guess(p) for arm, p in zip(arms, ps)])
    q = arms[0].tracer.refine(np.concatenate(ps), guess)
    return q.imag.reshape(len(arms), -1)


def _solve_p(arms: Sequence[CutArm], xs: Sequence[np.ndarray]) -> list:
    """Newton's method on Re q(p) = x for each arm, kept inside a bracket from its samples (bisection when
    a step leaves it: near a fold Re q is flat in p and a plain step can jump to the arm's other end);
    all arms in one batch."""
    sizes = [x.size for x in xs]
    X, B, A, P = [], [], [], []
    for arm, x in zip(arms, xs):
        x = np.clip(x, arm.x_lo, arm.x_hi)
        order = np.argsort(arm.q.real)
        xr, pr = arm.q.real[order], arm.p[order]
        i = np.clip(np.searchsorted(xr, x), 1, xr.size - 1)
        X.append(x)
        B.append(pr[i - 1])  # Re q <= x there (a sample)
        A.append(pr[i])  # Re q >= x there
        P.append(np.interp(x, xr, pr))
    x, below, above, p = (np.concatenate(v) for v in (X, B, A, P))
    splits = np.cumsum(sizes)[:-1]
    owner = np.repeat(np.arange(len(arms)), sizes)
    tracer = arms[0].tracer
    active = np.arange(p.size)  # points still iterating (a point near a fold may need bisection steps)
    for _ in range(80):
        pa, own = p[active], owner[active]
        guess = np.empty(pa.shape, dtype=complex)
        for k in np.unique(own):
            sel = own == k
            guess[sel] = arms[k].guess(pa[sel])
        q = tracer.refine(pa, guess)
        f = q.real - x[active]
        low = f <= 0
        lo, hi = np.where(low, pa, below[active]), np.where(low, above[active], pa)
        below[active], above[active] = lo, hi
        with np.errstate(all="ignore"):
            new = pa - f / tracer.dq_dp(pa, q).real
        inside = np.isfinite(new) & ((new - lo) * (new - hi) <= 0)
        new = np.where(inside, new, 0.5 * (lo + hi))
        done = inside & (np.abs(new - pa) <= 1e-13 * np.maximum(1.0, np.abs(pa)))  # Newton: the next
        p[active] = new  # step (taken) is then at rounding level
        done |= np.abs(f) <= 4e-16 * np.maximum(1.0, np.abs(x[active]))  # Re q = x to rounding (a fold's
        done |= np.abs(hi - lo) <= 1e-13 * np.maximum(1.0, np.abs(pa))  # slope is 0: no Newton step there)
        active = active[~done]
        if not active.size:
            break
    return np.split(p, splits)


@dataclass(frozen=True)
class CutLocus:
    """The cut of K around the strip x_min <= Re q <= x_max.

    Attributes
    ----------
    points : ndarray of complex
        Sample points of the cut curves inside the strip.
    x_start : float
        Smallest Re q of the cut in the strip (``-inf`` if the cut reaches x_min).
    im_low, im_high : float
        Range of Im q of the cut inside the strip (both eta_f for Euler-Bernoulli).
    arms : tuple of CutArm
        The curves cut at their turning points; each is a graph over Re q.
    folds : tuple of Fold
        Turning points of Re q inside the strip.
    """

    points: np.ndarray
    x_start: float
    im_low: float
    im_high: float
    arms: tuple = ()
    folds: tuple = ()

    def im_range_between(self, x_left: float, x_right: float) -> tuple[float, float] | None:
        """(low, high) Im q of the cut with x_left <= Re q <= x_right, or None if it does not pass there."""
        sel = self.points[(self.points.real >= x_left) & (self.points.real <= x_right)]
        if sel.size == 0:
            return None
        return float(sel.imag.min()), float(sel.imag.max())

    @property
    def flat(self) -> bool:
        """Every arm in the strip lies on one horizontal line (Euler-Bernoulli: Im q = eta_f)."""
        return bool(self.points.size) and self.im_high - self.im_low <= 1e-12


def cut_locus(bound: BoundModel, x_min: float, x_max: float, *, samples: int = 2001) -> CutLocus:
    """Trace the cut of K of the bound model's track over x_min <= Re q <= x_max (every curve q_j(p), p real).

    The p-range (:func:`far_range`) reaches until every curve has left the strip or settled at its limit
    q_inf; the grid is uniform in asinh(p/2) (fine near p = 0, geometric far out) and refined adaptively.
    A curve that ends inside the strip at its limit gives an *end* of the cut (:class:`Fold` with
    ``end=True``): K is singular there (a root p of N runs off to infinity), and the tiling treats it as
    a branch point.
    """
    return cut_loci(bound, [(x_min, x_max)], samples=samples)[0]


def cut_loci(bound: BoundModel, strips: list[tuple[float, float]], *, samples: int = 2001) -> tuple:
    """:func:`cut_locus` of several strips ``[(x_min, x_max), ...]`` from one trace of the curves (over the
    p-range of the widest): each is what :func:`cut_locus` of that strip alone returns, up to where the
    samples of an arm lie (its points are exact wherever they are used)."""
    tracer = CutTracer(bound.foundation, bound.foundation_floats())
    reach = max(max(abs(x_min), abs(x_max)) for x_min, x_max in strips) + 1.0
    P = far_range(tracer, reach)
    U = float(np.arcsinh(P / 2.0))
    grid = 2.0 * np.sinh(np.linspace(-U, U, samples))
    grid[0], grid[-1] = -P, P
    ps, Q = trace_curves(tracer, -P, P, grid=grid)
    pieces, turning = [], []
    for j in range(Q.shape[1]):
        arms_j, turns = split_at_turns(tracer, ps, Q[:, j])
        pieces += [CutArm(p_arm, q_arm, tracer) for p_arm, q_arm in arms_j if p_arm.size > 1]
        ends = [
            Fold(float(ps[k]), complex(Q[k, j]), True, 0, True) for k in (0, -1) if abs(Q[k, j].real) <= reach
        ]
        turning += turns + ends
    pieces, turning = _distinct_arms(pieces), _distinct_folds(turning)
    return tuple(_locus(pieces, turning, x_min, x_max) for x_min, x_max in strips)


#: Two arms or folds closer than this (relative to max(1, |q|)) are one: a curve traced twice.
_SAME = 1e-10


def _distinct_folds(folds: list[Any]) -> list[Any]:
    """The folds without repeats. Where N is even in p (alpha = 0), q_j(p) = q_j(-p): every curve is traced
    twice, over p < 0 and over p > 0, and its folds and ends come twice, one rounding apart (a column of
    zero width between them)."""
    kept: list[Any] = []
    for f in folds:
        kind = (f.opens, f.cusp, f.end)
        close = _SAME * max(1.0, abs(f.q))
        if not any(abs(f.q - g.q) <= close and kind == (g.opens, g.cusp, g.end) for g in kept):
            kept.append(f)
    return kept


def _distinct_arms(arms: list[CutArm]) -> list:
    """The arms without repeats (see :func:`_distinct_folds`): the same range of Re q and the same Im q at
    five points of it."""
    kept: list[CutArm] = []
    profiles: list[Any] = []
    for arm in arms:
        lo, hi = arm.x_lo, arm.x_hi
        order = np.argsort(arm.q.real)
        xs = np.linspace(lo, hi, 5)
        ys = np.interp(xs, arm.q.real[order], arm.q.imag[order])
        scale = _SAME * max(1.0, abs(lo), abs(hi), float(np.abs(ys).max()))
        same = any(
            abs(lo - plo) <= scale and abs(hi - phi) <= scale and np.all(np.abs(ys - pys) <= 1e3 * scale)
            for plo, phi, pys in profiles
        )
        if not same:
            kept.append(arm)
            profiles.append((lo, hi, ys))
    return kept


def _locus(pieces: list[CutArm], turning: list, x_min: float, x_max: float) -> CutLocus:
    """The arms and folds of the traced curves that meet the strip x_min <= Re q <= x_max."""
    arms = []
    for arm in pieces:
        inside = (arm.q.real >= x_min) & (arm.q.real <= x_max)
        if np.any(inside) or (arm.q.real.min() < x_min and arm.q.real.max() > x_max):
            arms.append(arm)
    folds = [f for f in turning if x_min <= f.q.real <= x_max]
    pts = np.concatenate([a.q for a in arms]) if arms else np.zeros(0, complex)
    inside = pts[(pts.real >= x_min) & (pts.real <= x_max)]
    extra = np.array([f.q for f in folds], dtype=complex)
    inside = np.concatenate([inside, extra])
    if inside.size == 0:
        return CutLocus(inside, np.inf, np.nan, np.nan, tuple(arms), tuple(folds))
    x_start = float(inside.real.min())
    if any(a.x_lo < x_min < a.x_hi for a in arms):
        x_start = -np.inf  # the cut reaches the strip's left edge: no gap (supercritical speed)
    return CutLocus(
        inside, x_start, float(inside.imag.min()), float(inside.imag.max()), tuple(arms), tuple(folds)
    )


def side_of_cut(q: complex | mpmath.mpc, tol: float, cut: CutLocus, floor: float) -> str:
    """Position of a root q relative to the cut: "below" or "above" every cut curve over Re q, or "between"
    two of them (a layered track's curves, the lens of the Timoshenko-Rayleigh cut); a root on a curve
    within ``tol`` counts as below it (a limit from below). Where no curve lies over Re q, the cut is the
    nearest traced point's Im q beyond the cut's start, else ``floor`` (eta_f: the cut on the axis)."""
    y = float(mpmath.im(q))
    x = float(mpmath.re(q))
    arms = [arm for arm in cut.arms if arm.x_lo <= x <= arm.x_hi]
    if arms:
        above = int(np.sum(y - arms_y_at(arms, np.array([x]))[:, 0] > tol))
        return "below" if above == 0 else "above" if above == len(arms) else "between"
    threshold = floor
    if cut.points.size and x >= cut.x_start:
        near = cut.points[np.argmin(np.abs(cut.points.real - x))]
        threshold = float(near.imag)
    return "above" if y - threshold > tol else "below"
