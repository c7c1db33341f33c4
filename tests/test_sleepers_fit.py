"""The Floquet multipliers of a sampled free vibration (moving_bogie.validation.sleepers_fit), the finite-beam
check's fit window and the harmonics chosen for its dominant frequency, on both sides.

References, independent by construction: synthetic signals built here as sums of Floquet modes
``Re a e^{i q tau} P(tau)`` with known exponents ``q`` and known periodic parts ``P`` (a few harmonics of
``Omega_0``): the fit must return the growth rate ``-Im q`` and the frequency ``|Re q + n Omega_0|`` of the
largest harmonic of the mode it finds dominant. On the Floquet side, a root at short bays is the smeared
track's vibration, carried by the harmonic that undoes the fold of the root into the strip (docs/sleepers.md
(S10)): its dominant frequency is the same for every fold.
"""

from __future__ import annotations

import numpy as np
import pytest

from moving_bogie.model.catalogue import default_catalogue
from moving_bogie.roots.verdict import UNSTABLE, Verdict
from moving_bogie.validation import sleepers_check
from moving_bogie.validation.sleepers_fit import (
    dominant_harmonic,
    extrapolated,
    fit_floquet_modes,
    period_rms,
    periodic_limit,
)

#: the catalogue's rails on periodic supports, (beam, track) -> their generated functions
PERIODIC = default_catalogue().periodic

OMEGA0 = 0.47  # the bay-passing frequency of the synthetic runs (that of examples/sleepers_zones.toml)
T0 = 2 * np.pi / OMEGA0
STEPS = 200  # time steps per period, as the finite rail's run


def _run(
    modes: list[tuple[complex, complex, dict[int, complex]]], periods: int = 40
) -> tuple[np.ndarray, np.ndarray]:
    """tau and ``sum Re a e^{i q tau} sum_n c_n e^{i n Omega0 tau}`` over ``(a, q, {n: c_n})``."""
    tau = np.arange(periods * STEPS + 1) * (T0 / STEPS)
    x = np.zeros(tau.size)
    for a, q, harmonics in modes:
        periodic = sum(c * np.exp(1j * n * OMEGA0 * tau) for n, c in harmonics.items())
        x += np.real(a * np.exp(1j * q * tau) * periodic)
    return tau, x


def _rms_slope(tau: np.ndarray, x: np.ndarray, start: float) -> float:
    """The least-squares slope of log RMS per period after ``start``: an envelope estimate, for contrast."""
    mids, rms = period_rms(tau[tau >= start], x[tau >= start], T0)
    return float(np.polyfit(mids, np.log(rms), 1)[0])


def test_two_modes_of_equal_growth_give_their_common_rate():
    """Two Floquet modes growing at the same rate 0.0025 at frequencies 0.13 and 0.31 (not on the parametric
    line): their RMS per period beats, and its slope misses the rate by more than 3 %; the multipliers give
    it to 1e-8 and the frequency of the larger mode."""
    rate = 0.0025
    modes = [(1.0, 0.13 - 1j * rate, {0: 1.0, 1: 0.2}), (0.8, 0.31 - 1j * rate, {0: 1.0, -1: 0.3j})]
    tau, x = _run(modes)
    start = 0.4 * tau[-1]
    assert abs(_rms_slope(tau, x, start) / rate - 1) > 0.03
    fit = fit_floquet_modes(tau, x, T0, start)
    assert abs(fit.rate / rate - 1) < 1e-8
    assert fit.rank == 4  # two real modes: two pairs of complex-conjugate multipliers
    angles = np.abs(np.angle(np.exp(1j * np.array([0.13, 0.31]) * T0)))  # 0.31 T0 > pi: folded
    assert np.allclose(np.sort(np.abs(np.angle(fit.multipliers))), np.sort(np.repeat(angles, 2)))
    assert fit.frequency == pytest.approx(0.13, rel=1e-8)


