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
from typing import TypeVar

import numpy as np

from moving_bogie.kernels.hill import VehicleMatrices
from moving_bogie.kernels.sleeper_track import SleeperTrack
from moving_bogie.response.steady_bay import SteadyResponse
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
from moving_bogie.validation.sleepers_floquet import STEADY_TOL, FloquetSide, floquet_frequency, floquet_side
from moving_bogie.validation.sleepers_rail import (
    ABSORBING,
    MARGIN,
    SleeperBeamSettings,
    SleeperRail,
    rail_for_run,
)

__all__ = [
    "ABSORBING",
    "MARGIN",
    "Comparison",
    "FloquetSide",
    "SleeperBeamSettings",
    "SleeperCheck",
    "STEADY_TOL",
    "check_sleepers",
    "floquet_frequency",
    "floquet_side",
]

#: the periodic limit read from the fit window's last three quarters must agree with the whole window's
#: within this fraction of the tolerance (relative to the limit's peak-to-peak); otherwise the window holds
#: too few periods to separate the transient's modes, and the loaded run is made again, twice as long (once)
WINDOW_AGREEMENT = 0.25

T = TypeVar("T")


def _relative(floquet: float, finite: float) -> float:
    return abs(finite - floquet) / abs(floquet) if floquet != 0 else math.inf


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


def _rate_change(free: BeamRun, fit: FloquetFit, T0: float) -> float:
    """How far the free vibration's rate moves when it is fitted to the last three quarters of the window of
    ``fit`` only, relative to the rate (a window too short to separate the modes shows here); 0 when that
    part is too short to fit."""
    signals = np.vstack([free.deflection, free.internal])
    later = fit.window[0] + 0.25 * (fit.window[1] - fit.window[0])
    try:
        rate = fit_floquet_modes(free.tau, signals, T0, later).rate
    except ValueError:  # decayed to round-off, or too short: nothing to compare
        return 0.0
    return abs(rate - fit.rate) / abs(fit.rate) if fit.rate != 0 else math.inf


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


def _limit_of(loaded: BeamRun, T0: float, start: float) -> PeriodicLimit:
    """The loaded run's periodic limit (:func:`periodic_limit`) from ``start`` to its last averaged step, of
    every signal of the run, smoothed: the contact forces, the deflections under the wheels and the
    vehicle's internal unknowns, so that modes of one shape at one wheel are told apart by the others."""
    keep = slice(0, loaded.tau.size - 1)  # the last step is not averaged (smooth_steps)
    signals = smooth_steps(np.vstack([loaded.force, loaded.deflection, loaded.internal]))[:, keep]
    return periodic_limit(loaded.tau[keep], signals, T0, start)


def _window_change(loaded: BeamRun, limit: PeriodicLimit, T0: float, start: float) -> float:
    """How far the contact forces' periodic limit moves when it is read from the last three quarters of the
    window from ``start`` only, relative to each force's peak-to-peak (the largest): a window too short to
    separate the transient's modes shows here."""
    later = _limit_of(loaded, T0, start + 0.25 * (loaded.tau[-1] - start))
    forces = slice(0, loaded.force.shape[0])
    change = np.abs(later.values[forces] - limit.values[forces])
    return float(np.max(np.max(change, axis=1) / np.ptp(limit.values[forces], axis=1)))


def _steady_comparison(
    track: SleeperTrack, steady: SteadyResponse, loaded: BeamRun, T0: float, start: float, tol: float
) -> tuple[Comparison, PeriodicLimit, np.ndarray]:
    """The loaded run's periodic limit (:func:`_limit_of`: the stroboscopic map's fixed point, so that a
    slowly decaying vibration is removed rather than waited out) against the Floquet steady force (S18) of
    each wheel at the same positions in the bay, judged by max |difference| relative to that wheel's
    Floquet peak-to-peak (the worst wheel's is compared); with the limit and the rear wheel's Floquet force
    at its times (for the figure)."""
    limit = _limit_of(loaded, T0, start)
    position = (loaded.entry + track.alpha * limit.tau) % track.lam
    phase = np.exp(1j * track.Omega0 * np.outer(position / track.alpha, steady.harmonics))
    references = np.real(phase @ steady.force_harmonics).T  # (contacts, phases)
    spreads = np.ptp(references, axis=1)
    relative = np.max(np.abs(limit.values[: spreads.size] - references), axis=1) / spreads
    worst = int(np.argmax(relative))
    name = "steady force over a bay"
    finite = float(np.ptp(limit.values[worst]))
    comparison = Comparison(name, float(spreads[worst]), finite, float(relative[worst]), tol)
    return comparison, limit, references[0]


@dataclass(frozen=True)
class _SteadyCheck:
    """The steady force's comparison, the loaded run it read, its periodic limit and the Floquet force."""

    comparison: Comparison
    loaded: BeamRun
    limit: PeriodicLimit
    reference: np.ndarray


def _twice(
    attempt: Callable[[int, Callable[[float], None] | None], tuple[T, float]],
    periods: int,
    limit: float,
    what: str,
    notes: list[str],
    progress: Callable[[float], None] | None,
) -> tuple[T, int]:
    """``attempt(periods, progress)`` -> (its result, how far ``what`` moves between the fit window and its
    last three quarters); made once more over twice the periods when that move exceeds ``limit`` (too few
    periods to separate the transient's modes), noted, as a move left after that is. Returns the last
    result and its periods."""
    for again in (False, True):
        result, moved = attempt(periods, None if again else progress)
        if moved <= limit:
            break
        told = (
            f"{what} moved by {moved:.2%} between the fit window and its last three quarters over {periods}"
        )
        if again:
            notes.append(f"{told} periods, made again: the record may be too short")
        else:
            notes.append(f"{told} periods: the run is made again over {2 * periods}")
            periods *= 2
    return result, periods


