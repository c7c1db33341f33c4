"""What the finite rail's time series say: the Floquet multipliers of the stroboscopic map (docs/sleepers.md
(S26)).

A free vibration of the vehicle on the periodic rail is a sum of Floquet modes ``e^{i q tau} P(tau)``, ``P``
periodic with the bay-passing period ``T0 = lam / alpha``. Sampled once per period, at a fixed phase ``t_j``
in it, each mode is a geometric sequence of ratio ``mu = e^{i q T0}`` (its Floquet multiplier) whatever
``P``: the samples ``y_k = x(t_0 + t_j + k T0)`` of every phase ``t_j`` and every recorded signal (the
channels) obey one linear map ``y_{k+1} = A y_k`` on the span of the modes present. :func:`fit_floquet_modes`
fits that map by least squares on the leading singular subspace of the snapshots (dynamic mode
decomposition), and takes its eigenvalues: the multipliers, each mode's shape over the channels and its
amplitude. Two modes of equal growth (a complex pair), or a decaying mode beside the growing one, are two
eigenvalues of the map, so neither biases the other (a root-mean-square envelope sees their beating).

The mode that dominates the end of the window gives the growth rate ``ln |mu| / T0`` (``-Im q``) and, from
the Fourier series of its shape over one period at the first channel, the frequency ``|Re q + n Omega_0|``
of its largest harmonic ``n``. Neither uses the Floquet theory of the rail: they read the time series only.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

__all__ = [
    "FloquetFit",
    "LIMIT_LEVEL",
    "RANK_GAP",
    "RANK_LEVEL",
    "ROUND_OFF",
    "dominant_harmonic",
    "fit_floquet_modes",
    "extrapolated",
    "PeriodicLimit",
    "periodic_limit",
    "period_rms",
    "smooth_steps",
    "stroboscopic_samples",
]

#: singular values of the snapshots below this fraction of the largest are round-off (the signals are
#: scaled to 1): never fitted
RANK_LEVEL = 1e-8

#: the modes kept stand above the rest of the snapshots by this factor: the rank is the last such gap in the
#: singular values (else the largest). A mode left out biases the multipliers by about its size, a large part
#: of a slow rate (a decaying mode at 1e-4 of the growing one moves a growth of 0.03 per period by 3 %), so a
#: small second mode must be kept; modes fitted to what is not modal (the waves the release radiates and the
#: rail's ends reflect) perturb the dominant multiplier and can outgrow it, so they must not (the zone
#: example: gaps of 1e4 or more after its 2 modes; the growing case of the tests: 1.4e3 after its 1, then
#: ratios below 4)
RANK_GAP = 100.0

#: the periodic limit's fit keeps, beside the modes above the last fall by RANK_GAP, every mode whose singular
#: value is above this fraction of the largest: a mode left out biases the limit by its part of the transient
#: over |1 - mu|, a large part for a slow mode, while a mode fitted to what is not modal only adds a small
#: part that decays (measured: two wheels on Hertz springs below the zone keep 4 modes, the fourth at 4.7e-4,
#: and the limit 0.09 % of the force's peak-to-peak off, 0.25 % with 3; a bogie in a damped zone keeps 6
#: modes down to 1.6e-3, 0.13 % off, 0.8 % with the one mode before the largest fall)
LIMIT_LEVEL = 1e-4

#: a run below this fraction of its largest value is at its round-off (the finite rail's released run
#: settles near 1e-8 of its start): periods below it are left out of the fit
ROUND_OFF = 1e-6

#: the fewest stroboscopic samples per fitted multiplier (the map of rank r is fitted to K - 1 >= 3 r pairs)
SAMPLES_PER_MODE = 3

#: the fewest periods a window must hold: room for rank 2, a complex-conjugate pair of multipliers (one
#: oscillating mode of a real signal)
MIN_PERIODS = 2 * SAMPLES_PER_MODE + 1


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


def stroboscopic_samples(
    tau: np.ndarray, signals: np.ndarray, period: float, start: float
) -> tuple[np.ndarray, int, float, np.ndarray]:
    """The snapshots ``Y[c, k]`` (channel ``c`` = signal ``s``, phase ``j``: ``c = s * phases + j``) at
    ``tau_i + j dt + k period`` from the first step ``tau_i >= start``, each signal divided by its largest
    value there; with the number of phases (steps per period), ``tau_i`` and those largest values.

    The steps must be uniform and divide ``period`` (the finite rail's run takes a whole number of steps per
    bay-passing period)."""
    dt = float(tau[1] - tau[0])
    phases = round(period / dt)
    if phases < 2 or abs(phases * dt - period) > 1e-9 * period:
        raise ValueError(f"the time step {dt:.6g} does not divide the period {period:.6g}")
    first = int(np.searchsorted(tau, start - 1e-9 * period))
    count = (tau.size - first) // phases
    block = np.atleast_2d(signals)[:, first : first + count * phases]
    scales = np.maximum(np.max(np.abs(block), axis=1), np.finfo(float).tiny)
    # (signals, periods, phases) -> (signals, phases, periods)
    snapshots = (block / scales[:, None]).reshape(block.shape[0], count, phases).transpose(0, 2, 1)
    return snapshots.reshape(-1, count), phases, float(tau[first]), scales


@dataclass(frozen=True)
class FloquetFit:
    """The stroboscopic map fitted to a window of a run (module doc).

    ``multipliers`` (rank r), ``shares`` each mode's part of the signal at the end of the window (the
    largest 1), ``dominant`` the index of the largest share; ``rate = ln |mu| / period`` and ``frequency
    = |Re q + harmonic Omega_0|`` of that mode; ``components[i]`` mode ``i`` over the first period of the
    window at the first signal (in its units: the fitted signal over period ``k`` is
    ``Re sum_i components[i] mu_i^k``), ``samples`` the number of periods fitted, ``window`` (first, last
    sampled time), ``singular_values`` of the snapshots (relative to the largest), ``period`` the sampling
    period.
    """

    multipliers: np.ndarray
    shares: np.ndarray
    dominant: int
    rate: float
    frequency: float
    harmonic: int
    components: np.ndarray
    samples: int
    window: tuple[float, float]
    singular_values: np.ndarray
    period: float

    @property
    def rank(self) -> int:
        return int(self.multipliers.size)

    @property
    def multiplier(self) -> complex:
        return complex(self.multipliers[self.dominant])

    def period_rms(self, periods: np.ndarray, modes: Sequence[int] | None = None) -> np.ndarray:
        """The root-mean-square over each period ``k`` (counted from the window's start) of the fitted
        first signal, of all modes or of those indexed by ``modes``."""
        chosen = np.arange(self.rank) if modes is None else np.asarray(modes)
        powers = self.multipliers[chosen][:, None] ** np.asarray(periods, float)[None, :]
        values = np.real(np.einsum("ik,ij->kj", powers, self.components[chosen]))
        return np.sqrt(np.mean(values * values, axis=1))


def dominant_harmonic(shape: np.ndarray, multiplier: complex, period: float) -> tuple[float, int]:
    """``(|Re q + n Omega_0|, n)`` for the harmonic ``n`` of largest amplitude of one mode.

    ``shape[j]`` is the mode at ``t_j = j period / phases``, ``e^{i q t_j} P(t_j)``, with the principal
    exponent ``q = -i Log(mu) / period`` (``|Re q| <= Omega_0 / 2``); ``P``'s Fourier coefficients over the
    period (a discrete Fourier transform of ``shape e^{-i q t_j}``) are the amplitudes of the frequencies
    ``q + n Omega_0``."""
    phases = shape.size
    omega0 = 2 * np.pi / period
    q = -1j * np.log(complex(multiplier)) / period
    t = np.arange(phases) * period / phases
    coefficients = np.fft.fft(shape * np.exp(-1j * q * t))
    n = int(np.fft.fftfreq(phases, 1.0 / phases)[int(np.argmax(np.abs(coefficients)))])
    return abs(q.real + n * omega0), n


def _rank(relative: np.ndarray, level: float, most: int, keep_above: float | None = None) -> int:
    """The number of modes to fit, from the singular values ``relative`` to the largest (``_fitted_map``)."""
    if keep_above is not None:
        kept = min(int(np.count_nonzero(relative > keep_above)), max(most, 1))
        return max(kept, _rank(relative, level, most))
    above = relative[relative > level]
    candidates = min(above.size, max(most, 1))
    if candidates == 1:
        return 1
    # the fall after each candidate rank r = 1..candidates (to round-off past the last value above level)
    after = np.append(above[1:], level)[:candidates]
    falls = above[:candidates] / after
    gaps = np.nonzero(falls >= RANK_GAP)[0]
    return int(gaps[-1] + 1) if gaps.size else int(np.argmax(falls) + 1)


def _fitted_map(
    snapshots: np.ndarray, level: float, keep_above: float | None = None
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(multipliers, mode shapes over the channels, singular values): the least-squares map
    ``Y_1 = A Y_0`` on the leading ``r`` left singular vectors of ``Y_0``: ``r`` at the last fall by
    ``RANK_GAP`` or more from one singular value to the next (else the largest fall), among those above
    ``level`` of the largest, or more to keep every value above ``keep_above`` when given; at most
    ``(K - 1) / 3``."""
    before, after = snapshots[:, :-1], snapshots[:, 1:]
    u, s, vh = np.linalg.svd(before, full_matrices=False)
    relative = s / s[0]
    rank = _rank(relative, level, before.shape[1] // SAMPLES_PER_MODE, keep_above)
    u, s, vh = u[:, :rank], s[:rank], vh[:rank]
    reduced = u.T @ after @ vh.T / s
    multipliers, vectors = np.linalg.eig(reduced)
    return multipliers, u @ vectors, relative


def fit_floquet_modes(
    tau: np.ndarray, signals: np.ndarray, period: float, start: float, *, level: float = RANK_LEVEL
) -> FloquetFit:
    """Fit the stroboscopic map to the run ``signals`` (signals x times, on the uniform steps ``tau``) from
    ``start`` to its end (module doc). The first signal sets the dominant harmonic.

    The periods after the run has decayed below ``ROUND_OFF`` of its largest value are left out. Raises
    ValueError when the window holds fewer than ``MIN_PERIODS`` periods above it (nothing is left to fit)."""
    signals = np.atleast_2d(signals)
    snapshots, phases, first, scales = stroboscopic_samples(tau, signals, period, start)
    size = np.max(np.abs(snapshots) * np.repeat(scales, phases)[:, None], axis=0, initial=0.0)
    above = np.nonzero(size >= ROUND_OFF * np.max(np.abs(signals)))[0]
    count = int(above[-1]) + 1 if above.size else 0
    snapshots = snapshots[:, :count]
    if count < MIN_PERIODS:
        raise ValueError(f"the fit window holds fewer than {MIN_PERIODS} periods")
    multipliers, shapes, singular = _fitted_map(snapshots, level)
    amplitudes = np.linalg.lstsq(shapes, snapshots[:, 0].astype(complex), rcond=None)[0]
    shares = np.abs(amplitudes) * np.linalg.norm(shapes, axis=0) * np.abs(multipliers) ** (count - 1)
    shares = shares / np.max(shares)
    dominant = int(np.argmax(shares))
    mu = complex(multipliers[dominant])
    components = (shapes[:phases] * amplitudes).T * scales[0]
    frequency, harmonic = dominant_harmonic(components[dominant], mu, period)
    window = (first, first + (count - 1) * period + (phases - 1) * period / phases)
    rate = math.log(abs(mu)) / period
    return FloquetFit(
        multipliers, shares, dominant, rate, frequency, harmonic, components, count, window, singular, period
    )


def extrapolated(fine: FloquetFit, coarse: FloquetFit) -> tuple[float, float]:
    """(rate, frequency) of the dominant mode extrapolated to a zero time step from the fits of two runs, at
    ``dt`` and ``2 dt``: ``(4 x_dt - x_2dt) / 3``, Richardson's rule for a second-order integrator (Newmark's
    average acceleration: its error in the multipliers falls like ``dt^2``). The frequency is extrapolated
    only when both runs find it at the same harmonic (otherwise the finer run's)."""
    rate = (4 * fine.rate - coarse.rate) / 3
    same = abs(coarse.frequency - fine.frequency) <= 0.01 * fine.frequency
    frequency = (4 * fine.frequency - coarse.frequency) / 3 if same else fine.frequency
    return rate, frequency


@dataclass(frozen=True)
class PeriodicLimit:
    """The periodic response a forced run tends to, read from the run alone (:func:`periodic_limit`).

    ``values[s, j]`` is signal ``s`` at phase ``j`` of the last sampled period, whose times are ``tau``;
    ``transient`` the largest part of the first signal not yet settled at that period, relative to the
    limit's peak-to-peak; ``multipliers`` those of the transient's modes (all ``|mu| < 1`` for a run that
    settles)."""

    values: np.ndarray
    tau: np.ndarray
    transient: float
    multipliers: np.ndarray

    @property
    def settles(self) -> bool:
        """Whether every mode of the transient decays (the limit exists)."""
        return bool(np.all(np.abs(self.multipliers) < 1.0))

    def notes(self, tol: float) -> list[str]:
        """What a check says of the limit: a run too short to fit it, a run that does not settle, or a
        transient still above ``tol`` at the run's end (removed by the fit rather than waited out)."""
        if math.isnan(self.transient):
            too_short = "the loaded run is too short to fit its periodic limit"
            return [f"{too_short}: its last bay is compared as it is"]
        slowest = float(np.max(np.abs(self.multipliers), initial=0.0))
        if not self.settles:
            return [f"the loaded run does not settle (a multiplier of modulus {slowest:.6g} >= 1)"]
        if self.transient <= tol:
            return []
        return [
            f"the loaded run's force still carries a transient of {self.transient:.2%} of its peak-to-peak "
            f"at its end (slowest multiplier modulus {slowest:.6g}): its periodic limit, the fixed point of "
            "the stroboscopic map, is compared"
        ]


def periodic_limit(tau: np.ndarray, signals: np.ndarray, period: float, start: float) -> PeriodicLimit:
    """The fixed point ``y*`` of the stroboscopic map of a forced periodic run (docs/sleepers.md (S26)).

    A forced run on the periodic rail is its periodic response plus free Floquet modes: sampled once per
    period at every phase, ``y_k = y* + sum_i t_i mu_i^k phi_i``. The differences ``d_k = y_{k+1} - y_k``
    are then a free run of the same map, ``d_k = sum_i t_i (mu_i - 1) mu_i^k phi_i``: its multipliers and
    shapes are fitted as :func:`fit_floquet_modes` fits a free run, the amplitudes by least squares over
    every difference (the modes up to the last fall of the singular values by ``RANK_GAP``, and every mode
    above ``LIMIT_LEVEL``), and ``y* = y_K - sum_i t_i mu_i^K phi_i``. A transient that decays slowly (a
    multiplier near the unit circle) is thus removed, not waited out; the limit uses the run only, no
    Floquet theory. A window of too few periods to fit gives the run's last period as it is, with
    ``transient`` NaN."""
    signals = np.atleast_2d(signals)
    snapshots, phases, first, scales = stroboscopic_samples(tau, signals, period, start)
    count = snapshots.shape[1]
    if count < MIN_PERIODS + 1:  # too few periods to fit: the last period as it is (``transient`` NaN)
        last = tau >= tau[-1] - period * (1 - 1e-9)
        return PeriodicLimit(signals[:, last], tau[last], math.nan, np.zeros(0, dtype=complex))
    differences = np.diff(snapshots, axis=1)
    last = snapshots[:, -1].astype(complex)
    if np.max(np.abs(differences)) <= ROUND_OFF * np.max(np.abs(snapshots)):
        transient_now = np.zeros_like(last)
        multipliers = np.zeros(0, dtype=complex)
    else:
        multipliers, shapes, _ = _fitted_map(differences, RANK_LEVEL, LIMIT_LEVEL)
        powers = multipliers[None, :] ** np.arange(count - 1)[:, None]
        design = (powers[:, None, :] * shapes[None, :, :]).reshape(-1, multipliers.size)
        amplitudes = np.linalg.lstsq(design, differences.T.reshape(-1).astype(complex), rcond=None)[0]
        # t_i mu_i^(K-1) phi_i summed: the part of the last sample not yet settled
        settle = amplitudes * multipliers ** (count - 1) / (multipliers - 1.0)
        transient_now = shapes @ settle
    limit = np.real(last - transient_now).reshape(-1, phases) * scales[:, None]
    offsets = np.real(transient_now).reshape(-1, phases)[0] * scales[0]
    spread = float(np.ptp(limit[0])) or 1.0
    times = first + (count - 1) * period + np.arange(phases) * period / phases
    return PeriodicLimit(limit, times, float(np.max(np.abs(offsets))) / spread, multipliers)
