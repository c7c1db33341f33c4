"""Counting across the cut: E_chr continued analytically through the cut of K (a recovery of the search).

K(xi, q) of Eq. (29) sums the residues of the p-roots of N(p, q) on one side of the real p-axis, and the cut
of K is where one of them crosses it. Where the traced cut cannot be followed in double precision (next to
an avoided crossing of two cut curves q_j(p), where |dq/dp| reaches 1e4-1e5 and q(p) is good to 1e-11
only), a cell whose edges were meant to pass beside the cut can meet it, and its count fails. Such a cell is
counted here without placing any edge beside the cut:

1. The p-roots are followed along the cell's boundary (each matched to the nearest one of the previous
   sample, the loop closing on itself: no branch point of the roots inside). Im p_k is harmonic in q
   where p_k is analytic, so a root whose Im p keeps its sign along the boundary keeps it inside: the
   roots that may cross the real p-axis in the cell, the set C, are read off the boundary (those whose
   |Im p| comes within ``_SIDE_TOL`` of 0 there).
2. For every subset S of C, E_S is E_chr with the roots of S summed above the axis and those of C \\ S
   below (:class:`~moving_bogie.kernels.characteristic.ContinuedCharacteristic`): it is analytic in the
   whole cell, whatever the cut does inside, and equals E_chr where the roots of C lie on those sides.
   The argument principle counts its zeros on the cell's own boundary.
3. A root of E_chr in the cell is a zero of the E_S whose S is the set of roots of C above the axis
   there, and only those are: the zeros of each E_S are located (bisection and Newton, as in
   :mod:`locate`) and kept where the roots of C lie on the sides S says.

A cell where a root of C is not clearly the one nearest its reference, a zero of some E_S lies on the
cut itself, or a count fails, is not counted here (None): the search falls back to splitting it.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from typing import TypeAlias

import numpy as np

from moving_bogie.kernels.characteristic import CharacteristicArray, ContinuedCharacteristic
from moving_bogie.kernels.track import NEAREST
from moving_bogie.roots.count.contour import (
    BoundingBox,
    EdgeZeroError,
    Region,
    initial_samples,
    winding_numbers,
)
from moving_bogie.roots.refine.locate import LocatedCell, locate
from moving_bogie.typing import ComplexArray

__all__ = [
    "ContinuedRegion",
    "CountedRegion",
    "CrossingRoots",
    "count_continued",
    "crossing_roots",
    "touches_cut",
]

#: A p-root whose |Im p| comes within this (relative to max(1, |p|)) of 0 on the boundary may change side
#: inside: its side is fixed both ways. The edges beside the cut pass at 2e-11 from it, where the p-roots
#: have |Im p| ~ 2e-11 / |dq/dp|: every root near the cut is taken.
_SIDE_TOL = 1e-8
#: The edges beside the cut keep the p-roots at least about 1e-13 max(1, |p|) from the real axis
#: (:func:`~moving_bogie.kernels.cut.clearance`): a root closer than this on a boundary is on the cut.
_TOUCH = 1e-14
#: At most this many roots may change side in one cell (2^C continued functions are counted).
_MAX_CROSSING = 3
#: Along the boundary each root moves by less than this fraction of its distance to the others per sample.
_TRACK = 0.25
#: A zero of E_S whose root of C has |Im p| below this (relative) lies on the cut: its side is not decided.
_ON_CUT = 1e-13


@dataclass(frozen=True)
class ContinuedRegion(BoundingBox):
    """A search cell counted by continuation through the cut: its roots of E_chr are already located.

    ``region`` is the cell, ``count`` the roots of E_chr in it (with multiplicity), ``cells`` the located
    roots as :func:`~moving_bogie.roots.refine.locate.locate` returns them (q0, multiplicity, cell),
    ``crossing``
    how many p-roots had their side fixed.
    """

    region: Region
    count: int
    cells: tuple[LocatedCell, ...]
    crossing: int

    x0 = property(lambda self: self.region.x0)
    x1 = property(lambda self: self.region.x1)
    y0 = property(lambda self: self.region.y0)
    y1 = property(lambda self: self.region.y1)

    def __str__(self) -> str:
        return f"{self.region} (counted through the cut, {self.crossing} root(s) of N fixed)"


#: A region of a counted tiling: a search cell, or one counted through the cut.
CountedRegion: TypeAlias = Region | ContinuedRegion


@dataclass(frozen=True)
class CrossingRoots:
    """The p-roots that may cross the real p-axis in a region (the set C of the module docstring): a
    reference value of each (its mean along the boundary), ``refs``, and all the p-roots followed along
    the boundary, ``tracked`` (samples, degree)."""

    refs: ComplexArray
    tracked: ComplexArray


def _track(P: ComplexArray) -> ComplexArray | None:
    """The roots ``P`` (samples, degree) along a closed boundary reordered so that column k follows one root,
    or None where a step is not clear (a root moves more than ``_TRACK`` of its distance to the others) or
    the loop does not close on the same order."""
    if not np.all(np.isfinite(P)):
        return None
    out = np.empty_like(P)
    out[0] = P[0]
    deg = P.shape[1]
    for i in range(1, P.shape[0]):
        prev = out[i - 1]
        D = np.abs(prev[:, None] - P[i][None, :])
        match = np.argmin(D, axis=1)
        if np.unique(match).size != deg:
            return None
        sep = np.abs(prev[:, None] - prev[None, :]) + np.diag(np.full(deg, np.inf))
        if np.any(D[np.arange(deg), match] > _TRACK * sep.min(axis=1)):
            return None
        out[i] = P[i][match]
    scale = np.maximum(1.0, np.abs(out[0]))
    if np.any(np.abs(out[-1] - out[0]) > 1e-9 * scale):
        return None  # the roots come back permuted: a branch point of N's roots inside
    return out


def crossing_roots(fast: CharacteristicArray, region: Region) -> CrossingRoots | None:
    """The p-roots that may cross the real p-axis inside ``region`` (set C of the module docstring), or
    None when the roots cannot be followed along the boundary or a root of C is not clearly the nearest
    to its reference there."""
    tracked = _boundary_roots(fast, region)
    if tracked is None:
        return None
    C = np.nonzero(_near_axis(tracked, _SIDE_TOL) | _changes_side(tracked))[0]
    if C.size == 0 or C.size > _MAX_CROSSING:
        return None
    refs = tracked[:, C].mean(axis=0)
    for j, ref in zip(C, refs):
        own = np.abs(tracked[:, j] - ref)
        others = np.min(np.abs(np.delete(tracked, j, axis=1) - ref), axis=1)
        if np.any(own >= NEAREST * others):
            return None
    return CrossingRoots(refs, tracked)


def touches_cut(fast: CharacteristicArray, region: Region) -> bool:
    """Whether the boundary of ``region`` meets the cut of K: a p-root changes side along it, or comes
    closer to the real p-axis than the edges beside the cut let it (``_TOUCH``), or the roots cannot be
    followed along it."""
    tracked = _boundary_roots(fast, region)
    return tracked is None or bool(np.any(_changes_side(tracked) | _near_axis(tracked, _TOUCH)))


def _boundary_roots(fast: CharacteristicArray, region: Region) -> ComplexArray | None:
    """The p-roots at the first boundary samples of ``region``, followed along it (:func:`_track`)."""
    z, _ = initial_samples(region)
    return _track(fast.kernel.p_roots(z))


def _changes_side(tracked: ComplexArray) -> np.ndarray:
    """Per root followed along a boundary: above the real p-axis somewhere, on or below it elsewhere."""
    return np.any(tracked.imag > 0, axis=0) & np.any(tracked.imag <= 0, axis=0)


def _near_axis(tracked: ComplexArray, tol: float) -> np.ndarray:
    """Per root followed along a boundary: whether |Im p| comes within tol max(1, |p|) of 0 somewhere."""
    return np.any(np.abs(tracked.imag) <= tol * np.maximum(1.0, np.abs(tracked)), axis=0)


def count_continued(
    fast: CharacteristicArray, region: Region, newton_cell: float = 0.25
) -> ContinuedRegion | None:
    """Count and locate the roots of E_chr in ``region`` through the cut (module docstring).

    Returns a :class:`ContinuedRegion`, or None when the region cannot be counted this way.
    """
    found = crossing_roots(fast, region)
    if found is None:
        return None
    refs = found.refs
    subsets = list(itertools.product((False, True), repeat=refs.size))
    continued = [ContinuedCharacteristic(fast, refs, above) for above in subsets]
    results = [winding_numbers(f, [region])[0] for f in continued]
    counts = [n for n in results if not isinstance(n, EdgeZeroError)]
    if len(counts) < len(results):
        return None
    cells: list[LocatedCell] = []
    for f, above, n in zip(continued, subsets, counts):
        if n == 0:
            continue
        located, warning = locate(f, region, n, newton_cell)
        if warning is not None:
            return None
        for q0, mult, cell in located:
            sides = _natural_sides(fast, complex(q0), refs)
            if sides is None:
                return None  # a zero on the cut itself: its side is not decided here
            if sides == above:
                cells.append((q0, mult, cell))
    return ContinuedRegion(region, sum(m for _, m, _ in cells), tuple(cells), refs.size)


def _natural_sides(fast: CharacteristicArray, q: complex, refs: ComplexArray) -> tuple[bool, ...] | None:
    """Whether each root of N nearest to ``refs`` lies above the real p-axis at ``q`` (a tuple of bools),
    None if one of them lies on it (within ``_ON_CUT``)."""
    P = fast.kernel.p_roots(np.array([q]))[0]
    out: list[bool] = []
    for ref in refs:
        p = P[np.argmin(np.abs(P - ref))]
        if abs(p.imag) <= _ON_CUT * max(1.0, abs(p)):
            return None
        out.append(bool(p.imag > 0))
    return tuple(out)
