"""Counting the roots of E_chr in a window tiled around the cut of K (step 1 of
:func:`~moving_bogie.roots.frequencies.induced_frequencies`).

The window is tiled into regions that never meet the cut (:mod:`~moving_bogie.roots.search_regions`) and the
argument principle counts the roots in each (:mod:`~moving_bogie.roots.contour`). A root on a shared edge
moves all the edges; a thin cell next to crossing cut curves whose count fails is left out and reported
with the unsearched sliver. :func:`frame` is the part of a window twice as large outside the window (the
check that no root lies just beyond it).
"""

from __future__ import annotations

import dataclasses

from moving_bogie.errors import MovingBogieError
from moving_bogie.kernels.cut import cut_locus
from moving_bogie.roots.contour import EdgeZeroError, Rectangle, winding_number
from moving_bogie.roots.cut_cells import ColumnCell, Sliver
from moving_bogie.roots.search_regions import tile_window

__all__ = ["CountMismatch", "count_tiling", "frame"]


class CountMismatch(MovingBogieError):
    """The argument principle and the roots found disagree."""


#: Perturbations of the tiling tried in turn when an edge meets a root (eps factor, gap height fraction);
#: eps only shrinks, so the unsearched sliver never exceeds 2 eps.
_RETRIES = ((1.0, 0.1), (0.8, 0.113), (0.6, 0.087), (0.5, 0.121))


def count_tiling(fast, params, window, eps, eps_branch):
    """Tile the window and count the roots in every tile; on a root sitting on an edge, move all the
    edges (the tiles share them, so they move together) and count again."""
    cut = cut_locus(params, window.x0, window.x1, foundation=fast.kernel.foundation)
    error = None
    for factor, fraction in _RETRIES:
        gap_height = fraction * max(window.width, window.height)
        tiling = tile_window(
            window, cut, eps=eps * factor, eps_branch=eps_branch * factor, gap_height=gap_height
        )
        try:
            counts, left_out = _counts(fast, tiling.regions, eps * factor)
        except EdgeZeroError as exc:
            error = exc
            continue
        if left_out:
            tiling = dataclasses.replace(tiling, unsearched=tiling.unsearched + tuple(left_out))
        return cut, tiling, counts
    raise CountMismatch(f"could not place contours away from the roots and the cut: {error}")


#: A cell between two cut curves thinner than this many eps (next to where they cross) whose count fails
#: is left out and reported with the sliver (its edges pass within eps of both curves, where the side of a
#: p-root is decided at rounding level).
_THIN = 10


def _counts(fast, regions, eps):
    """Winding numbers of the regions, and the thin cells left out (as slivers) whose count failed."""
    counts, left_out = [], []
    for region in regions:
        thin = isinstance(region, ColumnCell) and region.height < _THIN * eps
        try:
            counts.append(winding_number(fast, region, max_points=20_000 if thin else 400_000))
        except EdgeZeroError:
            if not thin:
                raise
            counts.append(0)
            y0, y1 = region.y0 - eps, region.y1 + eps
            left_out.append(Sliver(region.x0, region.x1, y0, y1, y1 - y0))
    return counts, left_out


def frame(window: Rectangle, big: Rectangle) -> tuple:
    """``big`` minus ``window`` (same left edge): the strips below, above and to the right of it."""
    return (
        Rectangle(big.x0, big.x1, big.y0, window.y0),
        Rectangle(big.x0, big.x1, window.y1, big.y1),
        Rectangle(window.x1, big.x1, window.y0, window.y1),
    )
