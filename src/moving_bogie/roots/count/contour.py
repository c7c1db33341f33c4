"""Counting zeros of an analytic function in a rectangle by the argument principle.

The number of zeros inside a closed contour on which f is analytic and non-zero equals the winding number
of f along it, (1/2 pi) times the total change of arg f. The change is accumulated over a sampled boundary
that is refined until every step of arg f is below ``max_step`` (a zero next to the boundary shows up as
steps that stay large however fine the sampling: that raises :class:`EdgeZeroError`, so the caller can
move the edge instead of returning a wrong count).
"""

from __future__ import annotations

import weakref
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Protocol, runtime_checkable

import numpy as np
import numpy.typing as npt

from moving_bogie.roots.count.lattice import NEAR, STEP, lattice_boundary
from moving_bogie.typing import ComplexArray, FloatArray

_SUBDIVIDE = 8  # pieces a segment whose arg step is too large is cut into
#: Initial sampling step along a boundary within |q| <= _NEAR of the origin; beyond, it grows like |q|
#: (``_SPACING |q| / _NEAR``: a relative resolution of 5e-4), see :func:`initial_samples`.
_SPACING = STEP
_NEAR = NEAR


#: A segment shorter than this many units in the last place of its end points cannot be refined further
#: in double precision (its midpoints round to its ends): a cell whose size times ``min_segment`` is
#: below that (a thin cell next to a crossing of cut curves) stops refining there, not after thousands of
#: refinement levels that do not move.
_ULPS = 64


def _resolution(z: ComplexArray, shortest: float | FloatArray) -> FloatArray:
    """The shortest segment worth refining at ``z``: ``shortest``, or the double-precision floor there."""
    return np.maximum(shortest, _ULPS * np.finfo(float).eps * np.maximum(1.0, np.abs(z)))


#: A piece of a split region (recovery, locating) smaller than this gets ``_PIECE_POINTS[0]`` boundary
#: points at most, a larger one ``_PIECE_POINTS[1]``: a count that needs more has a zero on its edge.
_SMALL_PIECE = 1e-3
_PIECE_POINTS = (20_000, 100_000)


def piece_points(region: Region) -> int:
    """The most boundary points a piece of a split region may take (``max_points`` of the winding numbers)."""
    return _PIECE_POINTS[0] if max(region.width, region.height) < _SMALL_PIECE else _PIECE_POINTS[1]


class EdgeZeroError(RuntimeError):
    """A zero lies on (or within sampling resolution of) the contour."""


class BoundingBox:
    """Width, height and centre of a search region from its bounds x0, x1, y0, y1."""

    x0: float
    x1: float
    y0: float
    y1: float

    @property
    def width(self) -> float:
        return self.x1 - self.x0

    @property
    def height(self) -> float:
        return self.y1 - self.y0

    @property
    def center(self) -> complex:
        return complex(0.5 * (self.x0 + self.x1), 0.5 * (self.y0 + self.y1))


class Region(Protocol):
    """A search region as counting and locating use it: a :class:`Rectangle` or a curved cell
    (:mod:`~moving_bogie.roots.search.cut_cells`), with its bounds, the points it contains, its pieces
    (:meth:`split`) and its closed boundary. A curved cell also has ``points_at`` and
    ``boundary_parameters``, by which its boundary is refined along the curve itself."""

    @property
    def x0(self) -> float: ...

    @property
    def x1(self) -> float: ...

    @property
    def y0(self) -> float: ...

    @property
    def y1(self) -> float: ...

    @property
    def width(self) -> float: ...

    @property
    def height(self) -> float: ...

    @property
    def center(self) -> complex: ...

    def contains(self, z: complex, margin: float = 0.0) -> bool: ...

    def split(self, fraction: float = 0.5) -> tuple[Region, ...]: ...

    def boundary(self, spacing: float) -> ComplexArray: ...


@runtime_checkable
class CurvedRegion(Region, Protocol):
    """A region whose boundary is a curve t -> z (:class:`~moving_bogie.roots.search.cut_cells.ColumnCell`,
    ``TipCell``): its boundary parameters about ``spacing`` apart, and the points at parameters ``t``."""

    def boundary_parameters(self, spacing: float) -> FloatArray: ...

    def points_at(self, t: FloatArray) -> ComplexArray: ...


#: A function counted on a contour: complex arrays to complex arrays (E_chr batched, Eq. (48)).
ContourFunction = Callable[[ComplexArray], ComplexArray]


