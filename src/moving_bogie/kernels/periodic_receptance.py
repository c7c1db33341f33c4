"""Receptance between (contact, harmonic) pairs of a load moving over a rail on supports (docs/sleepers.md).

A force F e^{i q_m tau} at contact c (position s_c in the moving frame) gives at contact c' the harmonics
q_n = q + n Omega_0; the receptance between them (Eq. (S9), dimensionless: k_e / chi times the SI one) is

    H[(c', n), (c, m)] = (1 / 2 pi) int [ delta_nm G_n e^{i (p - n K) (s_c - s_c')}
                                          - z G_n G_m e^{i (p - m K) s_c - i (p - n K) s_c'} / D ] dp,

G_n = G(p - n K, w), w = q + alpha p, D = 1 + z S(p, w). It is evaluated as (Eq. (S11))

- for n = m: the continuous rail on the smeared supports, G_c = G / (1 + z G), by residues (exact), plus
  the integral of e^{i (p - n K) (s_c - s_c')} z^2 G_n^2 S'_n / (D (1 + z G_n)), with S'_n = S - G_n the
  lattice sum without its own term, in the form (lam / 2) cot(lam x / 2) - 1 / x that has no pole;
- for n != m: the integral of the second term as it stands.

Neither integrand has a pole where G_n has one (they cancel in the formula), so the only singularities
near the real axis are the free waves of the periodic rail (zeros of D) and of the smeared one. The
integrals are adaptive Gauss-Kronrod (7-15) on panels of a quarter of K, with a tail bound, to ``tol``
relative to the largest free-rail receptance.
"""

from __future__ import annotations

import threading
from dataclasses import dataclass
from typing import Any

import mpmath
import numpy as np
from numpy.typing import ArrayLike

from moving_bogie.kernels.free_wave_poles import Sheet, SheetPoles, sheet_poles
from moving_bogie.kernels.gauss_kronrod import GAUSS, KRONROD, NODES
from moving_bogie.kernels.sleeper_track import SleeperTrack, stable_cot
from moving_bogie.kernels.smeared_rail import smeared_receptance

__all__ = ["Receptance", "receptance"]

#: cot y - 1 / y = -sum_k c_k y^(2k-1), c_k = 2^(2k) |B_2k| / (2k)!, for |y| < 0.5 (14 terms: < 1e-17)
_COT_SERIES = [
    float(2 ** (2 * k) * abs(mpmath.bernoulli(2 * k)) / mpmath.factorial(2 * k)) for k in range(1, 15)
]


def _cot_series(y: np.ndarray) -> np.ndarray:
    """cot y - 1 / y by its Taylor series (|y| < 0.5)."""
    series = np.zeros_like(y)
    y2 = y * y
    for c in reversed(_COT_SERIES):
        series = series * y2 + c
    return -series * y


@dataclass(frozen=True)
class Receptance:
    """H over (contact, harmonic) pairs at one q, row/column index i_n * contacts + c.

    ``matrix`` is H; ``error`` the estimated absolute error of its entries (Gauss-Kronrod and tail);
    ``scale`` the largest free-rail receptance, the reference of the relative tolerance.
    """

    matrix: np.ndarray
    error: float
    scale: float
    panels: int


def _sum4(a: np.ndarray) -> np.ndarray:
    """The sum over the first axis (the four roots of the symbol), term by term in their order."""
    return a[0] + a[1] + a[2] + a[3]


