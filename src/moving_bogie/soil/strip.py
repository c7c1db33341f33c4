"""The equivalent stiffness chi(k1, omega) of the soil under a strip of half-width b (docs/soil.md, Eq. (S5)).

Dieterman & Metrikine (1996): a track touching the soil over |y| <= b, with the load spread uniformly over
the width and the track's deflection equal to the soil's on the centre line, feels per unit length

    chi(k1, omega) = 2 pi / I,   I = int_{-inf}^{inf} sinc(k2 b) U(sqrt(k1^2 + k2^2), omega) dk2,

sinc(x) = sin(x) / x, for the wave exp(i (omega t - k1 x)): the stiffness of the whole strip (per track).

The integral: U minus its large-wavenumber form U_inf = C / kappa + D / (kappa^2 + beta^2)^(3/2) (the top
layer's Lamb flexibility expanded, C = (1 - nu) / mu, D = k_s^2 (8 nu^2 - 12 nu + 7) / (8 mu), beta = omega /
c_s, with the top layer's complex moduli) is integrated by Gauss-Kronrod (7, 15) panels, and U_inf exactly:

    int sinc(k2 b) / sqrt(a^2 + k2^2) dk2 = 2 J(a b) / (a b),
    int sinc(k2 b) / (a^2 + k2^2)^(3/2) dk2 = 2 (J(a b) / (a b) - K_0(a b)) / a^2,

J(x) = int_0^x K_0(t) dt. The panels grade geometrically towards k2 = 0 (where a surface-wave pole of U comes
close when k1 is near its wavenumber), follow kappa geometrically through the band of the soil's wave speeds
(finer with less damping, where the poles of U lie close to the path) and cover the oscillations of the sinc.
The estimate of the error is the Gauss-Kronrod difference plus a bound of the neglected tail.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import special

from moving_bogie.typing import ComplexArray, FloatArray

from .flexibility import surface_flexibility
from .profile import SoilProfile

__all__ = ["StripStiffness", "strip_stiffness"]

# Gauss-Kronrod (7, 15) on [-1, 1] (Piessens et al., QUADPACK): the 15 Kronrod nodes, their weights, and the
# weights of the 7-point Gauss rule on the odd-indexed nodes.
_XK = np.array(
    [
        0.991455371120812639206854697526329,
        0.949107912342758524526189684047851,
        0.864864423359769072789712788640926,
        0.741531185599394439863864773280788,
        0.586087235467691130294144845693013,
        0.405845151377397166906606412076961,
        0.207784955007898467600689403773245,
        0.0,
    ]
)
_WK = np.array(
    [
        0.022935322010529224963732008058970,
        0.063092092629978553290700663189204,
        0.104790010322250183839876322541518,
        0.140653259715525918745189590510238,
        0.169004726639267902826583426598550,
        0.190350578064785409913256402421014,
        0.204432940075298892414161999234649,
        0.209482141084727828012999174891714,
    ]
)
_WG = np.array(
    [
        0.129484966168869693270611432679082,
        0.279705391489276667901467771423780,
        0.381830050505118944950369775488975,
        0.417959183673469387755102040816327,
    ]
)
#: Panels graded geometrically towards k2 = 0, and geometric in kappa up to the last node (module docstring).
NEAR_PANELS, KAPPA_PANELS = 8, 10
NODES = np.concatenate([-_XK[:-1], _XK[::-1]])
WEIGHTS_K = np.concatenate([_WK[:-1], _WK[::-1]])
WEIGHTS_G = np.zeros(15)
WEIGHTS_G[1::2] = np.concatenate([_WG[:-1], _WG[::-1]])


@dataclass(frozen=True)
class StripStiffness:
    """chi (N/m^2, per unit length of the whole strip) at each (k1, omega), and its estimated error."""

    chi: ComplexArray
    error: FloatArray


def _integral_inf(a: FloatArray, b: float) -> FloatArray:
    """2 J(a b) / (a b): int sinc(k2 b) / sqrt(a^2 + k2^2) dk2 over the real line."""
    x = a * b
    return 2 * special.iti0k0(x)[1] / x


def _integral_inf3(a: FloatArray, b: float) -> FloatArray:
    """int sinc(k2 b) / (a^2 + k2^2)^(3/2) dk2 = 2 (J(a b) / (a b) - K_0(a b)) / a^2."""
    x = a * b
    return 2 * (special.iti0k0(x)[1] / x - special.k0(x)) / a**2


def _breakpoints(k1: float, omega: float, soil: SoilProfile, b: float, top: float) -> FloatArray:
    """Panel ends in k2 for one (k1, omega) (module docstring)."""
    layers = soil.layers
    scale = min(k1, top)
    near = np.geomspace(1e-4 * scale, scale, NEAR_PANELS)
    eta = min(layer.eta for layer in layers) * abs(omega)
    speeds = [c for layer in layers for c in (layer.c_s, layer.c_p)]
    band = [abs(omega) / max(speeds) * 0.8, abs(omega) / (0.5 * soil.c_s_min)]
    ratio = 1 + min(0.1, max(1.5 * eta, 0.01))
    kappa = []
    # the poles of U lie in this band of kappa, on the real axis without damping (k1 must exceed them)
    # and next to it with damping, where the panels follow them at a relative width of 1.5 omega eta
    if band[1] > band[0] and eta > 0:
        kappa.append(np.geomspace(band[0], band[1], int(np.log(band[1] / band[0]) / np.log(ratio)) + 2))
    kappa.append(np.geomspace(max(k1, 1e-3 * scale), top, KAPPA_PANELS))
    kap = np.concatenate(kappa)
    kap = kap[kap > k1]
    waves = np.sqrt(kap**2 - k1**2)
    sinc = np.arange(0.0, top, 2 * np.pi / b)
    ends = np.unique(np.concatenate([[0.0, top], near, waves, sinc]))
    return ends[ends <= top]


def strip_stiffness(k1: FloatArray, omega: FloatArray, soil: SoilProfile, b: float) -> StripStiffness:
    """chi(k1, omega) of a strip of half-width ``b`` (m) on ``soil`` for real k1 > 0 and real omega.

    On an undamped soil the k2 path must not meet a surface-wave pole: take |k1| above the wavenumber of the
    slowest wave (phase speed omega / k1 below every mode's), or give the layers Kelvin-Voigt damping.
    """
    k1 = np.abs(np.atleast_1d(np.asarray(k1, dtype=float)))
    omega = np.broadcast_to(np.asarray(omega, dtype=float), k1.shape)
    if k1.size == 0:
        return StripStiffness(chi=np.empty(k1.shape, dtype=complex), error=np.empty(k1.shape))
    top_layer = soil.layers[0]
    factor = 1 + 1j * omega * top_layer.eta
    mu = top_layer.mu * factor
    nu = top_layer.nu
    c_coef = (1 - nu) / mu
    ks2 = top_layer.rho * omega**2 / mu
    d_coef = ks2 * (8 * nu**2 - 12 * nu + 7) / (8 * mu)
    beta = np.abs(omega) / top_layer.c_s
    h_top = top_layer.h if np.isfinite(top_layer.h) else np.inf
    nodes, weights_k, weights_g, owner = [], [], [], []
    tops = np.empty(k1.shape)
    for i, (a, w) in enumerate(zip(k1.ravel(), omega.ravel(), strict=True)):
        top = 20 * max(1 / b, 1 / h_top, abs(w) / soil.c_s_min)
        tops[i] = top
        ends = _breakpoints(a, w, soil, b, top)
        half, mid = np.diff(ends) / 2, (ends[1:] + ends[:-1]) / 2
        nodes.append((mid[:, None] + half[:, None] * NODES).ravel())
        weights_k.append((half[:, None] * WEIGHTS_K).ravel())
        weights_g.append((half[:, None] * WEIGHTS_G).ravel())
        owner.append(np.full(nodes[-1].size, i))
    k2 = np.concatenate(nodes)
    who = np.concatenate(owner)
    kappa = np.sqrt(k1.ravel()[who] ** 2 + k2**2)
    u = surface_flexibility(kappa, omega.ravel()[who], soil)
    u_inf = c_coef.ravel()[who] / kappa + d_coef.ravel()[who] / (kappa**2 + beta.ravel()[who] ** 2) ** 1.5
    integrand = 2 * np.sinc(k2 * b / np.pi) * (u - u_inf)  # np.sinc(x) = sin(pi x) / (pi x); twice [0, inf)
    starts = np.concatenate([[0], np.cumsum([n.size for n in nodes])[:-1]])
    rest_k = np.add.reduceat(integrand * np.concatenate(weights_k), starts)
    rest_g = np.add.reduceat(integrand * np.concatenate(weights_g), starts)
    a_eff = np.sqrt(k1.ravel() ** 2 + beta.ravel() ** 2)
    closed = c_coef.ravel() * _integral_inf(k1.ravel(), b) + d_coef.ravel() * _integral_inf3(a_eff, b)
    total = closed + rest_k
    # the tail beyond k2 = top: the envelope 2 |U - U_inf| / (k2 b) at the last node decays at least like
    # k2^-4 there (U - U_inf = O(kappa^-5) past the layers' exponentials), so its integral is below top / 3
    last = np.concatenate([starts[1:] - 1, [k2.size - 1]])
    envelope = 2 * np.abs(u - u_inf)[last] / (k2[last] * b)
    tail = envelope * tops.ravel() / 3
    error_i = np.abs(rest_k - rest_g) + tail
    chi: ComplexArray = np.asarray(2 * np.pi / total, dtype=complex)
    return StripStiffness(
        chi=chi.reshape(k1.shape), error=(np.abs(chi) * error_i / np.abs(total)).reshape(k1.shape)
    )