@dataclass(frozen=True)
class Rectangle(BoundingBox):
    x0: float
    x1: float
    y0: float
    y1: float

    def contains(self, z: complex, margin: float = 0.0) -> bool:
        return (self.x0 - margin <= z.real <= self.x1 + margin) and (
            self.y0 - margin <= z.imag <= self.y1 + margin
        )

    def split(self, fraction: float = 0.5) -> tuple[Rectangle, Rectangle]:
        """Two halves across the longer side, the cut at ``fraction`` of it."""
        if self.width >= self.height:
            xm = self.x0 + fraction * self.width
            return Rectangle(self.x0, xm, self.y0, self.y1), Rectangle(xm, self.x1, self.y0, self.y1)
        ym = self.y0 + fraction * self.height
        return Rectangle(self.x0, self.x1, self.y0, ym), Rectangle(self.x0, self.x1, ym, self.y1)

    def boundary(self, spacing: float, least: int = 8) -> ComplexArray:
        """Counter-clockwise closed polyline, each edge sampled at about ``spacing`` (at least ``least``
        points)."""
        corners = [
            complex(self.x0, self.y0),
            complex(self.x1, self.y0),
            complex(self.x1, self.y1),
            complex(self.x0, self.y1),
        ]
        pieces = []
        for a, b in zip(corners, corners[1:] + corners[:1]):
            n = max(least, int(np.ceil(abs(b - a) / spacing)))
            pieces.append(a + (b - a) * np.arange(n) / n)
        pts = np.concatenate(pieces)
        return np.append(pts, pts[0])


#: The default :func:`initial_samples` of the curved regions alive (keyed by the region itself).
_CURVED_SAMPLES: weakref.WeakKeyDictionary[Region, tuple[ComplexArray, FloatArray]] = (
    weakref.WeakKeyDictionary()
)


def _local_step(z: ComplexArray) -> FloatArray:
    return _SPACING * np.maximum(1.0, np.abs(z) / _NEAR)


def initial_samples(region: Region, spacing: float | None = None) -> tuple[ComplexArray, FloatArray]:
    """(z, t): the first samples of the closed boundary of ``region`` (z[-1] = z[0]) and their boundary
    parameters (those of a curved cell, ``points_at``; indices for a rectangle).

    With ``spacing``, uniform at that step. By default 1/64 of the longer side, then every segment longer
    than the local step ``_SPACING max(1, |q| / _NEAR)`` is cut into ``_SUBDIVIDE`` pieces (repeatedly):
    0.005 within |q| <= 10, where the vehicle's and the beam's induced frequencies lie, a relative
    resolution of 5e-4 farther out, where E_chr approaches its leading part (:mod:`far_field`) and its
    roots are the sequence along the real axis of a Timoshenko-Rayleigh beam, a few units of Re q apart.
    A huge window (the far-field radius of such a beam reaches 1e3) then costs 1e5 samples, not 1e7.
    A rectangle within |q| <= 10 takes the same bounds on the lattice of :mod:`lattice` instead (points it
    shares with other rectangles along a common line). A curved cell's default samples are computed once
    and kept while the cell lives (read-only): its boundary points are Newton solves on the cut, and the
    counts of one tiling (recounts, locating, checks against it) sample the same cells again.
    """
    if spacing is None and getattr(region, "points_at", None) is not None:  # before the slower isinstance
        kept = _CURVED_SAMPLES.get(region)
        if kept is not None:
            return kept
    curved = region if isinstance(region, CurvedRegion) else None
    if spacing is None and curved is not None:
        z, t = kept = _CURVED_SAMPLES[curved] = _samples(region, None, curved)
        z.flags.writeable = t.flags.writeable = False  # shared by every count of the cell
        return kept
    return _samples(region, spacing, curved)


def _samples(
    region: Region, spacing: float | None, curved: CurvedRegion | None
) -> tuple[ComplexArray, FloatArray]:
    """:func:`initial_samples`, computed (``curved``: ``region`` if it is a curved cell, else None)."""
    if spacing is None and type(region) is Rectangle:
        lattice = lattice_boundary(region.x0, region.x1, region.y0, region.y1)
        if lattice is not None:  # near the origin, on the lattice other rectangles share
            return lattice, np.arange(lattice.size, dtype=float)
    size = max(region.width, region.height)
    step = spacing or size / 64
    if curved is not None:
        t = curved.boundary_parameters(step)
        z = np.append(curved.points_at(t[:-1]), 0)
        z[-1] = z[0]
    else:
        z = region.boundary(step)
        t = np.arange(z.size, dtype=float)
    for _ in range(8 if spacing is None else 0):
        za, zb, ta, tb = z[:-1], z[1:], t[:-1], t[1:]
        pieces = np.ceil(np.abs(zb - za) / _local_step(0.5 * (za + zb)) * (1 - 1e-12)).astype(int)
        pieces = np.maximum(pieces, 1)
        if np.all(pieces == 1):
            break
        # every segment's start, then its interior points at fractions k / pieces
        owner = np.repeat(np.arange(za.size), pieces)
        k = np.arange(owner.size) - np.repeat(np.cumsum(pieces) - pieces, pieces)
        u = k / pieces[owner]
        t_new = ta[owner] + u * (tb - ta)[owner]
        if curved is not None:
            z_new = np.where(k == 0, za[owner], curved.points_at(t_new))
        else:
            z_new = za[owner] + u * (zb - za)[owner]
        z, t = np.append(z_new, z[-1]), np.append(t_new, t[-1])
    return z, t


