"""Stiffness matrices of a soil layer and of the half-space (Kausel & Roesset 1981), P-SV, per unit area.

The degrees of freedom are (u_x, u_z) at the top of a layer, then at its bottom; the forces are the tractions
the outside applies there. Down-going waves are referred to the top of the layer and up-going waves to its
bottom, so every exponential is exp(-gamma zeta) with Re gamma >= 0 and |.| <= 1 (no growth, no loss of digits
at high frequency); the basis of ``generated/soil_layer.py`` stays regular as omega / (c k) -> 0
(derivations/soil.py), so one form serves every frequency, the static limit included.
"""

from __future__ import annotations

import numpy as np

from moving_bogie.generated.soil_layer import layer_basis
from moving_bogie.typing import ComplexArray

from .mat2 import Mat2
from .profile import SoilLayer

__all__ = ["blocks_of_waves", "halfspace_stiffness", "layer_stiffness", "layer_waves", "vertical_wavenumber"]

#: Below this |x|, exprel(x) = (e^x - 1) / x is summed as its Taylor series (error < 1e-20).
_SERIES = 0.1


def vertical_wavenumber(k2_minus: ComplexArray) -> ComplexArray:
    """sqrt(k^2 - k_j^2) on the radiating branch: Re >= 0, and Im >= 0 where Re = 0 (the limit of
    vanishing damping under exp(i omega t): waves travel away from the surface)."""
    gamma = np.sqrt(k2_minus)  # the principal root: Re >= 0; Re = 0 only on the negative real axis
    edge = gamma.real == 0
    if edge.any():
        g = gamma[edge]
        gamma[edge] = np.where(g.imag < 0, -g, g)
    return gamma


def _exprel(x: ComplexArray) -> ComplexArray:
    """(e^x - 1) / x, its Taylor series where |x| < _SERIES."""
    out = np.empty_like(x)
    small = np.abs(x) < _SERIES
    big = ~small
    out[big] = np.expm1(x[big]) / x[big]
    xs = x[small]
    series = np.ones_like(xs)
    term = np.ones_like(xs)
    for n in range(2, 13):
        term = term * xs / n
        series = series + term
    out[small] = series
    return out


def layer_waves(
    k: ComplexArray, omega: ComplexArray, layer: SoilLayer
) -> tuple[ComplexArray, ComplexArray, ComplexArray, tuple[ComplexArray, ...]]:
    """(p, s, delta, basis): vertical wavenumbers, s - p, and the 24 basis coefficients of the layer.

    ``k`` and ``omega`` broadcast; the Lame constants are lambda (1 + i omega eta), mu (1 + i omega eta).
    """
    factor = 1 + 1j * omega * layer.eta
    mu, lam = layer.mu * factor, layer.lam * factor
    ks2 = layer.rho * omega**2 / mu
    kp2 = ks2 * layer.xi
    k = np.asarray(k, dtype=complex)
    p = vertical_wavenumber(k**2 - kp2)
    s = vertical_wavenumber(k**2 - ks2)
    ds, dp = -ks2 / (s + k), -kp2 / (p + k)
    sp_sum = s + p
    rs = -sp_sum / ((s + k) * (layer.xi - 1))
    rp = -layer.xi * sp_sum / ((p + k) * (layer.xi - 1))
    delta = ks2 * (layer.xi - 1) / sp_sum
    basis = layer_basis(k, ds, dp, rs, rp, lam, mu)
    return p, s, delta, tuple(basis)


def halfspace_stiffness(k: ComplexArray, omega: ComplexArray, layer: SoilLayer) -> tuple[Mat2, ComplexArray]:
    """The 2 x 2 stiffness of the half-space at its surface, K = -T D^{-1}, and det D."""
    _, _, _, a = layer_waves(k, omega, layer)
    disp = Mat2(a[0], a[4], a[1], a[5])
    trac = Mat2(-a[2], -a[6], -a[3], -a[7])
    return trac @ disp.inv(), disp.det()


def layer_stiffness(
    k: ComplexArray, omega: ComplexArray, layer: SoilLayer
) -> tuple[Mat2, Mat2, Mat2, Mat2, ComplexArray]:
    """The blocks (K_tt, K_tb, K_bt, K_bb) and det D of the 4 x 4 stiffness of a layer of thickness h
    (dofs u_x, u_z at the top, then at the bottom): K = F D^{-1}.

    D = [[P, Q], [R, S]] holds the displacements of the down- and up-going basis at the top and bottom; Q and
    R carry the decaying exponentials, so the Schur complement X = (P - Q S^{-1} R)^{-1} is well conditioned.
    """
    return blocks_of_waves(layer_waves(k, omega, layer), layer.h)


def blocks_of_waves(
    waves: tuple[ComplexArray, ComplexArray, ComplexArray, tuple[ComplexArray, ...]], h: float
) -> tuple[Mat2, Mat2, Mat2, Mat2, ComplexArray]:
    """:func:`layer_stiffness` from the layer's waves (:func:`layer_waves`) and thickness."""
    p, s, delta, a = waves
    ep, es = np.exp(-p * h), np.exp(-s * h)
    x = -delta * h
    small = np.abs(x) < 1
    # E(h) = (e^{-s h} - e^{-p h}) / (s - p): the series form where the difference would cancel
    e_h = np.empty_like(ep)
    big = ~small
    e_h[big] = (es[big] - ep[big]) / delta[big]
    e_h[small] = -h * ep[small] * _exprel(x[small])
    d1, d2, d3 = a[0:4], a[4:8], a[8:12]
    u1, u2, u3 = a[12:16], a[16:20], a[20:24]
    d2h = [d2[i] * es + d3[i] * e_h for i in range(4)]  # f2 of the down-going waves at the bottom
    u2h = [u2[i] * es + u3[i] * e_h for i in range(4)]  # f2 of the up-going waves at the top
    down_top = Mat2(d1[0], d2[0], d1[1], d2[1])
    up_bottom = Mat2(u1[0], u2[0], u1[1], u2[1])
    up_top = Mat2(u1[0] * ep, u2h[0], u1[1] * ep, u2h[1])
    down_bottom = Mat2(d1[0] * ep, d2h[0], d1[1] * ep, d2h[1])
    f_top_d = Mat2(-d1[2], -d2[2], -d1[3], -d2[3])
    f_top_u = Mat2(-u1[2] * ep, -u2h[2], -u1[3] * ep, -u2h[3])
    f_bot_d = Mat2(d1[2] * ep, d2h[2], d1[3] * ep, d2h[3])
    f_bot_u = Mat2(u1[2], u2[2], u1[3], u2[3])
    s_inv = up_bottom.inv()
    s_inv_r = s_inv @ down_bottom
    schur = down_top - up_top @ s_inv_r
    x_inv = schur.inv()
    q_s_inv = up_top @ s_inv
    k_tt = (f_top_d - f_top_u @ s_inv_r) @ x_inv
    k_bt = (f_bot_d - f_bot_u @ s_inv_r) @ x_inv
    k_tb = f_top_u @ s_inv - k_tt @ q_s_inv
    k_bb = f_bot_u @ s_inv - k_bt @ q_s_inv
    return k_tt, k_tb, k_bt, k_bb, up_bottom.det() * schur.det()
