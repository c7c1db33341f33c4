"""The steady response of a track on the soil to a constant load P moving at speed v (docs/soil.md, Eq. (S8)).

In the frame of the load, xi = x - v t (positive ahead), the rail's deflection is

    w(xi) = (1 / 2 pi) int P exp(-i k1 xi) / D(k1, k1 v) dk1 = (P / pi) Re int_0^inf exp(-i k1 xi) / D dk1,

D the rail's dynamic stiffness on the soil (:meth:`~.track.SoilTrack.rail_stiffness`) at omega = k1 v
(D(-k1, -omega) is the complex conjugate of D(k1, omega) under Kelvin-Voigt damping). The integral runs on
Gauss-Kronrod (7, 15) panels, geometric in k1, bisected where the two rules differ (adaptively, all panels
of a round at once); below k_lo = 1e-6 / b the integrand grows only like log(1 / k1) (chi vanishes like
1 / log there) and above k_hi it is 1 / (EI k1^4): both ends are bounded and added to the error.
The soil must be damped (eta > 0 in every layer): at and beyond the critical velocity the undamped steady
response is unbounded.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from moving_bogie.errors import ParameterError
from moving_bogie.typing import ComplexArray, FloatArray

from .profile import SoilProfile
from .strip import NODES, WEIGHTS_G, WEIGHTS_K, strip_stiffness
from .track import SoilTrack

__all__ = ["Deflection", "MovingLoad", "deflection", "moving_load"]


@dataclass(frozen=True)
class Deflection:
    """w(xi) (m) at the points ``xi`` (m, ahead of the load positive) and its estimated error."""

    xi: FloatArray
    w: FloatArray
    error: FloatArray


def _integrand(track: SoilTrack, soil: SoilProfile, k1: FloatArray, v: float) -> ComplexArray:
    omega = k1 * v
    chi = strip_stiffness(k1, omega, soil, track.b).chi
    return np.asarray(1 / track.rail_stiffness(k1, omega, chi), dtype=complex)


def _panels(
    f: Callable[[FloatArray], ComplexArray],
    xi: FloatArray,
    k_lo: float,
    k_hi: float,
    rtol: float,
    rounds: int,
) -> tuple[ComplexArray, FloatArray]:
    """int_{k_lo}^{k_hi} exp(-i k1 xi) f(k1) dk1 for each xi by adaptive Gauss-Kronrod panels (geometric
    halves); a panel is kept when its Kronrod-Gauss difference is below its share (its width in log k1) of
    rtol times the running total. Returns (integral, error estimate) per xi."""
    panels = np.geomspace(k_lo, k_hi, 25)
    panels = np.stack([panels[:-1], panels[1:]], -1)
    span = np.log(k_hi / k_lo)
    total = np.zeros(xi.shape, dtype=complex)
    error = np.zeros(xi.shape)
    for step in range(rounds):
        half, mid = (panels[:, 1] - panels[:, 0]) / 2, (panels[:, 1] + panels[:, 0]) / 2
        k1 = mid[:, None] + half[:, None] * NODES
        g = f(k1.ravel()).reshape(k1.shape)
        weighted = np.exp(-1j * np.multiply.outer(xi, k1)) * g
        kronrod = (weighted * WEIGHTS_K).sum(-1) * half
        diff = np.abs(kronrod - (weighted * WEIGHTS_G).sum(-1) * half)
        scale = np.abs(total + kronrod.sum(-1)).max()
        share = np.log(panels[:, 1] / panels[:, 0]) / span
        keep = (diff.max(axis=0) <= rtol * scale * share) | (step == rounds - 1)
        total += kronrod[:, keep].sum(-1)
        error += diff[:, keep].sum(-1)
        if keep.all():
            break
        a, b = panels[~keep, 0], panels[~keep, 1]
        centre = np.sqrt(a * b)
        panels = np.concatenate([np.stack([a, centre], -1), np.stack([centre, b], -1)])
    return total, error


def deflection(
    track: SoilTrack,
    soil: SoilProfile,
    load: float,
    v: float,
    xi: FloatArray | None = None,
    *,
    rtol: float = 1e-5,
    rounds: int = 8,
) -> Deflection:
    """The steady deflection w(xi) (m) under ``load`` (N, downwards) moving at ``v`` (m/s) (module doc)."""
    if v != 0 and any(layer.eta <= 0 for layer in soil.layers):
        raise ParameterError(
            "eta", "a moving load needs Kelvin-Voigt damping eta > 0 in every [[soil]] layer"
        )
    xi = np.atleast_1d(np.asarray(0.0 if xi is None else xi, dtype=float))
    chi_b = abs(strip_stiffness(np.array([1 / track.b]), np.zeros(1), soil, track.b).chi[0])
    k_ref = max(1 / track.b, (chi_b / track.EI) ** 0.25)
    k_lo, k_hi = 1e-6 / track.b, 300 * k_ref
    total, error = _panels(lambda k1: _integrand(track, soil, k1, v), xi, k_lo, k_hi, rtol, rounds)
    # the ends: int_0^k_lo of a log-growing integrand is below 2 k_lo |f(k_lo)|; beyond k_hi,
    # 1 / (3 EI k_hi^3)
    g_lo = abs(_integrand(track, soil, np.array([k_lo]), v)[0])
    error = error + 2 * k_lo * g_lo + 1 / (3 * track.EI * k_hi**3)
    return Deflection(xi=xi, w=load / np.pi * total.real, error=abs(load) / np.pi * error)


@dataclass(frozen=True)
class MovingLoad:
    """The deflection under the load against speed, its peak, and the static deflection (m)."""

    v: FloatArray
    w: FloatArray
    w_static: float
    v_peak: float
    w_peak: float
    error: float

    @property
    def daf(self) -> FloatArray:
        """Dynamic amplification: w(0, v) / w_static."""
        return self.w / self.w_static

    @property
    def daf_peak(self) -> float:
        return self.w_peak / self.w_static


def moving_load(
    track: SoilTrack, soil: SoilProfile, load: float, speeds: FloatArray, *, rtol: float = 1e-5
) -> MovingLoad:
    """w(0) at each speed of ``speeds`` (m/s), w_static, and the peak of |w(0)| refined by golden-section
    search between the neighbours of the largest grid value."""
    speeds = np.asarray(speeds, dtype=float)
    static = deflection(track, soil, load, 0.0, rtol=rtol)
    values = [deflection(track, soil, load, float(v), rtol=rtol) for v in speeds]
    w = np.array([d.w[0] for d in values])
    error = max([static.error[0], *(d.error[0] for d in values)])
    i = int(np.argmax(np.abs(w)))
    v_peak, w_peak = float(speeds[i]), float(w[i])
    if 0 < i < len(speeds) - 1:
        g = (np.sqrt(5) - 1) / 2
        a, b = float(speeds[i - 1]), float(speeds[i + 1])
        x1, x2 = b - g * (b - a), a + g * (b - a)
        f1, f2 = (abs(deflection(track, soil, load, x, rtol=rtol).w[0]) for x in (x1, x2))
        for _ in range(20):  # the bracket shrinks to 1e-4 of two grid steps
            if f1 > f2:
                b, x2, f2 = x2, x1, f1
                x1 = b - g * (b - a)
                f1 = abs(deflection(track, soil, load, x1, rtol=rtol).w[0])
            else:
                a, x1, f1 = x1, x2, f2
                x2 = a + g * (b - a)
                f2 = abs(deflection(track, soil, load, x2, rtol=rtol).w[0])
        v_peak = x1 if f1 > f2 else x2
        w_peak = float(deflection(track, soil, load, v_peak, rtol=rtol).w[0])
    return MovingLoad(v=speeds, w=w, w_static=float(static.w[0]), v_peak=v_peak, w_peak=w_peak, error=error)