def winding_number(
    f: ContourFunction,
    rect: Region,
    *,
    spacing: float | None = None,
    max_step: float = np.pi / 5,
    min_segment: float = 1e-11,
    max_points: int = 400_000,
) -> int:
    """Number of zeros of ``f`` (vectorised over numpy arrays) inside ``rect``.

    Parameters
    ----------
    f : callable
        Analytic and non-zero on the boundary; takes and returns complex arrays.
    spacing : float, optional
        Uniform initial sampling step (default: :func:`initial_samples`, 0.005 near the origin). Two zeros
        closer to the edge than to each other inside one initial step would cancel their phase jumps; the
        fine default keeps that below the spacing of induced frequencies seen in practice, and region edges
        are kept away from places where roots accumulate (see ``search_regions``).
    max_step : float
        Largest accepted change of arg f between neighbouring samples (radians).
    min_segment : float
        Relative segment length (to the rectangle size) below which refinement gives up.
    """
    size = max(rect.width, rect.height)
    # a curved cell (roots/search/cut_cells.py) is refined along its own edges, a rectangle along its sides
    points_at = getattr(rect, "points_at", None)
    z, t = initial_samples(rect, spacing)
    ta, tb = (t[:-1], t[1:]) if points_at is not None else (None, None)
    w = f(z)
    za, zb, wa, wb = z[:-1], z[1:], w[:-1], w[1:]
    total, points = 0.0, z.size
    m = _SUBDIVIDE
    frac = np.arange(1, m) / m
    # only the segments still too coarse are kept and refined, so the work is linear in the points used;
    # each is cut into m pieces at once (a zero near the edge needs many levels of refinement, and one
    # batched evaluation per level costs little more for more points)
    while True:
        if not (np.all(np.isfinite(wa)) and np.all(np.isfinite(wb))):
            raise EdgeZeroError(f"non-finite value on the contour of {rect}")
        if np.any(wa == 0) or np.any(wb == 0):
            raise EdgeZeroError(f"zero on the contour of {rect}")
        ratio = wb / wa
        step = np.angle(ratio)
        bad = (np.abs(step) > max_step) | (np.abs(np.log(np.abs(ratio))) > 1.0)
        total += float(step[~bad].sum())
        if not np.any(bad):
            break
        if np.any(np.abs(zb - za)[bad] < _resolution(za[bad], min_segment * size)) or points > max_points:
            raise EdgeZeroError(f"a zero lies on or next to the contour of {rect}")
        za, zb, wa, wb = za[bad], zb[bad], wa[bad], wb[bad]
        if ta is not None and tb is not None and points_at is not None:
            ta, tb = ta[bad], tb[bad]
            tt = ta[:, None] + frac[None, :] * (tb - ta)[:, None]
            zi = points_at(tt.ravel()).reshape(tt.shape)
            ta, tb = np.column_stack([ta, tt]).ravel(), np.column_stack([tt, tb]).ravel()
        else:
            zi = za[:, None] + frac[None, :] * (zb - za)[:, None]
        wi = f(zi.ravel()).reshape(zi.shape)
        points += zi.size
        za, zb = np.column_stack([za, zi]).ravel(), np.column_stack([zi, zb]).ravel()
        wa, wb = np.column_stack([wa, wi]).ravel(), np.column_stack([wi, wb]).ravel()
    turns = total / (2 * np.pi)
    n = int(round(turns))
    if abs(turns - n) > 1e-3:
        raise EdgeZeroError(f"winding number {turns} is not an integer on {rect}")
    return n