def _steady_check(
    run: Callable[..., BeamRun],
    track: SleeperTrack,
    steady: SteadyResponse,
    settings: SleeperBeamSettings,
    tol: float,
    notes: list[str],
    progress: Callable[[float], None] | None,
) -> _SteadyCheck:
    """The loaded run of ``settings.periods`` (``run(periods, progress=)``) against the Floquet steady force;
    run again with twice the periods when its periodic limit moves by more than ``WINDOW_AGREEMENT tol``
    between the fit window and its last three quarters (:func:`_twice`)."""
    T0 = track.lam / track.alpha

    def attempt(periods: int, stage: Callable[[float], None] | None) -> tuple[_SteadyCheck, float]:
        loaded = run(periods, progress=stage)
        start = settings.transient * periods * T0
        comparison, limit, reference = _steady_comparison(track, steady, loaded, T0, start, tol)
        return _SteadyCheck(comparison, loaded, limit, reference), _window_change(loaded, limit, T0, start)

    what = "the loaded run's periodic limit (relative to its peak-to-peak)"
    checked = _twice(attempt, settings.periods, WINDOW_AGREEMENT * tol, what, notes, progress)[0]
    notes.extend(checked.limit.notes(tol))
    if not steady.converged:
        notes.append(
            f"the Floquet steady response still changes by {steady.change:.2g} of its largest value at its "
            f"last harmonics (asked: {STEADY_TOL:g})"
        )
    return checked


def _run(
    rails: dict[int, tuple[SleeperRail, float]],
    track: SleeperTrack,
    vehicle: VehicleMatrices,
    loads: np.ndarray,
    settings: SleeperBeamSettings,
    periods: int,
    dt: float,
    loaded: bool,
    progress: Callable[[float], None] | None = None,
) -> BeamRun:
    """A run of ``periods`` bay-passing periods on its rail (:func:`rail_for_run`, kept in ``rails``)."""
    if periods not in rails:
        rails[periods] = rail_for_run(
            track,
            vehicle.positions,
            periods * track.lam,
            settings.elements,
            settings.margin,
            settings.absorbing,
        )
    rail, entry = rails[periods]
    T0 = track.lam / track.alpha
    return simulate_sleeper_beam(
        rail, vehicle, loads, entry=entry, tau_max=periods * T0, dt=dt, loaded=loaded, progress=progress
    )


def _growing(
    run: Callable[..., BeamRun],
    free: BeamRun,
    fit: FloquetFit,
    spread: float,
    settings: SleeperBeamSettings,
    tol: float,
    notes: list[str],
    progress: Callable[[float], None] | None,
) -> tuple[BeamRun, FloquetFit, float, FloquetFit]:
    """(free run, its fit, the fit's spread, the fit at twice the step) of an unstable case: the free run
    (``free``, already made over ``settings.periods``) made again over twice the periods when the rate
    moves by more than ``WINDOW_AGREEMENT tol`` between the fit window and its last three quarters
    (:func:`_twice`), then the same run at ``2 dt`` (:func:`extrapolated`)."""
    T0 = fit.period
    dt = T0 / settings.steps_per_period

    def attempt(periods: int, _: object) -> tuple[tuple[BeamRun, FloquetFit, float], float]:
        if periods == settings.periods:
            made = (free, fit, spread)
        else:
            again = run(periods, dt, False)
            made = (again, *_free_vibration_fit(again, T0, settings.transient * periods * T0, notes))
        return made, _rate_change(made[0], made[1], T0)

    what = "the free vibration's rate"
    (free, fit, spread), periods = _twice(
        attempt, settings.periods, WINDOW_AGREEMENT * tol, what, notes, None
    )
    coarse_run = run(periods, 2 * dt, False, progress)
    coarse = _free_vibration_fit(coarse_run, T0, settings.transient * periods * T0, notes)[0]
    return free, fit, spread, coarse


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
    rails: dict[int, tuple[SleeperRail, float]] = {}
    run = partial(_run, rails, track, vehicle, loads, settings)
    dt = T0 / settings.steps_per_period
    start = time.perf_counter()
    share = 0.9 / (1.5 if root is not None and side.frequency is not None else 2.0)  # the first run's
    free = run(settings.periods, dt, False, _stage(progress, 0.1, share))
    notes = list(side.result.notes)
    fit, spread = _free_vibration_fit(free, T0, settings.transient * settings.periods * T0, notes)
    comparisons: list[Comparison] = []
    loaded = coarse = None
    steady_tau = steady_force = limit_force = None
    if root is not None and side.frequency is not None:
        later = _stage(progress, 0.1 + share, 0.9 - share)
        free, fit, spread, coarse = _growing(run, free, fit, spread, settings, tol, notes, later)
        comparisons = _rate_comparisons(fit, coarse, root, side.frequency, tol, notes)
    else:
        rate_text = _rate_text(fit.rate, time_scale)
        notes.append(
            f"no Floquet root with Im q <= 0 (stable): the free vibration's rate {rate_text} is not compared"
        )
        assert steady is not None
        stage = _stage(progress, 0.1 + share, 0.9 - share)
        checked = _steady_check(partial(run, dt=dt, loaded=True), track, steady, settings, tol, notes, stage)
        comparisons.append(checked.comparison)
        loaded, steady_force = checked.loaded, checked.reference
        steady_tau, limit_force = checked.limit.tau, checked.limit.values[0]
    rail = rails[max(rails)][0]  # that of the longest run
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
