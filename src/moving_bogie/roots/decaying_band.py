"""The decaying roots on the physical sheet of a track whose kernel is a quadrature: a band above the real
axis.

The kernel G(0, Omega) = (1/2 pi) int dk / D(k, Omega + k v), integrated along real k (docs/soil.md,
Eq. (S9)), is analytic for Im Omega < 0. It continues analytically into Im Omega > 0 as long as no
singularity of the integrand reaches the real k axis: a free wave of the soil (a pole or branch point of
chi, met by the real k2 path of the strip's quadrature) or of the track on its soil (a zero of D) at a real
wavenumber. Where one does, Omega = omega - k v lies on a singular line, and beyond it the integral along
real k is another function (the continuation deforms the path). Below every singular line, E_chr is
analytic and its roots with Im Omega > 0 (decaying) are counted by the argument principle as those with
Im Omega < 0 are.

The track says where its kernel stays analytic (:class:`~moving_bogie.kernels.track_model.BandTrack`: on
the soil, :mod:`moving_bogie.soil.sheet`): under the depth ``band_depth(X)`` it gives at Re q = X, in a
rectangle its ``waves_clear`` passes. The band searched is a staircase under that depth: STEPS rectangles
X1 2^-(i+1) <= Re q <= X1 2^-i, 0 <= Im q <= band_depth(X1 2^-(i+1)), X1 the window's size; a rectangle
that its ``waves_clear`` refuses is halved in depth (HALVINGS times at most) or dropped. The roots found in
the band, the least Im Omega among them (the margin, in 1/s) and the band itself are reported; beyond the
band (Re Omega < X1 2^-STEPS, or above the staircase) nothing is searched. The count is coarser than
the window's (BAND_TOL, BAND_STEP, BAND_SAMPLES) with the same guard: where the receptance's error reaches
|E_chr| / 2 on the edge, the rectangle is counted again at the track's tolerance.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import mpmath
import numpy as np

from moving_bogie.kernels.track_model import BandTrack
from moving_bogie.roots.count.contour import EdgeZeroError, Rectangle
from moving_bogie.roots.quadrature_window import (
    QuadratureCharacteristic,
    count_rectangle,
    induced,
    locate,
)

if TYPE_CHECKING:
    from moving_bogie.roots.frequency_result import InducedFrequency

__all__ = ["STEPS", "DecayingBand", "decaying_band"]

#: Rectangles of the staircase; depth halvings of a rectangle the track refuses.
STEPS, HALVINGS = 2, 5
#: The band's count: the receptance's relative tolerance, the largest step of arg E_chr and the initial
#: samples along a rectangle's long side (refined where the phase turns; the guard of
#: :func:`~moving_bogie.roots.quadrature_window.count_rectangle` recounts at the track's own tolerance
#: where an error reaches |E_chr| / 2).
BAND_TOL, BAND_STEP, BAND_SAMPLES = 1e-2, np.pi / 3, 4


class BandRectangle(Rectangle):
    """A rectangle of the band: its first boundary samples at about the spacing asked on every edge, at
    least one segment per edge (a :class:`Rectangle` takes at least 8 per edge, which on a thin band's
    short sides costs values of E_chr that the phase does not need; the count refines where it turns)."""

    def boundary(self, spacing: float, least: int = 1) -> np.ndarray:
        return super().boundary(spacing, least)


@dataclass(frozen=True)
class DecayingBand:
    """The decaying roots found in the band (q units, like the window) and what was searched.

    ``rects``: the staircase's rectangles searched (q); ``counts``: their argument-principle counts (None:
    a root on an edge); ``dropped``: rectangles not searched (a track wave in them); ``scale``: rad/s per q.
    """

    rects: tuple[Rectangle, ...]
    counts: tuple[int | None, ...]
    roots: tuple[InducedFrequency, ...]
    dropped: tuple[Rectangle, ...]
    x_end: float
    scale: float
    damped: bool = True
    caveat: str = ""  # what the track's check of a rectangle is (BandTrack.band_caveat)

    @property
    def count(self) -> int | None:
        return None if any(c is None for c in self.counts) else sum(c for c in self.counts if c is not None)

    @property
    def complete(self) -> bool:
        """Every rectangle counted, the count matched by the roots located."""
        return self.count is not None and self.count == len(self.roots) and not self.dropped

    @property
    def margin(self) -> float | None:
        """The least Im q of the decaying roots found; None when none was found or when a rectangle's count
        is not established or not matched by the roots located (a root may be missing)."""
        if self.count is None or self.count != len(self.roots):
            return None
        return min((float(mpmath.im(r.q)) for r in self.roots), default=None)

    @property
    def depth(self) -> float:
        """The shallowest top of the rectangles searched (q; 0 when none was)."""
        return min((r.y1 for r in self.rects), default=0.0)

    def statement(self) -> str:
        """One line, in rad/s and 1/s: what was searched above the axis and what was found."""
        s = self.scale
        if not self.damped:
            return "Im omega > 0 is not searched: a layer without damping has singular lines on the real axis"
        if not self.rects:
            return "Im omega > 0 is not searched: the track's free waves lie in the band"
        parts = [
            f"{r.x0 * s:.4g} <= Re omega <= {r.x1 * s:.4g} rad/s, 0 < Im omega <= {r.y1 * s:.3g} 1/s"
            for r in self.rects
        ]
        found = "no root" if not self.roots else f"{len(self.roots)} decaying root(s)"
        if self.count is None:
            found += (
                " located (a count not established: a root on an edge, or values within their error of 0)"
            )
        elif self.count != len(self.roots):
            found += f" located of {self.count} counted (a root may be missing)"
        return (
            f"above the axis (physical sheet, below the singular lines): {found} in "
            + "; ".join(parts)
            + (f" ({self.caveat})" if self.caveat else "")
            + (f"; {len(self.dropped)} rectangle(s) dropped (a track's wave)" if self.dropped else "")
            + f"; not searched: Re omega < {self.x_end * s:.4g} rad/s, above these depths (beyond the "
            "singular lines the integral along real k is not the continued function), and beyond the window"
        )

    def to_dict(self) -> dict[str, object]:
        """The band in rad/s and 1/s (``rects``), its ``count``, the ``roots`` and ``margin_1_s``."""
        s = self.scale
        margin = self.margin
        return {
            "sheet": "physical (the integral along real k, below the singular lines)",
            "rects": [
                {"re_rad_s": [r.x0 * s, r.x1 * s], "im_1_s": [r.y0 * s, r.y1 * s], "count": c}
                for r, c in zip(self.rects, self.counts, strict=True)
            ],
            "not_searched_re_below_rad_s": self.x_end * s,
            "dropped": [
                {"re_rad_s": [r.x0 * s, r.x1 * s], "im_1_s": [r.y0 * s, r.y1 * s]} for r in self.dropped
            ],
            "count": self.count,
            "roots": [
                r.to_dict() | {"omega_rad_s": [float(mpmath.re(r.q)) * s, float(mpmath.im(r.q)) * s]}
                for r in self.roots
            ],
            "margin_1_s": None if margin is None else margin * s,
            "damped": self.damped,
        }


def decaying_band(E: QuadratureCharacteristic, radius: float, steps: int = STEPS) -> DecayingBand:
    """Count and locate the roots of ``E`` in the staircase of ``steps`` rectangles under the depth its
    track gives (module docstring), the window's size ``radius`` (q) its right end."""
    track = E.bound.track
    if not isinstance(track, BandTrack):
        raise TypeError(f"the track {track.name!r} does not say where its kernel stays analytic")
    scale, caveat = track.band_scale, track.band_caveat
    ends = [radius * 2.0**-i for i in range(steps + 1)]
    rects: list[Rectangle] = []
    dropped: list[Rectangle] = []
    for x1, x0 in zip(ends[:-1], ends[1:], strict=True):
        depth = track.band_depth(x0)
        if depth <= 0:
            return DecayingBand((), (), (), (), radius, scale, damped=False, caveat=caveat)
        for _ in range(HALVINGS + 1):
            if track.waves_clear(x0, x1, 0.0, depth):
                rects.append(BandRectangle(x0, x1, 0.0, depth))
                break
            depth /= 2
        else:
            dropped.append(Rectangle(x0, x1, 0.0, depth))
    counts: list[int | None] = []
    roots = []
    for rect in rects:
        try:
            n, stands = count_rectangle(E, rect, BAND_TOL, BAND_STEP, BAND_SAMPLES)
        except EdgeZeroError:
            counts.append(None)
            continue
        counts.append(n if stands else None)
        roots += [
            induced(E, q, slope, step, "above") for q, slope, step in locate(E, rect, n, (0.0, rect.y1))
        ]
    return DecayingBand(
        tuple(rects), tuple(counts), tuple(roots), tuple(dropped), ends[-1], scale, caveat=caveat
    )