def winding_numbers(
    f: ContourFunction,
    regions: Sequence[Region],
    *,
    max_step: float = np.pi / 5,
    min_segment: float = 1e-11,
    max_points: Sequence[int] | npt.NDArray[np.int_] | None = None,
) -> list[int | EdgeZeroError]:
    """:func:`winding_number` of many regions at once: every refinement level of all of them is one
    evaluation of ``f`` (the cost of an evaluation of E_chr is mostly per call, not per point).

    Returns, per region, its winding number or the :class:`EdgeZeroError` that :func:`winding_number`
    would raise for it. ``max_points`` (per region) defaults to 400 000.
    """
    n_reg = len(regions)
    limit = np.full(n_reg, 400_000) if max_points is None else np.asarray(max_points)
    sizes = np.array([max(r.width, r.height) for r in regions], dtype=float)
    curves = [getattr(r, "points_at", None) for r in regions]
    zs, ts = [], []
    for r in regions:
        z, t = initial_samples(r)
        zs.append(z)
        ts.append(t)
    w_all = f(np.concatenate(zs)) if zs else np.zeros(0, complex)
    ws = np.split(w_all, np.cumsum([z.size for z in zs])[:-1]) if zs else []
    owner = np.concatenate([np.full(z.size - 1, k) for k, z in enumerate(zs)]) if zs else np.zeros(0, int)
    za = np.concatenate([z[:-1] for z in zs]) if zs else np.zeros(0, complex)
    zb = np.concatenate([z[1:] for z in zs]) if zs else np.zeros(0, complex)
    wa = np.concatenate([w[:-1] for w in ws]) if zs else np.zeros(0, complex)
    wb = np.concatenate([w[1:] for w in ws]) if zs else np.zeros(0, complex)
    ta = np.concatenate([t[:-1] for t in ts]) if zs else np.zeros(0)
    tb = np.concatenate([t[1:] for t in ts]) if zs else np.zeros(0)
    total = np.zeros(n_reg)
    points = np.array([z.size for z in zs])
    errors: list[EdgeZeroError | None] = [None] * n_reg
    m = _SUBDIVIDE
    frac = np.arange(1, m) / m
    while owner.size:
        with np.errstate(all="ignore"):
            ratio = wb / wa
            step = np.angle(ratio)
            bad = (np.abs(step) > max_step) | (np.abs(np.log(np.abs(ratio))) > 1.0)
        broken = ~(np.isfinite(wa) & np.isfinite(wb)) | (wa == 0) | (wb == 0)
        for k in np.unique(owner[broken]):
            if errors[k] is None:
                errors[k] = EdgeZeroError(f"non-finite value or zero on the contour of {regions[k]}")
        bad |= broken
        np.add.at(total, owner[~bad], step[~bad])
        too_fine = bad & (np.abs(zb - za) < _resolution(za, min_segment * sizes[owner]))
        for k in np.unique(owner[too_fine]):
            if errors[k] is None:
                errors[k] = EdgeZeroError(f"a zero lies on or next to the contour of {regions[k]}")
        for k in np.unique(owner[bad]):
            if errors[k] is None and points[k] > limit[k]:
                errors[k] = EdgeZeroError(f"a zero lies on or next to the contour of {regions[k]}")
        failed = np.array([e is not None for e in errors], dtype=bool)
        bad &= ~failed[owner]
        if not np.any(bad):
            break
        owner, za, zb, wa, wb, ta, tb = (x[bad] for x in (owner, za, zb, wa, wb, ta, tb))
        tt = ta[:, None] + frac[None, :] * (tb - ta)[:, None]
        zi = za[:, None] + frac[None, :] * (zb - za)[:, None]
        for k in np.unique(owner):
            if curves[k] is not None:
                sel = owner == k
                zi[sel] = curves[k](tt[sel].ravel()).reshape(-1, m - 1)
        wi = f(zi.ravel()).reshape(zi.shape)
        np.add.at(points, owner, m - 1)
        owner = np.repeat(owner, m)
        za, zb = np.column_stack([za, zi]).ravel(), np.column_stack([zi, zb]).ravel()
        wa, wb = np.column_stack([wa, wi]).ravel(), np.column_stack([wi, wb]).ravel()
        ta, tb = np.column_stack([ta, tt]).ravel(), np.column_stack([tt, tb]).ravel()
    return _winding_results(total, errors, regions)


def _winding_results(
    total: FloatArray, errors: Sequence[EdgeZeroError | None], regions: Sequence[Region]
) -> list[int | EdgeZeroError]:
    """Per region, its winding number (``total`` change of arg / 2 pi, an integer to 1e-3) or its error."""
    out: list[int | EdgeZeroError] = []
    for k, error in enumerate(errors):
        if error is not None:
            out.append(error)
            continue
        turns = total[k] / (2 * np.pi)
        n = int(round(turns))
        out.append(
            n
            if abs(turns - n) <= 1e-3
            else EdgeZeroError(f"winding number {turns} is not an integer on {regions[k]}")
        )
    return out
