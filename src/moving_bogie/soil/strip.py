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

An item asked to rtol >= LOOSE (1e-7) starts from a coarse grid (:data:`COARSE`: few panels near k2 = 0 and
in the band, at least one per decade of kappa, four sinc periods per panel, the tail cut where its bound is
about rtol / 4) and takes COARSE_ROUNDS more bisection rounds; tighter items start from the fine grid
(:data:`FINE`), which meets 1e-11 mostly before any bisection.
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


@dataclass(frozen=True)
class _Start:
    """The initial panels of an item: graded near k2 = 0, the band's ratio, geometric in kappa up to
    ``reach`` times the soil's largest relevant wavenumber, and sinc periods per panel (module docstring)."""

    near: int
    ratio: float
    kappa: int
    reach: float
    periods: int
    #: At least one kappa panel per decade from k1 (a coarse start: bisection alone would need many rounds
    #: to grade towards a small k1).
    decades: bool = False


#: For rtol < LOOSE: the fine start (a grid that meets 1e-11 before bisection); for looser items a
#: coarse start that bisection refines where the Kronrod-Gauss differences ask for it.
FINE = _Start(near=NEAR_PANELS, ratio=BAND_RATIO, kappa=KAPPA_PANELS, reach=20.0, periods=SINC_PERIODS)
COARSE = _Start(near=2, ratio=2.5, kappa=3, reach=4.0, periods=4, decades=True)
#: A coarse start's reach is (REACH_TAIL / rtol)^(1/5): the tail's bound is then about rtol / 4 (on the
#: examples' soils the bound is 1.5e-4 of the integral at reach 5; it falls like reach^-5). The bound is
#: computed and stated whatever the reach.
REACH_TAIL = 1.9
#: Bisection rounds a coarse start may take beyond ``rounds``.
COARSE_ROUNDS = 4


def _geometric(first: FloatArray, last: FloatArray, count: IntArray, width: int) -> FloatArray:
    """Rows of ``count`` points from ``first`` to ``last`` (> 0) in geometric progression, NaN-padded to
    ``width`` columns."""
    j = np.arange(width)[None, :]
    t = j / np.maximum(count - 1, 1)[:, None]
    rows = first[:, None] * (last / first)[:, None] ** t
    return np.where(j < count[:, None], rows, np.nan)