def test_a_decaying_mode_beside_the_growing_one_does_not_bias_the_rate():
    """The principal parametric zone: both modes on Re q = Omega_0 / 2 (real negative multipliers), one
    growing at 0.00225, one decaying at 0.0042 with a fifth of its amplitude at the window's start (the zone
    example's pair): the RMS slope is 3 % too steep, the fit gives the growing rate to 1e-8 and the frequency
    Omega_0 / 2."""
    grow, decay = 0.00225, 0.0042
    modes = [
        (1.0, OMEGA0 / 2 - 1j * grow, {0: 1.0, 1: 0.1}),
        (-0.5, OMEGA0 / 2 + 1j * decay, {0: 1.0, -1: 0.4}),
    ]
    tau, x = _run(modes)
    start = 0.4 * tau[-1]
    assert abs(_rms_slope(tau, x, start) / grow - 1) > 0.03
    fit = fit_floquet_modes(tau, x, T0, start)
    assert abs(fit.rate / grow - 1) < 1e-8
    assert fit.frequency == pytest.approx(OMEGA0 / 2, rel=1e-10)
    decaying = np.log(np.abs(fit.multipliers)) / T0
    assert np.min(np.abs(decaying + decay)) < 1e-8  # the decaying mode is found too


@pytest.mark.parametrize("n", [2, -3])
def test_the_frequency_is_that_of_the_largest_harmonic(n):
    """A mode whose harmonic ``n`` carries the most (twice the next): the frequency is
    ``|Re q + n Omega_0|``, from the fit and from the shape alone (another harmonic gives another value)."""
    q = 0.1 - 0.002j
    tau, x = _run([(1.0, q, {0: 0.5, n: 1.0, n + 1: 0.3})])
    fit = fit_floquet_modes(tau, x, T0, 0.4 * tau[-1])
    assert fit.frequency == pytest.approx(abs(q.real + n * OMEGA0), rel=1e-8)
    assert abs(fit.harmonic) == abs(n)
    t = np.arange(STEPS) * T0 / STEPS
    shape = np.exp(1j * q * t) * (0.5 + np.exp(1j * n * OMEGA0 * t) + 0.3 * np.exp(1j * (n + 1) * OMEGA0 * t))
    assert dominant_harmonic(shape, np.exp(1j * q * T0), T0) == (pytest.approx(abs(q.real + n * OMEGA0)), n)


def _noisy_start(tau: np.ndarray, x: np.ndarray, until: float) -> np.ndarray:
    """``x`` with a large non-modal signal (seeded noise, 10 times the modes) before ``until``."""
    noise = 10 * np.random.default_rng(7).standard_normal(tau.size)
    return np.where(tau < until, x + noise, x)


def test_the_fit_reads_its_window_only():
    """Noise before the window's start, two modes after it: the fit from the start gives the growing rate
    to 1e-8; from tau = 0 the noise spoils it."""
    grow = 0.002
    tau, x = _run([(1.0, 0.2 - 1j * grow, {0: 1.0}), (0.5, OMEGA0 / 2 + 0.004j, {0: 1.0})])
    start = 0.4 * tau[-1]
    x = _noisy_start(tau, x, start)
    assert abs(fit_floquet_modes(tau, x, T0, start).rate / grow - 1) < 1e-8
    assert abs(fit_floquet_modes(tau, x, T0, 0.0).rate / grow - 1) > 0.01


