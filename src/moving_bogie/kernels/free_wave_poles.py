"""The rail's free waves as poles of the receptance's integrand, and the sheet they leave it on (Eq. (S15)).

The integrand of the receptance (Eq. (S9)) has a pole in the wavenumber p wherever the periodic rail has a
free (Bloch) wave: a zero of D(p, w) = 1 + z(w) S(p, w) at w = q + alpha p. For Im q below the rail's
free waves none lies on the real axis, and the integral over real p is analytic in q. As Im q grows, a zero
p*(q) crosses the real axis where q = w_B(p) - alpha p for a real Bloch wavenumber p: the singular lines of
the receptance. The receptance continued across them is the integral over a contour deformed so that every
zero stays on the side it had below the lines: the integral over the real axis plus 2 pi i (crossed from
above) or -2 pi i (from below) times each crossed pole's residue (docs/sleepers.md, "Beyond the free
waves").

The zeros are those of ``h(p) = 1 / S + z`` (D = S h), analytic where S has its poles (the lattice
translates of the symbol's roots, one zero of D beside each): Newton's method from each translate within
the integration's reach finds them. Their side below the lines is read by following each down the vertical
path from q to Im q = ``y0`` (below the free waves), where none is on the real axis. The residue of the
integrand's factor -z / D at a zero is ``z^2 / h'(p*)`` (there S = -1 / z).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from moving_bogie.kernels.sleeper_track import SleeperTrack, stable_cot

__all__ = ["ContinuationError", "Sheet", "SheetPoles", "regular_band", "sheet_poles"]


class ContinuationError(ArithmeticError):
    """The free waves' poles could not be followed: the receptance is not continued at this q."""


@dataclass(frozen=True)
class SheetPoles:
    """Zeros p_k of D(p, q + alpha p) near the real axis, each with its side below the singular lines
    (``sides``: +1 above the real axis, -1 below) and the residue ``coefficients`` of -z / D there."""

    poles: np.ndarray
    sides: np.ndarray
    coefficients: np.ndarray

    @property
    def crossed(self) -> int:
        """How many poles lie on the other side of the real axis than they had below the lines."""
        return int(np.count_nonzero(np.sign(self.poles.imag) != self.sides))


@dataclass(frozen=True)
class Sheet:
    """The sheet of the receptance above the free waves: continued from Im q = ``y0`` (below them) along
    vertical paths. Within ``regular`` of p = 0 no zero of D whose residue exceeds ``regular_atol``
    crosses the real axis in the band searched (:func:`regular_band`), so there the integral over real p
    is already the continuation to that tolerance (and is computed to no finer one)."""

    y0: float
    regular: float = 0.0
    regular_atol: float = np.inf


def _h(track: SleeperTrack, q: complex, p: np.ndarray) -> np.ndarray:
    """h(p) = 1 / S(p, w) + z(w) at w = q + alpha p: zero where D = 1 + z S is."""
    w = q + track.alpha * p
    with np.errstate(divide="ignore", invalid="ignore"):  # a start on a pole: not finite, not converged
        r, res = track.symbol_roots_first(w)
        half = track.lam / 2
        S = np.sum(half * stable_cot(half * (p - r)) * res, axis=0)
        return 1 / S + track.support(w)


#: the step of the derivatives' five-point stencil (its error is of order step^4)
_STEP = 1e-3
_STENCIL = np.array([-2, -1, 1, 2]) * _STEP
_WEIGHTS = np.array([1, -8, 8, -1]) / (12 * _STEP)


