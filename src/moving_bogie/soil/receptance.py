"""The rail's receptance on the soil at complex frequency, between moving contacts (docs/soil.md, Eq. (S9)).

A vertical force F exp(i Omega t) at xi_j, moving with the vehicle (xi = x - v t, positive ahead), deflects
the rail at xi_i by G(xi_i - xi_j, Omega) F exp(i Omega t), downwards:

    G(Delta, Omega) = (1 / 2 pi) int exp(-i k Delta) dk / D(k, Omega + k v),                      (S9)

D the rail's dynamic stiffness on the soil (Eqs. (S6)-(S7), :meth:`~.track.SoilTrack.rail_stiffness`).
At Omega = 0 it is the moving load's deflection per unit load (Eq. (S8)).

**Where it is analytic.** For real k, Im omega = Im Omega. The soil and the track are passive: their
responses to a force exp(i omega t) are transforms of causal responses, analytic for Im omega < 0 (their
free waves decay, Im omega > 0), so D(k, omega) has no zero and U(kappa, omega) no pole there and G is
analytic for Im Omega < 0. With Kelvin-Voigt damping in every layer G is continuous up to the real axis;
Omega = 0 is a branch point (chi(k1, k1 v + Omega) -> 0 like 1 / log k1 as k1, Omega -> 0: the kernel's
cut at Omega = 0 when the soil's waves are faster than the load).

**Quadrature.** Gauss-Kronrod (7, 15) panels in |k| from k_lo = 1e-9 / b to k_hi on both sides of k = 0
(one up to 1e-3 / b, where the integrand is smooth unless Omega = 0, then geometric; bisected
geometrically), each Omega of a call (and its speed v: one per Omega may be given) on its own panels,
each panel bisected until its Kronrod-Gauss difference is below its share of ``tol`` |G| for every
offset, the nodes of all of them evaluated together. At Omega = 0 the integrand at -k is the conjugate of
that at k (D(-k, -conj w) = conj D(k, w)): one side is summed, G = (1 / pi) Re int_0^inf. Outside
[k_lo, k_hi] the integrand grows only like log(1 / k) (below) and is below 2 / (EI k^4) (above; checked at
k_hi): both ends are bounded and added to the error.

**chi only as accurate as 1/D needs.** An error e of chi changes 1/D by at most
|S| e / (|D| (|D| - |S| e)), S = dD/dchi (:meth:`~.track.SoilTrack.chi_sensitivity`). Where |k| b >=
``LOCAL_KB`` and |S chi_loc| <= tol |D| / 2, chi_loc = 2 b / U(|k|, omega) (the strip's limit |k| b >> 1:
the sinc is narrow beside the variation of U, one U value) is taken with the error allowance
e = |chi_loc| (100 %; tests/test_soil_receptance.py checks |chi / chi_loc - 1| < 1/2 there on the
examples' soils); elsewhere chi is the strip's quadrature (:func:`~.strip.strip_stiffness`) to the
relative tolerance tol |D| / (2 |S chi_loc|) (between 1e-10 and 0.1) with its own error estimate e. So
1/D is good to about tol relative at every node, and the bound above summed with the weights is the
error of G that chi leaves; beside the panels' Kronrod-Gauss differences and the ends it makes
``error``. The far panels (|k| up to 300 / b and beyond), where the strip quadrature would cost
thousands of U values each, take one U value each.

**Many speeds at Omega = 0 (a DAF curve).** Their first panels are the same: at each first node with
|k| b < ``LOCAL_KB``, chi(|k|, |k| v) is interpolated in v from a table at a few speeds, with an error
estimate (:mod:`.receptance_chi`), and taken wherever that estimate meets the allowance above (the
estimate is then the node's e); elsewhere the strip's quadrature as above.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from moving_bogie.typing import ComplexArray, FloatArray

from .flexibility import surface_flexibility
from .illinois import IntArray
from .profile import SoilProfile
from .rayleigh import BoolArray
from .receptance_chi import POINTS, speed_table
from .strip import NODES, WEIGHTS_G, WEIGHTS_K, strip_stiffness
from .track import SoilTrack

__all__ = ["LOCAL_KB", "SoilReceptance", "local_stiffness", "soil_receptance"]

#: |k| b from which chi may be the local strip stiffness 2 b / U (module docstring).
LOCAL_KB = 4.0
#: Initial panels on each side of k = 0 (one from k_lo to K_NEAR / b, then geometric), most bisection rounds.
PANELS, ROUNDS, K_NEAR = 8, 10, 1e-3
#: chi at the first nodes is interpolated in the speed (:mod:`.receptance_chi`) for at least this many
#: speeds at Omega = 0 (the table costs POINTS quadratures per node).
BY_SPEED = 2 * POINTS
#: The strip quadrature's relative tolerance is kept within these (module docstring).
CHI_RTOL = (1e-10, 0.1)


@dataclass(frozen=True)
class SoilReceptance:
    """G[..., j] at each Omega (rad/s) and offset Delta_j (m), m/N; ``error`` its estimated absolute error
    per Omega (the largest over the offsets); ``nodes`` the k nodes used and ``chi_quadratures`` how many
    of them needed the strip's quadrature."""

    omega: ComplexArray
    offsets: FloatArray
    G: ComplexArray
    error: FloatArray
    nodes: int
    chi_quadratures: int