def test_the_check_fits_the_window_of_its_settings(monkeypatch):
    """check_sleepers on a synthetic free run (its rail runs replaced, the Floquet side given): the window is
    the last 60 % of the record of the default settings (docs/sleepers.md (S26); noise before it would spoil
    the rate), the rate and the frequency are those of the modes put in, within 1e-8, and the two halves of
    the window agree."""
    from moving_bogie.generated import vehicle_mass
    from moving_bogie.kernels.hill import VehicleMatrices
    from moving_bogie.kernels.sleeper_track import SleeperTrack
    from moving_bogie.validation.sleepers_beam import BeamRun

    vehicle = VehicleMatrices.from_module(vehicle_mass, {"eta_M": 14.0})  # its wheel's path sizes the rail
    track = SleeperTrack(PERIODIC["eb", "sleepers"], {"lam": T0 * 0.24, "alpha": 0.24, "eta_sup": 0.01})
    assert track.Omega0 == pytest.approx(OMEGA0, rel=1e-12)
    settings = sleepers_check.SleeperBeamSettings()
    q = OMEGA0 / 2 - 0.002j
    tau, x = _run([(1.0, q, {0: 1.0, -1: 0.5}), (0.3, OMEGA0 / 2 + 0.005j, {0: 1.0})], settings.periods)
    x = _noisy_start(tau, x, 0.4 * tau[-1])

    def synthetic(*args: object, **kwargs: object) -> BeamRun:
        return BeamRun(
            tau, x[None, :], np.zeros((1, tau.size)), np.zeros((0, tau.size)), T0 / STEPS, 0.0, 0.0
        )

    monkeypatch.setattr(sleepers_check, "simulate_sleeper_beam", synthetic)
    side = sleepers_check.FloquetSide(_UnstableResult(), q, OMEGA0 / 2, None, 0.0)
    result = sleepers_check.check_sleepers(track, vehicle, np.zeros(1), settings=settings, floquet=side)
    assert result.fit_start == pytest.approx(0.4 * settings.periods * T0, abs=T0 / STEPS)
    assert result.fit.window[1] == pytest.approx(tau[-1], abs=T0 / STEPS)
    assert [c.quantity for c in result.comparisons] == ["growth rate -Im q", "dominant frequency"]
    assert all(c.relative < 1e-8 for c in result.comparisons), result.comparisons
    assert result.rate_spread < 1e-10
    assert result.agrees
    # the figure in SI: deflections times the metres per unit given (w_st), the labels in m
    from moving_bogie.validation.sleepers_plots import plot_sleeper_check

    free_panel, envelope = plot_sleeper_check(result, newtons=3.2e4, metres=2e-3).axes
    assert (
        free_panel.get_ylabel() == "deflection [m]" and envelope.get_ylabel() == "RMS of the deflection [m]"
    )
    np.testing.assert_allclose(free_panel.lines[0].get_ydata(), 2e-3 * x)


class _UnstableResult:
    """What check_sleepers reads of a Floquet search: its verdict and its notes."""

    verdict = Verdict(UNSTABLE)
    notes = ()


def test_the_floquet_side_takes_the_harmonic_that_undoes_the_fold():
    """A wheel on short bays (lam 0.4, Omega_0 = 4.7): its root, folded by -1, 0 or 1 strips, is one vibration
    of the smeared track, at |Re q| of the unfolded root; floquet_frequency finds that harmonic in the null
    vector of the Hill matrix at each fold (any other is at least Omega_0 - 2 |Re q| = 3.3 away)."""
    from moving_bogie.generated import vehicle_mass
    from moving_bogie.kernels.hill import FloquetSystem, VehicleMatrices
    from moving_bogie.kernels.sleeper_track import SleeperTrack

    vehicle = VehicleMatrices.from_module(vehicle_mass, {"eta_M": 2.0})
    groups = {"lam": 0.4, "alpha": 0.3, "kappa_f": 0.0, "eta_f": 0.0, "eta_sup": 0.2}
    track = SleeperTrack(PERIODIC["eb", "sleepers"], groups)
    system = FloquetSystem(track, vehicle, N=1, tol=1e-10)
    q = 0.7 + 0.1j  # a starting point near the continuous track's root 0.686 + 0.115i (eta_f 0.2, alpha 0.3)
    for _ in range(30):
        step = system(q) / ((system(q + 1e-7) - system(q - 1e-7)) / 2e-7)
        q -= step
        if abs(step) < 1e-12:
            break
    for fold in (0, 1):
        frequency = sleepers_check.floquet_frequency(track, vehicle, q - fold * track.Omega0, 1)
        assert frequency == pytest.approx(abs(q.real), rel=1e-6)


def test_the_rate_is_extrapolated_to_a_zero_time_step():
    """Two runs whose rates carry a second-order error, 0.002 + 1e-4 (dt / h)^2 at dt = h and 2 h:
    Richardson's rule gives 0.002 to 1e-8 (and the frequencies, equal, unchanged)."""
    exact, error = 0.002, 1e-4
    fits = []
    for factor in (1, 4):
        tau, x = _run([(1.0, 0.2 - 1j * (exact + factor * error), {0: 1.0})])
        fits.append(fit_floquet_modes(tau, x, T0, 0.4 * tau[-1]))
    rate, frequency = extrapolated(*fits)
    assert abs(rate / exact - 1) < 1e-8
    assert frequency == pytest.approx(0.2, rel=1e-8)


