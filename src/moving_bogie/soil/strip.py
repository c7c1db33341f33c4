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
(where the poles of U lie on or next to the path) and cover the oscillations of the sinc; every panel whose
Kronrod and Gauss sums differ by more than its share of the tolerance is bisected, all (k1, omega) at once,
so the panels close in on the poles of U only where they are. The estimate of the error is the sum of the
Gauss-Kronrod differences plus a bound of the neglected tail.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import special

from moving_bogie.kernels.gauss_kronrod import GAUSS as WEIGHTS_G
from moving_bogie.kernels.gauss_kronrod import KRONROD as WEIGHTS_K
from moving_bogie.kernels.gauss_kronrod import NODES
from moving_bogie.typing import ComplexArray, FloatArray

from .flexibility import surface_flexibility
from .illinois import IntArray
from .profile import SoilProfile

__all__ = ["StripStiffness", "strip_stiffness"]

#: Panels graded geometrically towards k2 = 0, and geometric in kappa up to the last node (module docstring).
NEAR_PANELS, KAPPA_PANELS = 8, 10
#: Ratio of the initial geometric panels in kappa over the band of the soil's wave speeds (damped soil).
BAND_RATIO = 1.1
#: The band's ratio for an item whose tolerance is at least LOOSE (bisection closes in on the poles where
#: that tolerance needs it; the receptance of Eq. (S9) asks chi only as accurately as 1/D needs).
LOOSE, LOOSE_BAND_RATIO = 1e-7, 1.5
#: Periods of the sinc per initial panel when panels are bisected (Gauss-Kronrod 15 resolves two; bisection
#: catches the rest); one without bisection (``rounds=1``, a fixed grid).
SINC_PERIODS = 2
#: Nodes of U evaluated at once.
CHUNK = 4096


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


def _breakpoints(
    k1: float, omega: complex, soil: SoilProfile, b: float, top: float, periods: int, ratio: float
) -> FloatArray:
    """Initial panel ends in k2 for one (k1, omega) (module docstring), bisected later."""
    layers = soil.layers
    scale = min(k1, top)
    near = np.geomspace(1e-4 * scale, scale, NEAR_PANELS)
    eta = min(layer.eta for layer in layers) * abs(omega)
    speeds = [c for layer in layers for c in (layer.c_s, layer.c_p)]
    band = [abs(omega) / max(speeds) * 0.8, abs(omega) / (0.5 * soil.c_s_min)]
    kappa = []
    # the poles of U lie in this band of kappa, on the real axis without damping (k1 must exceed them)
    # and next to it with damping: a geometric band of ratio ``ratio``, bisected where the rules differ
    if band[1] > band[0] and eta > 0:
        kappa.append(np.geomspace(band[0], band[1], int(np.log(band[1] / band[0]) / np.log(ratio)) + 2))
    kappa.append(np.geomspace(max(k1, 1e-3 * scale), top, KAPPA_PANELS))
    kap = np.concatenate(kappa)
    kap = kap[kap > k1]
    waves = np.sqrt(kap**2 - k1**2)
    sinc = np.arange(0.0, top, periods * 2 * np.pi / b)
    ends = np.unique(np.concatenate([[0.0, top], near, waves, sinc]))
    return ends[ends <= top]


def _flexibility(kappa: ComplexArray, omega: ComplexArray, soil: SoilProfile) -> ComplexArray:
    """U(kappa, omega) in blocks of CHUNK nodes (the same values; small arrays stay in the cache)."""
    out = np.empty(kappa.shape, dtype=complex)
    for i in range(0, kappa.size, CHUNK):
        out[i : i + CHUNK] = surface_flexibility(kappa[i : i + CHUNK], omega[i : i + CHUNK], soil)
    return out


@dataclass(frozen=True)
class _Integrand:
    """2 sinc(k2 b) (U - U_inf) at (k1, omega) of item ``who`` (module docstring)."""

    k1: FloatArray
    omega: ComplexArray
    c_coef: ComplexArray
    d_coef: ComplexArray
    beta: FloatArray
    soil: SoilProfile
    b: float

    def difference(self, k2: FloatArray, who: IntArray) -> ComplexArray:
        """U - U_inf."""
        kappa = np.sqrt(self.k1[who] ** 2 + k2**2)
        u = _flexibility(kappa.astype(complex), self.omega[who].astype(complex), self.soil)
        u_inf = self.c_coef[who] / kappa + self.d_coef[who] / (kappa**2 + self.beta[who] ** 2) ** 1.5
        return np.asarray(u - u_inf, dtype=complex)

    def __call__(self, k2: FloatArray, who: IntArray) -> ComplexArray:
        return 2 * np.sinc(k2 * self.b / np.pi) * self.difference(k2, who)