def local_stiffness(k1: FloatArray, omega: ComplexArray, soil: SoilProfile, b: float) -> ComplexArray:
    """chi_loc = 2 b / U(|k1|, omega): the strip's stiffness in the limit |k1| b >> 1 (module docstring)."""
    u = surface_flexibility(np.abs(k1).astype(complex), np.asarray(omega, dtype=complex), soil)
    return np.asarray(2 * b / u, dtype=complex)


@dataclass(frozen=True)
class _Integrand:
    """1 / D(k, Omega + k v) at triples (k, Omega, v), and the bound of its error through chi."""

    track: SoilTrack
    soil: SoilProfile
    tol: float

    def __call__(
        self,
        k: FloatArray,
        omega_ref: ComplexArray,
        v: FloatArray,
        guess: tuple[ComplexArray, FloatArray] | None = None,
    ) -> tuple[ComplexArray, FloatArray, int]:
        """(1/D, error bound of 1/D, strip quadratures used) at each (k[i], omega_ref[i], v[i]); ``guess``:
        chi interpolated there and its error estimate (:mod:`.receptance_chi`), taken where it is as
        accurate as 1/D needs."""
        track = self.track
        w = omega_ref + k * v
        chi = local_stiffness(k, w, self.soil, track.b)
        sens = track.chi_sensitivity(w, chi)
        d_loc = track.rail_stiffness(k, w, chi)
        ratio = np.abs(sens * chi) / np.maximum(np.abs(d_loc), 1e-300)
        exact = (np.abs(k) * track.b < LOCAL_KB) | (2 * ratio > self.tol)
        err = np.abs(chi)
        if guess is not None:
            taken = exact & self._good(k, w, *guess)
            exact &= ~taken
            chi[taken], err[taken] = guess[0][taken], guess[1][taken]
            sens[taken] = track.chi_sensitivity(w[taken], chi[taken])
        if exact.any():
            rtol = np.clip(self.tol / (2 * np.maximum(ratio[exact], 1e-300)), *CHI_RTOL)
            strip = strip_stiffness(np.abs(k[exact]), w[exact], self.soil, track.b, rtol=rtol)
            chi[exact], err[exact] = strip.chi, strip.error
            sens[exact] = track.chi_sensitivity(w[exact], strip.chi)
        d = track.rail_stiffness(k, w, chi)
        gap = np.abs(d) - np.abs(sens) * err
        bound = np.where(gap > 0, np.abs(sens) * err / (np.abs(d) * np.maximum(gap, 1e-300)), np.inf)
        return np.asarray(1 / d, dtype=complex), bound, int(exact.sum())

    def _good(self, k: FloatArray, w: ComplexArray, chi: ComplexArray, err: FloatArray) -> BoolArray:
        """Where chi with the error ``err`` gives 1/D to tol / 2: 2 |S| err <= tol |D| (module docstring)."""
        d = self.track.rail_stiffness(k, w, chi)
        sens = self.track.chi_sensitivity(w, chi)
        return np.asarray(np.isfinite(err) & (2 * np.abs(sens) * err <= self.tol * np.abs(d)))


