"""Beam length, entry point, time step and reflection-free window of the finite-beam model.

The finite beam stands in for the paper's infinite one (Section 3.2) only as long as its supports
are invisible at the wheels. Two things can make them visible:

1. The near field. The steady deflection under a moving force decays like ``exp(-gamma |xi|)``, with
   ``gamma`` the smallest ``|Im p|`` over the roots of ``D(p, 0) = p^4 - 4 (alpha^2 - eta_s) p^2 -
   8 i eta_f alpha p + 4`` (Eq. (24) at ``q = 0`` with the Pasternak term). Keeping each support at
   least ``margin = ln(1/tol) / gamma`` away from the nearest wheel, from ``tau = 0`` to ``tau_max``,
   keeps the near field (and the initial static shape, paper's ref. [26]) on the beam to ``tol``.
2. Reflected waves. The sudden start and the motion radiate waves. A free wave of wavenumber ``p``
   travels at the group velocity ``c(p) = (p^3 + 2 eta_s p) / (2 omega(p))``, ``omega^2 = 1 + eta_s p^2
   + p^4/4``, which grows without bound with ``p`` on an Euler-Bernoulli beam; but the ``N``-mode
   model carries no wavenumber above ``k_max = N pi / L``, so its fastest waves travel at ``c_max =
   c(k_max)``. A wave leaving the rear wheel at ``tau = 0`` comes back from the left support at
   ``2 x0 / (c_max - alpha)``; one leaving the front wheel returns from the right support at ``2 (L -
   x0 - d) / (c_max + alpha)``. The earlier of the two (and the time the front wheel's near field
   reaches the right support) is ``tau_valid``: in ``(0, tau_valid)`` no reflection has reached the
   wheels. Waves slower than the vehicle never catch it after a reflection behind it, nor outrun it
   to the right support, which is why only ``c_max - alpha > 0`` counts.

With foundation damping, every free wave decays in time like ``exp(-eta_f tau)`` (modal damping
``2 eta_f`` is the same for all modes), so a reflection whose round trip takes ``T_d = ln(1/tol) /
eta_f`` or longer arrives below ``tol``. :func:`choose_geometry` therefore asks every reflection
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
from dataclasses import dataclass

import numpy as np

from moving_bogie.validation.track_modes import ModalTrack

__all__ = [
    "BeamGeometry",
    "choose_geometry",
    "default_time_step",
    "group_velocity",
    "max_group_velocity",
    "near_field_decay_rate",
    "reflection_window",
]


def near_field_decay_rate(
    alpha: float, eta_f: float, eta_s: float = 0.0, S: float | None = None, r: float = 0.0
) -> float:
    """Smallest spatial decay rate ``min |Im p|`` of the moving-force deflection.

    The roots of ``D(p, 0) = p^4 - 4 (alpha^2 - eta_s) p^2 - 8 i eta_f alpha p + 4`` (Eq. (24) at
    ``q = 0``, plus the Pasternak term ``4 eta_s p^2``) give the exponentials ``exp(i p xi)`` the
    steady deflection is made of on either side of the load.

    Returns
    -------
    float
        ``gamma >= 0``; 0 at and above the undamped critical velocity ``alpha = sqrt(1 + eta_s)``,
        Eq. (65), where the deflection radiates undamped waves.
    """
    if S is not None:
        # Timoshenko-Rayleigh: the denominator of the moving-load symbol (residual module).
        from moving_bogie.validation.residual import symbol_polynomials

        return float(np.min(np.abs(np.roots(symbol_polynomials(alpha, eta_f, eta_s, S, r)[1]).imag)))
    roots = np.roots([1.0, 0.0, -4.0 * (alpha * alpha - eta_s), -8j * eta_f * alpha, 4.0])
    return float(np.min(np.abs(roots.imag)))


def group_velocity(p: float | np.ndarray, eta_s: float = 0.0) -> float | np.ndarray:
    """Group velocity ``d omega / d p`` of free waves, ``omega^2 = 1 + eta_s p^2 + p^4 / 4``.

    This is the undamped dispersion relation of the dimensionless beam operator (fixed frame).
    """
    p = np.asarray(p, dtype=float)
    omega = np.sqrt(1.0 + eta_s * p * p + 0.25 * p**4)
    c = (p**3 + 2.0 * eta_s * p) / (2.0 * omega)
    return float(c) if c.ndim == 0 else c


def max_group_velocity(k_max: float, eta_s: float = 0.0, S: float | None = None, r: float = 0.0) -> float:
    """Fastest free wave that modes up to `k_max` carry.

    Euler-Bernoulli: ``c(k_max)`` (:func:`group_velocity` grows with ``p``). Timoshenko-Rayleigh: the
    largest ``d omega / d p`` over ``0 < p <= k_max`` of both branches of the modal 2x2 system of
    :attr:`~moving_bogie.validation.modal.ModalBeam.diagonals`,
    ``r^2 omega^4 - (r^2 (1 + (S + eta_s) p^2) + S + p^2/4) omega^2 + (1 + (S + eta_s) p^2)(S + p^2/4)
    - S^2 p^2 = 0`` (sampled on 4000 points, so a slight underestimate between samples).
    """
    if S is None:
        return float(group_velocity(k_max, eta_s))
    p = np.linspace(0.0, k_max, 4001)
    a = 1.0 + (S + eta_s) * p * p
    b = S + 0.25 * p * p
    half_sum = 0.5 * (r * r * a + b)
    root = np.sqrt(half_sum**2 - r * r * (a * b - S * S * p * p))
    fastest = 0.0
    for omega2 in ((half_sum - root) / (r * r), (half_sum + root) / (r * r)):
        fastest = max(fastest, float(np.max(np.gradient(np.sqrt(omega2), p))))
    return fastest


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


def _margin(
    alpha: float, eta_f: float, eta_s: float, tol: float, max_margin: float, S: float | None, r: float
) -> float:
    gamma = near_field_decay_rate(alpha, eta_f, eta_s, S, r)
    return min(math.log(1.0 / tol) / gamma, max_margin) if gamma > 0 else max_margin


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
    alpha: float,
    eta_f: float,
    eta_s: float,
    d: float,
    tau_max: float,
    n_modes: int,
    length: float | None = None,
    entry: float | None = None,
    tol: float = 1e-3,
    min_wavenumber: float = 4.0,
    max_margin: float = 100.0,
    S: float | None = None,
    r: float = 0.0,
    track: ModalTrack | None = None,
) -> BeamGeometry:
    """Beam length and entry point for a run to `tau_max` with `n_modes` modes.

    Parameters
    ----------
    alpha, eta_f, eta_s, d : float
        Velocity, foundation damping, Pasternak parameter, wheel spacing (dimensionless).
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
    S, r : float, optional
        Timoshenko-Rayleigh beam, Eq. (59): its near-field decay and fastest wave
        (:func:`max_group_velocity`); Euler-Bernoulli without `S`.
    track : ModalTrack, optional
        Any track model's finite-rail blocks (:mod:`~moving_bogie.validation.track_modes`, a layered
        track): the near-field decay from the roots of its moving-load symbol, the fastest wave over
        every dispersion branch and, in place of ``eta_f``, the slowest decay rate of its free waves.

    Returns
    -------
    BeamGeometry
    """
    if track is None:
        margin = _margin(alpha, eta_f, eta_s, tol, max_margin, S, r)
        decay = eta_f

        def fastest(k_max: float) -> float:
            return max_group_velocity(k_max, eta_s, S, r)

    else:
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
        # required(L) decreases with L (coarser modes, slower waves): bisect required(L) = L.
        lo, hi = hard, hard
        while required(hi) > hi:
            hi *= 2.0
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if required(mid) > mid else (lo, mid)
        length = max(hard, min(hi, n_modes * math.pi / min_wavenumber))
        reflection_ok = length >= hi
    else:
        reflection_ok = False
    c_max = c_of(length)
    if entry is None:
        if reflection_ok:
            entry = clearance(length)
        else:
            # Equalize 2 x0 / (c - alpha) and 2 (L - x0 - d) / (c + alpha), then clamp.
            entry = (length - d) * (c_max - alpha) / (2.0 * c_max) if c_max > alpha else margin
            entry = min(max(entry, margin), length - d - alpha * tau_max - margin)
    return BeamGeometry(
        length=float(length),
        entry=float(entry),
        k_max=n_modes * math.pi / length,
        c_max=c_max,
        margin=margin,
        tau_valid=reflection_window(length, entry, d, alpha, c_max, margin),
    )


#: Wavenumber band that carries the response: the static deflection spectrum ``8 / (p^4 + 4)``
#: leaves about 1.3 % of the deflection under a load above it (``8 / (3 pi p^3)``).
RELEVANT_WAVENUMBER = 4.0


def default_time_step(
    k_max: float,
    alpha: float,
    eta_s: float = 0.0,
    *,
    relevant_wavenumber: float = RELEVANT_WAVENUMBER,
    steps_per_period: float = 32.0,
) -> float:
    """Time step that resolves the relevant band with `steps_per_period` steps per period.

    Average acceleration is unconditionally stable, so ``h`` is only an accuracy choice, and the
    trapezoidal rule's error is a period error of about ``(omega h)^2 / 12`` per cycle. The motion
    to resolve is that of the wavenumbers up to ``k = min(k_max, relevant_wavenumber)``: their
    frequency ``omega(k) = sqrt(1 + eta_s k^2 + k^4 / 4)`` and the rate ``alpha k`` at which a
    wheel crosses their half wavelength ``pi / k`` (which drives the time variation of the contact
    terms ``a_j, b_j, c_j`` and with it the curvature term ``alpha^2 c_j.q``). Modes above the band
    carry little of the response; measured on Case 1, refining ``h`` changes the results by the same
    amount with ``k_max = 4`` or ``8``, i.e. the unresolved top modes do not add time error.

    Parameters
    ----------
    k_max : float
        Highest modelled wavenumber ``N pi / L``.
    alpha, eta_s : float
        Velocity and Pasternak parameter.
    relevant_wavenumber : float, optional
        Upper end of the resolved band (default 4).
    steps_per_period : float, optional
        Default 32: about 0.1 % error in the contact deflection of Case 1 (measured, see
        ``docs/finite_beam.md``).
    """
    k = min(k_max, relevant_wavenumber)
    omega = math.sqrt(1.0 + eta_s * k * k + 0.25 * k**4)
    return 2.0 * math.pi / (steps_per_period * max(omega, alpha * k))
