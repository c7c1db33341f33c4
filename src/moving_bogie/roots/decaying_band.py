"""The decaying roots of a vehicle on the soil on the physical sheet: a band above the real axis.

The kernel G(0, Omega) = (1/2 pi) int dk / D(k, Omega + k v), integrated along real k (docs/soil.md,
Eq. (S9)), is analytic for Im Omega < 0. It continues analytically into Im Omega > 0 as long as no
singularity of the integrand reaches the real k axis: a free wave of the soil (a pole or branch point of
chi, met by the real k2 path of the strip's quadrature) or of the track on its soil (a zero of D) at a real
wavenumber. Where one does, Omega = omega - k v lies on a singular line, and beyond it the integral along
real k is another function (the continuation deforms the path). Below every singular line, E_chr is
analytic and its roots with Im Omega > 0 (decaying) are counted by the argument principle as those with
Im Omega < 0 are.

**The soil's lines.** A free wave of the soil at a real horizontal wavenumber kappa solves
-omega^2 m + k + i omega c = 0 with its kinetic m > 0, strain k >= 0 and Kelvin-Voigt c = sum eta_j k_j
(each layer's strain energy times its eta), so Im omega = c / (2 m) >= eta_min |omega|^2 / 2 (|omega|^2 = k/m)
when underdamped, and Im omega >= k / c >= 1 / eta_max when overdamped. Its phase speed is at least
c_lo = 0.87 c_s,min (every surface wave of a soil with nu >= 0 is faster than 0.87 times its least shear
speed, :func:`~moving_bogie.soil.rayleigh.soil_modes`; 0.5 c_s,min for a negative nu), so the k1 <= kappa <=
|omega| / c_lo that meets it has |Re Omega| <= |omega| (1 + v / c_lo), and at Re Omega = X the soil's lines
lie no lower than

    y_soil(X) = min(eta_min X^2 / (2 (1 + v / c_lo)^2), 1 / eta_max)        (rad/s).

It vanishes like X^2 at Omega = 0 (the branch point where the lines start) and without damping: no band of
constant depth exists along the whole real axis. The band searched is a staircase under y_soil: STEPS
rectangles X1 2^-(i+1) <= Re Omega <= X1 2^-i, 0 <= Im Omega <= y_soil(X1 2^-(i+1)), X1 the window's size.

**The track's lines** (zeros of D at real k) have no such bound (the rail's bending and the ballast store
energy without damping). Each rectangle is scanned: at K_POINTS wavenumbers of each sign, geometric from
1e-3 / b to beyond the rail's bending in the window, the winding number of D(k, Omega + k v) along the
rectangle's edge (EDGE_POINTS samples, segments halved where a phase step reaches pi / 4, until every step
is below pi / 2) must be 0; a rectangle where it is not is halved in depth (HALVINGS times at most) or
dropped. This is a scan, not a bound (a wave between two scanned wavenumbers that enters and leaves the
rectangle is not seen), and the notes say so.

The roots found in the band, the least Im Omega among them (the margin, in 1/s) and the band itself are
reported; beyond the band (Re Omega < X1 2^-STEPS, or above the staircase) nothing is searched.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import mpmath
import numpy as np

from moving_bogie.roots.count.contour import EdgeZeroError, Rectangle

if TYPE_CHECKING:
    from moving_bogie.roots.frequency_result import InducedFrequency
    from moving_bogie.roots.quadrature_window import QuadratureCharacteristic
    from moving_bogie.soil.profile import SoilProfile
    from moving_bogie.soil.track import SoilTrack

__all__ = ["DecayingBand", "decaying_band", "soil_depth"]

#: Rectangles of the staircase; wavenumbers per sign and edge samples of the track's scan; depth halvings;
#: refinements of the scan's edge.
STEPS, K_POINTS, EDGE_POINTS, HALVINGS, REFINE = 2, 16, 24, 5, 4
#: The band's count: the receptance's relative tolerance, the largest step of arg E_chr and the initial
#: samples along a rectangle's long side (refined where the phase turns; the guard of
#: :func:`~moving_bogie.roots.quadrature_window.count_rectangle` recounts at the track's own tolerance
#: where an error reaches |E_chr| / 2).
BAND_TOL, BAND_STEP, BAND_SAMPLES = 1e-2, np.pi / 3, 4
#: The least phase speed of the soil's free waves over its least shear speed (module docstring).
SLOWEST, SLOWEST_ANY_NU = 0.87, 0.5


class BandRectangle(Rectangle):
    """A rectangle of the band: its first boundary samples at about the spacing asked on every edge, at
    least one segment per edge (a :class:`Rectangle` takes at least 8 per edge, which on a thin band's
    short sides costs values of E_chr that the phase does not need; the count refines where it turns)."""

    def boundary(self, spacing: float, least: int = 1) -> np.ndarray:
        return super().boundary(spacing, least)


def soil_depth(soil: SoilProfile, v: float, x: float) -> float:
    """y_soil(X) (rad/s) at Re Omega = ``x`` (rad/s) for a load at ``v`` (m/s): 0 without damping in some
    layer (module docstring)."""
    etas = [layer.eta for layer in soil.layers]
    if min(etas) <= 0:
        return 0.0
    floor = SLOWEST if min(layer.nu for layer in soil.layers) >= 0 else SLOWEST_ANY_NU
    c_lo = floor * soil.c_s_min
    return float(min(min(etas) * x**2 / (2 * (1 + v / c_lo) ** 2), 1 / max(etas)))


def _wavenumbers(track: SoilTrack, v: float, x1: float) -> np.ndarray:
    """The scan's k (1/m), both signs: from 1e-3 / b to where EI k^4 exceeds 16 m_tot (x1 + k v)^2."""
    m_tot = track.m + track.m_s + track.rho_b * track.A_b
    k_hi = 2 * max(1 / track.b, (16 * m_tot * x1**2 / track.EI) ** 0.25, 4 * v * np.sqrt(m_tot / track.EI))
    k = np.geomspace(1e-3 / track.b, k_hi, K_POINTS)
    return np.concatenate([-k[::-1], k])