def _h_and_slope(track: SleeperTrack, q: complex, p: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """h and dh/dp (the five-point central stencil), in one evaluation of the symbol."""
    values = _h(track, q, np.concatenate([p, *(p + d for d in _STENCIL)]))
    parts = values.reshape(5, p.size)
    with np.errstate(invalid="ignore", over="ignore"):  # a start at a pole of S: non-finite, not stepped
        return parts[0], _WEIGHTS @ parts[1:]


def _newton(
    track: SleeperTrack, q: complex, p: np.ndarray, iterations: int, cap: np.ndarray | float = np.inf
) -> tuple[np.ndarray, np.ndarray]:
    """Newton's method on h from each p, each step at most ``cap`` long; returns the zeros and whether
    each converged."""
    done = np.zeros(p.shape, dtype=bool)
    for _ in range(iterations):
        if np.all(done):
            break
        value, slope = _h_and_slope(track, q, p)
        with np.errstate(divide="ignore", invalid="ignore"):
            step = value / slope
            step = step * np.minimum(1.0, cap / np.abs(step))
        step = np.where(np.isfinite(step) & ~done, step, 0.0)
        p = p - step
        done |= np.abs(step) < 1e-12 * np.maximum(1.0, np.abs(p))
    return p, done


def _starts(track: SleeperTrack, q: complex, reach: float, band: float) -> np.ndarray:
    """The poles of S(p, q + alpha p) within the reach and within ``3 band`` of the real axis (those of the
    harmonic 0 all): p = j K + kappa, N~(kappa, q + j Omega_0 + alpha kappa) = 0 (the symbol's roots
    translated by the lattice), every j at once (the companion matrices' eigenvalues)."""
    # a root r of the symbol at w = q + alpha p puts a pole at j K + r: |r| grows with |w|
    w = abs(q) + abs(track.alpha) * (reach + 2 * track.K) * np.array([1, -1, 1j, -1j])
    size = float(np.max(np.abs(track.symbol_roots_first(w)[0])))
    J = int(np.ceil((reach + size) / track.K)) + 2
    j = np.arange(-J, J + 1)
    n = np.array([track.moving_polynomials(q + k * track.Omega0)[0] for k in j])
    while np.all(n[:, 0] == 0):
        n = n[:, 1:]
    d = n.shape[1] - 1
    companion = np.zeros((j.size, d, d), dtype=complex)
    companion[:, 0, :] = -n[:, 1:] / n[:, :1]
    companion[:, range(1, d), range(d - 1)] = 1
    p = (j[:, None] * track.K + np.linalg.eigvals(companion)).ravel()
    keep = (np.abs(p.real) <= reach + track.K) & ((np.abs(p.imag) < 3 * band) | (np.repeat(j, d) == 0))
    return p[keep]


def _zeros(track: SleeperTrack, q: complex, reach: float, band: float) -> np.ndarray:
    """The distinct zeros of D(p, q + alpha p) with |Re p| within the reach and |Im p| < band."""
    poles = _starts(track, q, reach, band)
    edge = _edge(track, poles, reach)
    for factor in (1.0, 0.9, 1.1, 0.8):  # a zero or a pole next to the rectangle: move its edges
        try:
            expected = _zero_count(track, q, edge, band * factor, poles)
        except ContinuationError:
            continue
        band *= factor
        break
    else:
        raise ContinuationError(f"the free waves' poles at q = {q:.6g} could not be counted")
    p = _distinct(track, q, poles + 1e-9, edge, band)
    for rows in (4,):  # some zero lies in no start's basin: a grid of starts as well
        if p.size >= expected:
            break
        x = np.arange(-edge, edge, track.K / (2 * rows))
        y = band * (np.arange(rows) + 0.5) / rows
        grid = (x[:, None] + 1j * np.concatenate([y, -y])[None, :]).ravel()
        p = _distinct(track, q, np.concatenate([p, grid]), edge, band)
    if p.size != expected:
        raise ContinuationError(
            f"{p.size} of the {expected} free waves' poles within the reach were found at q = {q:.6g}"
        )
    return p


def _distinct(track: SleeperTrack, q: complex, starts: np.ndarray, edge: float, band: float) -> np.ndarray:
    """The distinct zeros in |Re p| < edge, |Im p| < band that Newton's method reaches from ``starts``."""
    p, ok = _newton(track, q, starts, 40)
    p = p[ok & (np.abs(p.imag) < band) & (np.abs(p.real) < edge)]
    # a zero reached from several starts is kept once (the first of each)
    same = np.abs(p[:, None] - p[None, :]) <= 1e-8 * np.maximum(1.0, np.abs(p))[:, None]
    return p[~np.any(np.tril(same, -1), axis=1)]


def _edge(track: SleeperTrack, poles: np.ndarray, reach: float) -> float:
    """A real part between the reach and one K beyond it, as far from every pole of S as the samples of
    that interval allow: the vertical edges of the rectangle :func:`_zero_count` counts in."""
    xs = np.linspace(reach, reach + track.K, 33)
    gap = np.min(np.abs(np.abs(poles.real)[None, :] - xs[:, None]) + np.abs(poles.imag)[None, :], axis=1)
    return float(xs[np.argmax(gap)])


def _D(track: SleeperTrack, q: complex, p: np.ndarray) -> np.ndarray:
    """D(p, q + alpha p) = 1 + z S."""
    w = q + track.alpha * p
    r, res = track.symbol_roots_first(w)
    half = track.lam / 2
    return 1 + track.support(w) * np.sum(half * stable_cot(half * (p - r)) * res, axis=0)


def _zero_count(track: SleeperTrack, q: complex, edge: float, band: float, poles: np.ndarray) -> int:
    """The zeros of D in |Re p| < edge, |Im p| < band: the argument principle (D's winding number on the
    rectangle) plus the poles of S inside (D's poles, simple). Its boundary is sampled until no step turns
    the phase by more than 1 rad (ContinuationError after five halvings of the spacing)."""
    corners = np.array(
        [-edge - 1j * band, edge - 1j * band, edge + 1j * band, -edge + 1j * band, -edge - 1j * band]
    )
    spacing = 0.25
    for _ in range(6):
        z = np.concatenate(
            [
                a + (b - a) * np.arange(int(abs(b - a) / spacing) + 8) / (int(abs(b - a) / spacing) + 8)
                for a, b in zip(corners[:-1], corners[1:])
            ]
        )
        with np.errstate(all="ignore"):
            turn = np.angle(np.roll(_D(track, q, z), -1) / _D(track, q, z))
        if np.all(np.isfinite(turn)) and np.max(np.abs(turn)) < 1.0:
            inside = int(np.count_nonzero((np.abs(poles.real) < edge) & (np.abs(poles.imag) < band)))
            return int(round(float(np.sum(turn)) / (2 * np.pi))) + inside
        spacing /= 2
    raise ContinuationError(f"the free waves' poles at q = {q:.6g} could not be counted")


def _follow(track: SleeperTrack, q: complex, p: np.ndarray, y0: float) -> np.ndarray:
    """The zeros p at q followed down the vertical path to Re q + i y0 (steps halved until every Newton
    correction converges and moves each zero by less than a quarter of its distance to the others)."""
    y, dy = q.imag, (q.imag - y0) / 8
    for _ in range(_MAX_STEPS):
        if y <= y0 + 1e-15:
            return p
        step = min(dy, y - y0)
        target = complex(q.real, y - step)
        new, ok = _newton(track, target, p, 8)
        gap = np.abs(p[:, None] - p[None, :]) + np.diag(np.full(p.size, np.inf))
        near = gap.min(axis=1) if p.size > 1 else np.full(p.size, np.inf)
        if np.all(ok) and np.all(np.abs(new - p) < 0.25 * near):
            p, y = new, y - step
            dy = min(2 * step, (q.imag - y0) / 4)
            continue
        dy = step / 2
        if dy < 1e-6 * max(q.imag - y0, 1e-12):
            break
    raise ContinuationError(f"the free waves' poles at q = {q:.6g} could not be followed down")


#: the most steps of :func:`_follow`
_MAX_STEPS = 200


def _weight(track: SleeperTrack, q: complex, p: np.ndarray, slope: np.ndarray, harmonics: int) -> np.ndarray:
    """A bound of each zero's residue in the receptance of harmonics |n| <= ``harmonics``:
    |z^2 / h'| max_n |G(p - n K, w)|^2 (the residue of -z G_n G_m / D)."""
    w = q + track.alpha * p
    n = np.arange(-harmonics, harmonics + 1)
    shift = p[:, None] - n[None, :] * track.K
    G = np.abs(track.green(shift, np.broadcast_to(w[:, None], shift.shape))).max(axis=1)
    return np.abs(track.support(w) ** 2 / slope) * G**2


def _unsafe(
    track: SleeperTrack, q: complex, p: np.ndarray, drop: float, harmonics: int, atol: float
) -> np.ndarray:
    """Which zeros p at q may have crossed the real axis on the vertical path down by ``drop`` with a
    residue above ``atol`` (a crossing moves the receptance by that residue): those whose straight path
    at the rate dp / dq = -h_q / h_p, p(q - i drop) ~ p + dp, neither stays on one side of the real axis
    by at least half its length at both ends nor moves away from it by at least half its length."""
    _, slope = _h_and_slope(track, q, p)
    # dp = i drop h_q / h_p, and i h_q is dh / d(Im q)
    dp = drop * (_h(track, q + 1e-6j, p) - _h(track, q - 1e-6j, p)) / 2e-6 / slope
    end = p + dp
    half = 0.5 * np.abs(dp) + 1e-9
    clear = np.minimum(np.abs(p.imag), np.abs(end.imag)) > half
    away = np.abs(end.imag) - np.abs(p.imag) > half
    safe = (clear | away) & (np.sign(end.imag) == np.sign(p.imag)) & np.isfinite(dp)
    return ~safe & ~(_weight(track, q, p, slope, harmonics) < atol)


def regular_band(
    track: SleeperTrack,
    x0: float,
    x1: float,
    y0: float,
    top: float,
    reach: float,
    harmonics: int,
    atol: float,
) -> bool:
    """Whether no zero of D within the reach whose residue in harmonics |n| <= ``harmonics`` exceeds
    ``atol`` can cross the real axis for Re q in [x0, x1] as Im q rises from ``y0`` to ``top``: then the
    integral over real p is the continued receptance in that band, to ``atol``.

    Sampled along the top edge every (top - y0) / 4 by :func:`sheet_poles`: a zero moves by
    |dp / dq| dx between samples, a quarter of the path down that each sample checks, so a crossing
    between samples shows at one of them.
    """
    drop = top - y0
    xs = np.linspace(x0, x1, max(2, int(np.ceil((x1 - x0) / (drop / 4))) + 1))
    return all(sheet_poles(track, complex(x, top), reach, y0, harmonics, atol).poles.size == 0 for x in xs)


def sheet_poles(
    track: SleeperTrack,
    q: complex,
    reach: float,
    y0: float,
    harmonics: int,
    atol: float,
    band: float = 1.5,
) -> SheetPoles:
    """The zeros of D near the real axis at q (Im q above ``y0``) that lie on the other side of the real
    axis than they had at Re q + i y0, with their sides there (the poles the continuation adds).

    A zero moves with q as dp / dq = -h_q / h_p; one whose straight path down to ``y0`` at that rate
    ends on its own side by more than the path's length (so it cannot have crossed), or whose residue in
    harmonics |n| <= ``harmonics`` is below ``atol``, is left out; the others are followed down the
    vertical path.

    Raises
    ------
    ContinuationError
        When a zero cannot be followed down to ``y0`` or ends there on the real axis.
    """
    p = _zeros(track, q, reach, band)
    drop = q.imag - y0
    if p.size == 0 or drop <= 0:
        return _no_poles()
    p = p[_unsafe(track, q, p, drop, harmonics, atol)]
    if p.size == 0:
        return _no_poles()
    below = _follow(track, q, p, y0)
    if np.any(np.abs(below.imag) < 1e-10):
        raise ContinuationError(f"a free wave's pole lies on the real axis below q = {q:.6g}")
    crossed = np.sign(below.imag) != np.sign(p.imag)
    p, below = p[crossed], below[crossed]
    w = q + track.alpha * p
    _, slope = _h_and_slope(track, q, p)
    return SheetPoles(p, np.sign(below.imag), track.support(w) ** 2 / slope)


def _no_poles() -> SheetPoles:
    empty = np.zeros(0, dtype=complex)
    return SheetPoles(empty, np.zeros(0), empty)
