"""Comparison window of the finite-beam validation: where the finite beam stands in for the infinite one.

The paper checks every closed-form time series against a long simply supported beam (Section 3.2).
The supports are invisible at the wheels only for a while; this module says for how long.

Comparison window
-----------------
The finite beam's ``tau_valid`` ends where the *fastest* wave the modes can carry could be back from a
support. That is a hard bound: before ``tau_valid`` there is no reflection at all. After it, the waves
that have had time to return are those with ``p_s(tau) <= p <= k_max``, where ``p_s(tau)`` is the
smallest wavenumber that can make the round trip to support ``s`` in ``tau`` (``c(p) - alpha = 2 x0 /
tau`` behind the rear wheel, ``c(p) + alpha = 2 (L - x0 - d) / tau`` ahead of the front wheel, with
``c(p)`` the largest group velocity of any dispersion branch up to ``p``). Their share of a wheel's
deflection is bounded by the track's point-load spectrum of a suddenly applied load (static deflection
1 per wheel; ``(8/pi) / (p^4 + 4)`` on the one-layer Euler-Bernoulli track):
``T(p_s) = int_{p_s}^{k_max}`` of it. A simply supported end reflects with magnitude 1, and every free
wave decays at least like ``exp(-s_min tau)``, ``s_min`` the slowest decay rate of the track's damped
per-mode blocks (``eta_f`` on the one-layer Euler-Bernoulli track). Summing over both supports with both
wheels as sources,

    R(tau) = 2 exp(-s_min tau) [T(p_left(tau)) + T(p_right(tau))]

bounds what the reflections can add at the wheels (ignoring dispersion, which spreads them further).
The window ends at the first ``tau`` where ``R`` exceeds ``reflection_level`` (default 1e-3, the
level the geometry already treats as negligible), or where the front wheel's near field reaches the
right support. Undamped cases keep essentially ``tau_valid``; in damped cases the reflections arrive
damped below 1e-3 and the window covers the run (Case 7, default beam: ``tau_valid`` 98, window 200).

Tolerance
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from moving_bogie.validation.finite_beam import FiniteBeamResult
from moving_bogie.validation.track_modes import ModalTrack

__all__ = [
    "DEFAULT_TAU_STEP",
    "comparison_window",
    "default_tau_max",
    "reflection_bound",
    "truncation_a_priori",
]


#: Default end of the run: undamped cases stop near the strict reflection-free window of the
#: 500-mode beam (``tau_valid`` ~ 98, because ``L`` is capped at ``500 pi / 4``); damped ones, whose
#: reflections return damped below 1e-3, run twice as long.
DEFAULT_TAU_MAX_UNDAMPED = 100.0
DEFAULT_TAU_MAX_DAMPED = 200.0

#: Output spacing of the common tau grid (the response's periods are 12 or longer; the finite
#: beam's Hermite interpolation and the closed form are both exact to far below the tolerance there).
DEFAULT_TAU_STEP = 0.05


def default_tau_max(params: Any) -> float:
    """Default end of a validation run: 200 when the track is damped, 100 without (see module notes)."""
    return DEFAULT_TAU_MAX_DAMPED if ModalTrack.of(params).damped else DEFAULT_TAU_MAX_UNDAMPED


def truncation_a_priori(k_max: float, track: ModalTrack) -> float:
    """Share of a point load's static deflection missed by modes up to `k_max`.

    The tail of the track's static point-load spectrum beyond `k_max`
    (:meth:`~moving_bogie.validation.track_modes.ModalTrack.truncation_share`); on the one-layer
    Euler-Bernoulli track ``(8/pi) int_{k_max}^inf dp / (p^4 + 4) < 8 / (3 pi k_max^3)``.
    """
    return track.truncation_share(k_max)


def reflection_bound(
    tau: np.ndarray,
    *,
    track: ModalTrack,
    length: float,
    entry: float,
    d: float,
    k_max: float,
) -> np.ndarray:
    """Upper bound ``R(tau)`` of what waves reflected at the supports add to a wheel's deflection.

    See the module docstring: zero until the fastest modelled wave can be back (``tau_valid``),
    then ``2 exp(-s_min tau) [T(p_left) + T(p_right)]`` with ``T`` the spectral share of the
    wavenumbers that have had time to return.
    """
    tau = np.asarray(tau, dtype=float)
    alpha = float(track.values["alpha"])
    p = np.linspace(0.0, k_max, 4001)
    c = track.group_velocity_envelope(p)  # non-decreasing in p
    bound = np.zeros_like(tau)
    gap_right = length - entry - d
    for distance, relative in ((entry, c - alpha), (gap_right, c + alpha)):
        ok = relative > 0
        if not ok.any():
            continue
        # Round-trip time of wavenumber p, non-increasing in p; the smallest p back by tau is p_s(tau).
        with np.errstate(divide="ignore"):
            trip = 2.0 * distance / relative[ok]
        p_ok = p[ok]
        arrived = tau >= trip[-1]
        p_s = np.interp(tau[arrived], trip[::-1], p_ok[::-1])
        bound[arrived] += 2.0 * track.spectrum_tail(p_s, k_max)
    return bound * np.exp(-track.free_wave_decay_rate(k_max) * tau)


def comparison_window(params: Any, finite: FiniteBeamResult, *, reflection_level: float = 1e-3) -> float:
    """End of the window ``[0, tau_w]`` in which the finite beam stands in for the infinite one.

    One dispersion branch (a beam whose only unknown is its deflection, on a track without mass layers):
    the first ``tau`` at which :func:`reflection_bound` exceeds `reflection_level`, or at which the
    front wheel's near field (decay ``exp(-gamma xi)``, margin ``ln(1000) / gamma``) reaches the right
    support, capped at the end of the run; never shorter than ``finite.tau_valid``.

    Several branches (a rotation unknown, mass layers): see :func:`_strict_window`; the bound's single
    spectrum does not tell how the branches share a wheel's deflection.
    """
    d = finite.span
    track = ModalTrack.of(params)
    alpha = float(track.values["alpha"])
    tau = finite.tau
    tau_end = float(tau[-1])
    if track.size > 1:
        return _strict_window(track, finite, alpha, d, reflection_level)
    bound = reflection_bound(
        tau, track=track, length=finite.length, entry=finite.entry, d=d, k_max=finite.k_max
    )
    over = np.nonzero(bound > reflection_level)[0]
    end = tau_end if over.size == 0 else float(tau[max(over[0] - 1, 0)])
    gamma = track.near_field_decay_rate()
    if gamma > 0 and alpha > 0:
        margin = math.log(1e3) / gamma
        end = min(end, (finite.length - finite.entry - d - margin) / alpha)
    return float(min(max(end, min(finite.tau_valid, tau_end)), tau_end))


def _strict_window(
    track: ModalTrack, finite: FiniteBeamResult, alpha: float, d: float, level: float
) -> float:
    """Several branches: the strict ``tau_valid``, or the whole run when every reflection is damped.

    A reflection arriving after ``tau_valid`` has travelled at least ``tau_valid`` (the waves leave at the
    sudden start), and every free wave decays at least like ``exp(-s_min tau)`` with ``s_min`` the
    slowest decay rate over the dispersion branches
    (:meth:`~moving_bogie.validation.track_modes.ModalTrack.free_wave_decay_rate`): when
    ``exp(-s_min tau_valid) <= level`` no reflection exceeds `level` (relative to a unit wave) and the
    window is the run. The front wheel's near field (decay from the roots of the track's moving-load
    symbol) caps it.
    """
    tau_end = float(finite.tau[-1])
    end = min(finite.tau_valid, tau_end)
    if track.free_wave_decay_rate(finite.k_max) * finite.tau_valid >= math.log(1.0 / level):
        end = tau_end
    gamma = track.near_field_decay_rate()
    if gamma > 0 and alpha > 0:
        end = min(end, (finite.length - finite.entry - d - math.log(1e3) / gamma) / alpha)
    return float(max(end, 0.0))
