"""A radius R beyond which E_chr has no root in the lower half-plane (the far field of Eq. (48)).

``derivations/asymptotics.py`` derives, for every track, the decay K = O(|q|^-gamma) of Eq. (29)
(``KERNEL_DECAY`` of its generated module). For a vehicle on n wheels with wheel masses M_cc and body
masses M_ii, the block system of :mod:`moving_bogie.kernels.vehicle` gives
E_chr = E_lead + (terms smaller by |q|^-delta) with E_lead = det(-2 q^2 Kmat M_cc) det(-q^2 M_ii) and
delta = min(2 - gamma, 1) (:func:`leading_gap`; for the
bogie and two masses this is the expansion that ``derivations/asymptotics.py`` derives symbolically,
checked in tests/test_verdict.py). Wherever

    rho(q) = |E_chr(q) - E_lead(q)| / |E_lead(q)| < 1,

E_chr cannot vanish (E_chr = 0 would give |E_lead| < |E_lead|). :func:`far_field_radius` looks for the
smallest R = R0 2^k at which rho <= 1/2 (a margin of 2) at every sample of the lower half-plane beyond R that
it checks: the half circles |q| = R, 2R, 4R, ..., 32R (angles clustered towards the real axis, where the
factors e^{i p_k d} of K(+-d) stop decaying), the two rays just below the real axis from R to 32R and seven
rays in between, of which it evaluates the half Re q >= 0 (rho(-conj q) = rho(q), :func:`sample_points`).
Beyond 32R the derived decay rho = O(|q|^-delta) / |det Kmat / K0^n| takes over (for the bogie on
Euler-Bernoulli det Kmat / K0^2 = 1 - K+ K- / K0^2 with |K+ K- / K0^2| <= 1/2 asymptotically).
The check is numerical, with that margin: it is what makes "stable" a statement about every root with
Im q < 0, and when it fails the verdict says UNDETERMINED.
"""

from __future__ import annotations

import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from moving_bogie.kernels.bound import BoundModel
from moving_bogie.kernels.characteristic import CharacteristicArray
from moving_bogie.kernels.vehicle import VehicleSystem
from moving_bogie.typing import ComplexArray

#: rho must stay below this on every sample (1 would be enough for no root; 1/2 leaves a margin of 2).
MARGIN = 0.5
#: The samples reach out to this multiple of R (half circles at R, 2R, ..., OUTER R).
OUTER = 32
#: Doublings of R tried before giving up.
MAX_DOUBLINGS = 12


@dataclass(frozen=True)
class FarField:
    """Outcome of the far-field check: ``radius`` R (None when none could be justified), the largest rho."""

    radius: float | None
    rho: float
    start: float
    reason: str = ""

    def to_dict(self) -> dict:
        rho = self.rho if np.isfinite(self.rho) else None
        return {"radius": self.radius, "rho": rho, "margin": MARGIN, "reason": self.reason or None}


def kernel_decay(bound: BoundModel) -> Fraction | None:
    """gamma of K = O(|q|^-gamma) for the bound model's track (``KERNEL_DECAY`` of its generated module).

    The module is that of the parameters' own catalogue (``BoundModel.kernel_decay``).
    """
    return bound.kernel_decay


def leading_gap(gamma: Fraction) -> Fraction:
    """delta: the rest of E_chr is smaller than E_lead by |q|^-delta, delta = min(2 - gamma, 1).

    The wheel rows of the block system are 2 Kmat D_c. with D = -q^2 M + O(q): their leading part
    -2 q^2 Kmat M_cc is of order |q|^(2 - gamma); pi I is smaller by |q|^(gamma - 2), the damping and
    stiffness terms by |q|^-1, and the coupling to the internal rows (D_ci, D_ic = O(q), M_ci = 0) by |q|^-2.
    """
    return min(2 - gamma, Fraction(1))


def e_lead(system: VehicleSystem, q: ComplexArray, K: Sequence[ComplexArray]) -> np.ndarray:
    """E_lead = det(-2 q^2 Kmat M_cc) det(-q^2 M_ii) for arrays of q (Kmat from the kernel values K).

    Massless contact points (M_cc = 0: a wheel on a contact spring, ``hertz_mass``) have
    E_lead = pi^n det(-q^2 M_ii): the wheel rows are pi I + 2 Kmat S with S = D_cc - D_ci D_ii^-1 D_ic
    of order |q| (a contact damper) or 1, so 2 Kmat S is smaller than pi I by |q|^(1 - gamma) or
    |q|^-gamma (a kernel decaying like |q|^-1 with a contact damper has no such leading part, and the
    check fails).
    """
    n, N = system.contacts, system.size
    M = np.array(system.mass, dtype=float)
    q = np.asarray(q, dtype=complex)
    if not np.any(M[:n, :n]):
        inner = np.linalg.det(M[n:, n:]) if N > n else 1.0
        return np.pi**n * (-(q**2)) ** (N - n) * inner + 0j
    Kmat = np.empty(q.shape + (n, n), dtype=complex)
    for i in range(n):
        for j in range(n):
            Kmat[..., i, j] = K[system.index[i][j]]
    constant = np.linalg.det(M[:n, :n]) * (np.linalg.det(M[n:, n:]) if N > n else 1.0)
    return (-2 * q**2) ** n * (-(q**2)) ** (N - n) * constant * np.linalg.det(Kmat)


