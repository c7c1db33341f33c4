"""Free waves of a track on the soil and its critical velocity (docs/soil.md).

The free waves of the coupled track and soil (both undamped: eta = 0, c_pad = 0) are the real zeros of
the track's determinant (:meth:`~.track.SoilTrack.determinant`) with chi(k1, omega) of the soil, at
phase speeds c = omega / k1 below the soil's slowest wave at that frequency (the fundamental mode c_0(omega)),
where chi is real: above it the track radiates into the soil and no wave is guided. At each frequency c runs
on a grid from ``c_low`` c_0 up to c_0 (1 - 1e-12), geometric at both ends (chi falls to 0 at c_0 like a
square root); each sign change is refined by the Illinois method in s = sqrt(1 - c / c_0), to 1e-10 of s
or until c is held to 1e-12 of c_0.

The critical velocity is the smallest phase velocity of those waves (Dieterman & Metrikine 1996) on the
rail's bending branch (:func:`critical_velocity`): inside a branch, refined by golden-section search between
neighbouring frequencies; where the branch ends on the soil's fundamental mode, the limit there: where the
track's own curve (chi = 0) crosses that mode, the root of the soil's secular function along the curve,
checked against the mode. Beside it,
the uncoupled estimate of Mezher et al. (2016): the first intersection of the track's own dispersion curve
(the soil replaced by nothing under the ballast, chi = 0) with the soil's fundamental mode.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from moving_bogie.typing import FloatArray

from .illinois import IntArray, illinois
from .profile import SoilProfile
from .rayleigh import secular, soil_modes
from .strip import strip_stiffness
from .track import SoilTrack

__all__ = ["CriticalVelocity", "FreeWaves", "critical_velocity", "free_waves", "uncoupled_curve"]

#: Default frequency grid (rad/s) of the critical-velocity search: 0.1 to 100 Hz.
DEFAULT_OMEGA = np.geomspace(0.6, 600.0, 32)
#: A guided wave whose phase speed is within this relative distance of the soil's fundamental mode is the
#: soil's own wave, slowed by the track's mass (at low frequency chi ~ sqrt(1 - c / c_0) needs only
#: 1 - c / c_0 ~ (m omega^2 / chi's scale)^2, 1e-12 to 1e-8 on the examples); a run of such waves alone is
#: not the rail's branch (:func:`critical_velocity`).
HUGGING = 1e-6
#: A free wave's s = sqrt(1 - c / c_0) is refined to S_RTOL relative, or only until c is held to C_RTOL
#: relative where that is looser (:func:`free_waves`).
S_RTOL, C_RTOL = 1e-10, 1e-12
#: The root on the track's own curve is its meeting with c_0 when they agree to this (:func:`_meeting`).
MEETING_CHECK = 1e-9


@dataclass(frozen=True)
class FreeWaves:
    """Phase velocities c[i, j] (m/s) of the coupled track's guided waves at omega[i] (slowest first; NaN
    where there are fewer), and the soil's fundamental mode c_soil[i]."""

    omega: FloatArray
    c: FloatArray
    c_soil: FloatArray


def _determinant(track: SoilTrack, soil: SoilProfile, c: FloatArray, omega: FloatArray) -> FloatArray:
    k1 = omega / c
    # fixed panels: next to c_0 (where chi -> 0) bisection would not end
    chi = strip_stiffness(k1, omega, soil, track.b, rounds=1).chi
    return np.real(track.determinant(k1, omega, chi))


