"""Counting the roots of E_chr in a window tiled around the cut of K (step 1 of
:func:`~moving_bogie.roots.frequencies.induced_frequencies`).

The window is tiled into regions that never meet the cut (:mod:`~moving_bogie.roots.search.search_regions`)
and the
argument principle counts the roots in each (:mod:`~moving_bogie.roots.count.contour`). A root on a shared
edge
moves all the edges; a thin cell next to crossing cut curves whose count fails is left out and reported
with the unsearched sliver. :func:`frame` is the part of a window twice as large outside the window (the
check that no root lies just beyond it).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from dataclasses import dataclass

from moving_bogie.errors import MovingBogieError
from moving_bogie.kernels.bound import BoundModel
from moving_bogie.kernels.characteristic import CharacteristicArray
from moving_bogie.kernels.cut import CutLocus, cut_locus
from moving_bogie.roots.count.contour import (
    EdgeZeroError,
    Rectangle,
    Region,
    piece_points,
    winding_number,
    winding_numbers,
)
from moving_bogie.roots.count.outcomes import Note, Reason
from moving_bogie.roots.search.continuation import (
    ContinuedRegion,
    CountedRegion,
    count_continued,
    touches_cut,
)
from moving_bogie.roots.search.cut_cells import ColumnCell, Sliver
from moving_bogie.roots.search.search_regions import Tiling, tile_window

__all__ = ["CountMismatch", "TilingCount", "count_tiling", "frame"]


class CountMismatch(MovingBogieError):
    """The argument principle and the roots found disagree."""


@dataclass(frozen=True)
class TilingCount:
    """The window tiled and counted: ``counts[k]`` roots in ``tiling.regions[k]``; ``notes`` say which
    regions were left out (:attr:`~moving_bogie.roots.count.outcomes.Reason.UNSEARCHED`)."""

    cut: CutLocus
    tiling: Tiling
    counts: tuple[int, ...]
    notes: tuple[Note, ...]


@dataclass(frozen=True)
class _Attempt:
    """One tiling tried (edges at ``eps``): its regions, their counts, the cells left out, the failures."""

    tiling: Tiling
    regions: list[CountedRegion]
    counts: list[int]
    left_out: list[Sliver]
    failed: list[int]
    eps: float


@dataclass(frozen=True)
class _Recovery:
    """What the recovery of one failing tile gives: the ``pieces`` counted and their ``counts``, and the
    pieces ``lost`` (left out) with the error of their last count."""

    pieces: tuple[CountedRegion, ...]
    counts: tuple[int, ...]
    lost: tuple[tuple[Region, EdgeZeroError | None], ...]


@dataclass
class _Budget:
    """What the recoveries of all failing tiles of one tiling share: the evaluations when they began, and
    the pieces counted so far."""

    since: int
    splits: int = 0


#: Perturbations of the tiling tried in turn when an edge meets a root (eps factor, gap height fraction);
#: eps only shrinks, so the unsearched sliver never exceeds 2 eps.
_RETRIES = ((1.0, 0.1), (0.8, 0.113), (0.6, 0.087), (0.5, 0.121))
#: The gap height is that fraction of the window's size, up to this size: a window as large as a
#: far-field radius of 1e3 would otherwise make every column over the cut 2e2 high (and its edges long).
_GAP_SCALE = 10.0


def count_tiling(
    fast: CharacteristicArray,
    bound: BoundModel,
    window: Rectangle,
    eps: float,
    eps_branch: float,
    cut: CutLocus | None = None,
    newton_cell: float = 0.25,
) -> TilingCount:
    """Tile the window and count the roots in every tile (``cut``: the window's :class:`CutLocus` if traced
    already, :func:`~moving_bogie.kernels.cut.cut_loci`).

    Recovery, in this order, when a contour cannot be placed (a root on or next to an edge, or an edge that
    cannot be resolved next to the cut):

    1. move all the edges (the tiles share them, so they move together) and count again, a few times,
       unless every failing tile meets the cut (a p-root on the real axis on its boundary, where the
       traced cut is not good enough): moving the edges does not help there;
    2. in the tiling with the fewest failures, split each failing tile (:meth:`split`, several fractions)
       and count the pieces, recursively: the piece that still fails shrinks around the trouble;
    3. a piece that still fails when ``_MAX_DEPTH`` splits deep is left out: it is listed with the
       unsearched slivers (its bounding box, with ``reason``), counted as 0 and named in the warnings,
       so the result says what was not searched (the verdict is UNDETERMINED when it reaches Im q < 0).

    Before 1 and 2, a failing tile is counted through the cut (:mod:`continuation`: E_chr continued
    analytically across it, so no edge has to pass beside the cut); such a tile comes back as a
    :class:`~moving_bogie.roots.search.continuation.ContinuedRegion` with its roots located (``newton_cell``
    as in :func:`~moving_bogie.roots.refine.locate.locate`).

    Returns the :class:`TilingCount`.
    """
    if cut is None:
        cut = cut_locus(bound, window.x0, window.x1)
    best = None
    for factor, fraction in _RETRIES:
        gap_height = fraction * min(max(window.width, window.height), _GAP_SCALE)
        tiling = tile_window(
            window, cut, eps=eps * factor, eps_branch=eps_branch * factor, gap_height=gap_height
        )
        cells = _search_cells(tiling)
        counts, left_out, failed = _counts(fast, cells, eps * factor)
        regions: list[CountedRegion] = list(cells)
        failed = _through_cut(fast, regions, counts, failed, newton_cell)
        if best is None or len(failed) < len(best.failed):
            best = _Attempt(tiling, regions, counts, left_out, failed, eps * factor)
        if not failed or all(touches_cut(fast, cells[k]) for k in failed):
            break  # moving the edges does not move the cut: split those tiles instead
    assert best is not None  # _RETRIES is not empty
    tiling, regions, counts, left_out = best.tiling, best.regions, best.counts, best.left_out
    notes = []
    budget = _Budget(since=fast.evaluations)
    recovered: dict[int, _Recovery] = {}
    for k in best.failed:
        region = regions[k]
        assert not isinstance(region, ContinuedRegion)  # a region counted through the cut did not fail
        recovered[k] = recovery = _recover(fast, region, best.eps, newton_cell, budget)
        for piece, error in recovery.lost:
            y0, y1 = piece.y0, piece.y1
            left_out.append(Sliver(piece.x0, piece.x1, y0, y1, y1 - y0, reason=str(error)))
            notes.append(
                Note(
                    Reason.UNSEARCHED,
                    f"the roots in {piece} ({piece.width:.1e} x {piece.height:.1e}) could not be counted "
                    f"({error})",
                )
            )
    flat_regions: list[CountedRegion] = []
    flat_counts: list[int] = []
    for k, (region, n) in enumerate(zip(regions, counts)):
        if k in recovered:
            flat_regions += recovered[k].pieces
            flat_counts += recovered[k].counts
        else:
            flat_regions.append(region)
            flat_counts.append(n)
    unsearched = _bands_through_cut(fast, tiling.unsearched, flat_regions, flat_counts, newton_cell)
    tiling = dataclasses.replace(tiling, regions=tuple(flat_regions), unsearched=unsearched + tuple(left_out))
    return TilingCount(cut, tiling, tuple(flat_counts), tuple(notes))


def _search_cells(tiling: Tiling) -> list[Region]:
    """The regions of a tiling just made (none of them counted through the cut yet)."""
    cells = [r for r in tiling.regions if not isinstance(r, ContinuedRegion)]
    assert len(cells) == len(tiling.regions)
    return cells


#: A band left out around the cut taller than this (next to an avoided crossing of two cut curves, where
#: its edges keep a wide clearance) is counted through the cut instead (:func:`count_continued`).
BAND_THROUGH_CUT = 5e-9


def _bands_through_cut(
    fast: CharacteristicArray,
    unsearched: Sequence[Sliver],
    regions: list[CountedRegion],
    counts: list[int],
    newton_cell: float,
) -> tuple[Sliver, ...]:
    """Count the tall bands of ``unsearched`` through the cut: each one counted is dropped from the list,
    its region (with the cells it covers replaced) added to ``regions`` and ``counts``; returns the rest."""
    rest = []
    for sliver in unsearched:
        if sliver.height <= BAND_THROUGH_CUT or sliver.cell is None or sliver.reason:
            rest.append(sliver)
            continue
        found = [_position(regions, c) for c in sliver.covers]
        at = [k for k in found if k is not None]
        if len(at) < len(found):  # a covered cell was split or counted otherwise: leave the band as it is
            rest.append(sliver)
            continue
        continued = count_continued(fast, sliver.cell, newton_cell)
        if continued is None:
            rest.append(sliver)
            continue
        for k in sorted(at, reverse=True):
            del regions[k], counts[k]
        regions.append(continued)
        counts.append(continued.count)
    return tuple(rest)


def _through_cut(
    fast: CharacteristicArray,
    regions: list[CountedRegion],
    counts: list[int],
    failed: list[int],
    newton_cell: float,
) -> list[int]:
    """Count the ``failed`` regions through the cut where that works (replacing them in ``regions`` and
    ``counts``); returns the indices that still fail."""
    rest = []
    for k in failed:
        region = regions[k]
        assert not isinstance(region, ContinuedRegion)  # only the tiling's own cells fail
        continued = count_continued(fast, region, newton_cell)
        if continued is None:
            rest.append(k)
        else:
            regions[k], counts[k] = continued, continued.count
    return rest


def _position(regions: Sequence[CountedRegion], cell: Region) -> int | None:
    """The index of ``cell`` in ``regions`` (itself, or counted through the cut), None if it is not there."""
    for k, r in enumerate(regions):
        if r is cell or (isinstance(r, ContinuedRegion) and r.region is cell):
            return k
    return None


#: How many times a failing tile is split before the piece that still fails is left out.
_MAX_DEPTH = 8
_FRACTIONS = (0.5, 0.37, 0.63, 0.29)
#: Evaluations of E_chr the recoveries of one tiling may spend (a few seconds); the pieces still to be
#: split then are left out with the others.
_RECOVERY_POINTS = 1_000_000
#: ... and at most this many pieces (tiny pieces cost little each but many calls).
_RECOVERY_SPLITS = 200


def _recover(
    fast: CharacteristicArray, region: Region, eps: float, newton_cell: float, budget: _Budget
) -> _Recovery:
    """Pieces of ``region`` that can be counted, their counts, and the (piece, error) left out. A piece
    that fails is first counted through the cut (:func:`count_continued`), then split; once the
    recoveries of the tiling (``budget``: the evaluations when they began, the pieces so far) have spent
    ``_RECOVERY_POINTS`` evaluations or ``_RECOVERY_SPLITS`` pieces, what is left is left out."""
    pieces: list[CountedRegion] = []
    counts: list[int] = []
    lost: list[tuple[Region, EdgeZeroError | None]] = []
    stack: list[tuple[Region, int, EdgeZeroError | None]] = [(region, 0, None)]
    while stack:
        r, depth, error = stack.pop()
        budget.splits += 1
        if fast.evaluations - budget.since > _RECOVERY_POINTS or budget.splits > _RECOVERY_SPLITS:
            lost.append((r, EdgeZeroError(f"{error}; the recovery spent its budget")))
            continue
        continued = count_continued(fast, r, newton_cell) if depth else None  # depth 0: tried already
        if continued is not None:
            pieces.append(continued)
            counts.append(continued.count)
            continue
        if depth >= _MAX_DEPTH:
            lost.append((r, error))
            continue
        for frac in _FRACTIONS:
            parts = r.split(frac)
            got: list[tuple[Region, int]] = []
            bad: list[tuple[Region, EdgeZeroError]] = []
            for part in parts:
                try:
                    got.append((part, winding_number(fast, part, max_points=piece_points(part))))
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
    return _Recovery(tuple(pieces), tuple(counts), tuple(lost))


#: A cell between two cut curves thinner than this many eps (next to where they cross) whose count fails
#: is left out and reported with the sliver (its edges pass within eps of both curves, where the side of a
#: p-root is decided at rounding level).
_THIN = 10
#: A region smaller than _TINY whose count fails is left out the same way (at most that high); one smaller
#: than _SMALL gets a smaller budget of points (a count that needs more is a root on its edge).
_TINY = 1e-8
_SMALL = 1e-3


def _counts(
    fast: CharacteristicArray, regions: Sequence[Region], eps: float
) -> tuple[list[int], list[Sliver], list[int]]:
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
    counts: list[int] = []
    left_out: list[Sliver] = []
    failed: list[int] = []
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


def frame(window: Rectangle, big: Rectangle) -> tuple[Rectangle, Rectangle, Rectangle]:
    """``big`` minus ``window`` (same left edge): the strips below, above and to the right of it."""
    return (
        Rectangle(big.x0, big.x1, big.y0, window.y0),
        Rectangle(big.x0, big.x1, window.y1, big.y1),
        Rectangle(window.x1, big.x1, window.y0, window.y1),
    )
