"""Comparison window of the finite-beam validation: where the finite beam stands in for the infinite one.

The paper checks every closed-form time series against a long simply supported beam (Section 3.2).
The supports are invisible at the wheels only for a while; this module says for how long.

Comparison window
-----------------
The finite beam's ``tau_valid`` ends where the *fastest* wave the modes can carry (group velocity
``c(k_max)``) could be back from a support. That is a hard bound: before ``tau_valid`` there is no
reflection at all. After it, the waves that have had time to return are those with ``p_s(tau) <= p
<= k_max``, where ``p_s(tau)`` is the wavenumber whose round trip to support ``s`` takes ``tau``
(``c(p) - alpha = 2 x0 / tau`` behind the rear wheel, ``c(p) + alpha = 2 (L - x0 - d) / tau`` ahead of
the front wheel). Their share of a wheel's deflection is bounded by the point-load spectrum
``8 / (p^4 + 4)`` of a suddenly applied load (static deflection 1 per wheel): at most
``T(p_s) = (8 / 3 pi) (p_s^-3 - k_max^-3)``. A simply supported end reflects with magnitude 1, and
every free wave decays like ``exp(-eta_f tau)`` (the modal damping ``2 eta_f`` is the same for all
modes). Summing over both supports with both wheels as sources,

    R(tau) = 2 exp(-eta_f tau) [T(p_left(tau)) + T(p_right(tau))]

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

from moving_bogie.validation.finite_beam import FiniteBeamResult, layered_track
from moving_bogie.validation.geometry import group_velocity, near_field_decay_rate
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
    """Default end of a validation run: 200 with foundation damping, 100 without (see module notes)."""
    return DEFAULT_TAU_MAX_DAMPED if float(params.eta_f) > 0 else DEFAULT_TAU_MAX_UNDAMPED


def truncation_a_priori(k_max: float) -> float:
    """Share ``8 / (3 pi k_max^3)`` of a point load's static deflection missed by modes up to `k_max`.

    The static deflection spectrum of a point load is ``8 / (p^4 + 4)`` (normalised to deflection
    1); its tail beyond ``k_max`` integrates to at most this.
    """
    return 8.0 / (3.0 * math.pi * k_max**3)


def _tail(p: np.ndarray, k_max: float) -> np.ndarray:
    """Spectral share of a point load's deflection between `p` and `k_max` (bound ``8/(3 pi p^3)`` tail)."""
    with np.errstate(divide="ignore"):
        share = (8.0 / (3.0 * math.pi)) * (np.power(p, -3.0) - k_max**-3.0)
    return np.clip(share, 0.0, 1.0)


def reflection_bound(
    tau: np.ndarray,
    *,
    length: float,
    entry: float,
    d: float,
    alpha: float,
    eta_f: float,
    eta_s: float,
    k_max: float,
) -> np.ndarray:
    """Upper bound ``R(tau)`` of what waves reflected at the supports add to a wheel's deflection.

    See the module docstring: zero until the fastest modelled wave can be back (``tau_valid``),
    then ``2 exp(-eta_f tau) [T(p_left) + T(p_right)]`` with ``T`` the spectral share of the
    wavenumbers that have had time to return.
    """
    tau = np.asarray(tau, dtype=float)
    p = np.linspace(0.0, k_max, 4001)
    c = np.asarray(group_velocity(p, eta_s))  # increasing in p
    bound = np.zeros_like(tau)
    gap_right = length - entry - d
    for distance, relative in ((entry, c - alpha), (gap_right, c + alpha)):
        ok = relative > 0
        if not ok.any():
            continue
        # Round-trip time of wavenumber p, decreasing in p; the smallest p back by tau is p_s(tau).
        with np.errstate(divide="ignore"):
            trip = 2.0 * distance / relative[ok]
        p_ok = p[ok]
        arrived = tau >= trip[-1]
        p_s = np.interp(tau[arrived], trip[::-1], p_ok[::-1])
        bound[arrived] += 2.0 * _tail(p_s, k_max)
    return bound * np.exp(-eta_f * tau)


def comparison_window(params: Any, finite: FiniteBeamResult, *, reflection_level: float = 1e-3) -> float:
    """End of the window ``[0, tau_w]`` in which the finite beam stands in for the infinite one.

    The first ``tau`` at which :func:`reflection_bound` exceeds `reflection_level`, or at which the
    front wheel's near field (decay ``exp(-gamma xi)``, margin ``ln(1000) / gamma``) reaches the
    right support, capped at the end of the run; never shorter than ``finite.tau_valid``.

    Layered track: see :func:`_layered_window`.

    Timoshenko-Rayleigh beam: the bound uses the Euler-Bernoulli spectrum and group velocity, so
    the window is the strict ``tau_valid`` of its fastest modelled wave (both branches), capped by
    the near field.
    """
    alpha, eta_f, d = float(params.alpha), float(params.eta_f), float(params.d)
    eta_s = float(getattr(params, "eta_s", 0.0))
    tau = finite.tau
    tau_end = float(tau[-1])
    track = layered_track(params)
    if track is not None:
        return _layered_window(track, finite, alpha, d, reflection_level)
    if getattr(params, "beam", "eb") == "tr":
        gamma = near_field_decay_rate(alpha, eta_f, eta_s, float(params.S), float(params.r))
        end = min(finite.tau_valid, tau_end)
        if gamma > 0 and alpha > 0:
            end = min(end, (finite.length - finite.entry - d - math.log(1e3) / gamma) / alpha)
        return float(max(end, 0.0))
    bound = reflection_bound(
        tau,
        length=finite.length,
        entry=finite.entry,
        d=d,
        alpha=alpha,
        eta_f=eta_f,
        eta_s=eta_s,
        k_max=finite.k_max,
    )
    over = np.nonzero(bound > reflection_level)[0]
    end = tau_end if over.size == 0 else float(tau[max(over[0] - 1, 0)])
    gamma = near_field_decay_rate(alpha, eta_f, eta_s)
    if gamma > 0 and alpha > 0:
        margin = math.log(1e3) / gamma
        end = min(end, (finite.length - finite.entry - d - margin) / alpha)
    return float(min(max(end, min(finite.tau_valid, tau_end)), tau_end))


def _layered_window(
    track: ModalTrack, finite: FiniteBeamResult, alpha: float, d: float, level: float
) -> float:
    """Window on a layered track: the strict ``tau_valid``, or the whole run when every reflection is damped.

    A reflection arriving after ``tau_valid`` has travelled at least ``tau_valid`` (the waves leave at the
    sudden start), and every free wave decays at least like ``exp(-s_min tau)`` with ``s_min`` the
    slowest decay rate over the dispersion branches
    (:meth:`~moving_bogie.validation.track_modes.ModalTrack.free_wave_decay_rate`): when
    ``exp(-s_min tau_valid) <= level`` no reflection exceeds `level` (relative to a unit wave) and the
    window is the run. The front wheel's near field (decay from the roots of the track's moving-load
    symbol) caps it as on the one-layer track.
    """
    tau_end = float(finite.tau[-1])
    end = min(finite.tau_valid, tau_end)
    if track.free_wave_decay_rate(finite.k_max) * finite.tau_valid >= math.log(1.0 / level):
        end = tau_end
    gamma = track.near_field_decay_rate()
    if gamma > 0 and alpha > 0:
        end = min(end, (finite.length - finite.entry - d - math.log(1e3) / gamma) / alpha)
    return float(max(end, 0.0))
