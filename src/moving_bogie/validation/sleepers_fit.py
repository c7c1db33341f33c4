"""What the finite rail's time series say: growth rate and dominant frequency (docs/sleepers.md (S26)).

A free vibration of the vehicle on the periodic rail is a sum of Floquet modes ``e^{i q tau} P(tau)``, ``P``
periodic with the bay-passing period ``T0 = lam / alpha``; once the least damped one dominates, the
root-mean-square of the deflection under the wheel over successive periods ``T0`` grows by ``e^{-Im q T0}``
per period (exactly so in a parametric zone, where ``Re q = Omega_0 / 2``). :func:`envelope_rate` fits that
rate by least squares to the logarithm of the per-period values (those above 1e-6 of the largest);
:func:`dominant_frequency` finds the peak of the spectrum of the signal with the fitted growth removed.
Neither uses the Floquet theory: they read the time series only.
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import minimize_scalar

__all__ = ["dominant_frequency", "envelope_rate", "period_rms", "smooth_steps"]


def smooth_steps(x: np.ndarray) -> np.ndarray:
    """``(x_{n-1} + 2 x_n + x_{n+1}) / 4`` at interior steps: removes the period-two oscillation that the
    trapezoidal rule leaves in the accelerations of the stiffest elements (a second-order average)."""
    out = np.array(x, dtype=float, copy=True)
    out[..., 1:-1] = 0.25 * x[..., :-2] + 0.5 * x[..., 1:-1] + 0.25 * x[..., 2:]
    return out


def period_rms(tau: np.ndarray, x: np.ndarray, period: float) -> tuple[np.ndarray, np.ndarray]:
    """(mid times, root-mean-square of ``x``) over the successive whole periods in ``tau`` (trapezoidal)."""
    count = int((tau[-1] - tau[0]) / period + 1e-9)
    mids, values = [], []
    for k in range(count):
        a, b = tau[0] + k * period, tau[0] + (k + 1) * period
        grid = np.linspace(a, b, 257)
        y = np.interp(grid, tau, x)
        values.append(np.sqrt(np.trapezoid(y * y, grid) / period))
        mids.append((a + b) / 2)
    return np.array(mids), np.array(values)


def envelope_rate(tau: np.ndarray, x: np.ndarray, period: float, start: float) -> tuple[float, float]:
    """(rate, spread): the least-squares slope of log RMS per period against time, over the periods after
    ``start``, and the largest difference between the slopes fitted to the first and the second half of
    them (how steady the rate is: a transient not yet gone shows here)."""
    inside = tau >= start
    mids, rms = period_rms(tau[inside], x[inside], period)
    # a decay that reached the round-off of the run stops there: those periods say nothing of the rate
    keep = rms >= 1e-6 * np.max(period_rms(tau, x, period)[1])
    mids, rms = mids[keep], rms[keep]
    if mids.size < 6:
        raise ValueError("the fit window holds fewer than 6 periods")
    logs = np.log(rms)
    rate = float(np.polyfit(mids, logs, 1)[0])
    half = mids.size // 2
    first, second = (
        float(np.polyfit(m, y, 1)[0]) for m, y in ((mids[:half], logs[:half]), (mids[half:], logs[half:]))
    )
    return rate, abs(first - second)


def dominant_frequency(tau: np.ndarray, x: np.ndarray, rate: float, start: float, top: float) -> float:
    """The angular frequency below ``top`` at which the Hann-windowed spectrum of ``x e^{-rate tau}`` (from
    ``start`` on, its mean removed) peaks: a grid of a quarter of the resolution, then a bounded search."""
    inside = tau >= start
    t, y = tau[inside], x[inside] * np.exp(-rate * (tau[inside] - start))
    y = (y - y.mean()) * np.hanning(y.size)
    dt = float(np.mean(np.diff(t)))

    def power(w: float) -> float:
        return float(abs(np.sum(y * np.exp(-1j * w * t))) * dt)

    step = 2 * np.pi / (t[-1] - t[0]) / 4
    grid = np.arange(step, top, step)
    best = grid[int(np.argmax([power(w) for w in grid]))]
    found = minimize_scalar(
        lambda w: -power(w), bounds=(best - step, best + step), method="bounded", options={"xatol": 1e-10}
    )
    return float(found.x)
