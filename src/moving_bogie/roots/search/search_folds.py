"""The column around a fold of the cut: two tip cells (or a box), for :mod:`search_regions`.

A fold where two arms of one curve meet gets an inner tip cell (inside the lens) and an outer one (framed
around it); other curves passing through the fold's box narrow its column (:func:`fold_event`), or are left
out with it; curves above or below get ordinary column cells (:mod:`search_columns`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from moving_bogie.kernels.cut import CutArm, CutLocus, arms_y_at
from moving_bogie.kernels.cut_curves import Fold
from moving_bogie.roots.count.contour import Rectangle, Region
from moving_bogie.roots.search.cut_cells import Sliver, TipCell
from moving_bogie.roots.search.search_columns import COLUMN_SAMPLES, arms_over, box, column

__all__ = ["fold_event"]


def _ends_at(arm: CutArm, fold: Fold) -> bool:
    """Whether ``arm`` starts or ends at ``fold`` (same p and same q: curves may share their end p)."""
    tol = 1e-9 * (1.0 + abs(fold.q))
    return any(abs(arm.p[k] - fold.p) < 1e-12 and abs(arm.q[k] - fold.q) < tol for k in (0, -1))


def fold_event(
    cut: CutLocus,
    a: float,
    b: float,
    fold: Fold,
    regions: list[Region],
    unsearched: list[Sliver],
    eps: float,
    band_lo: float,
    band_hi: float,
) -> None:
    """The column [a, b] around a fold (two tip cells) or a cusp (a box left unsearched).

    Where another curve of the cut passes through the fold's lens or close to it inside [a, b] (a steep
    arm beside the fold, or one crossing an arm of the lens), the fold's column is narrowed around the
    fold until none does (the lens is about sqrt(Re q - fold) wide there, the other curve a fixed distance
    away), and ordinary columns (:func:`~moving_bogie.roots.search.search_columns.column`, which split at
    crossings) fill the rest of [a, b]: the box that this curve would otherwise force around the whole
    column is not left out.
    """
    if not fold.cusp:
        narrow = _clear_column(cut, a, b, fold, eps)
        if narrow != (a, b):
            if narrow[0] > a:
                column(cut, a, narrow[0], regions, unsearched, eps, band_lo, band_hi)
            _fold_column(cut, narrow[0], narrow[1], fold, regions, unsearched, eps, band_lo, band_hi)
            if narrow[1] < b:
                column(cut, narrow[1], b, regions, unsearched, eps, band_lo, band_hi)
            return
    _fold_column(cut, a, b, fold, regions, unsearched, eps, band_lo, band_hi)


#: Each narrowing of a fold's column divides its half-width by this, down to _SMALLEST_TIP eps.
_SHRINK = 4.0
_SMALLEST_TIP = 500.0


def _clear_column(cut: CutLocus, a: float, b: float, fold: Fold, eps: float) -> tuple[float, float]:
    """[a, b], or the narrower column around ``fold`` in which no other curve passes through its box.

    Unchanged when nothing passes through, when a curve only partly crosses [a, b] (it ends next to the
    fold: the box stays) or the fold is not the meeting point of two arms.
    """
    near = _fold_neighbours(cut, a, b, fold, eps)
    if not near.through or near.partial or len(near.pair) != 2:
        return a, b
    x_f = float(fold.q.real)
    half = max(x_f - a, b - x_f)
    smallest = _SMALLEST_TIP * eps * max(1.0, abs(x_f))
    lo, hi = a, b
    while near.through and half / _SHRINK >= smallest:
        half /= _SHRINK
        lo, hi = max(a, x_f - half), min(b, x_f + half)
        near = _fold_neighbours(cut, lo, hi, fold, eps)
        if near.partial:
            return a, b
    return lo, hi


@dataclass(frozen=True)
class _FoldNeighbours:
    """The arms around a fold in its column: the ``pair`` meeting at the fold, the ``others`` crossing the
    whole column, those crossing only part of it (``partial``), the curves that pass ``through`` the
    fold's box (within 8 eps of the Im range of the pair), and the box's Im range ``low``..``high``."""

    pair: list[CutArm]
    others: list[CutArm]
    partial: list[CutArm]
    through: list[CutArm]
    low: float
    high: float


def _fold_neighbours(cut: CutLocus, a: float, b: float, fold: Fold, eps: float) -> _FoldNeighbours:
    """The :class:`_FoldNeighbours` of the fold's column [a, b]."""
    pair = [arm for arm in cut.arms if _ends_at(arm, fold)]
    full = arms_over(cut, a, b)
    others = [arm for arm in full if all(arm is not x for x in pair)]
    partial = [
        arm
        for arm in cut.arms
        if arm.x_lo < b
        and arm.x_hi > a
        and all(arm is not x for x in full)
        and all(arm is not x for x in pair)
    ]
    xs = np.linspace(a, b, COLUMN_SAMPLES)
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
    return _FoldNeighbours(pair, others, partial, through, low, high)


def _fold_column(
    cut: CutLocus,
    a: float,
    b: float,
    fold: Fold,
    regions: list[Region],
    unsearched: list[Sliver],
    eps: float,
    band_lo: float,
    band_hi: float,
) -> None:
    """The column [a, b] around a fold: two tip cells, or a box (a cusp, an end of the cut, or curves
    passing through the fold's box).

    The lens of the fold opens towards larger Re q (``fold.opens`` = +1: its tip cells reach Re q = b) or
    towards smaller Re q (-1: they reach a). Curves of the cut that only partly cross the column, or pass
    through the fold's box, are left out with it; the outer tip cell is framed closely around the lens and
    rectangles fill the column above and below the frame.
    """
    near = _fold_neighbours(cut, a, b, fold, eps)
    pair, others, through, low, high = near.pair, near.others, near.through, near.low, near.high
    xs = np.linspace(a, b, COLUMN_SAMPLES)
    spans = dict(zip(map(id, others), arms_y_at(others, xs))) if others else {}
    below = [arm for arm in others if arm not in through and spans[id(arm)].max() < low]
    above = [arm for arm in others if arm not in through and spans[id(arm)].min() > high]
    # other curves passing above or below the fold get ordinary column cells there
    if below:
        top = max(float(arm.y_at(xs).max()) for arm in below)
        split = 0.5 * (top + low)
        column(cut, a, b, regions, unsearched, eps, band_lo, split, below)
        band_lo = split
    if above:
        bottom = min(float(arm.y_at(xs).min()) for arm in above)
        split = 0.5 * (bottom + high)
        column(cut, a, b, regions, unsearched, eps, split, band_hi, above)
        band_hi = split
    if fold.cusp or len(pair) != 2 or through:  # a box around the fold (cusp, end)
        box(a, b, low - eps, high + eps, regions, unsearched, band_lo, band_hi)
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
    tips = (
        TipCell(fold, lower, upper, x_tip, eps, True),
        TipCell(fold, lower, upper, x_tip, eps, False, (x_far, y_low, y_high)),
    )
    regions.extend(tips)
    x0, x1 = sorted((float(fold.q.real) - fold.opens * eps, x_tip))
    d = max(arm.clearance(np.linspace(max(a, arm.x_lo), min(b, arm.x_hi), 9), eps) for arm in pair)
    frame = Rectangle(a, b, y_low, y_high)  # the two tip cells and the band around the lens between them
    unsearched.append(Sliver(x0, x1, min(at_tip) - d, max(at_tip) + d, 2 * d, cell=frame, covers=tips))
