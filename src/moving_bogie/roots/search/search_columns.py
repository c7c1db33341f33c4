"""Column cells of the tiling between the cut's arms (graphs over Re q), for :mod:`search_regions`.

A column [a, b] gets cells between consecutive arms at the distance eps (or the arm's
:func:`~moving_bogie.kernels.cut.clearance`), split at crossings of arms, with thin lenses left out with
the arms that bound them; where the arms cannot be followed, a padded strip or boxes are left out.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from moving_bogie.kernels.brent import brentq
from moving_bogie.kernels.cut import CutArm, CutLocus, arms_y_at
from moving_bogie.roots.count.contour import Rectangle, Region
from moving_bogie.roots.search.cut_cells import ColumnCell, Edge, Sliver
from moving_bogie.typing import FloatArray

__all__ = ["COLUMN_SAMPLES", "arms_over", "box", "column", "fill_columns"]

COLUMN_SAMPLES = 17  # Re q samples per column where the order of the curves is checked
_MERGE = 3.0  # arms closer than this many eps are left out together (sliver <= 5 eps)
_TOUCH = 1e-14  # a gap between two arms this small is zero (they meet, e.g. where they cross Re q = 0)
_NARROW = 50.0  # a column narrower than this many eps (at a crossing of arms) is left out as a box


def arms_over(cut: CutLocus, a: float, b: float) -> list[CutArm]:
    """The arms of the cut that span the whole column [a, b]."""
    return [arm for arm in cut.arms if arm.x_lo <= a + 1e-12 and arm.x_hi >= b - 1e-12]


def fill_columns(
    cut: CutLocus,
    x0: float,
    x1: float,
    regions: list[Region],
    unsearched: list[Sliver],
    eps: float,
    band_lo: float,
    band_hi: float,
    density: float,
    most: int = 6,
) -> None:
    """Columns between two events, ``density`` of them per unit of Re q (at least one, at most ``most``)."""
    xs = np.linspace(x0, x1, min(most, max(1, int(np.ceil(density * (x1 - x0) - 1e-9)))) + 1)
    for a, b in zip(xs[:-1], xs[1:]):
        column(cut, a, b, regions, unsearched, eps, band_lo, band_hi)


def column(
    cut: CutLocus,
    a: float,
    b: float,
    regions: list[Region],
    unsearched: list[Sliver],
    eps: float,
    band_lo: float,
    band_hi: float,
    arms: Sequence[CutArm] | None = None,
) -> None:
    """Cells of one column [a, b] between the cut's arms (graphs over Re q there), or a padded fallback.

    Where two arms cross, the column is split at the crossing; where two arms are closer than
    ``_MERGE`` eps, the thin lens between them is left out with them (a sliver at most 5 eps high).
    """
    xs = np.linspace(a, b, COLUMN_SAMPLES)
    arms = arms_over(cut, a, b) if arms is None else arms
    if not arms:
        regions.append(Rectangle(a, b, band_lo, band_hi))
        return
    ys = arms_y_at(arms, xs)
    if b - a <= _NARROW * eps * max(1.0, abs(a)):  # a sliver of a column at a crossing: boxes left out
        _boxes(a, b, ys, regions, unsearched, eps, band_lo, band_hi)
        return
    order = np.argsort(ys[:, COLUMN_SAMPLES // 2])
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
                column(cut, c0, c1, regions, unsearched, eps, band_lo, band_hi, arms)
            return
        if split is not None and a < split < b:
            # a split next to an end makes a column too narrow to count in: widen it to _NARROW eps
            if split - a < narrow:
                split = a + narrow if b - a > 2 * narrow else b
            elif b - split < narrow:
                split = b - narrow if b - a > 2 * narrow else a
        if split is not None and a < split < b:
            column(cut, a, split, regions, unsearched, eps, band_lo, band_hi, arms)
            column(cut, split, b, regions, unsearched, eps, band_lo, band_hi, arms)
            return
        if np.any(g < 0):  # crossing curves the split could not separate
            _padded(a, b, ys, regions, unsearched, eps, band_lo, band_hi)
            return
    if ys.min() - eps <= band_lo or ys.max() + eps >= band_hi:
        _padded(a, b, ys, regions, unsearched, eps, band_lo, band_hi)
        return
    edges = [Edge(y=band_lo)]
    for group in _groups(gaps, eps):
        lo_arm, hi_arm = arms[group[0]], arms[group[-1]]
        band = (Edge(arm=lo_arm, side=-1, delta=eps), Edge(arm=hi_arm, side=1, delta=eps))
        edges += band
        y_lo, y_hi = ys[group[0]], ys[group[-1]]
        d_lo, d_hi = lo_arm.clearance(xs, eps), hi_arm.clearance(xs, eps)  # eps, or more (fast arms)
        thickness = float((y_hi - y_lo).max()) + d_lo + d_hi
        y0, y1 = float(y_lo.min() - d_lo), float(y_hi.max() + d_hi)
        unsearched.append(Sliver(a, b, y0, y1, thickness, cell=ColumnCell(a, b, *band)))
    edges.append(Edge(y=band_hi))
    regions.extend(ColumnCell(a, b, lo, hi) for lo, hi in zip(edges[::2], edges[1::2]))


def _groups(gaps: FloatArray, eps: float) -> list[list[int]]:
    """The arms (indices, sorted by Im q; ``gaps`` between neighbours) in groups: arms closer than
    ``_MERGE`` eps share one pair of edges."""
    groups: list[list[int]] = [[0]]
    for k in range(len(gaps)):
        if np.all(gaps[k] <= _MERGE * eps):
            groups[-1].append(k + 1)
        else:
            groups.append([k + 1])
    return groups


def _split_point(
    lower: CutArm, upper: CutArm, xs: FloatArray, gap: FloatArray, eps: float
) -> tuple[float | None, bool]:
    """Where the column must be split for the arms ``lower`` < ``upper`` (at the middle), and whether that
    is their crossing (else the Re q where their gap passes _MERGE eps); (None, False) if neither happens
    inside."""

    def g(x: float, target: float = 0.0) -> float:
        return float(upper.y_at(np.array([x]))[0] - lower.y_at(np.array([x]))[0]) - target

    for target in (0.0, _MERGE * eps):
        change = np.nonzero(np.sign(gap[:-1] - target) * np.sign(gap[1:] - target) < 0)[0]
        if change.size:
            k = change[0]
            ga, gb = g(xs[k], target), g(xs[k + 1], target)
            if ga * gb > 0:  # the sign change was at rounding level: split at the nearer sample
                return float(xs[k] if abs(ga) < abs(gb) else xs[k + 1]), target == 0.0
            x = brentq(g, xs[k], xs[k + 1], args=(target,), xtol=1e-15, rtol=1e-15)
            return x, target == 0.0
    return None, False


def _slope(arm: CutArm, x: float) -> float:
    """|d Im q / d Re q| of ``arm`` at Re q = x."""
    p = arm.p_at(np.array([x]))
    t = complex(arm.tracer.dq_dp(p, arm.q_at(p))[0])
    return abs(t.imag) / abs(t.real) if t.real else np.inf


def _padded(
    a: float,
    b: float,
    ys: FloatArray,
    regions: list[Region],
    unsearched: list[Sliver],
    eps: float,
    band_lo: float,
    band_hi: float,
) -> None:
    """The column [a, b] with a strip around the arms (``ys``: their Im q) left out, padded by eps and 5 %
    of their spread."""
    pad = eps + 0.05 * float(ys.max() - ys.min())
    c_lo, c_hi = max(band_lo, float(ys.min()) - pad), min(band_hi, float(ys.max()) + pad)
    if c_lo > band_lo:
        regions.append(Rectangle(a, b, band_lo, c_lo))
    if c_hi < band_hi:
        regions.append(Rectangle(a, b, c_hi, band_hi))
    unsearched.append(Sliver(a, b, c_lo, c_hi, c_hi - c_lo, cell=_rect(a, b, c_lo, c_hi)))


def _boxes(
    a: float,
    b: float,
    ys: FloatArray,
    regions: list[Region],
    unsearched: list[Sliver],
    eps: float,
    band_lo: float,
    band_hi: float,
) -> None:
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
        unsearched.append(Sliver(a, b, lo, hi, hi - lo, cell=_rect(a, b, lo, hi)))
        bottom = max(bottom, hi)
    if bottom < band_hi:
        regions.append(Rectangle(a, b, bottom, band_hi))


def box(
    a: float,
    b: float,
    lo: float,
    hi: float,
    regions: list[Region],
    unsearched: list[Sliver],
    band_lo: float,
    band_hi: float,
) -> None:
    """The column [a, b] with the box lo <= Im q <= hi left out (reported as a sliver)."""
    lo, hi = max(lo, band_lo), min(hi, band_hi)
    if lo > band_lo:
        regions.append(Rectangle(a, b, band_lo, lo))
    if hi < band_hi:
        regions.append(Rectangle(a, b, hi, band_hi))
    unsearched.append(Sliver(a, b, lo, hi, hi - lo, cell=_rect(a, b, lo, hi)))


def _rect(a: float, b: float, lo: float, hi: float) -> Rectangle | None:
    """The box a <= Re q <= b, lo <= Im q <= hi as a region, None if it is empty."""
    return Rectangle(a, b, lo, hi) if b > a and hi > lo else None
