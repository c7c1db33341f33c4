"""The finite-beam check of the Floquet theory of a vehicle on a rail on sleepers (docs/sleepers.md).

Three quantities, each from the Floquet theory (:mod:`moving_bogie.roots.strip`,
:mod:`moving_bogie.response.steady_bay`) and from the finite rail in the time domain
(:mod:`moving_bogie.validation.sleepers_beam`, which uses no Floquet theory):

- the growth (or decay) rate of the free vibration: ``-Im q`` of the least damped root against
  ``ln |mu| / T0``, ``mu`` the Floquet multiplier of the mode that dominates a run released from the static
  deflection with the loads removed: an eigenvalue of its stroboscopic map, sampled once per bay-passing
  period ``T0`` (:func:`~moving_bogie.validation.sleepers_fit.fit_floquet_modes`);
- the dominant frequency of that free vibration: ``|Re q + n Omega_0|`` for the harmonic ``n`` that carries
  the largest contact displacement in the root's null vector of the Hill matrix (S13), against the same for
  the fitted mode's largest harmonic at the rear wheel;
- the steady contact force over a bay (S16)-(S18), against the loaded run's last bay; the difference is
  judged relative to the Floquet force's peak-to-peak variation over the bay.

The rate and the frequency are compared when the Floquet theory finds a root (Im q <= 0: an unstable case);
the steady force when it finds none (a stable case: the loaded run then tends to the steady response).
Each must agree within ``tol`` (1 % by default), relative to the Floquet value.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from functools import partial

import numpy as np

from moving_bogie.kernels.hill import FloquetSystem, VehicleMatrices
from moving_bogie.kernels.sleeper_track import SleeperTrack
from moving_bogie.response.steady_bay import SteadyResponse, steady_response
from moving_bogie.roots.strip import FloquetResult, floquet_frequencies
from moving_bogie.validation.sleeper_verdict import Comparison, SleeperCheck
from moving_bogie.validation.sleepers_beam import BeamRun, simulate_sleeper_beam
from moving_bogie.validation.sleepers_fit import (
    FloquetFit,
    PeriodicLimit,
    extrapolated,
    fit_floquet_modes,
    periodic_limit,
    smooth_steps,
)
from moving_bogie.validation.sleepers_rail import SleeperRail

__all__ = [
    "Comparison",
    "FloquetSide",
    "SleeperBeamSettings",
    "SleeperCheck",
    "check_sleepers",
    "floquet_side",
]

#: the rail beyond the wheels' path at each end, in units of 1 / chi (the static deflection decays like
#: e^{-x} cos x: below 1e-4 of its peak there)
MARGIN = 10.0


#: the Floquet steady response's convergence in the harmonics, relative to its largest value (the mean force
#: 2): a hundredth of its default, so that its truncation stays far below the tolerance on the force's
#: peak-to-peak, a few percent of the mean
STEADY_TOL = 1e-5


@dataclass(frozen=True)
class SleeperBeamSettings:
    """The finite model's resolution: Hermite elements per bay, time steps per bay-passing period, the
    periods of the free run, the fraction of them left out of the fit as the transient and the rail beyond
    the wheel's path at each end (units of 1 / chi)."""

    elements: int = 8
    steps_per_period: int = 200
    periods: int = 40
    transient: float = 0.4
    margin: float = MARGIN


def _dominant_root(result: FloquetResult) -> complex | None:
    roots = [r.q for r in result.roots if r.q.imag <= 0]
    return min(roots, key=lambda q: q.imag) if roots else None


def floquet_frequency(track: SleeperTrack, vehicle: VehicleMatrices, q: complex, N: int) -> float:
    """``|Re q + n Omega_0|`` for the harmonic n with the largest contact displacement in the null vector of
    the Hill matrix (S13) at the root ``q`` (the smallest right singular vector)."""
    system = FloquetSystem(track, vehicle, N, tol=1e-10)
    matrix, _ = system.matrix(q)
    null = np.linalg.svd(matrix)[2][-1].conj()
    c = vehicle.contacts
    amplitudes = np.abs(null[: system.harmonics.size * c].reshape(-1, c)[:, 0])
    n = system.harmonics[int(np.argmax(amplitudes))]
    return abs(q.real + n * track.Omega0)


def _relative(floquet: float, finite: float) -> float:
    return abs(finite - floquet) / abs(floquet) if floquet != 0 else math.inf


