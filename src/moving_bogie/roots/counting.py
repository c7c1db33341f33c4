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
from moving_bogie.roots.contour import EdgeZeroError, Rectangle, winding_number, winding_numbers
from moving_bogie.roots.cut_cells import ColumnCell, Sliver
from moving_bogie.roots.search_regions import tile_window

__all__ = ["CountMismatch", "count_tiling", "frame"]


class CountMismatch(MovingBogieError):
    """The argument principle and the roots found disagree."""


#: Perturbations of the tiling tried in turn when an edge meets a root (eps factor, gap height fraction);
#: eps only shrinks, so the unsearched sliver never exceeds 2 eps.
_RETRIES = ((1.0, 0.1), (0.8, 0.113), (0.6, 0.087), (0.5, 0.121))
#: The gap height is that fraction of the window's size, up to this size: a window as large as a
#: far-field radius of 1e3 would otherwise make every column over the cut 2e2 high (and its edges long).
_GAP_SCALE = 10.0


def count_tiling(fast, params, window, eps, eps_branch, cut=None):
    """Tile the window and count the roots in every tile (``cut``: the window's :class:`CutLocus` if traced
    already, :func:`~moving_bogie.kernels.cut.cut_loci`).

    Recovery, in this order, when a contour cannot be placed (a root on or next to an edge, or an edge that
    cannot be resolved next to the cut):

    1. move all the edges (the tiles share them, so they move together) and count again, a few times;
    2. in the tiling with the fewest failures, split each failing tile (:meth:`split`, several fractions)
       and count the pieces, recursively: the piece that still fails shrinks around the trouble;
    3. a piece that still fails when ``_MAX_DEPTH`` splits deep is left out: it is listed with the
       unsearched slivers (its bounding box, with ``reason``), counted as 0 and named in the warnings,
       so the result says what was not searched (the verdict is UNDETERMINED when it reaches Im q < 0).

    Returns (cut, tiling, counts, warnings).
    """
    if cut is None:
        cut = cut_locus(params, window.x0, window.x1, foundation=fast.kernel.foundation)
    best = None
    for factor, fraction in _RETRIES:
        gap_height = fraction * min(max(window.width, window.height), _GAP_SCALE)
        tiling = tile_window(
            window, cut, eps=eps * factor, eps_branch=eps_branch * factor, gap_height=gap_height
        )
        counts, left_out, failed = _counts(fast, tiling.regions, eps * factor)
        if best is None or len(failed) < len(best[3]):
            best = (tiling, counts, left_out, failed, eps * factor)
        if not failed:
            break
    tiling, counts, left_out, failed, used_eps = best
    regions, counts, warnings = list(tiling.regions), list(counts), []
    for k in failed:
        pieces, piece_counts, lost = _recover(fast, regions[k], used_eps)
        regions[k], counts[k] = pieces, piece_counts
        for piece, error in lost:
            y0, y1 = piece.y0, piece.y1
            left_out.append(Sliver(piece.x0, piece.x1, y0, y1, y1 - y0, reason=str(error)))
            warnings.append(
                f"unsearched: the roots in {piece} ({piece.width:.1e} x {piece.height:.1e}) could not be "
                f"counted ({error})"
            )
    flat_regions, flat_counts = [], []
    for region, n in zip(regions, counts):
        if isinstance(region, list):
            flat_regions += region
            flat_counts += n
        else:
            flat_regions.append(region)
            flat_counts.append(n)
    tiling = dataclasses.replace(
        tiling, regions=tuple(flat_regions), unsearched=tiling.unsearched + tuple(left_out)
    )
    return cut, tiling, flat_counts, warnings


#: How many times a failing tile is split before the piece that still fails is left out.
_MAX_DEPTH = 8
_FRACTIONS = (0.5, 0.37, 0.63, 0.29)


def _recover(fast, region, eps):
    """Pieces of ``region`` that can be counted, their counts, and the (piece, error) left out."""
    pieces, counts, lost = [], [], []
    stack = [(region, 0, None)]
    while stack:
        r, depth, error = stack.pop()
        if depth >= _MAX_DEPTH:
            lost.append((r, error))
            continue
        for frac in _FRACTIONS:
            parts = r.split(frac)
            got, bad = [], []
            for part in parts:
                try:
                    got.append((part, winding_number(fast, part)))
                except EdgeZeroError as exc:
                    bad.append((part, exc))
            if len(bad) < len(parts):
                break
        else:  # no split gives a piece that can be counted: leave the whole of r out
            lost.append((r, bad[0][1]))
            continue
        for part, n in got:
            pieces.append(part)
            counts.append(n)
        stack.extend((part, depth + 1, exc) for part, exc in bad)
    return pieces, counts, lost


#: A cell between two cut curves thinner than this many eps (next to where they cross) whose count fails
#: is left out and reported with the sliver (its edges pass within eps of both curves, where the side of a
#: p-root is decided at rounding level).
_THIN = 10
#: A region smaller than _TINY whose count fails is left out the same way (at most that high); one smaller
#: than _SMALL gets a smaller budget of points (a count that needs more is a root on its edge).
_TINY = 1e-8
_SMALL = 1e-3


def _counts(fast, regions, eps):
    """Winding numbers of the regions (0 for a failing one), the thin cells left out (as slivers) whose
    count failed, and the indices of the other regions whose count failed. All regions are refined
    together (:func:`winding_numbers`)."""
    thin = [
        (isinstance(region, ColumnCell) and region.height < _THIN * eps)
        or max(region.width, region.height) < _TINY
        for region in regions
    ]
    small = [t or max(r.width, r.height) < _SMALL for t, r in zip(thin, regions)]
    results = winding_numbers(fast, regions, max_points=[20_000 if t else 400_000 for t in small])
    counts, left_out, failed = [], [], []
    for k, (region, result) in enumerate(zip(regions, results)):
        if not isinstance(result, EdgeZeroError):
            counts.append(result)
            continue
        counts.append(0)
        if not thin[k]:
            failed.append(k)
            continue
        y0, y1 = region.y0 - eps, region.y1 + eps
        left_out.append(Sliver(region.x0, region.x1, y0, y1, y1 - y0))
    return counts, left_out, failed


def frame(window: Rectangle, big: Rectangle) -> tuple:
    """``big`` minus ``window`` (same left edge): the strips below, above and to the right of it."""
    return (
        Rectangle(big.x0, big.x1, big.y0, window.y0),
        Rectangle(big.x0, big.x1, window.y1, big.y1),
        Rectangle(window.x1, big.x1, window.y0, window.y1),
    )