def _breakpoints(
    k1: FloatArray, omega: ComplexArray, soil: SoilProfile, b: float, top: FloatArray, starts: list[_Start]
) -> tuple[FloatArray, FloatArray, IntArray]:
    """The initial panels (lo, hi, item) in k2 of every item (k1, omega) (module docstring), bisected
    later: ends graded towards 0, through the band of kappa where the poles of U lie (on the real axis
    without damping, k1 above them; next to it with damping), geometric in kappa up to ``top``, and every
    few periods of the sinc."""
    near_n, kappa_n, periods = (
        np.array([getattr(s, key) for s in starts]) for key in ("near", "kappa", "periods")
    )
    ratio = np.array([s.ratio for s in starts])
    w = np.abs(omega)
    c_max = max(c for layer in soil.layers for c in (layer.c_s, layer.c_p))
    band0, band1 = w / c_max * 0.8, w / (0.5 * soil.c_s_min)
    damped = (min(layer.eta for layer in soil.layers) * w > 0) & (band1 > band0)
    band0, band1 = np.where(damped, band0, 1.0), np.where(damped, band1, 1.0)
    band_n = (np.log(band1 / band0) / np.log(ratio)).astype(int) + 2
    lo = k1
    decades = np.array([s.decades for s in starts])
    kap_n = np.where(decades, np.maximum(kappa_n, np.log10(top / lo).astype(int) + 2), kappa_n)
    band = _geometric(band0, band1, band_n, int(band_n.max()))
    band[~damped] = np.nan
    kap = np.concatenate([band, _geometric(lo, top, kap_n, int(kap_n.max()))], axis=1)
    with np.errstate(invalid="ignore"):
        waves = np.where(kap > k1[:, None], np.sqrt(kap**2 - k1[:, None] ** 2), np.nan)
    step = periods * 2 * np.pi / b
    sinc_n = np.ceil(top / step).astype(int)
    sinc = np.arange(int(sinc_n.max()))[None, :] * step[:, None]
    sinc = np.where(np.arange(sinc.shape[1])[None, :] < sinc_n[:, None], sinc, np.nan)
    scale = np.minimum(k1, top)
    near = _geometric(1e-4 * scale, scale, near_n, int(near_n.max()))
    ends = np.concatenate([np.zeros((k1.size, 1)), top[:, None], near, waves, sinc], axis=1)
    ends[~(ends <= top[:, None])] = np.nan
    ends.sort(axis=1)
    ends[:, 1:][ends[:, 1:] == ends[:, :-1]] = np.nan  # repeated ends
    ends.sort(axis=1)
    first, second = ends[:, :-1], ends[:, 1:]
    valid = np.isfinite(second)
    who = np.broadcast_to(np.arange(k1.size)[:, None], first.shape)
    return first[valid], second[valid], who[valid]


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
    f: _Integrand,
    panels: tuple[FloatArray, FloatArray, IntArray],
    closed: ComplexArray,
    rtol: FloatArray,
    rounds: IntArray,
) -> tuple[ComplexArray, FloatArray]:
    """Sum over each item's panels (``panels``: lo, hi, item) of Gauss-Kronrod (7, 15), all items at once;
    a panel is bisected while its Kronrod-Gauss difference exceeds rtol |closed + integral| / (its item's
    panel count), at most ``rounds`` (per item) times. Returns (integral, sum of the kept panels'
    differences) per item."""
    n = closed.size
    lo, hi, who = panels
    total, error = np.zeros(n, dtype=complex), np.zeros(n)
    for step in range(int(rounds.max())):
        half, mid = (hi - lo) / 2, (hi + lo) / 2
        g = f((mid[:, None] + half[:, None] * NODES).ravel(), np.repeat(who, NODES.size)).reshape(-1, 15)
        kronrod, gauss = (g @ WEIGHTS_K) * half, (g @ WEIGHTS_G) * half
        diff = np.abs(kronrod - gauss)
        estimate = closed + total + _sum(who, kronrod, n)
        count = np.bincount(who, minlength=n)
        keep = (diff <= rtol[who] * np.abs(estimate[who]) / count[who]) | (step >= rounds[who] - 1)
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
    ``rounds`` bisections, COARSE_ROUNDS more from a coarse start (module docstring); ``rounds=1``: the
    fine initial panels only, one per period of the sinc); ``rtol`` may be an array, one tolerance per
    (k1, omega); ``error`` states what was reached. On an undamped soil the
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
    loose = rtol >= LOOSE
    starts = [(COARSE if x and rounds > 1 else FINE) for x in loose]
    # the tail beyond top falls like reach^-5 (U - U_inf = O(kappa^-5)): a coarse start reaches as far as
    # its rtol needs (REACH_TAIL, module constants), between COARSE.reach and FINE.reach
    reach = np.array([start.reach for start in starts])
    reach = np.where(loose, np.clip((REACH_TAIL / rtol) ** 0.2, COARSE.reach, FINE.reach), reach)
    tops = reach * np.maximum(max(1 / b, 1 / h_top), np.abs(omega) / soil.c_s_min)
    if rounds == 1:
        starts = [_Start(NEAR_PANELS, BAND_RATIO, KAPPA_PANELS, 20.0, 1)] * k1.size
    panels = _breakpoints(k1, w, soil, b, tops, starts)
    closed = np.asarray(
        c_coef * _integral_inf(k1, b) + d_coef * _integral_inf3(np.sqrt(k1**2 + beta**2), b), dtype=complex
    )
    f = _Integrand(k1, w, c_coef, d_coef, beta, soil, b)
    most = np.where(loose & (rounds > 1), rounds + COARSE_ROUNDS, rounds)
    rest, quadrature_error = _adaptive(f, panels, closed, rtol, most)
    total = closed + rest
    # the tail beyond k2 = top: the envelope 2 |U - U_inf| / (k2 b) there decays at least like k2^-4
    # (U - U_inf = O(kappa^-5) past the layers' exponentials), so its integral is below top / 3
    tail = 2 * np.abs(f.difference(tops, np.arange(k1.size))) / b / 3
    chi: ComplexArray = np.asarray(2 * np.pi / total, dtype=complex)
    error = np.abs(chi) * (quadrature_error + tail) / np.abs(total)
    return StripStiffness(chi=chi.reshape(shape), error=error.reshape(shape))