@functools.lru_cache(maxsize=16)
def _reference_wavenumber(track: SoilTrack, soil: SoilProfile) -> float:
    """max(1 / b, (|chi(1 / b, 0)| / EI)^(1/4)): the scale of the rail's static deflection (as Eq. (S8))."""
    chi_b = abs(strip_stiffness(np.array([1 / track.b]), np.zeros(1), soil, track.b).chi[0])
    return float(max(1 / track.b, (chi_b / track.EI) ** 0.25))


def _sum_panels(
    f: _Integrand,
    items: tuple[ComplexArray, FloatArray],
    offsets: FloatArray,
    ends: FloatArray,
    sign: float,
    rounds: int,
) -> tuple[ComplexArray, FloatArray, int, int]:
    """int over sign * [k_lo, k_hi] of exp(-i k Delta) / D for every item (Omega, v) and offset Delta, each
    item on its own
    panels (initially its row of ``ends``), bisected (geometrically) until each one's Kronrod-Gauss
    difference is below its share (its width in log k) of tol |total| for every offset. Returns (integral,
    error, nodes, strip quadratures)."""
    omega, speed = items
    n = omega.size
    span = np.log(ends[:, -1] / ends[:, 0])
    lo, hi = ends[:, :-1].ravel(), ends[:, 1:].ravel()
    who = np.repeat(np.arange(n), ends.shape[1] - 1)
    total = np.zeros((n, offsets.size), dtype=complex)
    error = np.zeros(n)
    nodes = quadratures = 0
    for step in range(rounds):
        half, mid = (hi - lo) / 2, (hi + lo) / 2
        k = sign * (mid[:, None] + half[:, None] * NODES).ravel()
        guess = _by_speed(f, k, items, ends) if step == 0 else None
        inv, bound, used = f(k, np.repeat(omega[who], NODES.size), np.repeat(speed[who], NODES.size), guess)
        nodes, quadratures = nodes + k.size, quadratures + used
        g = (np.exp(-1j * np.multiply.outer(offsets, k)) * inv).reshape(offsets.size, -1, NODES.size)
        kronrod = (g @ WEIGHTS_K) * half  # (offsets, panels)
        diff = np.abs(kronrod - (g @ WEIGHTS_G) * half)
        chi_err = (bound.reshape(-1, NODES.size) @ WEIGHTS_K) * half  # (panels,)
        running = total + np.stack([_by_owner(who, row, n) for row in kronrod], -1)
        scale = np.abs(running).max(axis=1)  # (Omega,)
        share = np.log(hi / lo) / span[who]
        keep = (diff <= f.tol * scale[who] * share).all(axis=0) | (step == rounds - 1)
        total += np.stack([_by_owner(who[keep], row[keep], n) for row in kronrod], -1)
        error += np.bincount(who[keep], diff[:, keep].max(axis=0) + chi_err[keep], minlength=n)
        if keep.all():
            break
        a, b, who = lo[~keep], hi[~keep], who[~keep]
        centre = np.sqrt(a * b)
        lo, hi, who = np.concatenate([a, centre]), np.concatenate([centre, b]), np.concatenate([who, who])
    return total, error, nodes, quadratures