def _edge(rect: Rectangle, t: np.ndarray) -> np.ndarray:
    """The point at fraction ``t`` of the counter-clockwise boundary of ``rect`` from its lower left."""
    w, h = rect.width, rect.height
    s = t * 2 * (w + h)
    return np.select(
        [s <= w, s <= w + h, s <= 2 * w + h],
        [
            rect.x0 + s + 1j * rect.y0,
            rect.x1 + 1j * (rect.y0 + s - w),
            rect.x1 - (s - w - h) + 1j * rect.y1,
        ],
        default=rect.x0 + 1j * (rect.y1 - (s - 2 * w - h)),
    )


def track_waves_clear(track: SoilTrack, soil: SoilProfile, v: float, rect: Rectangle) -> bool:
    """Whether no zero of D(k, Omega + k v) (a free wave of the track on its soil) lies in ``rect`` (rad/s)
    at any scanned k: the edge sampled (EDGE_POINTS, segments halved up to REFINE times where a phase step
    reaches pi / 4 at some k) until every step is below pi / 2, and every winding number 0 (module
    docstring). False when the sampling does not resolve the phase."""
    from moving_bogie.soil.strip import strip_stiffness

    k = _wavenumbers(track, v, rect.x1)

    def determinant(t: np.ndarray) -> np.ndarray:
        K, W = np.meshgrid(k, _edge(rect, t), indexing="ij")
        omega = W + K * v
        chi = strip_stiffness(K.ravel(), omega.ravel(), soil, track.b, rtol=1e-3).chi.reshape(K.shape)
        det = np.asarray(track.determinant(K, omega, chi))
        # the ballasted determinant also vanishes where the rod's sin(lam) / lam does (lam = n pi, on the
        # real axis), where D itself does not: divided out
        return det / track._ballast(omega)[0] if track.ballasted else det

    t = np.linspace(0.0, 1.0, EDGE_POINTS + 1)
    D = determinant(t)
    for _ in range(REFINE + 1):
        steps = np.abs(np.angle(D[:, 1:] / D[:, :-1]))
        coarse = np.any(steps >= np.pi / 4, axis=0)
        if not coarse.any() or _ == REFINE:
            break
        mid = 0.5 * (t[:-1] + t[1:])[coarse]
        t = np.concatenate([t, mid])
        order = np.argsort(t)
        t, D = t[order], np.concatenate([D, determinant(mid)], axis=1)[:, order]
    steps = np.angle(D[:, 1:] / D[:, :-1])
    return bool(np.all(np.abs(steps) < np.pi / 2) and np.all(np.abs(steps.sum(axis=1)) < np.pi))


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
            + f" (the track's free waves scanned at {2 * K_POINTS} wavenumbers, not bounded)"
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
    """Count and locate the roots of ``E`` in the staircase of ``steps`` rectangles under the singular
    lines (module docstring), the window's size ``radius`` (q) its right end."""
    from moving_bogie.roots.quadrature_window import count_rectangle, induced, locate
    from moving_bogie.soil.rail_track import SoilRail

    rail = E.bound.track
    assert isinstance(rail, SoilRail)
    track, soil, scale = rail.spec.track, rail.spec.soil, float(rail.omega_0)
    ends = [radius * 2.0**-i for i in range(steps + 1)]
    rects: list[Rectangle] = []
    dropped: list[Rectangle] = []
    for x1, x0 in zip(ends[:-1], ends[1:], strict=True):
        depth = soil_depth(soil, rail.v, x0 * scale) / scale
        if depth <= 0:
            return DecayingBand((), (), (), (), radius, scale, damped=False)
        for _ in range(HALVINGS + 1):
            si = Rectangle(x0 * scale, x1 * scale, 0.0, depth * scale)
            if track_waves_clear(track, soil, rail.v, si):
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
    return DecayingBand(tuple(rects), tuple(counts), tuple(roots), tuple(dropped), ends[-1], scale)
