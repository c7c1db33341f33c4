"""The threshold mass of a moving mass on a track on the soil, by D-decomposition along real Omega.

A mass M on the rail at the contact (a wheel without suspension) vibrates at Omega where the rail's
deflection under the inertia force M Omega^2 w is w itself: 1 = M Omega^2 G(0, Omega) (Eq. (S9)). A root
crosses the real axis (the boundary of stability) where that M is real and positive:

    M(Omega) = 1 / (Omega^2 G(0, Omega)),   Im M(Omega) = 0,   Re M(Omega) > 0,   Omega > 0

(the pairs Omega, -conj(Omega) give the same M). The crossings are found as the sign changes of
Im 1 / G along a grid of real Omega, refined by the secant method; at each, the root moves with M as
dOmega / dM = -1 / (M^2 (Omega^2 G)'), so it enters Im Omega < 0 (instability) as M grows past the crossing
when Im dOmega / dM < 0. Without a mass there is no vibration, so the threshold mass is the smallest
crossing at which a root enters the lower half-plane (as long as none leaves it at a smaller one).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from moving_bogie.typing import FloatArray

from .profile import SoilProfile
from .receptance import soil_receptance
from .track import SoilTrack

__all__ = ["Crossing", "ThresholdMass", "threshold_mass"]

#: Secant steps refining a crossing, and its relative resolution in Omega.
STEPS, RESOLUTION = 30, 1e-10


@dataclass(frozen=True)
class Crossing:
    """A root on the real axis: at ``omega`` (rad/s) for the mass ``M`` (kg); ``unstable_above`` when it
    enters Im Omega < 0 as M grows past M."""

    omega: float
    M: float
    unstable_above: bool
    error: float  # the receptance's relative error there


@dataclass(frozen=True)
class ThresholdMass:
    """Every crossing on the grid of Omega, the threshold (smallest M at which a root enters Im Omega < 0;
    None when none does on the grid) and the grid itself (rad/s)."""

    crossings: tuple[Crossing, ...]
    M: float | None
    omega: FloatArray

    def to_dict(self) -> dict[str, object]:
        return {
            "M_threshold": self.M,
            "crossings": [
                {"omega": c.omega, "M": c.M, "unstable_above": c.unstable_above, "relative_error": c.error}
                for c in self.crossings
            ],
            "omega_grid": [float(self.omega[0]), float(self.omega[-1]), int(self.omega.size)],
            "units": {"omega": "rad/s", "M": "kg"},
        }


def _inverse(
    track: SoilTrack, soil: SoilProfile, v: float, omega: FloatArray
) -> tuple[np.ndarray, np.ndarray]:
    rec = soil_receptance(track, soil, v, omega.astype(complex))
    G = rec.G[..., 0]
    return 1 / G, rec.error / np.abs(G)


def _refine(
    track: SoilTrack, soil: SoilProfile, v: float, a: float, b: float
) -> tuple[float, complex, float]:
    """The Omega in [a, b] where Im 1/G = 0 (secant, bracketed), 1/G and its relative error there."""
    fa, fb = (float(_inverse(track, soil, v, np.array([x]))[0][0].imag) for x in (a, b))
    for _ in range(STEPS):
        c = b - fb * (b - a) / (fb - fa) if fb != fa else 0.5 * (a + b)
        if not a < c < b:
            c = 0.5 * (a + b)
        inv, err = _inverse(track, soil, v, np.array([c]))
        fc = float(inv[0].imag)
        if fc == 0 or (b - a) < RESOLUTION * b:
            return c, complex(inv[0]), float(err[0])
        a, fa, b, fb = (a, fa, c, fc) if np.sign(fc) != np.sign(fa) else (c, fc, b, fb)
    inv, err = _inverse(track, soil, v, np.array([c]))
    return c, complex(inv[0]), float(err[0])


def threshold_mass(track: SoilTrack, soil: SoilProfile, v: float, omega: FloatArray) -> ThresholdMass:
    """The crossings of a mass moving at ``v`` (m/s) on ``track`` over ``soil`` along the real ``omega``
    grid (rad/s, positive, increasing) and the threshold mass (module docstring)."""
    omega = np.asarray(omega, dtype=float)
    inv, _ = _inverse(track, soil, v, omega)
    change = np.nonzero(np.sign(inv.imag[:-1]) * np.sign(inv.imag[1:]) < 0)[0]
    crossings = []
    for i in change:
        w, inv_w, err = _refine(track, soil, v, float(omega[i]), float(omega[i + 1]))
        M = inv_w.real / w**2
        if M <= 0:
            continue
        h = 1e-6 * w
        ends = _inverse(track, soil, v, np.array([w - h, w + h]))[0]
        slope = (w + h) ** 2 / ends[1] - (w - h) ** 2 / ends[0]  # d(Omega^2 G) over 2 h
        d_omega = -1 / (M**2 * slope / (2 * h))
        crossings.append(Crossing(w, float(M), bool(d_omega.imag < 0), err))
    threshold = None
    for c in sorted(crossings, key=lambda c: c.M):
        if c.unstable_above:
            threshold = c.M
            break
    return ThresholdMass(tuple(crossings), threshold, omega)
