"""A rail on discrete supports at one parameter set: symbol, supports, lattice sum (docs/sleepers.md).

Everything is dimensionless in the scaling of ``generated/sleepers.py`` (the paper's, Eqs. (15)-(17),
with the smeared support stiffness k_e in the place of k_f): wavenumber p, frequency w, bay lam,
K = 2 pi / lam. G(p, w) = Q~ / N~ is k_e times the rail's receptance in the wavenumber domain,
z(w) = (Z_s / l) / k_e the supports' stiffness per unit length, and

    S(p, w) = sum_j G(p + j K, w)
            = sum over the four roots r of N~(., w) of (lam / 2) cot(lam (p - r) / 2) Res(G, r)

the lattice sum in closed form (docs/sleepers.md, Eq. (S7)).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from moving_bogie.kernels.brent import brentq
from moving_bogie.kernels.polynomial import horner

if TYPE_CHECKING:
    from moving_bogie.model.periodic import PeriodicFoundation

__all__ = ["SleeperTrack", "stable_cot"]


def stable_cot(z: np.ndarray) -> np.ndarray:
    """cot z for complex arrays, through exp(+-2 i z) of modulus at most 1 (no overflow far from the axis)."""
    z = np.asarray(z, dtype=complex)
    upper = z.imag > 0
    t = 2j * z
    e = np.exp(np.where(upper, t, -t))
    ratio = (e + 1) / (e - 1)
    return 1j * np.where(upper, ratio, -ratio)  # below the axis (1 + e) / (1 - e) = -ratio


@dataclass(frozen=True)
class SleeperTrack:
    """A beam on a sleeper track with its dimensionless groups (floats), ready to evaluate.

    Parameters
    ----------
    kernels : PeriodicFoundation
        The generated functions of one beam on one track of periodic supports, as the catalogue presents
        them (:class:`~moving_bogie.model.periodic.PeriodicFoundation`: a bound model's ``foundation``, a
        model's ``foundation``); nothing here looks them up by name.
    groups : dict
        Every group the beam's symbol and the track's support take (``lam``, ``alpha``, ``kappa_f``, ...).
    """

    kernels: PeriodicFoundation
    groups: dict = field(hash=False)

    @property
    def beam(self) -> str:
        """The beam's name (``generated.sleepers.BEAMS``), for output and the finite rail's elements."""
        return self.kernels.beam

    @property
    def track(self) -> str:
        """The track's name (``generated.sleepers.TRACKS``)."""
        return self.kernels.track

    def arguments(self, key: str) -> dict:
        """The groups of the beam's symbol (``key`` ``"groups"``) or moving symbol (``"moving_groups"``)."""
        kernels = self.kernels
        names = kernels.symbol_groups if key == "groups" else kernels.moving_groups
        return {name: self.groups[name] for name in names}

    @property
    def lam(self) -> float:
        """The bay l chi."""
        return float(self.groups["lam"])

    @property
    def K(self) -> float:
        """The reciprocal-lattice step 2 pi / lam."""
        return 2 * np.pi / self.lam

    @property
    def alpha(self) -> float:
        """The velocity v / v_ref."""
        return float(self.groups["alpha"])

    @property
    def Omega0(self) -> float:
        """The sleeper-passing frequency K alpha (in w: Omega_0 / omega_e = 2 pi v / (l omega_e))."""
        return self.K * self.alpha

    def support_polynomials(self) -> tuple:
        """(numerator, denominator) of z as polynomials in w, highest power first."""
        kernels = self.kernels
        return kernels.support_polynomials(**{n: self.groups[n] for n in kernels.support_groups})

    def support(self, w: np.ndarray) -> np.ndarray:
        """z(w) = (Z_s / l) / k_e (docs/sleepers.md, Eq. (S2))."""
        kernels = self.kernels
        args = {n: self.groups[n] for n in kernels.support_groups}
        return kernels.support(np.asarray(w, dtype=complex), **args) + 0j

    def support_element(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(M, C, K) of one support as a finite element, times the bay lam (docs/sleepers.md, Eq. (S24)).

        Unknowns: the rail's deflection at the support, then the support's own (the sleeper of
        ``sleepers-two-layer``); its dynamic stiffness at the rail, the others condensed out, is
        ``lam z(w)``: ``sleepers`` a spring ``lam`` and a dashpot ``2 lam eta_sup``; ``sleepers-two-layer``
        a railpad (``lam``, ``2 lam eta_pad``) over a sleeper of mass ``lam mu_sl`` on the ballast
        (``lam kappa_bal``, ``2 lam eta_bal``).
        """
        g, lam = self.groups, self.lam
        if self.track == "sleepers":
            return np.zeros((1, 1)), np.array([[2 * lam * g["eta_sup"]]]), np.array([[lam]])

        def pair(pad: float, ballast: float) -> np.ndarray:
            return lam * np.array([[pad, -pad], [-pad, pad + ballast]])

        mass = np.diag([0.0, lam * g["mu_sl"]])
        return mass, pair(2 * g["eta_pad"], 2 * g["eta_bal"]), pair(1.0, g["kappa_bal"])

    def rail_foundation(self) -> tuple[float, float]:
        """(stiffness, damping) per length of the continuous foundation, ``(kappa_f, 2 eta_f)``, of an
        Euler-Bernoulli rail (mass 1 and bending stiffness 1/4 per length, Eq. (S1)); ValueError naming
        the beam for another."""
        if self.beam != "eb":
            raise ValueError(f"beam: a rail of Euler-Bernoulli elements has no beam {self.beam!r}")
        return float(self.groups.get("kappa_f", 0.0)), 2 * float(self.groups.get("eta_f", 0.0))

    def free_wave_floor(self) -> float:
        """The lowest Im w of the rail's free waves at a real wavenumber (docs/sleepers.md, Eq. (S15)); 0 when
        none is known.

        A free (Bloch) wave of the periodic rail satisfies, integrated against its conjugate over one bay
        (the Bloch phases of the ends cancel), ``A - w^2 B + i w C = 0`` with the real forms
        ``B = int |w|^2`` (plus ``lam mu_sl |y|^2`` for a sleeper mass), ``C = 2 eta_f int |w|^2`` plus the
        supports' dashpots, and ``A`` the stiffness: an oscillating wave has ``Im w = C / (2 B)``, at least
        ``eta_f`` on an Euler-Bernoulli rail (compressed or not) on ``sleepers``, and at least
        ``min(eta_f, eta_bal / mu_sl)`` on ``sleepers-two-layer``. The pinned-pinned waves, which do not move
        the supports, reach ``eta_f``. An overdamped wave (damping ratio above 1) is not bounded so; nor is
        a Timoshenko rail, whose rotation is not damped by ``c_f``: 0.
        """
        if self.beam not in ("eb", "eb_axial"):
            return 0.0
        floor = float(self.groups.get("eta_f", 0.0))
        if self.track == "sleepers-two-layer" and self.groups["mu_sl"] > 0:
            floor = min(floor, float(self.groups["eta_bal"]) / float(self.groups["mu_sl"]))
        return floor

    def smeared_wave_floor(self) -> float:
        """The lowest Im w of the smeared rail's free waves at a real wavenumber (the zeros of 1 + z G,
        docs/sleepers.md, "Beyond the free waves"); 0 when not known.

        On an Euler-Bernoulli rail on ``sleepers``, ``1 + z G = 0`` reads
        ``p^4 - 4 w^2 + 8 i (eta_f + eta_sup) w + 4 (1 + kappa_f) = 0``: every wave decays at
        ``eta_f + eta_sup`` while it oscillates at every p, that is while
        ``(eta_f + eta_sup)^2 < 1 + kappa_f``.
        """
        if self.beam != "eb" or self.track != "sleepers":
            return 0.0
        rate = float(self.groups.get("eta_f", 0.0)) + float(self.groups["eta_sup"])
        return rate if rate**2 < 1 + float(self.groups.get("kappa_f", 0.0)) else 0.0

    def pinned_pinned(self) -> float:
        """The lowest pinned-pinned frequency w of the rail between two supports (docs/sleepers.md).

        The pinned-pinned mode has its nodes on the supports: the free wave of the undamped rail (every
        damping group 0) at the wavenumber p = pi / lam, the lowest root w > 0 of N~(pi / lam, w) = 0,
        bracketed by the first sign change of a doubling scan and found by Brent's method.
        """
        damping = self.kernels.damping_groups
        groups = {n: 0.0 if n in damping else self.groups[n] for n in self.kernels.symbol_groups}
        p2 = (np.pi / self.lam) ** 2

        def symbol(w: float) -> float:
            return float(np.real(horner(self.kernels.n_coeffs(w, **groups), p2)))

        low, high = 0.0, 1e-3
        while symbol(low) * symbol(high) > 0:
            low, high = high, 2 * high
            if high > 1e12:
                raise ValueError("the rail's symbol has no pinned-pinned root below w = 1e12")
        return brentq(symbol, low, high, xtol=1e-15)

    def _coeffs(self, w: np.ndarray) -> tuple[list, list]:
        w = np.asarray(w, dtype=complex)
        n = self.kernels.n_coeffs(w, **self.arguments("groups"))
        q = self.kernels.q_coeffs(w, **self.arguments("groups"))
        return [np.broadcast_to(np.asarray(c, dtype=complex), w.shape) for c in n], [
            np.broadcast_to(np.asarray(c, dtype=complex), w.shape) for c in q
        ]

    def green(self, p: np.ndarray, w: np.ndarray) -> np.ndarray:
        """G(p, w) = Q~ / N~ = k_e G0(k, omega) (docs/sleepers.md, Eq. (S1))."""
        n, q = self._coeffs(w)
        s = np.asarray(p, dtype=complex) ** 2
        return horner(q, s) / horner(n, s)

    def symbol_roots(self, w: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(roots r, residues Q~(r) / N~'(r)) of G(., w): arrays of shape w.shape + (4,).

        N~ is a quadratic in p^2 (every beam is even in p): its roots in p^2 by the quadratic formula in the
        form without cancellation, then r = +-sqrt(p^2).
        """
        r, res = self.symbol_roots_first(w)
        return np.ascontiguousarray(np.moveaxis(r, 0, -1)), np.ascontiguousarray(np.moveaxis(res, 0, -1))

    def symbol_roots_first(self, w: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`symbol_roots` with the axis of the four roots first: arrays of shape (4,) + w.shape."""
        n, q = self._coeffs(w)
        if len(n) != 3:
            raise ValueError(f"the symbol of beam {self.beam!r} is not a quadratic in p^2")
        a, b, c = n
        disc = np.sqrt(b * b - 4 * a * c)
        disc = np.where(np.abs(b + disc) >= np.abs(b - disc), disc, -disc)
        t = -(b + disc) / 2
        s = (t / a, c / t)  # the two roots in p^2
        root = [np.sqrt(x) for x in s]
        # Q~(r) / N~'(r), N~'(r) = 2 r (2 a r^2 + b): odd in r, so -r has the residue of r negated
        res = [horner(q, x) / (2 * y * (2 * a * x + b)) for x, y in zip(s, root)]
        return np.stack([*root, -root[0], -root[1]]), np.stack([*res, -res[0], -res[1]])

    def lattice_sum(self, p: np.ndarray, w: np.ndarray) -> np.ndarray:
        """S(p, w) = sum_j G(p + j K, w) in closed form (docs/sleepers.md, Eq. (S7))."""
        r, res = self.symbol_roots(w)
        p = np.asarray(p, dtype=complex)[..., None]
        half = self.lam / 2
        return np.sum(half * stable_cot(half * (p - r)) * res, axis=-1)

    def moving_polynomials(self, q: complex) -> tuple[np.ndarray, np.ndarray]:
        """(N~, Q~)(kappa, q + alpha kappa) as numpy polynomial coefficients in kappa, highest first."""
        args = self.arguments("moving_groups")
        n = self.kernels.moving_n_coeffs(q, self.alpha, **args)
        qq = self.kernels.moving_q_coeffs(q, self.alpha, **args)
        return np.array(n, dtype=complex), np.array(qq, dtype=complex)

    def free_receptance(self, q: complex, offsets: np.ndarray) -> np.ndarray:
        """(1 / 2 pi) int G(kappa, q + alpha kappa) exp(i kappa xi) dkappa for each offset xi, by residues.

        The continuous rail's receptance between two points a distance xi apart that move with the load (the
        paper's K(xi, q) up to its normalisation): closed in the upper half-plane for xi >= 0, in the lower
        one for xi < 0 (docs/sleepers.md, Eq. (S5)).
        """
        n, qq = self.moving_polynomials(q)
        while abs(n[0]) == 0:
            n = n[1:]
        roots = np.roots(n)
        dn = np.polyval(np.polyder(n), roots)
        res = np.polyval(qq, roots) / dn
        offsets = np.atleast_1d(np.asarray(offsets, dtype=float))
        out = np.empty(offsets.shape, dtype=complex)
        for i, xi in enumerate(offsets):
            if xi >= 0:
                sel = roots.imag > 0
                out[i] = 1j * np.sum(res[sel] * np.exp(1j * roots[sel] * xi))
            else:
                sel = roots.imag < 0
                out[i] = -1j * np.sum(res[sel] * np.exp(1j * roots[sel] * xi))
        return out