def sample_points(
    radius: float, outer: int = OUTER, per_circle: int = 1200, per_ray: int = 4000, inner_rays: int = 7
) -> np.ndarray:
    """q samples of {|q| >= radius, Im q < 0, Re q >= 0} up to ``outer * radius``: quarter circles and rays.

    They are the right half of a set symmetric under q -> -conj(q): half circles of ``per_circle`` angles
    (clustered towards the real axis), the two rays just below the real axis with ``per_ray`` points each
    (there the factors e^{i p_k d} of K(+-d) oscillate without decaying) and ``inner_rays`` rays in between
    with a quarter as many. E_chr has real coefficients, E_chr(-conj q) = conj E_chr(q), and so has E_lead:
    rho takes the same value at a point and at its mirror, which is why the left half is not sampled (the
    search window, Re q >= 0, rests on the same symmetry; tests/test_verdict.py checks it at the samples).
    """
    t = np.linspace(0.0, 1.0, per_circle)
    theta = -np.pi * (0.5 - 0.5 * np.cos(np.pi * t))  # clustered at 0 and -pi
    theta = np.clip(theta, -np.pi + 1e-7, -1e-7)
    circles = [radius * 2.0**k * np.exp(1j * theta) for k in range(int(np.log2(outer)) + 1)]
    r = np.linspace(radius, outer * radius, per_ray)
    below = -1e-7 * r * 1j
    angles = -np.pi * np.arange(1, inner_rays + 1) / (inner_rays + 1)
    inner = np.outer(np.linspace(radius, outer * radius, per_ray // 4), np.exp(1j * angles)).ravel()
    q = np.concatenate(circles + [r + below, -r + below, inner])
    return q[q.real >= 0]  # a ray on the imaginary axis (cos(-pi/2) > 0 in floating point) is kept


def rho(bound: BoundModel, q: np.ndarray, E: CharacteristicArray | None = None) -> np.ndarray:
    """|E_chr - E_lead| / |E_lead| at the points ``q`` (double precision); ``E``: the bound model's
    :class:`CharacteristicArray` if built already (its kernel's coefficient matrices are made once)."""
    E = CharacteristicArray(bound) if E is None else E
    q = np.asarray(q, dtype=complex)
    kv = E.kernel_values(q)
    with np.errstate(all="ignore"):
        full = E.system.e_chr_array(q, kv.K)
        main = e_lead(E.system, q, kv.K)
        out = np.abs(full - main) / np.abs(main)
    return np.where(np.isfinite(out), out, np.inf)


def _worst_rho(bound: BoundModel, q: np.ndarray, stop: bool, chunk: int = 4096) -> float:
    """The largest rho over the samples ``q``, nearest the origin first; with ``stop``, as soon as a chunk
    exceeds MARGIN (the radius fails there, and the rest would not change that)."""
    q = q[np.argsort(np.abs(q), kind="stable")]
    worst = 0.0
    E = CharacteristicArray(bound)
    for k in range(0, len(q), chunk):
        worst = max(worst, float(np.max(rho(bound, q[k : k + chunk], E))))
        if stop and worst > MARGIN:
            break
    return worst


def far_field_radius(bound: BoundModel, start: float) -> FarField:
    """Smallest R = start 2^k (k <= MAX_DOUBLINGS) with rho <= MARGIN on every sample beyond R.

    Parameters
    ----------
    bound : BoundModel
    start : float
        First radius tried (the default window's scale).
    """
    radius = float(start)
    worst = np.inf
    gamma = kernel_decay(bound)
    if gamma is None or gamma >= 2:
        reason = (
            "no far-field expansion: the decay of K(xi, q) is not generated for this track "
            "(KERNEL_DECAY; run python -m derivations)"
            if gamma is None
            else f"no far-field expansion: K = O(|q|^-{gamma}) decays too fast for the block leading part"
        )
        return FarField(None, worst, float(start), reason)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        for k in range(MAX_DOUBLINGS + 1):
            worst = _worst_rho(bound, sample_points(radius), stop=k < MAX_DOUBLINGS)
            if worst <= MARGIN:
                return FarField(radius, worst, float(start))
            radius *= 2.0
    reason = (
        f"no radius up to {radius / 2:.3g} keeps |E_chr - E_lead| / |E_lead| <= {MARGIN} "
        f"(largest {worst:.3g}): roots with Im q < 0 far out cannot be excluded"
    )
    return FarField(None, worst, float(start), reason)
