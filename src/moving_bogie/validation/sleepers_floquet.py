"""The Floquet theory's side of the finite-beam check on sleepers (:mod:`.sleepers_check`): the strip
search (:func:`~moving_bogie.roots.strip.floquet_frequencies`), its least damped root with ``Im q <= 0`` and
that root's dominant frequency (an unstable case), or the steady response over a bay (S16)-(S18) (a stable
one)."""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from moving_bogie.kernels.hill import FloquetSystem, VehicleMatrices
from moving_bogie.kernels.sleeper_track import SleeperTrack
from moving_bogie.response.steady_bay import SteadyResponse, steady_response
from moving_bogie.roots.strip import FloquetResult, floquet_frequencies

__all__ = ["STEADY_TOL", "FloquetSide", "floquet_frequency", "floquet_side"]

#: the Floquet steady response's convergence in the harmonics, relative to its largest value (the mean force
#: 2): a hundredth of its default, so that its truncation stays far below the tolerance on the force's
#: peak-to-peak, a few percent of the mean
STEADY_TOL = 1e-5


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
