"""Rectangles for the proven count: the search window minus a strip of half-height ``margin`` along the cut.

The proof of :mod:`winding` needs straight edges with exact corners, so its tiling is made of rectangles
only (the numerical search may use cells that follow a curved cut more closely): the part of the window
below the band of the cut, the part above it, the gap left of the cut's leftmost point (the branch point,
where K is analytic across the cut's line), and columns over the cut, each split into a rectangle below and
one above the cut's range in that column. Nothing here has to be exact: a rectangle that met the cut would
make its proven count fail (:class:`winding.NotProven`), never a wrong count. What the rectangles leave out
is listed as ``unsearched``.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from moving_bogie.kernels.cut import CutLocus
from moving_bogie.roots.count.contour import Rectangle


@dataclass(frozen=True)
class ProofTiling:
    regions: tuple[Rectangle | Staircase, ...]  # to count in
    unsearched: tuple[Rectangle, ...]  # along the cut, which no region covers


def proof_tiling(
    window: Rectangle,
    cut: CutLocus,
    *,
    margin: float,
    gap_height: float,
    columns: int = 48,
    pinches: Sequence[tuple[float, float, float]] = (),
) -> ProofTiling:
    """Rectangles covering ``window`` except the cut's strip (half-height ``margin``, more where sampled).

    Parameters
    ----------
    window : Rectangle
    cut : CutLocus
        Sampled cut of K (:func:`moving_bogie.kernels.cut.cut_locus`).
    margin : float
        Distance kept from the cut (and, along Re q, from its leftmost point).
    gap_height : float
        Half-height of the band of the cut: the gap region spans it, so that real roots left of the branch
        point are far from every edge.
    columns : int
        Columns over a curved cut (its sampled range in each column is padded by 5 % of the cut's total
        Im range, so that no edge crosses the curve between samples); a flat cut needs one.
    pinches : sequence of (x_lo, x_hi, margin)
        Stretches of Re q over which the strip is thinner (its own ``margin``), each a column of its own: a
        root closer to the cut than ``margin`` then lies in a tile, while the edges elsewhere keep their
        distance from the cut (an edge at distance h from the cut needs segments shorter than about h).
    """
    if not cut.points.size or cut.im_high < window.y0 or cut.im_low > window.y1:
        return ProofTiling((window,), ())
    band = (max(window.y0, cut.im_low - gap_height), min(window.y1, cut.im_high + gap_height))
    regions = [Rectangle(window.x0, window.x1, window.y0, band[0])] if band[0] > window.y0 else []
    if band[1] < window.y1:
        regions.append(Rectangle(window.x0, window.x1, band[1], window.y1))
    x_cut = max(window.x0, cut.x_start - margin)
    if x_cut > window.x0:
        regions.append(Rectangle(window.x0, min(x_cut, window.x1), *band))
    if x_cut >= window.x1:
        return ProofTiling(tuple(regions), ())
    spread = cut.im_high - cut.im_low
    n = 1 if spread <= 1e-12 else columns
    uniform = {x_cut + (window.x1 - x_cut) * k / n for k in range(n)}
    inside = [(max(lo, x_cut), min(hi, window.x1), thin) for lo, hi, thin in pinches]
    inside = [(lo, hi, thin) for lo, hi, thin in inside if lo < hi]
    edges = sorted(uniform | {x for lo, hi, _ in inside for x in (lo, hi) if x < window.x1})
    bounds = []
    for k, a in enumerate(edges):
        b = window.x1 if k == len(edges) - 1 else edges[k + 1]
        thin = [t for lo, hi, t in inside if lo <= 0.5 * (a + b) <= hi]
        bounds.append((a, min([margin] + thin)))
    unsearched: list[Rectangle] = []
    lower: list[Rectangle] = []
    upper: list[Rectangle] = []
    for k, (a, used) in enumerate(bounds):
        b = window.x1 if k == len(bounds) - 1 else bounds[k + 1][0]
        if b <= a:
            continue
        span = cut.im_range_between(a - used, b + used)
        if span is None:
            regions.append(Rectangle(a, b, *band))
            continue
        # a pinch column is narrow: its own range of the cut, not the whole cut's, sets its padding
        pad = used + 0.05 * (spread if used == margin else span[1] - span[0])
        lo, hi = max(band[0], span[0] - pad), min(band[1], span[1] + pad)
        if lo > band[0]:
            lower.append(Rectangle(a, b, band[0], lo))
        if hi < band[1]:
            upper.append(Rectangle(a, b, hi, band[1]))
        unsearched.append(Rectangle(a, b, lo, hi))
    slot = _slotted(window, regions, lower, upper, unsearched)
    if slot is not None:
        return ProofTiling((slot,), tuple(unsearched))
    return ProofTiling(tuple(_merged(regions, lower, upper)), tuple(unsearched))


@dataclass(frozen=True)
class Staircase:
    """Rectangles as one region: a base rectangle and columns standing on one of its horizontal edges, or
    the whole window but the strip along the cut (:func:`proof_tiling`); ``corners`` of its boundary
    counterclockwise (exact copies of the rectangles' corners), ``rects`` the members (the first one the
    base). Counting once on its boundary skips the edges the members share (a column's sides over the cut)."""

    corners: tuple[complex, ...]
    rects: tuple[Rectangle, ...]

    @property
    def width(self) -> float:
        return max(z.real for z in self.corners) - min(z.real for z in self.corners)

    @property
    def height(self) -> float:
        return max(z.imag for z in self.corners) - min(z.imag for z in self.corners)

    def __str__(self) -> str:
        return f"Staircase(base={self.rects[0]}, columns={len(self.rects) - 1})"


def _merged(
    regions: list[Rectangle], lower: list[Rectangle], upper: list[Rectangle]
) -> list[Rectangle | Staircase]:
    """``regions`` with the columns below the cut joined to the region below the band (its top edge is
    their base) and those above it to the region above; columns without such a base stay rectangles
    (a staircase made for the columns below is no base for those above)."""
    out: list[Rectangle | Staircase] = list(regions)
    for columns, on_top in ((lower, True), (upper, False)):
        if not columns:
            continue
        level = columns[0].y0 if on_top else columns[0].y1
        base = next(
            (
                r
                for r in out
                if isinstance(r, Rectangle)
                and (r.y1 if on_top else r.y0) == level
                and r.x0 <= columns[0].x0
                and columns[-1].x1 <= r.x1
            ),
            None,
        )
        if base is None:
            out += columns
            continue
        out.remove(base)
        out.append(staircase(base, columns, on_top))
    return out


def staircase(base: Rectangle, columns: list[Rectangle], on_top: bool) -> Staircase:
    """The boundary of ``base`` with ``columns`` (disjoint, sorted by Re q) on its top edge (``on_top``) or
    its bottom edge, counterclockwise."""
    xs = sorted({base.x0, base.x1} | {x for c in columns for x in (c.x0, c.x1)})
    pieces = []  # (x_left, x_right, level of the outer edge there), left to right
    for x_left, x_right in zip(xs, xs[1:]):
        column = next((c for c in columns if c.x0 <= x_left and x_right <= c.x1), None)
        if column is None:
            pieces.append((x_left, x_right, base.y1 if on_top else base.y0))
        else:
            pieces.append((x_left, x_right, column.y1 if on_top else column.y0))
    if on_top:  # along the bottom edge to the right, then back over the profile to the left
        points = [complex(base.x0, base.y0), complex(base.x1, base.y0)]
        for x_left, x_right, y in reversed(pieces):
            points += [complex(x_right, y), complex(x_left, y)]
    else:  # over the profile to the right, then back along the top edge to the left
        points = []
        for x_left, x_right, y in pieces:
            points += [complex(x_left, y), complex(x_right, y)]
        points += [complex(base.x1, base.y1), complex(base.x0, base.y1)]
    return Staircase(_simplified(points), (base, *columns))


def _simplified(points: list[complex]) -> tuple[complex, ...]:
    """A closed path's corners without repeated points and without corners on a straight line."""
    corners: list[complex] = []
    for z in points:
        if corners and corners[-1] == z:
            continue
        corners.append(z)
    changed = True
    while changed and len(corners) > 4:
        changed = False
        for k in range(len(corners)):
            a, b, c = corners[k - 1], corners[k], corners[(k + 1) % len(corners)]
            if a.real == b.real == c.real or a.imag == b.imag == c.imag:
                del corners[k]
                changed = True
                break
    return tuple(corners)


def _slotted(
    window: Rectangle,
    regions: list[Rectangle],
    lower: list[Rectangle],
    upper: list[Rectangle],
    unsearched: list[Rectangle],
) -> Staircase | None:
    """The window but the strip along the cut as one region, when the tiling is the region below the band,
    the one above it, the gap left of the cut and columns from the gap to the window's right edge, each
    split into a rectangle below the cut, one above it and the unsearched strip between them (else None).

    The strip reaches the window's edge, so the region is simply connected; its boundary runs under the
    strip from the right edge to the gap, around the strip's end and back over it. The sides the members
    share (the gap's, the columns') are inside it and not walked; those next to the cut's leftmost point
    (the branch point) would need the most segments.
    """
    if len(regions) != 3 or not lower or len(lower) != len(upper) or len(lower) != len(unsearched):
        return None
    below, above, gap = regions
    aligned = all(
        lo.x0 == up.x0 == u.x0 and lo.x1 == up.x1 == u.x1 and lo.y1 == u.y0 and u.y1 == up.y0
        for lo, up, u in zip(lower, upper, unsearched)
    )
    contiguous = all(a.x1 == b.x0 for a, b in zip(lower, lower[1:]))
    framed = (
        below == Rectangle(window.x0, window.x1, window.y0, lower[0].y0)
        and above == Rectangle(window.x0, window.x1, upper[0].y1, window.y1)
        and gap == Rectangle(window.x0, lower[0].x0, below.y1, above.y0)
        and lower[-1].x1 == window.x1
        and all(c.y0 == below.y1 for c in lower)
        and all(c.y1 == above.y0 for c in upper)
    )
    if not (aligned and contiguous and framed):
        return None
    points = [complex(window.x0, window.y0), complex(window.x1, window.y0)]
    for c in reversed(lower):  # under the strip, right to left
        points += [complex(c.x1, c.y1), complex(c.x0, c.y1)]
    for c in upper:  # over it, left to right
        points += [complex(c.x0, c.y0), complex(c.x1, c.y0)]
    points += [complex(window.x1, window.y1), complex(window.x0, window.y1)]
    return Staircase(_simplified(points), (below, above, gap, *lower, *upper))