@dataclass(frozen=True)
class FloquetSide:
    """The Floquet theory's answers: the search, its least damped root with Im q <= 0 and that root's
    dominant frequency (an unstable case), or the steady response (a stable one); the wall time."""

    result: FloquetResult
    root: complex | None
    frequency: float | None
    steady: SteadyResponse | None
    seconds: float


def floquet_side(
    track: SleeperTrack, vehicle: VehicleMatrices, loads: np.ndarray, harmonics: tuple[int, int] = (1, 6)
) -> FloquetSide:
    """Roots by :func:`floquet_frequencies` (N from ``harmonics[0]`` to ``harmonics[1]``), then the root's
    frequency (:func:`floquet_frequency`) or the steady response (:func:`steady_response`)."""
    start = time.perf_counter()
    result = floquet_frequencies(track, vehicle, N0=harmonics[0], N_max=harmonics[1])
    root = _dominant_root(result)
    nu = None if root is None else floquet_frequency(track, vehicle, root, result.harmonics)
    steady = None if root is not None else steady_response(track, vehicle, loads, points=129, tol=STEADY_TOL)
    return FloquetSide(result, root, nu, steady, time.perf_counter() - start)


def _stage(
    progress: Callable[[float], None] | None, start: float, width: float
) -> Callable[[float], None] | None:
    """The progress of one run of the finite rail, from ``start`` over ``width`` of the whole check (the
    Floquet side takes about its first tenth)."""
    if progress is None:
        return None
    progress(start)
    return lambda x: progress(start + width * x)


def _rate_text(rate: float, time_scale: float | None) -> str:
    """A rate with its unit: 1/s when the seconds per unit tau are known, else per unit tau."""
    return f"{rate:.4g} per unit tau" if time_scale is None else f"{rate / time_scale:.4g} 1/s"


