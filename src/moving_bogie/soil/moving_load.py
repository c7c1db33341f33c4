"""The steady response of a track on the soil to a constant load P moving at speed v (docs/soil.md, Eq. (S8)).

In the frame of the load, xi = x - v t (positive ahead), the rail's deflection is

    w(xi) = (1 / 2 pi) int P exp(-i k1 xi) / D(k1, k1 v) dk1 = (P / pi) Re int_0^inf exp(-i k1 xi) / D dk1,

D the rail's dynamic stiffness on the soil (:meth:`~.track.SoilTrack.rail_stiffness`) at omega = k1 v
(D(-k1, -omega) is the complex conjugate of D(k1, omega) under Kelvin-Voigt damping): the rail's receptance
at Omega = 0 times P, w(xi) = P G(xi, 0) (:func:`~.receptance.soil_receptance`, Eq. (S9), one side of
k1 = 0): its Gauss-Kronrod panels, geometric in k1 and bisected where the two rules differ, each speed on
its own panels and every speed of a call evaluated together; chi only as accurate as 1/D needs; the ends
below k_lo (where the integrand grows only like log(1 / k1)) and above k_hi (1 / (EI k1^4)) bounded and,
with chi's error, added to the error.
The soil must be damped (eta > 0 in every layer): at and beyond the critical velocity the undamped steady
response is unbounded.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from moving_bogie.errors import ParameterError
from moving_bogie.kernels.fminbound import fminbound
from moving_bogie.typing import FloatArray

from .profile import SoilProfile
from .receptance import soil_receptance
from .track import SoilTrack

__all__ = ["PEAK_XTOL", "Deflection", "MovingLoad", "deflection", "moving_load"]

#: The peak speed is refined to this fraction of the bracket of two grid steps around the largest value.
PEAK_XTOL = 1e-4


@dataclass(frozen=True)
class Deflection:
    """w(xi) (m) at the points ``xi`` (m, ahead of the load positive) and its estimated error."""

    xi: FloatArray
    w: FloatArray
    error: FloatArray


def deflection(
    track: SoilTrack,
    soil: SoilProfile,
    load: float,
    v: float | FloatArray,
    xi: FloatArray | None = None,
    *,
    rtol: float = 1e-5,
) -> Deflection:
    """The steady deflection w(xi) (m) under ``load`` (N, downwards) moving at ``v`` (m/s) (module doc); an
    array of speeds gives ``w`` and ``error`` of shape (speeds, xi), all computed together."""
    if np.any(np.asarray(v) != 0) and any(layer.eta <= 0 for layer in soil.layers):
        raise ParameterError(
            "eta", "a moving load needs Kelvin-Voigt damping eta > 0 in every [[soil]] layer"
        )
    xi = np.atleast_1d(np.asarray(0.0 if xi is None else xi, dtype=float))
    rest = np.zeros(np.shape(v), dtype=complex)  # Omega = 0: the steady response
    rec = soil_receptance(track, soil, np.asarray(v, dtype=float), rest, xi, tol=rtol)
    w = load * rec.G.real
    error = np.multiply.outer(abs(load) * rec.error, np.ones(xi.size))
    if np.ndim(v) == 0:
        w, error = w[0], error[0]
    return Deflection(xi=xi, w=w, error=error)


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
    """w(0) at each speed of ``speeds`` (m/s), w_static, and the peak of |w(0)| refined between the
    neighbours of the largest grid value by Brent's bounded search (golden sections and parabolic steps,
    :func:`~moving_bogie.kernels.fminbound.fminbound`) to PEAK_XTOL of that bracket."""
    speeds = np.asarray(speeds, dtype=float)
    # the static deflection and every speed in one quadrature
    values = deflection(track, soil, load, np.concatenate([[0.0], speeds]), rtol=rtol)
    static, w = values.w[0, 0], values.w[1:, 0]
    error = float(values.error.max())
    i = int(np.argmax(np.abs(w)))
    v_peak, w_peak = float(speeds[i]), float(w[i])
    if 0 < i < len(speeds) - 1:
        seen: dict[float, float] = {}

        def minus_peak(x: float) -> float:
            seen[x] = float(deflection(track, soil, load, x, rtol=rtol).w[0])
            return -abs(seen[x])

        a, b = float(speeds[i - 1]), float(speeds[i + 1])
        v_peak = fminbound(minus_peak, a, b, xatol=PEAK_XTOL * (b - a))[0]
        w_peak = seen[v_peak]  # the best point is one of those evaluated
    return MovingLoad(v=speeds, w=w, w_static=float(static), v_peak=v_peak, w_peak=w_peak, error=error)
