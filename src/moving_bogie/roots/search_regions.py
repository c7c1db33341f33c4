"""Tiling of the search window into rectangles that never meet the cut of K.

The window is cut into: everything below the cut band, everything above it, the gap left of the branch
point (where K is analytic across Im q = eta_f, so undamped real roots lie strictly inside), and, when
the cut is a curve (Timoshenko-Rayleigh), thin columns above and below it. What is left unsearched is a
sliver of half-width ``eps`` around the cut (and ``eps_branch`` around the branch point): roots there
are within that distance of the cut; the result lists those slivers.
"""

from __future__ import annotations

from dataclasses import dataclass

from moving_bogie.kernels.cut import CutLocus
from moving_bogie.roots.contour import Rectangle


@dataclass(frozen=True)
class Tiling:
    regions: tuple  # Rectangles to count in
    unsearched: tuple  # Rectangles (slivers around the cut) not searched


def tile_window(
    window: Rectangle, cut: CutLocus, *, eps: float, eps_branch: float, gap_height: float, columns: int = 48
) -> Tiling:
    """Rectangles covering ``window`` minus an ``eps``-neighbourhood of the cut.

    Left of the branch point the gap region extends ``gap_height`` above and below the cut, so that roots
    on or near the line Im q = eta_f there (the real roots of undamped cases) are far from every edge.
    Edges run close to the cut only where the cut itself runs.
    """
    if not cut.points.size or cut.im_high < window.y0 or cut.im_low > window.y1:
        return Tiling((window,), ())
    lo, hi = cut.im_low - eps, cut.im_high + eps
    band_lo = max(window.y0, cut.im_low - gap_height)
    band_hi = min(window.y1, cut.im_high + gap_height)
    regions, unsearched = [], []
    if band_lo > window.y0:
        regions.append(Rectangle(window.x0, window.x1, window.y0, band_lo))
    if band_hi < window.y1:
        regions.append(Rectangle(window.x0, window.x1, band_hi, window.y1))
    x_gap = cut.x_start - eps_branch
    if x_gap > window.x0:
        regions.append(Rectangle(window.x0, min(x_gap, window.x1), band_lo, band_hi))
    x_band = max(window.x0, x_gap)
    if x_band >= window.x1:
        return Tiling(tuple(regions), ())
    if cut.im_high - cut.im_low <= 1e-12:
        if lo > band_lo:
            regions.append(Rectangle(x_band, window.x1, band_lo, lo))
        if hi < band_hi:
            regions.append(Rectangle(x_band, window.x1, hi, band_hi))
        unsearched.append(Rectangle(x_band, window.x1, max(lo, band_lo), min(hi, band_hi)))
        return Tiling(tuple(regions), tuple(unsearched))
    width = (window.x1 - x_band) / columns
    # the cut is sampled: pad each column's range so that no edge crosses it between samples
    pad = eps + 0.05 * (cut.im_high - cut.im_low)
    for k in range(columns):
        a, b = x_band + k * width, x_band + (k + 1) * width
        rng = cut.im_range_between(a - eps, b + eps)
        if rng is None:
            regions.append(Rectangle(a, b, band_lo, band_hi))
            continue
        c_lo, c_hi = rng[0] - pad, rng[1] + pad
        if c_lo - band_lo > eps:
            regions.append(Rectangle(a, b, band_lo, c_lo))
        if band_hi - c_hi > eps:
            regions.append(Rectangle(a, b, c_hi, band_hi))
        unsearched.append(Rectangle(a, b, max(band_lo, c_lo), min(band_hi, c_hi)))
    return Tiling(tuple(regions), tuple(unsearched))
