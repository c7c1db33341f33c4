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

from dataclasses import dataclass

from moving_bogie.roots.contour import Rectangle


@dataclass(frozen=True)
class ProofTiling:
    regions: tuple  # Rectangles to count in
    unsearched: tuple  # Rectangles along the cut that no region covers


def proof_tiling(
    window: Rectangle, cut, *, margin: float, gap_height: float, columns: int = 48
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
    pad = margin + 0.05 * spread
    unsearched = []
    for k in range(n):
        a = x_cut + (window.x1 - x_cut) * k / n
        b = window.x1 if k == n - 1 else x_cut + (window.x1 - x_cut) * (k + 1) / n
        span = cut.im_range_between(a - margin, b + margin)
        if span is None:
            regions.append(Rectangle(a, b, *band))
            continue
        lo, hi = max(band[0], span[0] - pad), min(band[1], span[1] + pad)
        if lo > band[0]:
            regions.append(Rectangle(a, b, band[0], lo))
        if hi < band[1]:
            regions.append(Rectangle(a, b, hi, band[1]))
        unsearched.append(Rectangle(a, b, lo, hi))
    return ProofTiling(tuple(regions), tuple(unsearched))
