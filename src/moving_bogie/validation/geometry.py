"""Beam length, entry point, time step and reflection-free window of the finite-beam model.

The finite beam stands in for the paper's infinite one (Section 3.2) only as long as its supports
are invisible at the wheels. Two things can make them visible:

1. The near field. The steady deflection under a moving force decays like ``exp(-gamma |xi|)``, with
   ``gamma`` the smallest ``|Im p|`` over the roots of the track's moving-load symbol (Eq. (24) at
   ``q = 0``: ``D(p, 0) = p^4 - 4 (alpha^2 - eta_s) p^2 - 8 i eta_f alpha p + 4`` on the one-layer
   Euler-Bernoulli track; :meth:`~moving_bogie.validation.track_modes.ModalTrack.near_field_decay_rate`
   for any track). Keeping each support at
   least ``margin = ln(1/tol) / gamma`` away from the nearest wheel, from ``tau = 0`` to ``tau_max``,
   keeps the near field (and the initial static shape, paper's ref. [26]) on the beam to ``tol``.
2. Reflected waves. The sudden start and the motion radiate waves. A free wave of wavenumber ``p``
   travels at the group velocity ``d omega_j / d p`` of its dispersion branch ``omega_j(p)`` (the
   eigenvalues of the track's per-mode blocks; on the one-layer Euler-Bernoulli track ``c(p) = (p^3 +
   2 eta_s p) / (2 omega(p))``, ``omega^2 = 1 + eta_s p^2 + p^4/4``, which grows without bound with
   ``p``); but the ``N``-mode model carries no wavenumber above ``k_max = N pi / L``, so its fastest
   waves travel at ``c_max``, the largest group velocity of any branch up to ``k_max``. A wave
   leaving the rear wheel at ``tau = 0`` comes back from the left support at
   ``2 x0 / (c_max - alpha)``; one leaving the front wheel returns from the right support at ``2 (L -
   x0 - d) / (c_max + alpha)``. The earlier of the two (and the time the front wheel's near field
   reaches the right support) is ``tau_valid``: in ``(0, tau_valid)`` no reflection has reached the
   wheels. Waves slower than the vehicle never catch it after a reflection behind it, nor outrun it
   to the right support, which is why only ``c_max - alpha > 0`` counts.

With damping, every free wave decays in time at least like ``exp(-s_min tau)``, ``s_min`` the slowest
decay rate of the track's damped per-mode blocks (``eta_f`` on the one-layer Euler-Bernoulli track, whose
modal damping ``2 eta_f`` is the same for all modes), so a reflection whose round trip takes ``T_d =
ln(1/tol) / s_min`` or longer arrives below ``tol``. :func:`choose_geometry` therefore asks every reflection
that arrives before ``tau_max`` to have travelled at least ``T_req = min(tau_max, T_d)``; this needs

    x0 >= max(margin, T_req (c_max - alpha) / 2),
    L - x0 - d >= alpha tau_max + max(margin, T_req (c_max - alpha) / 2),

and the smallest such ``L`` (``c_max`` depends on ``L`` through ``k_max``) gives the finest modal
resolution for the given ``N``. The resolution matters: a point load's deflection spectrum falls
like ``8 / p^4``, so the truncated series misses about ``8 / (3 pi k_max^3)`` of the static
deflection under a wheel (1.3 % at ``k_max = 4``, 0.4 % at 6) and about ``8 / (pi k_max)`` of its
curvature. When the reflection criterion would push ``k_max`` below ``min_wavenumber``, the length is
capped at ``N pi / min_wavenumber`` (but never below what keeps the wheels and their near field on
the beam until ``tau_max``), and ``tau_valid`` then reports how long the result is reflection-free.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

from moving_bogie.validation.track_modes import ModalTrack

__all__ = ["BeamGeometry", "choose_geometry", "default_time_step", "reflection_window"]


@dataclass(frozen=True)
class BeamGeometry:
    """A finite beam for one run and how far it can be trusted.

    Attributes
    ----------
    length : float
        Dimensionless beam length ``L``.
    entry : float
        Rear-wheel position ``x0`` at ``tau = 0``.
    k_max : float
        Highest modelled wavenumber ``N pi / L``.
    c_max : float
        Group velocity at ``k_max``: the fastest wave the modes can carry.
    margin : float
        Near-field clearance ``ln(1/tol) / gamma`` kept between wheels and supports.
    tau_valid : float
        End of the window ``(0, tau_valid)`` free of reflections (``inf`` if none can ever return).
    """

    length: float
    entry: float
    k_max: float
    c_max: float
    margin: float
    tau_valid: float


def reflection_window(
    length: float, entry: float, d: float, alpha: float, c_max: float, margin: float
) -> float:
    """End ``tau_valid`` of the reflection-free window of a given beam; see the module docstring.

    Returns
    -------
    float
        Earliest of: the left-support reflection of the rear wheel's waves, ``2 x0 / (c_max -
        alpha)``; the right-support reflection of the front wheel's waves, ``2 (L - x0 - d) / (c_max
        + alpha)``; the front wheel's near field reaching the right support, ``(L - x0 - d - margin)
        / alpha``. Zero if a support starts inside a wheel's near field.
    """
    gap_right = length - entry - d
    slack = 1e-9 * max(margin, 1.0)  # the chosen geometries sit exactly on the margins
    if entry < margin - slack or gap_right < margin - slack:
        return 0.0
    tau_left = 2.0 * entry / (c_max - alpha) if c_max > alpha else math.inf
    tau_right = 2.0 * gap_right / (c_max + alpha)
    tau_exit = (gap_right - margin) / alpha if alpha > 0 else math.inf
    return min(tau_left, tau_right, tau_exit)


def choose_geometry(
    *,
    track: ModalTrack,
    d: float,
    tau_max: float,
    n_modes: int,
    length: float | None = None,
    entry: float | None = None,
    tol: float = 1e-3,
    min_wavenumber: float = 4.0,
    max_margin: float = 100.0,
) -> BeamGeometry:
    """Beam length and entry point for a run to `tau_max` with `n_modes` modes.

    Parameters
    ----------
    track : ModalTrack
        The track model's finite-rail blocks (:mod:`~moving_bogie.validation.track_modes`) with the
        velocity ``alpha`` among its values: the near-field decay from the roots of its moving-load symbol,
        the fastest wave over every dispersion branch and the slowest decay rate of its free waves.
    d : float
        Distance from the rear to the front contact (dimensionless).
    tau_max : float
        End of the run.
    n_modes : int
        Number of modes ``N``.
    length, entry : float, optional
        Impose ``L`` and/or ``x0``; the other is chosen (``x0`` to balance the two reflection
        times, clamped to the near-field margins).
    tol : float, optional
        Near-field level and reflection damping level regarded as negligible (default 1e-3).
    min_wavenumber : float, optional
        Smallest acceptable ``k_max = N pi / L`` when the reflection criterion and the resolution
        conflict (default 4: about 1.3 % truncation of the static deflection).
    max_margin : float, optional
        Cap of the near-field margin for (nearly) undamped critical velocities, where
        ``gamma -> 0`` (default 100).

    Returns
    -------
    BeamGeometry
    """
    alpha = float(track.values["alpha"])
    gamma = track.near_field_decay_rate()
    margin = min(math.log(1.0 / tol) / gamma, max_margin) if gamma > 0 else max_margin
    # the shortest beam the search below can reach (or the one imposed): its k_max bounds all others
    candidates = [margin + d + alpha * tau_max + (margin if entry is None else min(entry, margin))]
    k_top = n_modes * math.pi / min(candidates + ([] if length is None else [length]))
    decay = track.free_wave_decay_rate(k_top)
    fastest = track.fastest_wave(k_top)
    t_req = tau_max if decay <= 0 else min(tau_max, math.log(1.0 / tol) / decay)

    def c_of(L: float) -> float:
        return fastest(n_modes * math.pi / L)

    def clearance(L: float) -> float:
        return max(margin, 0.5 * t_req * max(c_of(L) - alpha, 0.0))

    def required(L: float) -> float:
        left = clearance(L) if entry is None else entry
        return left + d + alpha * tau_max + clearance(L)

    hard = (margin if entry is None else entry) + d + alpha * tau_max + margin
    if length is None:
        length, reflection_ok = _reflection_free_length(required, hard, n_modes * math.pi / min_wavenumber)
    else:
        reflection_ok = False
    c_max = c_of(length)
    if entry is None:
        entry = (
            clearance(length) if reflection_ok else _balanced_entry(length, d, alpha, tau_max, c_max, margin)
        )
    return BeamGeometry(
        length=float(length),
        entry=float(entry),
        k_max=n_modes * math.pi / length,
        c_max=c_max,
        margin=margin,
        tau_valid=reflection_window(length, entry, d, alpha, c_max, margin),
    )


def _reflection_free_length(
    required: Callable[[float], float], hard: float, longest: float
) -> tuple[float, bool]:
    """(L, reflection-free): the shortest L with ``required(L) <= L``, at least ``hard``, at most ``longest``.

    required(L) decreases with L (coarser modes, slower waves): bisect required(L) = L. When ``longest``
    (the smallest acceptable k_max) cuts it short, the run is not reflection-free.
    """
    lo, hi = hard, hard
    while required(hi) > hi:
        hi *= 2.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if required(mid) > mid else (lo, mid)
    length = max(hard, min(hi, longest))
    return length, length >= hi


def _balanced_entry(
    length: float, d: float, alpha: float, tau_max: float, c_max: float, margin: float
) -> float:
    """x0 that equalises the two reflection times 2 x0 / (c - alpha) and 2 (L - x0 - d) / (c + alpha),
    clamped to the near-field margins."""
    entry = (length - d) * (c_max - alpha) / (2.0 * c_max) if c_max > alpha else margin
    return min(max(entry, margin), length - d - alpha * tau_max - margin)


#: Wavenumber band that carries the response: the static deflection spectrum ``8 / (p^4 + 4)``
#: leaves about 1.3 % of the deflection under a load above it (``8 / (3 pi p^3)``).
RELEVANT_WAVENUMBER = 4.0


def default_time_step(
    k_max: float,
    track: ModalTrack,
    *,
    relevant_wavenumber: float = RELEVANT_WAVENUMBER,
    steps_per_period: float = 32.0,
) -> float:
    """Time step that resolves the relevant band with `steps_per_period` steps per period.

    Average acceleration is unconditionally stable, so ``h`` is only an accuracy choice, and the
    trapezoidal rule's error is a period error of about ``(omega h)^2 / 12`` per cycle. The motion
    to resolve is that of the wavenumbers up to ``k = min(k_max, relevant_wavenumber)``: the rail's
    frequency there (:meth:`~moving_bogie.validation.track_modes.ModalTrack.rail_frequency`; on the
    one-layer Euler-Bernoulli track ``omega(k) = sqrt(1 + eta_s k^2 + k^4 / 4)``) and the rate ``alpha k``
    at which a wheel crosses its half wavelength ``pi / k`` (which drives the time variation of the contact
    terms ``a_j, b_j, c_j`` and with it the curvature term ``alpha^2 c_j.q``). Modes above the band
    carry little of the response; measured on Case 1, refining ``h`` changes the results by the same
    amount with ``k_max = 4`` or ``8``, i.e. the unresolved top modes do not add time error.

    Parameters
    ----------
    k_max : float
        Highest modelled wavenumber ``N pi / L``.
    track : ModalTrack
        The track model's finite-rail blocks, the velocity ``alpha`` among its values.
    relevant_wavenumber : float, optional
        Upper end of the resolved band (default 4).
    steps_per_period : float, optional
        Default 32: about 0.1 % error in the contact deflection of Case 1 (measured, see
        ``docs/finite_beam.md``).
    """
    k = min(k_max, relevant_wavenumber)
    omega = track.rail_frequency(k)
    return 2.0 * math.pi / (steps_per_period * max(omega, float(track.values["alpha"]) * k))