def _by_speed(
    f: _Integrand, k: FloatArray, items: tuple[ComplexArray, FloatArray], ends: FloatArray
) -> tuple[ComplexArray, FloatArray] | None:
    """chi at the first nodes ``k`` of every item interpolated in the speed (:mod:`.receptance_chi`), and its
    error estimate, where the items are at least :data:`BY_SPEED` speeds at Omega = 0 on the same first
    panels (a DAF curve) and |k| b < LOCAL_KB (chi's quadrature needed); None otherwise."""
    omega, speed = items
    if omega.size < BY_SPEED or np.any(omega != 0) or np.any(ends != ends[:1]):
        return None
    k_item = np.abs(k[: k.size // omega.size])
    near = k_item * f.track.b < LOCAL_KB
    chi = np.zeros((omega.size, k_item.size), dtype=complex)
    error = np.full(chi.shape, np.inf)
    chi[:, near], error[:, near] = speed_table(k_item[near], speed, f.soil, f.track.b, f.tol)
    return chi.ravel(), error.ravel()


def _by_owner(who: IntArray, values: ComplexArray, n: int) -> ComplexArray:
    """The sums of ``values`` per owner 0..n-1."""
    return np.bincount(who, values.real, minlength=n) + 1j * np.bincount(who, values.imag, minlength=n)


def soil_receptance(
    track: SoilTrack,
    soil: SoilProfile,
    v: float | FloatArray,
    omega: ComplexArray,
    offsets: FloatArray = (0.0,),  # type: ignore[assignment]
    *,
    tol: float = 1e-6,
    rounds: int = ROUNDS,
    above: bool = False,
) -> SoilReceptance:
    """G(Delta_j, Omega) of Eq. (S9) at every ``omega`` (complex, rad/s, Im <= 0) and offset (m).

    Parameters
    ----------
    track, soil : SoilTrack, SoilProfile
        The track and its soil (damped: eta > 0 in every layer, as for the moving load).
    v : float or array of float
        The speed of the contacts (m/s); an array broadcast with ``omega`` (one speed per Omega).
    omega : array of complex
        Frequencies Omega (rad/s), Im Omega <= 0; each on its own k panels, all evaluated together.
    offsets : array of float
        Delta = xi_i - xi_j (m).
    tol : float
        Relative accuracy asked of each node's 1/D and of each panel (module docstring).
    above : bool
        Also Im Omega > 0: the caller keeps Omega under the singular lines, where the integral along real
        k is still the continued function (roots/decaying_band.py).
    """
    omega, speed = np.broadcast_arrays(np.asarray(omega, dtype=complex), np.asarray(v, dtype=float))
    shape = omega.shape if omega.ndim else (1,)
    omega, speed = omega.ravel().copy(), speed.ravel().copy()
    offsets = np.atleast_1d(np.asarray(offsets, dtype=float))
    if np.any(omega.imag > 0) and not above:
        raise ValueError("omega: the soil's receptance by real wavenumbers needs Im Omega <= 0")
    k_ref = _reference_wavenumber(track, soil)
    k_omega = (track.m * np.abs(omega) ** 2 / track.EI) ** 0.25
    k_v = np.abs(speed) * np.sqrt(track.m / track.EI)  # EI k^2 = m v^2: the speed's own wavenumber
    k_lo, k_hi = 1e-9 / track.b, np.maximum(300 * k_ref, 30 * np.maximum(k_v, k_omega))  # per item
    steps = np.linspace(0.0, 1.0, PANELS + 1)
    near = np.full((omega.size, 1), k_lo)
    ends = np.concatenate([near, K_NEAR / track.b * (k_hi[:, None] * track.b / K_NEAR) ** steps], axis=1)
    f = _Integrand(track, soil, tol)
    total = np.zeros((omega.size, offsets.size), dtype=complex)
    error, nodes, quadratures = np.zeros(omega.size), 0, 0
    # at Omega = 0 the integrand at -k is the conjugate of that at k (D(-k, -conj w) = conj D(k, w)):
    # G = (1 / pi) Re int_0^inf, one side
    sides = (1.0,) if not omega.any() else (1.0, -1.0)
    for sign in sides:
        part, err, n, used = _sum_panels(f, (omega, speed), offsets, ends, sign, rounds)
        total, error, nodes, quadratures = total + part, error + err, nodes + n, quadratures + used
        # the ends: below k_lo the integrand grows like log(1 / k) (2 k_lo |f(k_lo)| bounds it); beyond
        # k_hi, |D| >= EI k^4 / 2 (checked at k_hi) bounds it by 2 / (3 EI k_hi^3)
        edge = sign * np.stack([np.full(omega.size, k_lo), k_hi], -1)
        inv = f(edge.ravel(), np.repeat(omega, 2), np.repeat(speed, 2))[0].reshape(-1, 2)
        error[np.abs(inv[:, 1]) * track.EI * k_hi**4 > 2] = np.inf
        error += 2 * k_lo * np.abs(inv[:, 0]) + 2 / (3 * track.EI * k_hi**3)
    if len(sides) == 1:
        total, error = 2 * total.real + 0j, 2 * error
    G = total / (2 * np.pi)
    return SoilReceptance(
        omega=omega.reshape(shape),
        offsets=offsets,
        G=G.reshape((*shape, offsets.size)),
        error=(error / (2 * np.pi)).reshape(shape),
        nodes=nodes,
        chi_quadratures=quadratures,
    )