def test_a_decay_is_fitted_down_to_the_round_off_only():
    """A mode decaying at 0.06 (e^-30 over the record) over a floor of seeded noise at 1e-9 of its start: the
    fit stops at the period where the run falls below 1e-6 of its largest value (below is its round-off, not
    its modes: the finite rail's stable runs settle near 1e-8) and gives the rate to 1e-6."""
    tau, x = _run([(1.0, 0.2 + 0.06j, {0: 1.0})])
    x = x + 1e-9 * np.random.default_rng(3).standard_normal(tau.size)
    fit = fit_floquet_modes(tau, x, T0, 0.0)
    assert abs(fit.rate / -0.06 - 1) < 1e-6
    assert fit.window[1] < np.log(1e6) / 0.06 < fit.window[1] + 2 * T0


@pytest.mark.parametrize(
    ("singular", "rank"),
    [
        ([1, 5.3e-2, 6.6e-7, 5.7e-7, 3.6e-7], 2),  # the zone example: a growing and a decaying mode
        (
            [1, 2.0e-3, 4.3e-6, 3.6e-6, 1.3e-6, 1.1e-6, 9e-7, 8e-7, 7e-7],
            2,
        ),  # the same later: the decaying mode at 2e-3 is kept
        # a growing mode over the rail's reflections
        ([1, 7.0e-4, 3.7e-4, 1.6e-4, 1.1e-4, 3.2e-5, 2.0e-5, 1.3e-5, 1.1e-5, 6.7e-6], 1),
        ([1, 0.5, 0.3, 1e-9], 3),  # the last values below RANK_LEVEL: round-off
        ([1, 0.5, 0.05, 0.02, 0.01, 0.008, 0.005, 0.004, 0.003], 2),  # no fall of 100: the largest
    ],
)
def test_the_rank_is_at_the_last_gap_of_the_singular_values(singular, rank):
    """The measured singular values of the finite rail's snapshots (and two made up): the modes kept are
    those above the last fall by RANK_GAP = 100 (a rank beyond the gap fits the reflections, whose modes
    moved the growing case's rate by 7e-4 and could outgrow it)."""
    from moving_bogie.validation.sleepers_fit import RANK_LEVEL, _rank

    assert _rank(np.array(singular, float), RANK_LEVEL, 7) == rank


def test_the_periodic_limit_removes_a_slow_transient():
    """A forced run: a periodic response (harmonics 0, 1, 2 of Omega_0) plus two slowly decaying Floquet
    modes near the parametric line (decay 0.0015 per unit tau, still 60 % of the response's peak-to-peak
    at the end). The fixed point of the stroboscopic map gives the periodic part to 1e-6 of its
    peak-to-peak; the raw last period misses it by more than 10 %."""
    forced = {0: 2.0, 1: 0.3 - 0.2j, 2: 0.05j}
    modes = [
        (1.0, 0.5 * OMEGA0 + 0.003 + 0.0015j, {0: 1.0, -1: 0.4}),
        (0.7, 0.5 * OMEGA0 - 0.011 + 0.0015j, {0: 1.0, 1: 0.2j}),
        (1.0, 0.0, forced),  # q = 0: the periodic response itself
    ]
    tau, x = _run(modes, periods=60)
    limit = periodic_limit(tau, x, T0, 0.4 * tau[-1])
    periodic = np.real(sum(c * np.exp(1j * n * OMEGA0 * limit.tau) for n, c in forced.items()))
    spread = np.ptp(periodic)
    assert limit.settles
    assert limit.transient > 0.1  # the transient is far from gone at the end of the run
    assert np.max(np.abs(limit.values[0] - periodic)) < 1e-6 * spread
    last = np.interp(limit.tau, tau, x)
    assert np.max(np.abs(last - periodic)) > 0.1 * spread