def _integrand_factors(
    track: SleeperTrack, q: complex, harmonics: np.ndarray, positions: np.ndarray, p: np.ndarray
) -> tuple[np.ndarray, ...]:
    """The integrands of Eq. (S11) at nodes p (shape (P,)) as factors: ``(c, u, v, diag, out_ph, in_ph)``.

    The (P, R, R) integrand (R = len(harmonics) * contacts) is ``c u v^T`` (the n != m term,
    c = -z / D) except on its diagonal blocks n = m, which are ``diag out_ph in_ph^T``; shapes (P,),
    (P, R), (P, R), (P, H), (P, H, C), (P, H, C). :func:`_integrand` assembles them.
    """
    K, alpha, lam = track.K, track.alpha, track.lam
    w = q + alpha * p
    z = track.support(w)
    r, res = (a[:, :, None] for a in track.symbol_roots_first(w))  # (4, P, 1)
    cot = lam / 2 * stable_cot(lam / 2 * (p[None, :, None] - r))  # the same at every harmonic: lam K / 2 = pi
    S = _sum4(cot * res)[:, 0]
    D = 1 + z * S
    shift = p[:, None] - harmonics[None, :] * K  # (P, H), real
    x = shift[None] - r  # (4, P, H): p - n K - r
    inv = 1 / x
    G = _sum4(res * inv)  # (P, H): partial fractions of Q~/N~ (deg Q < deg N)
    own = cot - inv  # (lam / 2) cot(lam x / 2) - 1 / x: S'_n, its series where x is small
    small = (shift[None] - r.real) ** 2 + r.imag**2 < (1 / lam) ** 2  # |lam x / 2| < 1 / 2
    if np.any(small):
        own[small] = lam / 2 * _cot_series(lam / 2 * x[small])
    S_own = _sum4(res * own)
    s = np.asarray(positions, dtype=float)
    # the source's phase e^{i (p - n K) s_c} (P, H, C) as e^{i p s_c} e^{-i n K s_c}; the receiver's is its
    # conjugate (p real)
    in_ph = np.exp(1j * p[:, None, None] * s) * np.exp(-1j * K * harmonics[:, None] * s)[None, :, :]
    out_ph = in_ph.conj()
    P, H, C = out_ph.shape
    u = (G[:, :, None] * out_ph).reshape(P, H * C)
    v = (G[:, :, None] * in_ph).reshape(P, H * C)
    zG = z[:, None] * G
    diag = zG * zG * S_own / (D[:, None] * (1 + zG))  # (P, H): z^2 G^2 S'_n / (D (1 + z G))
    return -z / D, u, v, diag, out_ph, in_ph


def _integrand(
    track: SleeperTrack, q: complex, harmonics: np.ndarray, positions: np.ndarray, p: np.ndarray
) -> np.ndarray:
    """The integrands at nodes p (shape (P,)): shape (P, R, R), R = len(harmonics) * contacts."""
    c, u, v, diag, out_ph, in_ph = _integrand_factors(track, q, harmonics, positions, p)
    f = c[:, None, None] * u[:, :, None] * v[:, None, :]
    C = out_ph.shape[-1]
    for i in range(out_ph.shape[1]):
        blk = slice(i * C, (i + 1) * C)
        f[:, blk, blk] = diag[:, i, None, None] * out_ph[:, i, :, None] * in_ph[:, i, None, :]
    return f