def _free_vibration_fit(
    free: BeamRun, T0: float, fit_start: float, notes: list[str]
) -> tuple[FloquetFit, float]:
    """The stroboscopic map fitted to the free run (the deflection under every wheel and the vehicle's
    internal unknowns) from ``fit_start`` on, or from tau = 0 when the run has decayed to round-off before
    it (noted); with the spread of its rate, the difference between the rates fitted to the window's first
    and second halves (how steady the rate is: a transient not yet gone shows here)."""
    signals = np.vstack([free.deflection, free.internal])
    try:
        fit = fit_floquet_modes(free.tau, signals, T0, fit_start)
    except ValueError:  # decayed to round-off before the window: a stable case, whose rate is not compared
        fit = fit_floquet_modes(free.tau, signals, T0, 0.0)
        notes.append("the free vibration decayed to round-off early: its rate is fitted from tau = 0")
    middle = fit.window[0] + (fit.samples // 2) * T0
    try:
        first = fit_floquet_modes(
            free.tau[free.tau < middle], signals[:, free.tau < middle], T0, fit.window[0]
        )
        second = fit_floquet_modes(free.tau, signals, T0, middle)
        spread = abs(first.rate - second.rate)
    except ValueError:  # a half too short, or decayed to round-off
        spread = math.nan
    return fit, spread


def _rate_comparisons(
    fit: FloquetFit, coarse: FloquetFit, root: complex, frequency: float, tol: float, notes: list[str]
) -> list[Comparison]:
    """The growth rate and the dominant frequency of the Floquet root against the finite rail's, extrapolated
    to a zero time step from its runs at dt and 2 dt (noted when that moves the rate by more than ``tol``)."""
    rate, nu = extrapolated(fit, coarse)
    if abs(rate - fit.rate) > tol * abs(root.imag):
        notes.append(
            f"the time step moves the finite rail's rate by {abs(fit.rate / rate - 1):.2%} (more than the "
            "tolerance; near a zone's edge the rate tends to 0): it is compared extrapolated to dt -> 0"
        )
    return [
        Comparison("growth rate -Im q", -root.imag, rate, _relative(-root.imag, rate), tol),
        Comparison("dominant frequency", frequency, nu, _relative(frequency, nu), tol),
    ]


def _steady_comparison(
    track: SleeperTrack, steady: SteadyResponse, loaded: BeamRun, T0: float, start: float, tol: float
) -> tuple[Comparison, PeriodicLimit, np.ndarray]:
    """The loaded run's periodic limit (:func:`periodic_limit` of its smoothed contact force from ``start``
    to its last averaged step: the stroboscopic map's fixed point, so that a slowly decaying vibration is
    removed rather than waited out) against the Floquet steady force (S18) at the same positions in the bay,
    judged by max |difference| relative to the Floquet peak-to-peak; with the limit and the Floquet force at
    its times (for the figure)."""
    keep = slice(0, loaded.tau.size - 1)  # the last step is not averaged (smooth_steps)
    force = smooth_steps(loaded.force[0])[keep]
    limit = periodic_limit(loaded.tau[keep], force, T0, start)
    position = (loaded.entry + track.alpha * limit.tau) % track.lam
    phase = np.exp(1j * track.Omega0 * np.outer(position / track.alpha, steady.harmonics))
    reference = np.real(phase @ steady.force_harmonics[:, 0])
    spread = float(np.ptp(reference))
    diff = float(np.max(np.abs(limit.values[0] - reference)))
    name = "steady force over a bay"
    comparison = Comparison(name, spread, float(np.ptp(limit.values[0])), diff / spread, tol)
    return comparison, limit, reference


def check_sleepers(
    track: SleeperTrack,
    vehicle: VehicleMatrices,
    loads: np.ndarray,
    *,
    settings: SleeperBeamSettings | None = None,
    tol: float = 0.01,
    harmonics: tuple[int, int] = (1, 6),
    floquet: FloquetSide | None = None,
    time_scale: float | None = None,
    progress: Callable[[float], None] | None = None,
) -> SleeperCheck:
    """Compare the finite rail with the Floquet theory for one vehicle on one sleeper track (module doc).

    ``harmonics`` are the first and the largest N of the Floquet search (:func:`floquet_frequencies`);
    ``floquet`` the Floquet side already computed (:func:`floquet_side`), e.g. for a convergence study;
    ``time_scale`` the seconds per unit of tau (for the notes and the figure in SI units); ``progress`` is
    called with the fraction done (the Floquet side, then the finite rail's runs).
    """
    settings = SleeperBeamSettings() if settings is None else settings
    side = floquet_side(track, vehicle, loads, harmonics) if floquet is None else floquet
    root, steady = side.root, side.steady
    T0 = track.lam / track.alpha
    tau_free = settings.periods * T0
    margin = math.ceil(settings.margin / track.lam)
    travel = math.ceil(track.alpha * tau_free / track.lam) + 1
    rail = SleeperRail(track, 2 * margin + travel, settings.elements)
    entry = margin * track.lam
    dt = T0 / settings.steps_per_period
    start = time.perf_counter()
    simulate = partial(simulate_sleeper_beam, rail, vehicle, loads, entry=entry, tau_max=tau_free)
    share = 0.9 / (1.5 if root is not None and side.frequency is not None else 2.0)  # the first run's
    free = simulate(dt=dt, loaded=False, progress=_stage(progress, 0.1, share))
    notes = list(side.result.notes)
    fit, spread = _free_vibration_fit(free, T0, settings.transient * tau_free, notes)
    comparisons: list[Comparison] = []
    loaded = coarse = None
    steady_tau = steady_force = limit_force = None
    if root is not None and side.frequency is not None:
        # the same free run at twice the step: the rate and the frequency extrapolated to dt -> 0
        run = simulate(dt=2 * dt, loaded=False, progress=_stage(progress, 0.1 + share, 0.9 - share))
        coarse = _free_vibration_fit(run, T0, settings.transient * tau_free, notes)[0]
        comparisons = _rate_comparisons(fit, coarse, root, side.frequency, tol, notes)
    else:
        rate_text = _rate_text(fit.rate, time_scale)
        notes.append(
            f"no Floquet root with Im q <= 0 (stable): the free vibration's rate {rate_text} is not compared"
        )
        assert steady is not None
        loaded = simulate(dt=dt, progress=_stage(progress, 0.1 + share, 0.9 - share))
        start_fit = settings.transient * tau_free
        comparison, limit, steady_force = _steady_comparison(track, steady, loaded, T0, start_fit, tol)
        comparisons.append(comparison)
        steady_tau, limit_force = limit.tau, limit.values[0]
        notes.extend(limit.notes(tol))
    finite_s = time.perf_counter() - start
    return SleeperCheck(
        tuple(comparisons),
        side.result.verdict.state,
        root,
        track.Omega0,
        free,
        loaded,
        steady_tau,
        steady_force,
        fit,
        coarse,
        spread,
        rail,
        side.seconds,
        finite_s,
        tuple(notes),
        time_scale,
        limit_force,
    )
