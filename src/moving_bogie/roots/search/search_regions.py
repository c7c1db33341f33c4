"""Tiling of the search window into regions that never meet the cut of K.

The window is cut into: everything below the band of the cut, everything above it, the gap left of the
cut's leftmost point (where K is analytic across the cut's line, so undamped real roots lie strictly
inside), and, over the cut, cells whose edges follow the traced cut curves at the distance ``eps``
(:mod:`cut_cells`): below the lowest curve, between curves (the lens that opens at a fold of the
Timoshenko-Rayleigh cut), above the highest, and two cells around each fold. What is left unsearched is
the band of half-width ``eps`` around the cut (height 2 eps at every Re q; more where q moves fast with
p, :func:`~moving_bogie.kernels.cut.clearance`) and, at a cusp of the cut (the
branch point of K, Euler-Bernoulli), a box of half-width ``eps_branch``: roots there are within that
distance of the cut; the result lists those slivers with their height.

Folds get tip cells whichever way their lens opens. Where the traced curves cannot be followed (two
curves crossing or closer than 4 eps inside a column), the column falls back to a padded strip around the
cut's range in it, and the sliver reported there is that strip's height.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from moving_bogie.kernels.cut import CutLocus
from moving_bogie.kernels.cut_curves import Fold
from moving_bogie.roots.count.contour import Rectangle, Region
from moving_bogie.roots.search.cut_cells import Sliver
from moving_bogie.roots.search.search_columns import fill_columns
from moving_bogie.roots.search.search_folds import fold_event

if TYPE_CHECKING:
    from moving_bogie.roots.search.continuation import CountedRegion

__all__ = ["Tiling", "tile_window"]


@dataclass(frozen=True)
class Tiling:
    """The ``regions`` to count in (Rectangles and curved cells; once counted, some of them counted
    through the cut) and the ``unsearched`` slivers around the cut."""

    regions: tuple[CountedRegion, ...]
    unsearched: tuple[Sliver, ...]


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
    regions: list[Region] = []
    if band_lo > window.y0:
        regions.append(Rectangle(window.x0, window.x1, window.y0, band_lo))
    if band_hi < window.y1:
        regions.append(Rectangle(window.x0, window.x1, band_hi, window.y1))
    if cut.flat or not cut.arms:
        return _flat(window, cut, regions, eps, eps_branch, band_lo, band_hi)
    return _curved(window, cut, regions, eps, eps_branch, band_lo, band_hi, curved_columns)


def _flat(
    window: Rectangle,
    cut: CutLocus,
    regions: list[Region],
    eps: float,
    eps_branch: float,
    band_lo: float,
    band_hi: float,
) -> Tiling:
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
    unsearched: list[Sliver] = []
    b_lo, b_hi = max(band_lo, cut.im_low - eps_branch), min(band_hi, cut.im_high + eps_branch)
    x = x_band
    ends: list[float | None] = [*cusps, None]
    for c in ends:
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


def _curved(
    window: Rectangle,
    cut: CutLocus,
    regions: list[Region],
    eps: float,
    eps_branch: float,
    band_lo: float,
    band_hi: float,
    columns: int,
) -> Tiling:
    """The band over a curved cut: columns of cells between the folds, and the columns around them."""
    unsearched: list[Sliver] = []
    folds = sorted((f for f in cut.folds if window.x0 < f.q.real < window.x1), key=lambda f: f.q.real)
    # event intervals around folds (tip cells) and cusps (branch-point boxes)
    events: list[tuple[float, float, Fold]] = []
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

    def fill(x0: float, x1: float) -> None:
        fill_columns(cut, x0, x1, regions, unsearched, eps, band_lo, band_hi, density)

    edges_x = [x_band]
    for lo, hi, f in events:
        if hi <= edges_x[-1] or lo >= window.x1:
            continue
        if lo > edges_x[-1]:
            fill(edges_x[-1], lo)
        x0, x1 = max(lo, edges_x[-1]), min(hi, window.x1)
        fold_event(cut, x0, x1, f, regions, unsearched, eps, band_lo, band_hi)
        edges_x.append(x1)
    if edges_x[-1] < window.x1:
        fill(edges_x[-1], window.x1)
    return Tiling(tuple(regions), tuple(unsearched))