@pytest.mark.parametrize(
    ("singular", "rank", "kept"),
    [
        # two wheels on Hertz springs below the zone: two slow modes, the fourth value at 4.7e-4
        ([1, 1.2e-1, 1.0e-2, 4.7e-4, 4.4e-5, 3.5e-5, 9.2e-6, 7e-6, 5e-6], 3, 4),
        # a bogie in a damped zone: no fall of 100, six values above 1e-4
        ([1, 4.5e-2, 2.0e-2, 7.8e-3, 5.6e-3, 1.6e-3, 1.8e-4, 6e-5, 5e-5], 1, 7),
        # the zone example's two modes, then a gap of 100: the gap's rank
        ([1, 5.3e-2, 6.6e-7, 5.7e-7, 3.6e-7], 2, 2),
    ],
)
def test_the_limit_keeps_every_mode_above_its_level(singular, rank, kept):
    """The loaded runs' differences (measured singular values): the periodic limit keeps, beside the modes
    before the last fall by RANK_GAP (else the largest fall), every mode above LIMIT_LEVEL, at most one per
    three periods (7 here)."""
    from moving_bogie.validation.sleepers_fit import LIMIT_LEVEL, RANK_LEVEL, _rank

    values = np.array(singular, float)
    assert _rank(values, RANK_LEVEL, 7) == rank
    assert _rank(values, RANK_LEVEL, 7, LIMIT_LEVEL) == kept


def test_the_periodic_limit_of_two_wheels_separates_two_modes_of_one_shape():
    """Two wheels: a periodic response at each plus two slow modes near the parametric line with the same
    periodic part, in phase at the two wheels for one and in opposition for the other (the two wheels'
    modes; multipliers 0.12 rad apart, as 1.0109 and 1.1069 1/s at Omega_0 / 2 -+ 16 and 5 rad/s on the
    zone example), still 40 % of the response's peak-to-peak at the end of 40 periods. Fitted to both wheels
    the limit is each wheel's periodic response within 1e-6 of its peak-to-peak."""
    forced = [{0: 2.0, 1: 0.1 - 0.05j, 2: 0.02j}, {0: 2.0, 1: -0.08 + 0.06j, 2: 0.01}]
    shape = {0: 1.0, -1: 0.3}
    slow = [0.5 * OMEGA0 + 0.0123 + 0.00079j, 0.5 * OMEGA0 - 0.0036 + 0.00086j]
    runs = []
    for wheel, signs in enumerate([(1.0, 1.0), (1.0, -1.0)]):  # in phase, in opposition
        modes = [(0.5 * sign, q, shape) for sign, q in zip(signs, slow)]
        tau, x = _run([*modes, (1.0, 0.0, forced[wheel])], periods=40)
        runs.append(x)
    limit = periodic_limit(tau, np.array(runs), T0, 0.4 * tau[-1])
    assert limit.settles and limit.transient > 0.1
    for wheel in range(2):
        periodic = np.real(sum(c * np.exp(1j * n * OMEGA0 * limit.tau) for n, c in forced[wheel].items()))
        assert np.max(np.abs(limit.values[wheel] - periodic)) < 1e-6 * np.ptp(periodic)


def test_a_window_too_short_is_tried_once_more_over_twice_the_periods():
    """The check's two tries are one loop (sleepers_check._twice): a first run whose fit moves by more than
    the limit between the window and its last three quarters is made again over twice the periods (the
    progress goes to the first run only), once, and each move left is noted; a first run that settles is
    kept alone, without a note."""
    from moving_bogie.validation.sleepers_check import _twice

    def tries(moves: dict[int, float]):
        calls: list[tuple[int, object]] = []

        def attempt(periods: int, progress: object) -> tuple[int, float]:
            calls.append((periods, progress))
            return periods, moves[periods]

        return attempt, calls

    def report(x: float) -> None:
        pass

    attempt, calls = tries({40: 0.5, 80: 0.3})
    notes: list[str] = []
    assert _twice(attempt, 40, 0.1, "the rate", notes, report) == (80, 80)
    assert calls == [(40, report), (80, None)]
    assert len(notes) == 2 and notes[0].endswith("made again over 80") and "too short" in notes[1]
    attempt, calls = tries({40: 0.5, 80: 0.05})
    notes = []
    assert _twice(attempt, 40, 0.1, "the rate", notes, None) == (80, 80) and len(notes) == 1
    attempt, calls = tries({40: 0.05})
    notes = []
    assert _twice(attempt, 40, 0.1, "the rate", notes, None) == (40, 40) and not notes and len(calls) == 1