def free_waves(
    track: SoilTrack, soil: SoilProfile, omega: FloatArray, *, points: int = 30, c_low: float = 1e-3
) -> FreeWaves:
    """The guided free waves at each ``omega`` (rad/s) of the undamped track on the undamped soil."""
    track, soil = track.undamped(), soil.undamped()
    omega = np.atleast_1d(np.asarray(omega, dtype=float))
    c0 = soil_modes(omega, soil, modes=1).c[:, 0]
    low = np.geomspace(c_low, 0.5, points // 2)
    high = 1 - np.geomspace(0.5, 1e-12, points - points // 2 + 1)[1:]
    grid = c0[:, None] * np.concatenate([low, high])[None, :]
    f = _determinant(track, soil, grid.ravel(), np.repeat(omega, points)).reshape(grid.shape)
    rows, cols = np.nonzero(np.sign(f[:, :-1]) * np.sign(f[:, 1:]) < 0)
    w, c_end = omega[rows], c0[rows]

    def in_s(s: FloatArray, i: IntArray) -> FloatArray:  # chi ~ s near c_0: smooth in s
        return _determinant(track, soil, c_end[i] * (1 - s**2), w[i])

    s_lo, s_hi = np.sqrt(1 - grid[rows, cols] / c_end), np.sqrt(1 - grid[rows, cols + 1] / c_end)
    # rtol 1e-10 in s, or less where that already holds c to C_RTOL: |dc| / c_0 = 2 s |ds| (a wave hugging
    # c_0, s ~ 1e-6, is then held by its first bracket, below the determinant's rounding)
    rtol = np.maximum(S_RTOL, C_RTOL / (2 * np.maximum(s_lo, s_hi) ** 2))
    roots = c_end * (1 - illinois(in_s, s_lo, s_hi, rtol=rtol) ** 2) if rows.size else np.empty(0)
    count = np.bincount(rows, minlength=len(omega))
    c = np.full((len(omega), max(int(count.max(initial=0)), 1)), np.nan)
    for i in range(len(omega)):
        found = np.sort(roots[rows == i])
        c[i, : len(found)] = found
    return FreeWaves(omega=omega, c=c, c_soil=c0)


def uncoupled_curve(track: SoilTrack, omega: FloatArray) -> FloatArray:
    """Phase velocity (m/s) of the undamped track's own free wave without the soil (NaN where none)."""
    omega = np.asarray(omega, dtype=float)
    return omega / track.undamped().free_wavenumber(omega.astype(complex)).real


@dataclass(frozen=True)
class CriticalVelocity:
    """The coupled critical velocity and the uncoupled estimate, with the curves they come from."""

    v_cr: float
    omega_cr: float
    v_cr_uncoupled: float
    omega_uncoupled: float
    waves: FreeWaves
    c_track: FloatArray
    minima: tuple[tuple[float, float, str], ...] = field(default=())
    notes: tuple[str, ...] = field(default=())

    def to_dict(self) -> dict[str, object]:
        """JSON-ready, SI: v_cr and v_cr_uncoupled (m/s), the frequencies (rad/s), notes."""
        finite = bool(np.isfinite(self.v_cr))
        return {
            "v_cr": self.v_cr if finite else None,
            "omega_cr": self.omega_cr if finite else None,
            "k_cr": self.omega_cr / self.v_cr if finite else None,
            "v_cr_uncoupled": self.v_cr_uncoupled if np.isfinite(self.v_cr_uncoupled) else None,
            "omega_uncoupled": self.omega_uncoupled if np.isfinite(self.omega_uncoupled) else None,
            "branch_minima": [{"omega": w, "c": c, "at": where} for w, c, where in self.minima],
            "notes": list(self.notes),
        }


def _golden(fun: Callable[[float], float], a: float, b: float, steps: int = 30) -> tuple[float, float]:
    """Minimum of a unimodal ``fun`` on [a, b]: (x, fun(x))."""
    g = (np.sqrt(5) - 1) / 2
    x1, x2 = b - g * (b - a), a + g * (b - a)
    f1, f2 = fun(x1), fun(x2)
    for _ in range(steps):
        if f1 < f2:
            b, x2, f2 = x2, x1, f1
            x1 = b - g * (b - a)
            f1 = fun(x1)
        else:
            a, x1, f1 = x1, x2, f2
            x2 = a + g * (b - a)
            f2 = fun(x2)
    return (x1, f1) if f1 < f2 else (x2, f2)


@functools.lru_cache(maxsize=64)
def _meeting(track: SoilTrack, soil: SoilProfile, a: float, b: float) -> tuple[float, float]:
    """(omega, c_0(omega)): the frequency in [a, b] where the track's own curve (chi = 0) crosses the soil's
    fundamental mode c_0, and c_0 there; NaN when the track's determinant with chi = 0 at c_0 has one
    sign at both ends.

    Along the track's own curve c_t(omega) the soil's secular function changes sign where c_t meets a mode:
    its root in log omega (one secular value per Illinois step) is the meeting when c_0 there equals c_t
    to :data:`MEETING_CHECK`; otherwise (a higher mode or a layer's wave speed crossed in [a, b] as well)
    Illinois steps in log omega on the determinant at c_0 (a search of the soil's modes per step)."""
    elastic, free = soil.undamped(), track.undamped()

    def on_mode(log_w: FloatArray, _: IntArray) -> FloatArray:
        w = np.exp(log_w)
        c0 = soil_modes(w, elastic, modes=1).c[:, 0]
        return np.real(free.determinant(w / c0, w, np.zeros_like(w)))

    def on_curve(log_w: FloatArray, _: IntArray) -> FloatArray:
        w = np.exp(log_w)
        with np.errstate(invalid="ignore"):  # NaN where the track has no free wave: then no sign change
            return secular(uncoupled_curve(free, w), w, elastic)

    ends = np.log(np.array([a, b]))
    values = on_mode(ends, np.arange(2))
    if not np.all(np.isfinite(values)) or np.sign(values[0]) * np.sign(values[1]) >= 0:
        return float("nan"), float("nan")
    if np.sign(np.prod(on_curve(ends, np.arange(2)))) < 0:
        w = float(np.exp(illinois(on_curve, ends[:1], ends[1:], rtol=1e-12)[0]))
        c0 = float(soil_modes(np.array([w]), elastic, modes=1).c[0, 0])
        if abs(uncoupled_curve(free, np.array([w]))[0] / c0 - 1) < MEETING_CHECK:
            return w, c0
    w = float(np.exp(illinois(on_mode, ends[:1], ends[1:], rtol=1e-12)[0]))
    return w, float(soil_modes(np.array([w]), elastic, modes=1).c[0, 0])


def _uncoupled(track: SoilTrack, soil: SoilProfile, omega: FloatArray, c0: FloatArray) -> tuple[float, float]:
    """First intersection (omega, c) of the track's own curve with the soil's fundamental mode."""
    gap = uncoupled_curve(track, omega) - c0
    idx = np.nonzero(np.isfinite(gap[:-1]) & (np.sign(gap[:-1]) * np.sign(gap[1:]) < 0))[0]
    if idx.size == 0:
        return float("nan"), float("nan")
    w = _meeting(track, soil, float(omega[idx[0]]), float(omega[idx[0] + 1]))[0]
    return w, float(uncoupled_curve(track, np.array([w]))[0])


def _runs(has: npt.NDArray[np.bool_]) -> list[tuple[int, int]]:
    """(first, last) indices of each run of consecutive True."""
    edges = np.diff(np.concatenate([[0], has.astype(int), [0]]))
    return list(zip(np.nonzero(edges == 1)[0], np.nonzero(edges == -1)[0] - 1, strict=True))


def _least(track: SoilTrack, soil: SoilProfile, omega: float) -> float:
    c = free_waves(track, soil, np.array([omega])).c[0]
    return float(np.nanmin(c)) if np.isfinite(c).any() else np.inf


def _branch_minimum(
    track: SoilTrack, soil: SoilProfile, omega: FloatArray, slowest: FloatArray, run: tuple[int, int]
) -> tuple[float, float, str]:
    """(omega, c, where) of the least phase velocity on one run of frequencies with guided waves."""
    first, last = run
    i = first + int(np.argmin(slowest[first : last + 1]))
    if first < i < last:  # inside the run: golden-section search in log omega
        log_w, c = _golden(
            lambda x: _least(track, soil, float(np.exp(x))), np.log(omega[i - 1]), np.log(omega[i + 1])
        )
        return float(np.exp(log_w)), c, "interior"
    # at an end of the run: the branch ends between grid points where it meets the soil's fundamental mode
    # c_0; there chi -> 0, so the end is where the track's determinant with chi = 0 vanishes at
    # k1 = omega / c_0 (the track's own curve crosses c_0); the least phase velocity is c_0 there
    outer = i - 1 if i == first else i + 1
    if outer < 0 or outer >= len(omega):
        return float(omega[i]), float(slowest[i]), "range end"
    w_end, c_end = _meeting(track, soil, float(omega[i]), float(omega[outer]))
    if not np.isfinite(w_end):
        return float(omega[i]), float(slowest[i]), "grid"
    return w_end, c_end, "branch end"


def critical_velocity(
    track: SoilTrack, soil: SoilProfile, omega: FloatArray | None = None
) -> CriticalVelocity:
    """The least phase velocity of the coupled guided waves, and the uncoupled intersection estimate.

    Guided waves exist on runs of frequencies (branches). The first run from the low frequencies is the
    rail's bending branch; a later run may be a locally reacting branch (the sleepers and ballast
    bouncing between a rail held by its bending stiffness and the soil), whose phase speed falls towards 0
    as k1 grows, because the model gives sleepers and ballast no bending stiffness: the critical velocity is
    taken on the first run that holds a wave the track slows by more than :data:`HUGGING` below the
    soil's mode (a run of the soil's own wave alone is passed over), and every run's least phase velocity
    is listed (``minima``).
    """
    omega = DEFAULT_OMEGA if omega is None else np.asarray(omega, dtype=float)
    waves = free_waves(track, soil, omega)
    notes = []
    has: npt.NDArray[np.bool_] = np.asarray(np.isfinite(waves.c).any(axis=1))
    slowest = np.where(has, np.min(np.where(np.isfinite(waves.c), waves.c, np.inf), axis=1), np.nan)
    runs = _runs(has)
    minima = [_branch_minimum(track, soil, omega, slowest, run) for run in runs]
    # the rail's branch: the first run with a wave the track slows by more than HUGGING (a run that only
    # follows the soil's mode is split off it where the grid's top, 1 - 1e-12, misses a wave); when every
    # run follows it (a beam on a homogeneous half-space), the first
    own = [
        i
        for i, (a, b) in enumerate(runs)
        if np.any(1 - slowest[a : b + 1] / waves.c_soil[a : b + 1] > HUGGING)
    ]
    if not minima:
        v_cr, w_cr = float("nan"), float("nan")
        notes.append("no guided wave of the coupled track below the soil's fundamental mode in the range")
    else:
        w_cr, v_cr, where = minima[own[0] if own else 0]
        if where in ("range end", "grid"):
            notes.append("the least phase velocity lies at an end of the frequency range: widen it")
    w_u, v_u = _uncoupled(track, soil, omega, waves.c_soil)
    if not np.isfinite(v_u):
        notes.append(
            "the track's own curve does not cross the soil's fundamental mode in the frequency range"
        )
    return CriticalVelocity(
        v_cr=v_cr,
        omega_cr=w_cr,
        v_cr_uncoupled=v_u,
        omega_uncoupled=w_u,
        waves=waves,
        c_track=uncoupled_curve(track, omega),
        minima=tuple(minima),
        notes=tuple(notes),
    )
