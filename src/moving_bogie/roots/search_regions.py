"""Tiling of the search window into regions that never meet the cut of K.

The window is cut into: everything below the band of the cut, everything above it, the gap left of the
cut's leftmost point (where K is analytic across the cut's line, so undamped real roots lie strictly
inside), and, over the cut, cells whose edges follow the traced cut curves at the distance ``eps``
(:mod:`cut_cells`): below the lowest curve, between curves (the lens that opens at a fold of the
Timoshenko-Rayleigh cut), above the highest, and two cells around each fold. What is left unsearched is
the band of half-width ``eps`` around the cut (height 2 eps at every Re q) and, at a cusp of the cut (the
branch point of K, Euler-Bernoulli), a box of half-width ``eps_branch``: roots there are within that
distance of the cut; the result lists those slivers with their height.

Folds get tip cells whichever way their lens opens. Where the traced curves cannot be followed (two
curves crossing or closer than 4 eps inside a column), the column falls back to a padded strip around the
cut's range in it, and the sliver reported there is that strip's height.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import optimize

from moving_bogie.kernels.cut import CutLocus, arms_y_at
from moving_bogie.roots.contour import Rectangle
from moving_bogie.roots.cut_cells import ColumnCell, Edge, Sliver, TipCell

__all__ = ["Tiling", "tile_window"]

_COLUMN_SAMPLES = 17  # Re q samples per column where the order of the curves is checked
_MERGE = 3.0  # arms closer than this many eps are left out together (sliver <= 5 eps)
_TOUCH = 1e-14  # a gap between two arms this small is zero (they meet, e.g. where they cross Re q = 0)
_NARROW = 50.0  # a column narrower than this many eps (at a crossing of arms) is left out as a box


@dataclass(frozen=True)
class Tiling:
    regions: tuple  # Rectangles and curved cells to count in
    unsearched: tuple  # Slivers around the cut not searched


def tile_window(
    window: Rectangle,
    cut: CutLocus,
    *,
    eps: float,
    eps_branch: float,
    gap_height: float,
    columns: int = 48,
    curved_columns: int = 6,
) -> Tiling:
    """Regions covering ``window`` minus an ``eps``-band around the cut.

    Left of the cut the gap region extends ``gap_height`` above and below the cut, so that roots on or near
    the cut's line there (the real roots of undamped cases) are far from every edge. ``columns`` splits a
    flat cut's strip (as it always was), ``curved_columns`` the curved one: as many per width of 3 (or of
    the window if narrower) and at most that many between two folds of the cut.
    """
    if not cut.points.size or cut.im_high < window.y0 or cut.im_low > window.y1:
        return Tiling((window,), ())
    band_lo = max(window.y0, cut.im_low - gap_height)
    band_hi = min(window.y1, cut.im_high + gap_height)
    regions = []
    if band_lo > window.y0:
        regions.append(Rectangle(window.x0, window.x1, window.y0, band_lo))
    if band_hi < window.y1:
        regions.append(Rectangle(window.x0, window.x1, band_hi, window.y1))
    if cut.flat or not cut.arms:
        return _flat(window, cut, regions, eps, eps_branch, band_lo, band_hi)
    return _curved(window, cut, regions, eps, eps_branch, band_lo, band_hi, curved_columns)


def _flat(window, cut, regions, eps, eps_branch, band_lo, band_hi) -> Tiling:
    """A cut on one horizontal line (Euler-Bernoulli): strips below and above the line, and a box of
    half-width ``eps_branch`` around every branch point (cusp) on it (where K varies like a square root,
    an edge passing at distance eps would need samples eps apart)."""
    lo, hi = cut.im_low - eps, cut.im_high + eps
    x_gap = cut.x_start - eps_branch
    if x_gap > window.x0:
        regions.append(Rectangle(window.x0, min(x_gap, window.x1), band_lo, band_hi))
    x_band = max(window.x0, x_gap)
    if x_band >= window.x1:
        return Tiling(tuple(regions), ())
    cusps = sorted(f.q.real for f in cut.folds if f.cusp and x_band - eps_branch < f.q.real < window.x1)
    if (
        np.isfinite(cut.x_start)
        and x_gap > window.x0
        and not any(abs(c - cut.x_start) < eps_branch for c in cusps)
    ):
        cusps = sorted(cusps + [cut.x_start])
    unsearched = []
    b_lo, b_hi = max(band_lo, cut.im_low - eps_branch), min(band_hi, cut.im_high + eps_branch)
    x = x_band
    for c in cusps + [None]:
        end = window.x1 if c is None else max(x, c - eps_branch)
        if end > x:  # a strip between branch points
            if lo > band_lo:
                regions.append(Rectangle(x, end, band_lo, lo))
            if hi < band_hi:
                regions.append(Rectangle(x, end, hi, band_hi))
            y0, y1 = max(lo, band_lo), min(hi, band_hi)
            unsearched.append(Sliver(x, end, y0, y1, y1 - y0))
        if c is None:
            break
        box_end = min(window.x1, c + eps_branch)
        if box_end > end:  # the box around a branch point
            if b_lo > band_lo:
                regions.append(Rectangle(end, box_end, band_lo, b_lo))
            if b_hi < band_hi:
                regions.append(Rectangle(end, box_end, b_hi, band_hi))
            unsearched.append(Sliver(end, box_end, b_lo, b_hi, b_hi - b_lo))
        x = box_end
    return Tiling(tuple(regions), tuple(unsearched))


def _arms_over(cut, a, b):
    return [arm for arm in cut.arms if arm.x_lo <= a + 1e-12 and arm.x_hi >= b - 1e-12]


def _curved(window, cut, regions, eps, eps_branch, band_lo, band_hi, columns) -> Tiling:
    unsearched = []
    folds = sorted((f for f in cut.folds if window.x0 < f.q.real < window.x1), key=lambda f: f.q.real)
    # event intervals around folds (tip cells) and cusps (branch-point boxes)
    events = []
    for f in folds:
        # a fold with tip cells gets a column of its own, clear of the other folds; a cusp or an end of the
        # cut (a box left out) a narrow one
        near = min((abs(g.q.real - f.q.real) for g in folds if g is not f), default=np.inf)
        half = eps_branch if f.cusp else min(1e-3 * window.width, 1e-3, 0.3 * near)
        events.append((f.q.real - half, f.q.real + half, f))
    x_band = window.x0
    if np.isfinite(cut.x_start) and cut.x_start > window.x0:
        left = min([cut.x_start - eps_branch] + [e[0] for e in events])
        if left > window.x0:
            regions.append(Rectangle(window.x0, min(left, window.x1), band_lo, band_hi))
            x_band = left
    density = columns / min(window.width, 3.0)

    def fill(x0, x1):
        _columns(cut, x0, x1, regions, unsearched, eps, band_lo, band_hi, density)

    edges_x = [x_band]
    for lo, hi, f in events:
        if hi <= edges_x[-1] or lo >= window.x1:
            continue
        if lo > edges_x[-1]:
            fill(edges_x[-1], lo)
        _event(cut, max(lo, edges_x[-1]), min(hi, window.x1), f, regions, unsearched, eps, band_lo, band_hi)
        edges_x.append(min(hi, window.x1))
    if edges_x[-1] < window.x1:
        fill(edges_x[-1], window.x1)
    return Tiling(tuple(regions), tuple(unsearched))


def _columns(cut, x0, x1, regions, unsearched, eps, band_lo, band_hi, density, most=6):
    """Columns between two events, ``density`` of them per unit of Re q (at least one, at most ``most``)."""
    xs = np.linspace(x0, x1, min(most, max(1, int(np.ceil(density * (x1 - x0) - 1e-9)))) + 1)
    for a, b in zip(xs[:-1], xs[1:]):
        _column(cut, a, b, regions, unsearched, eps, band_lo, band_hi)


def _column(cut, a, b, regions, unsearched, eps, band_lo, band_hi, arms=None):
    """Cells of one column [a, b] between the cut's arms (graphs over Re q there), or a padded fallback.

    Where two arms cross, the column is split at the crossing; where two arms are closer than
    ``_MERGE`` eps, the thin lens between them is left out with them (a sliver at most 5 eps high).
    """
    xs = np.linspace(a, b, _COLUMN_SAMPLES)
    arms = _arms_over(cut, a, b) if arms is None else arms
    if not arms:
        regions.append(Rectangle(a, b, band_lo, band_hi))
        return
    ys = arms_y_at(arms, xs)
    if b - a <= _NARROW * eps * max(1.0, abs(a)):  # a sliver of a column at a crossing: boxes left out
        _boxes(a, b, ys, regions, unsearched, eps, band_lo, band_hi)
        return
    order = np.argsort(ys[:, _COLUMN_SAMPLES // 2])
    arms, ys = [arms[k] for k in order], ys[order]
    gaps = np.diff(ys, axis=0)
    gaps = np.where(np.abs(gaps) <= _TOUCH, 0.0, gaps)  # curves meeting at rounding level (at Re q = 0)
    for k in range(len(arms) - 1):
        g = gaps[k]
        if np.all(np.abs(g) < 1e-13):
            continue  # coincident curves (Euler-Bernoulli): merged below
        split, crossing = _split_point(arms[k], arms[k + 1], xs, g, eps)
        narrow = _NARROW * eps * max(1.0, abs(a))
        if split is not None and crossing and a < split < b:
            # a crossing gets a narrow column of its own centred on it (boxes left out around the arms):
            # no edge passes through the crossing point, where a root may sit (two mirror curves cross on
            # Re q = 0, where the purely imaginary roots lie)
            # narrower where an arm is steep (next to a fold), so that the boxes stay a few 1e-9 high
            steep = min(1e3, max(1.0, _slope(arms[k], split), _slope(arms[k + 1], split)))
            half = 0.45 * _NARROW * eps * max(1.0, abs(split)) / steep
            inner = [x for x in (split - half, split + half) if a + 1e-3 * half < x < b - 1e-3 * half]
            cuts = [a, *inner, b]
            for c0, c1 in zip(cuts[:-1], cuts[1:]):
                _column(cut, c0, c1, regions, unsearched, eps, band_lo, band_hi, arms)
            return
        if split is not None and a < split < b:
            # a split next to an end makes a column too narrow to count in: widen it to _NARROW eps
            if split - a < narrow:
                split = a + narrow if b - a > 2 * narrow else b
            elif b - split < narrow:
                split = b - narrow if b - a > 2 * narrow else a
        if split is not None and a < split < b:
            _column(cut, a, split, regions, unsearched, eps, band_lo, band_hi, arms)
            _column(cut, split, b, regions, unsearched, eps, band_lo, band_hi, arms)
            return
        if np.any(g < 0):  # crossing curves the split could not separate
            _padded(a, b, ys, regions, unsearched, eps, band_lo, band_hi)
            return
    if ys.min() - eps <= band_lo or ys.max() + eps >= band_hi:
        _padded(a, b, ys, regions, unsearched, eps, band_lo, band_hi)
        return
    # groups of arms closer than _MERGE eps share one pair of edges
    groups = [[0]]
    for k in range(len(arms) - 1):
        if np.all(gaps[k] <= _MERGE * eps):
            groups[-1].append(k + 1)
        else:
            groups.append([k + 1])
    edges = [Edge(y=band_lo)]
    for group in groups:
        lo_arm, hi_arm = arms[group[0]], arms[group[-1]]
        edges += [Edge(arm=lo_arm, side=-1, delta=eps), Edge(arm=hi_arm, side=1, delta=eps)]
        y_lo, y_hi = ys[group[0]], ys[group[-1]]
        thickness = float((y_hi - y_lo).max()) + 2 * eps
        unsearched.append(Sliver(a, b, float(y_lo.min() - eps), float(y_hi.max() + eps), thickness))
    edges.append(Edge(y=band_hi))
    regions.extend(ColumnCell(a, b, lo, hi) for lo, hi in zip(edges[::2], edges[1::2]))


def _split_point(lower, upper, xs, gap, eps):
    """Where the column must be split for the arms ``lower`` < ``upper`` (at the middle), and whether that
    is their crossing (else the Re q where their gap passes _MERGE eps); (None, False) if neither happens
    inside."""

    def g(x, target=0.0):
        return float(upper.y_at(np.array([x]))[0] - lower.y_at(np.array([x]))[0]) - target

    for target in (0.0, _MERGE * eps):
        change = np.nonzero(np.sign(gap[:-1] - target) * np.sign(gap[1:] - target) < 0)[0]
        if change.size:
            k = change[0]
            ga, gb = g(xs[k], target), g(xs[k + 1], target)
            if ga * gb > 0:  # the sign change was at rounding level: split at the nearer sample
                return (xs[k] if abs(ga) < abs(gb) else xs[k + 1]), target == 0.0
            x = optimize.brentq(g, xs[k], xs[k + 1], args=(target,), xtol=1e-15, rtol=1e-15)
            return x, target == 0.0
    return None, False


def _slope(arm, x) -> float:
    """|d Im q / d Re q| of ``arm`` at Re q = x."""
    p = arm.p_at(np.array([x]))
    t = complex(arm.tracer.dq_dp(p, arm.q_at(p))[0])
    return abs(t.imag) / abs(t.real) if t.real else np.inf


def _padded(a, b, ys, regions, unsearched, eps, band_lo, band_hi):
    pad = eps + 0.05 * float(ys.max() - ys.min())
    c_lo, c_hi = max(band_lo, float(ys.min()) - pad), min(band_hi, float(ys.max()) + pad)
    if c_lo > band_lo:
        regions.append(Rectangle(a, b, band_lo, c_lo))
    if c_hi < band_hi:
        regions.append(Rectangle(a, b, c_hi, band_hi))
    unsearched.append(Sliver(a, b, c_lo, c_hi, c_hi - c_lo))


def _boxes(a, b, ys, regions, unsearched, eps, band_lo, band_hi):
    """The narrow column [a, b] with a box left out around each cluster of arms (``ys``: their Im q),
    rectangles in between."""
    spans = sorted((float(y.min()) - eps, float(y.max()) + eps) for y in ys)
    merged = [list(spans[0])]
    for lo, hi in spans[1:]:
        if lo <= merged[-1][1] + 100 * eps:
            merged[-1][1] = max(merged[-1][1], hi)
        else:
            merged.append([lo, hi])
    bottom = band_lo
    for lo, hi in merged:
        lo, hi = max(lo, band_lo), min(hi, band_hi)
        if lo > bottom:
            regions.append(Rectangle(a, b, bottom, lo))
        unsearched.append(Sliver(a, b, lo, hi, hi - lo))
        bottom = max(bottom, hi)
    if bottom < band_hi:
        regions.append(Rectangle(a, b, bottom, band_hi))


def _box(a, b, lo, hi, regions, unsearched, band_lo, band_hi):
    """The column [a, b] with the box lo <= Im q <= hi left out (reported as a sliver)."""
    lo, hi = max(lo, band_lo), min(hi, band_hi)
    if lo > band_lo:
        regions.append(Rectangle(a, b, band_lo, lo))
    if hi < band_hi:
        regions.append(Rectangle(a, b, hi, band_hi))
    unsearched.append(Sliver(a, b, lo, hi, hi - lo))


def _ends_at(arm, fold) -> bool:
    """Whether ``arm`` starts or ends at ``fold`` (same p and same q: curves may share their end p)."""
    tol = 1e-9 * (1.0 + abs(fold.q))
    return any(abs(arm.p[k] - fold.p) < 1e-12 and abs(arm.q[k] - fold.q) < tol for k in (0, -1))


def _event(cut, a, b, fold, regions, unsearched, eps, band_lo, band_hi):
    """The column [a, b] around a fold (two tip cells) or a cusp (a box left unsearched).

    Where another curve of the cut passes through the fold's lens or close to it inside [a, b] (a steep
    arm beside the fold, or one crossing an arm of the lens), the fold's column is narrowed around the
    fold until none does (the lens is about sqrt(Re q - fold) wide there, the other curve a fixed distance
    away), and ordinary columns (:func:`_column`, which split at crossings) fill the rest of [a, b]: the
    box that this curve would otherwise force around the whole column is not left out.
    """
    if not fold.cusp:
        narrow = _clear_column(cut, a, b, fold, eps)
        if narrow != (a, b):
            if narrow[0] > a:
                _column(cut, a, narrow[0], regions, unsearched, eps, band_lo, band_hi)
            _fold_column(cut, *narrow, fold, regions, unsearched, eps, band_lo, band_hi)
            if narrow[1] < b:
                _column(cut, narrow[1], b, regions, unsearched, eps, band_lo, band_hi)
            return
    _fold_column(cut, a, b, fold, regions, unsearched, eps, band_lo, band_hi)


#: Each narrowing of a fold's column divides its half-width by this, down to _SMALLEST_TIP eps.
_SHRINK = 4.0
_SMALLEST_TIP = 500.0


def _clear_column(cut, a, b, fold, eps):
    """[a, b], or the narrower column around ``fold`` in which no other curve passes through its box.

    Unchanged when nothing passes through, when a curve only partly crosses [a, b] (it ends next to the
    fold: the box stays) or the fold is not the meeting point of two arms.
    """
    pair, _, partial, through, _, _ = _fold_neighbours(cut, a, b, fold, eps)
    if not through or partial or len(pair) != 2:
        return a, b
    x_f = float(fold.q.real)
    half = max(x_f - a, b - x_f)
    smallest = _SMALLEST_TIP * eps * max(1.0, abs(x_f))
    lo, hi = a, b
    while through and half / _SHRINK >= smallest:
        half /= _SHRINK
        lo, hi = max(a, x_f - half), min(b, x_f + half)
        pair, _, partial, through, _, _ = _fold_neighbours(cut, lo, hi, fold, eps)
        if partial:
            return a, b
    return lo, hi


def _fold_neighbours(cut, a, b, fold, eps):
    """(pair, others, partial, through, low, high) of the fold's column [a, b]: the two arms meeting at the
    fold, the other curves crossing the whole column, those crossing only part of it, the curves that pass
    through the fold's box (within 8 eps of the Im range of the pair), and the box's Im range."""
    pair = [arm for arm in cut.arms if _ends_at(arm, fold)]
    full = _arms_over(cut, a, b)
    others = [arm for arm in full if all(arm is not x for x in pair)]
    partial = [
        arm
        for arm in cut.arms
        if arm.x_lo < b
        and arm.x_hi > a
        and all(arm is not x for x in full)
        and all(arm is not x for x in pair)
    ]
    xs = np.linspace(a, b, _COLUMN_SAMPLES)
    pair_ys = [fold.q.imag] + [
        float(y) for arm in pair for y in arm.y_at(np.linspace(max(a, arm.x_lo), min(b, arm.x_hi), 9))
    ]
    low, high = min(pair_ys), max(pair_ys)
    for arm in partial:
        y = arm.y_at(np.linspace(max(a, arm.x_lo), min(b, arm.x_hi), 9))
        low, high = min(low, float(y.min())), max(high, float(y.max()))
    spans = dict(zip(map(id, others), arms_y_at(others, xs))) if others else {}
    through = list(partial)  # other curves passing through the fold's box: left out with it
    grown = True
    while grown:
        grown = False
        for arm in others:
            y = spans[id(arm)]
            if arm not in through and y.max() >= low - 8 * eps and y.min() <= high + 8 * eps:
                through.append(arm)
                low, high, grown = min(low, float(y.min())), max(high, float(y.max())), True
    return pair, others, partial, through, low, high


def _fold_column(cut, a, b, fold, regions, unsearched, eps, band_lo, band_hi):
    """The column [a, b] around a fold: two tip cells, or a box (a cusp, an end of the cut, or curves
    passing through the fold's box).

    The lens of the fold opens towards larger Re q (``fold.opens`` = +1: its tip cells reach Re q = b) or
    towards smaller Re q (-1: they reach a). Curves of the cut that only partly cross the column, or pass
    through the fold's box, are left out with it; the outer tip cell is framed closely around the lens and
    rectangles fill the column above and below the frame.
    """
    pair, others, _, through, low, high = _fold_neighbours(cut, a, b, fold, eps)
    xs = np.linspace(a, b, _COLUMN_SAMPLES)
    spans = dict(zip(map(id, others), arms_y_at(others, xs))) if others else {}
    below = [arm for arm in others if arm not in through and spans[id(arm)].max() < low]
    above = [arm for arm in others if arm not in through and spans[id(arm)].min() > high]
    # other curves passing above or below the fold get ordinary column cells there
    if below:
        top = max(float(arm.y_at(xs).max()) for arm in below)
        split = 0.5 * (top + low)
        _column(cut, a, b, regions, unsearched, eps, band_lo, split, below)
        band_lo = split
    if above:
        bottom = min(float(arm.y_at(xs).min()) for arm in above)
        split = 0.5 * (bottom + high)
        _column(cut, a, b, regions, unsearched, eps, split, band_hi, above)
        band_hi = split
    if fold.cusp or len(pair) != 2 or through:  # a box around the fold (cusp, end)
        _box(a, b, low - eps, high + eps, regions, unsearched, band_lo, band_hi)
        return
    x_tip, x_far = (b, a) if fold.opens > 0 else (a, b)
    at_tip = [float(arm.y_at(np.array([x_tip]))[0]) for arm in pair]
    lower, upper = (pair[0], pair[1]) if at_tip[0] < at_tip[1] else (pair[1], pair[0])
    # a frame close around the lens (a contour far from the fold needs no fine sampling of the fold)
    margin = max(b - a, 10.0 * (high - low), 1e3 * eps)
    y_low, y_high = max(band_lo, low - margin), min(band_hi, high + margin)
    if y_low > band_lo:
        regions.append(Rectangle(a, b, band_lo, y_low))
    if y_high < band_hi:
        regions.append(Rectangle(a, b, y_high, band_hi))
    regions.append(TipCell(fold, lower, upper, x_tip, eps, True))
    regions.append(TipCell(fold, lower, upper, x_tip, eps, False, (x_far, y_low, y_high)))
    x0, x1 = sorted((float(fold.q.real) - fold.opens * eps, x_tip))
    unsearched.append(Sliver(x0, x1, min(at_tip) - eps, max(at_tip) + eps, 2 * eps))
