"""Where the kernel of a track on the soil stays analytic above the real axis (the physical sheet).

The kernel G(0, Omega) = (1/2 pi) int dk / D(k, Omega + k v), integrated along real k (docs/soil.md,
Eq. (S9)), is analytic for Im Omega < 0. It continues analytically into Im Omega > 0 as long as no
singularity of the integrand reaches the real k axis: a free wave of the soil (a pole or branch point of
chi, met by the real k2 path of the strip's quadrature) or of the track on its soil (a zero of D) at a real
wavenumber. Where one does, Omega = omega - k v lies on a singular line. This module bounds the soil's
lines from below (:func:`soil_depth`) and scans a rectangle for the track's (:func:`track_waves_clear`);
:mod:`moving_bogie.roots.decaying_band` counts the decaying roots below them.

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
constant depth exists along the whole real axis. The band searched is a staircase under y_soil
(:mod:`moving_bogie.roots.decaying_band`).

**The track's lines** (zeros of D at real k) have no such bound (the rail's bending and the ballast store
energy without damping). Each rectangle is scanned: at K_POINTS wavenumbers of each sign, geometric from
1e-3 / b to beyond the rail's bending in the window, the winding number of D(k, Omega + k v) along the
rectangle's edge (EDGE_POINTS samples, segments halved where a phase step reaches pi / 4, until every step
is below pi / 2) must be 0; a rectangle where it is not is halved in depth (HALVINGS times at most) or
dropped. This is a scan, not a bound (a wave between two scanned wavenumbers that enters and leaves the
rectangle is not seen), and the notes say so.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from .profile import SoilProfile
    from .track import SoilTrack

__all__ = ["SCAN_NOTE", "soil_depth", "track_waves_clear"]

#: Wavenumbers per sign and edge samples of the track's scan; refinements of the scan's edge.
K_POINTS, EDGE_POINTS, REFINE = 16, 24, 4
#: The least phase speed of the soil's free waves over its least shear speed (module docstring).
SLOWEST, SLOWEST_ANY_NU = 0.87, 0.5
#: What the scan of the track's lines is, for the notes of a result.
SCAN_NOTE = f"the track's free waves scanned at {2 * K_POINTS} wavenumbers, not bounded"


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


def _edge(rect: tuple[float, float, float, float], t: np.ndarray) -> np.ndarray:
    """The point at fraction ``t`` of the counter-clockwise boundary of ``rect`` = (x0, x1, y0, y1) from its
    lower left."""
    x0, x1, y0, y1 = rect
    w, h = x1 - x0, y1 - y0
    s = t * 2 * (w + h)
    return np.select(
        [s <= w, s <= w + h, s <= 2 * w + h],
        [x0 + s + 1j * y0, x1 + 1j * (y0 + s - w), x1 - (s - w - h) + 1j * y1],
        default=x0 + 1j * (y1 - (s - 2 * w - h)),
    )


def track_waves_clear(
    track: SoilTrack, soil: SoilProfile, v: float, rect: tuple[float, float, float, float]
) -> bool:
    """Whether no zero of D(k, Omega + k v) (a free wave of the track on its soil) lies in ``rect`` =
    (x0, x1, y0, y1) (rad/s)
    at any scanned k: the edge sampled (EDGE_POINTS, segments halved up to REFINE times where a phase step
    reaches pi / 4 at some k) until every step is below pi / 2, and every winding number 0 (module
    docstring). False when the sampling does not resolve the phase."""
    from .strip import strip_stiffness

    k = _wavenumbers(track, v, rect[1])

    def determinant(t: np.ndarray) -> np.ndarray:
        K, W = np.meshgrid(k, _edge(rect, t), indexing="ij")
        omega = W + K * v
        chi = strip_stiffness(K.ravel(), omega.ravel(), soil, track.b, rtol=1e-3).chi.reshape(K.shape)
        return np.asarray(track.wave_determinant(K, omega, chi))

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