def _adaptive(
    f: _Integrand, ends: list[FloatArray], closed: ComplexArray, rtol: FloatArray, rounds: int
) -> tuple[ComplexArray, FloatArray]:
    """Sum over each item's panels (``ends``) of Gauss-Kronrod (7, 15), all items at once; a panel is bisected
    while its Kronrod-Gauss difference exceeds rtol |closed + integral| / (its item's panel count).
    Returns (integral, sum of the kept panels' differences) per item."""
    n = len(ends)
    lo = np.concatenate([e[:-1] for e in ends])
    hi = np.concatenate([e[1:] for e in ends])
    who = np.repeat(np.arange(n), [e.size - 1 for e in ends])
    total, error = np.zeros(n, dtype=complex), np.zeros(n)
    for step in range(rounds):
        half, mid = (hi - lo) / 2, (hi + lo) / 2
        g = f((mid[:, None] + half[:, None] * NODES).ravel(), np.repeat(who, NODES.size)).reshape(-1, 15)
        kronrod, gauss = (g @ WEIGHTS_K) * half, (g @ WEIGHTS_G) * half
        diff = np.abs(kronrod - gauss)
        estimate = closed + total + _sum(who, kronrod, n)
        count = np.bincount(who, minlength=n)
        keep = (diff <= rtol[who] * np.abs(estimate[who]) / count[who]) | (step == rounds - 1)
        total += _sum(who[keep], kronrod[keep], n)
        error += np.bincount(who[keep], diff[keep], minlength=n)
        if keep.all():
            break
        lo, hi, who = lo[~keep], hi[~keep], who[~keep]
        centre = (lo + hi) / 2
        lo, hi, who = np.concatenate([lo, centre]), np.concatenate([centre, hi]), np.concatenate([who, who])
    return total, error


def _sum(who: IntArray, values: ComplexArray, n: int) -> ComplexArray:
    return np.bincount(who, values.real, minlength=n) + 1j * np.bincount(who, values.imag, minlength=n)


def strip_stiffness(
    k1: FloatArray,
    omega: FloatArray | ComplexArray,
    soil: SoilProfile,
    b: float,
    *,
    rtol: float | FloatArray = 1e-11,
    rounds: int = 6,
) -> StripStiffness:
    """chi(k1, omega) of a strip of half-width ``b`` (m) on ``soil`` for real k1 > 0 and real omega, or
    complex omega with Im omega <= 0 (where U is analytic on the real path of k2: the soil is passive, its
    free waves decay, Im omega > 0).

    The k2 integral is refined until the Kronrod-Gauss differences sum to about ``rtol`` of it (at most
    ``rounds`` bisections; ``rounds=1``: the initial panels only, one per period of the sinc); ``rtol`` may
    be an array, one tolerance per (k1, omega); ``error`` states what was reached. On an undamped soil the
    k2 path must not meet a surface-wave pole: take |k1| above the wavenumber of the slowest wave (phase
    speed omega / k1 below every mode's), or give the layers Kelvin-Voigt damping.
    """
    k1 = np.abs(np.atleast_1d(np.asarray(k1, dtype=float)))
    if k1.size == 0:
        return StripStiffness(chi=np.empty(k1.shape, dtype=complex), error=np.empty(k1.shape))
    rtol = np.broadcast_to(np.asarray(rtol, dtype=float), k1.shape).ravel()
    shape, k1 = k1.shape, k1.ravel()
    w: ComplexArray = np.ascontiguousarray(np.broadcast_to(np.asarray(omega, dtype=complex), shape)).ravel()
    omega = w
    top_layer = soil.layers[0]
    mu = top_layer.mu * (1 + 1j * omega * top_layer.eta)
    nu = top_layer.nu
    c_coef = np.asarray((1 - nu) / mu, dtype=complex)
    d_coef = top_layer.rho * omega**2 / mu * (8 * nu**2 - 12 * nu + 7) / (8 * mu)
    beta = np.abs(omega) / top_layer.c_s
    h_top = top_layer.h if np.isfinite(top_layer.h) else np.inf
    tops = 20 * np.maximum(max(1 / b, 1 / h_top), np.abs(omega) / soil.c_s_min)
    periods = SINC_PERIODS if rounds > 1 else 1
    ratios = np.where(rtol < LOOSE, BAND_RATIO, LOOSE_BAND_RATIO)
    ends = [
        _breakpoints(a, complex(z), soil, b, t, periods, r)
        for a, z, t, r in zip(k1, w, tops, ratios, strict=True)
    ]
    closed = np.asarray(
        c_coef * _integral_inf(k1, b) + d_coef * _integral_inf3(np.sqrt(k1**2 + beta**2), b), dtype=complex
    )
    f = _Integrand(k1, w, c_coef, d_coef, beta, soil, b)
    rest, quadrature_error = _adaptive(f, ends, closed, rtol, rounds)
    total = closed + rest
    # the tail beyond k2 = top: the envelope 2 |U - U_inf| / (k2 b) there decays at least like k2^-4
    # (U - U_inf = O(kappa^-5) past the layers' exponentials), so its integral is below top / 3
    tail = 2 * np.abs(f.difference(tops, np.arange(k1.size))) / b / 3
    chi: ComplexArray = np.asarray(2 * np.pi / total, dtype=complex)
    error = np.abs(chi) * (quadrature_error + tail) / np.abs(total)
    return StripStiffness(chi=chi.reshape(shape), error=error.reshape(shape))
