"""The receptance of the smeared rail (the l -> 0 limit of the rail on supports, Eq. (S12)), by residues.

The continuous rail on the supports smeared along it has G_c = G / (1 + z G), a rational function of the
wavenumber kappa at w = q + alpha kappa: the integral (1 / 2 pi) int G_c e^{i kappa xi} dkappa is a sum of
residues, every q at once (companion matrices over the batch).
:func:`~moving_bogie.kernels.periodic_receptance.receptance` takes its diagonal harmonics from it (Eq. (S11)).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from moving_bogie.kernels.sleeper_track import SleeperTrack

__all__ = ["smeared_receptance"]


def _columns(coeffs: Any, shape: tuple[int, ...]) -> np.ndarray:
    """Coefficients (highest first; scalars or arrays of ``shape``) as an array shape + (deg + 1,)."""
    return np.stack([np.broadcast_to(np.asarray(c, dtype=complex), shape) for c in coeffs], axis=-1)


def _polymul(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Products of polynomials along the last axis (highest first), over the batch."""
    out = np.zeros(
        np.broadcast_shapes(a.shape[:-1], b.shape[:-1]) + (a.shape[-1] + b.shape[-1] - 1,), complex
    )
    for j in range(b.shape[-1]):
        out[..., j : j + a.shape[-1]] += a * b[..., j : j + 1]
    return out


def _polyadd(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Sums of polynomials along the last axis (highest first), over the batch."""
    n = max(a.shape[-1], b.shape[-1])
    pad = [np.concatenate([np.zeros(c.shape[:-1] + (n - c.shape[-1],), complex), c], axis=-1) for c in (a, b)]
    return pad[0] + pad[1]


def _polyval(c: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Horner over the batch: c of shape batch + (deg + 1,), x of shape batch + (k,)."""
    out = np.zeros(x.shape, dtype=complex) + c[..., :1]
    for k in range(1, c.shape[-1]):
        out = out * x + c[..., k : k + 1]
    return out


def _polynomial_in_kappa(coeffs_w: Any, q: np.ndarray, alpha: float) -> np.ndarray:
    """Coefficients in kappa (highest first) of a polynomial in w at w = q + alpha kappa, for each q."""
    out = np.zeros(q.shape + (1,), dtype=complex)
    lin = _columns((alpha, q), q.shape)
    for c in coeffs_w:
        out = _polyadd(_polymul(out, lin), np.full(q.shape + (1,), c, dtype=complex))
    return out


def smeared_receptance(track: SleeperTrack, q: ArrayLike, offsets: ArrayLike) -> np.ndarray:
    """(1 / 2 pi) int G_c(kappa, q + alpha kappa) e^{i kappa xi} dkappa, G_c = G / (1 + z G), by residues.

    The continuous rail on the supports smeared along it (the l -> 0 limit, Eq. (S12)); the integral is
    closed in the upper half-plane for xi >= 0 and in the lower one for xi < 0. ``q`` a number (the result
    has the shape of ``offsets``) or an array (the result: q.shape + offsets.shape), every q at once.
    """
    qs = np.asarray(q, dtype=complex)
    xi = np.atleast_1d(np.asarray(offsets, dtype=float))
    batch = qs.reshape(-1)
    args = track.arguments("moving_groups")
    kernels = track.kernels
    n = _columns(kernels.moving_n_coeffs(batch, track.alpha, **args), batch.shape)
    qq = _columns(kernels.moving_q_coeffs(batch, track.alpha, **args), batch.shape)
    z_num, z_den = track.support_polynomials()
    zn, zd = (_polynomial_in_kappa(c, batch, track.alpha) for c in (z_num, z_den))
    den = _polyadd(_polymul(n, zd), _polymul(zn, qq))
    num = _polymul(qq, zd)
    while den.shape[-1] > 1 and not np.any(den[:, 0]):
        den = den[:, 1:]
    if not np.all(den[:, 0]) or not np.all(den[:, -1]):  # a degree that drops at some q only, or kappa = 0
        rows = [_smeared_one(den_i, num_i, xi) for den_i, num_i in zip(den, num)]
        return np.array(rows).reshape(qs.shape + xi.shape)
    d = den.shape[-1] - 1
    companion = np.zeros(batch.shape + (d, d), dtype=complex)
    companion[:, 0, :] = -den[:, 1:] / den[:, :1]
    companion[:, range(1, d), range(d - 1)] = 1
    roots = np.linalg.eigvals(companion)  # the roots of den, as np.roots finds them
    res = _polyval(num, roots) / _polyval(den[:, :-1] * np.arange(d, 0, -1), roots)
    upper = (xi >= 0)[None, :, None]
    sel = np.where(upper, roots.imag[:, None, :] > 0, roots.imag[:, None, :] < 0)
    terms = np.where(sel, res[:, None, :] * np.exp(1j * roots[:, None, :] * xi[None, :, None]), 0)
    out = np.where(upper[..., 0], 1j, -1j) * np.sum(terms, axis=-1)
    return out.reshape(qs.shape + xi.shape)


def _smeared_one(den: np.ndarray, num: np.ndarray, xi: np.ndarray) -> np.ndarray:
    """:func:`smeared_receptance` at one q from the polynomials of G_c (any degree, by np.roots)."""
    den = np.trim_zeros(den, "f")
    roots = np.roots(den)
    res = np.polyval(num, roots) / np.polyval(np.polyder(den), roots)
    out = []
    for x in xi:
        sel = roots.imag > 0 if x >= 0 else roots.imag < 0
        out.append((1j if x >= 0 else -1j) * np.sum(res[sel] * np.exp(1j * roots[sel] * x)))
    return np.array(out)