def _panel_sums(
    track: SleeperTrack,
    q: complex,
    harmonics: np.ndarray,
    positions: np.ndarray,
    a: np.ndarray,
    b: np.ndarray,
    poles: Subtracted | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Kronrod and Gauss sums over panels [a_i, b_i]: arrays (panels, R, R) each (in chunks of panels).

    The weighted sums of the factors of :func:`_integrand_factors`, a batched matrix product for the
    rank-one part and one per diagonal block, without forming the (nodes, R, R) integrand; less the
    pole parts ``R_k / (p - p_k)`` of ``poles`` when given (:func:`_subtracted`).
    """
    R = _r(harmonics, positions)
    chunk = max(1, 200_000 // (15 * R * R))
    if a.size > chunk:
        parts = [
            _panel_sums(track, q, harmonics, positions, a[i : i + chunk], b[i : i + chunk], poles)
            for i in range(0, a.size, chunk)
        ]
        return np.concatenate([k for k, _ in parts]), np.concatenate([g for _, g in parts])
    half = (b - a) / 2
    mid = (a + b) / 2
    p = (mid[:, None] + half[:, None] * NODES[None, :]).ravel()
    c, u, v, diag, out_ph, in_ph = _integrand_factors(track, q, harmonics, positions, p)
    n, H, C = a.size, out_ph.shape[1], out_ph.shape[2]
    weights = np.stack([KRONROD, GAUSS])[:, None, :] * half[None, :, None]  # (2, panels, 15)
    cu = (weights * c.reshape(n, 15))[..., None] * u.reshape(n, 15, R)  # (2, panels, 15, R)
    sums = np.swapaxes(cu, -1, -2) @ v.reshape(n, 15, R)  # (2, panels, R, R)
    wd = weights[..., None] * diag.reshape(n, 15, H)  # (2, panels, 15, H)
    blocks = np.einsum("wpkh,pkhc,pkhd->wphcd", wd, out_ph.reshape(n, 15, H, C), in_ph.reshape(n, 15, H, C))
    for i in range(H):
        sums[:, :, i * C : (i + 1) * C, i * C : (i + 1) * C] = blocks[:, :, i]
    if poles is not None and poles.poles.size:
        inverse = weights[..., None] / (
            p.reshape(n, 15)[None, :, :, None] - poles.poles
        )  # (2, panels, 15, K)
        sums -= np.einsum("wpk,kr,ks->wprs", inverse.sum(axis=2), poles.left, poles.right)
    return sums[0], sums[1]


@dataclass(frozen=True)
class Subtracted:
    """Poles p_k of the integrand with their residue matrices ``left[k] right[k]^T`` (the coefficient of
    -z / D folded into ``left``) and their sides below the singular lines."""

    poles: np.ndarray
    left: np.ndarray
    right: np.ndarray
    sides: np.ndarray

    def integral(self, a: float, b: float) -> np.ndarray:
        """sum_k R_k int_a^b dp / (p - p_k) along the real axis deformed to leave p_k on its side:
        Log(b - p_k) - Log(p_k - a) + i pi side_k (analytic in p_k off the rays beyond a and b)."""
        p = self.poles
        f = np.log(b - p) - np.log(p - a) + 1j * np.pi * self.sides
        return np.einsum("k,kr,ks->rs", f, self.left, self.right)


def _subtracted(
    track: SleeperTrack, q: complex, harmonics: np.ndarray, positions: np.ndarray, sheet: SheetPoles
) -> Subtracted:
    """The residue matrices of the integrand at the free waves' poles: -z G_n G_m e^(...) / D'(p_k),
    the same on and off the diagonal blocks (docs/sleepers.md, "Beyond the free waves")."""
    p = sheet.poles
    w = q + track.alpha * p
    shift = p[:, None] - harmonics[None, :] * track.K  # (K, H), complex
    G = track.green(shift, np.broadcast_to(w[:, None], shift.shape))
    s = np.asarray(positions, dtype=float)
    out_ph = np.exp(-1j * shift[:, :, None] * s)  # e^{-i (p - n K) s_c'}
    in_ph = np.exp(1j * shift[:, :, None] * s)
    k = p.size
    left = (sheet.coefficients[:, None, None] * G[:, :, None] * out_ph).reshape(k, -1)
    right = (G[:, :, None] * in_ph).reshape(k, -1)
    return Subtracted(p, left, right, sheet.sides)


def _r(harmonics: np.ndarray, positions: np.ndarray) -> int:
    return len(harmonics) * len(positions)


def receptance(
    track: SleeperTrack,
    q: complex,
    harmonics: ArrayLike,
    positions: ArrayLike = (0.0,),
    *,
    tol: float = 1e-12,
    tail: float | None = None,
    max_rounds: int = 40,
    continued_from: Sheet | None = None,
) -> Receptance:
    """H[(c', n), (c, m)](q) of Eq. (S9) for the given harmonics n and contact positions s_c (dimensionless).

    Parameters
    ----------
    tol : float
        Relative tolerance (to the largest free-rail receptance) of every entry.
    tail : float, optional
        Half-width beyond the outermost harmonic's zone where the integration starts (default 2 K + 10).
    continued_from : Sheet, optional
        Above its level ``y0`` of Im q (below the rail's free waves) H is continued across the free
        waves' singular lines along the vertical path from it (:mod:`moving_bogie.kernels.free_wave_poles`):
        the poles of the integrand that crossed the real axis are subtracted and integrated in closed form
        along the deformed contour (none when the reach is within the sheet's regular reach).
        ContinuationError when the poles cannot be followed.

    The last :data:`_KEPT` receptances are kept by their arguments (the track's groups included): the Hill
    matrices of several vehicles on one track (the counts on either side of a zone edge, a column of
    eta_M) need it at the same q again. A kept one is handed out as a copy.
    """
    harmonics = np.asarray(harmonics, dtype=int)
    positions = np.asarray(positions, dtype=float)
    q = complex(q)
    at = np.complex128(q).tobytes()  # -0.0 apart from 0.0
    model = (track.beam, track.track, tuple(sorted(track.groups.items())))
    sheet = continued_from if continued_from is not None and q.imag > continued_from.y0 else None
    key = (model, at, harmonics.tobytes(), positions.tobytes(), tol, tail, max_rounds, sheet)
    kept = _kept.get(key)
    if kept is None:
        kept = _receptance(track, q, harmonics, positions, tol, tail, max_rounds, sheet)
        with _keeping:  # threads of one process (a threaded scheduler) share the memory
            _kept[key] = kept
            while len(_kept) > _KEPT:
                del _kept[next(iter(_kept))]  # the oldest
    return Receptance(kept.matrix.copy(), kept.error, kept.scale, kept.panels)


#: How many receptances :func:`receptance` keeps, and those it keeps (by their arguments).
_KEPT = 1024
_kept: dict[tuple, Receptance] = {}
_keeping = threading.Lock()


def _receptance(
    track: SleeperTrack,
    q: complex,
    harmonics: np.ndarray,
    positions: np.ndarray,
    tol: float,
    tail: float | None,
    max_rounds: int,
    sheet: Sheet | None = None,
) -> Receptance:
    """:func:`receptance` computed (Eqs. (S9), (S11)); continued on ``sheet`` when given."""
    C, H = positions.size, harmonics.size
    K = track.K
    offsets = positions[None, :] - positions[:, None]  # [c', c] -> s_c - s_c'
    free = np.zeros((H * C, H * C), dtype=complex)
    vals = smeared_receptance(track, q + harmonics * track.Omega0, offsets.ravel()).reshape(H, C, C)
    for i in range(H):
        free[i * C : (i + 1) * C, i * C : (i + 1) * C] = vals[i]
    scale = float(np.max(np.abs(np.diag(free))))
    atol = tol * scale
    reach = (np.max(np.abs(harmonics)) + 1) * K + (2 * K + 10 if tail is None else tail)
    # the reach first (the tail's estimate needs no integral inside it), then one adaptive integral
    poles = None
    while True:
        if sheet is not None and reach <= sheet.regular:
            # the integral over real p is the continuation to the sheet's tolerance, and no better
            atol = max(atol, sheet.regular_atol)
        elif sheet is not None:
            found = sheet_poles(track, q, reach, sheet.y0, int(np.max(np.abs(harmonics))), atol)
            poles = _subtracted(track, q, harmonics, positions, found) if found.poles.size else None
        # the tail of the integrand as it stands (a subtracted pole part falls like 1 / p, but is
        # integrated in closed form over the same reach)
        outer = _zone_magnitude(track, q, harmonics, positions, reach, K)
        tail_bound = outer * reach / (2 * K)
        if tail_bound < atol or reach > _MAX_REACH * K:
            break
        reach *= 1.6
    edges = np.arange(-reach, reach + 1e-9 * K, K / 4)
    total, err, panels = _adaptive(
        track, q, harmonics, positions, edges[:-1], edges[1:], atol, max_rounds, poles
    )
    if poles is not None:
        total = total + poles.integral(float(edges[0]), float(edges[-1]))
    return Receptance(free + total / (2 * np.pi), float((err + tail_bound) / (2 * np.pi)), scale, panels)


#: the farthest the integration reaches, in units of K, and the most panels of one refinement round
_MAX_REACH = 60
_MAX_PANELS = 4000


def _zone_magnitude(
    track: SleeperTrack,
    q: complex,
    harmonics: np.ndarray,
    positions: np.ndarray,
    reach: float,
    K: float,
    poles: Subtracted | None = None,
) -> float:
    """Largest entry of the integrals over the two outermost zones of width K (the tail's estimate)."""
    a = np.array([reach - K, -reach])
    kron, _ = _panel_sums(track, q, harmonics, positions, a, a + K, poles)
    return float(np.max(np.abs(kron)))


def _adaptive(
    track: SleeperTrack,
    q: complex,
    harmonics: np.ndarray,
    positions: np.ndarray,
    a: np.ndarray,
    b: np.ndarray,
    atol: float,
    max_rounds: int,
    poles: Subtracted | None = None,
) -> tuple[Any, float, int]:
    """Sum of the panel integrals, bisecting every panel whose Gauss-Kronrod difference exceeds its share.

    A panel's share is the part of the tolerance not yet spent by the accepted panels, in proportion to its
    width among the panels still open: the accepted errors never add up to more than ``atol``.
    """
    total = 0.0
    err = 0.0
    panels = 0
    for _ in range(max_rounds):
        kron, gauss = _panel_sums(track, q, harmonics, positions, a, b, poles)
        e = np.max(np.abs(kron - gauss), axis=(1, 2))
        panels += a.size
        ok = e <= (atol - err) * (b - a) / float(np.sum(b - a))
        total = total + np.sum(kron[ok], axis=0)
        err += float(np.sum(e[ok]))
        if np.all(ok) or np.count_nonzero(~ok) > _MAX_PANELS:
            break
        a, b = a[~ok], b[~ok]
        m = (a + b) / 2
        a, b = np.concatenate([a, m]), np.concatenate([m, b])
    if not np.all(ok):
        total = total + np.sum(kron[~ok], axis=0)
        err += float(np.sum(e[~ok]))
    return total, err, panels
