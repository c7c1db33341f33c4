"""D-decomposition of a vehicle on sleepers in its wheel mass at one velocity (docs/sleepers.md, (S19)-(S21)).

A root q of the Hill determinant changes side of the real axis only where det(A(q) + eta_M B(q)) = 0 for a
real q: at a real eigenvalue eta_M of the pencil (:mod:`~moving_bogie.kernels.mass_pencil`). The real
axis of one strip, Re q in [-Omega_0 / 4, 3 Omega_0 / 4] (the points 0 and Omega_0 / 2, where the
parametric zones' roots cross, inside it), is sampled; the mirror symmetry (S14), mu(Omega_0 - q) =
conj(mu(q)), gives the samples above Omega_0 / 2 from those below. The eigenvalues mu = 1 / eta_M are
matched from sample to sample (least total distance), each sign change of Im mu with Re mu > 0 is polished
by Brent's method on the branch, and kept when 1 / mu is real to 1e-7 and at most ``eta_max``.

The rule of hatching (S21) gives the direction: eta_M(q) is analytic, a root is q(eta_M) its inverse, and
for eta_M = eta* + e (e > 0 small) q - q* = e / eta_M'(q*): Im q < 0 exactly when Im eta_M' > 0, i.e. when
Im mu falls through 0 as q increases. Each crossing is computed again with one more harmonic on each side
(followed from it by the secant method); its relative move is the convergence in the harmonics.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np
from scipy.optimize import brentq, linear_sum_assignment

from moving_bogie.kernels.mass_pencil import MassPencil

__all__ = [
    "DColumn",
    "DCrossing",
    "InverseMasses",
    "d_column",
    "match_branches",
    "real_crossings",
    "signed_counts",
]

#: largest |Im mu| / |mu| of a polished crossing, and the move in the harmonics called converged
REAL_TOL = 1e-7
MOVE_TOL = 1e-3
#: the receptance's relative tolerance along the scan (its signs of Im mu only; crossings are polished at
#: the pencil's own)
SCAN_TOL = 1e-6
#: Brent's steps for a crossing: a zero of Im mu on one branch takes 3 or 4 on the example maps; a jump
#: from one branch to another (no zero) is bisected down to the tolerance, some 30 steps, and is given up
#: after these
POLISH_ITER = 12


class InverseMasses(Protocol):
    """A pencil in the wheel mass: mu = 1 / eta_M of every eta_M that makes E_chr vanish at q."""

    def inverse_masses(self, q: float) -> np.ndarray: ...


@dataclass(frozen=True)
class DCrossing:
    """A root on the real axis: at wheel mass ``eta_M`` the root crosses at the real frequency ``q``;
    ``change`` (+1 or -1) is the change of the unstable count as eta_M increases through it; ``moved`` the
    relative change of eta_M with one more harmonic on each side (NaN when it could not be followed)."""

    q: float
    eta_M: float
    change: int
    moved: float


@dataclass(frozen=True)
class DColumn:
    """The crossings at one velocity (sorted by eta_M), the harmonics -N-1..N, and what limits the count."""

    alpha: float
    Omega0: float
    crossings: tuple[DCrossing, ...]
    harmonics: int
    samples: int
    evaluations: int
    notes: tuple[str, ...] = field(default=())

    def counts(self, etas: np.ndarray | list[float]) -> np.ndarray:
        """Unstable roots in the strip at each eta_M: none at eta_M -> 0 (A has no root there, (S19)) plus
        the changes of the crossings below it (Eq. (S21))."""
        return signed_counts(self.crossings, etas)

    @property
    def converged(self) -> bool:
        """Every crossing moved less than MOVE_TOL (relative) with one more harmonic."""
        return all(np.isfinite(c.moved) and c.moved < MOVE_TOL for c in self.crossings)


def signed_counts(crossings: Sequence[DCrossing], etas: np.ndarray | list[float]) -> np.ndarray:
    """Unstable roots at each eta_M: none at eta_M -> 0 plus the changes of the crossings below it (S21)."""
    at = np.asarray(etas, dtype=float)
    out = np.zeros(at.shape, dtype=int)
    for c in crossings:
        out += np.where(at > c.eta_M, c.change, 0)
    return out


def strip_samples(Omega0: float, samples: int) -> np.ndarray:
    """The midpoints of ``samples`` (a multiple of 4) equal cells of [-Omega_0 / 4, 3 Omega_0 / 4]: sample
    k and 3 samples / 2 - 1 - k are mirror images about Omega_0 / 2 (k >= samples / 2)."""
    return -Omega0 / 4 + (np.arange(samples) + 0.5) * Omega0 / samples


def _branches(pencil: InverseMasses, qs: np.ndarray) -> np.ndarray:
    """mu at every sample (rows), the columns matched from sample to sample into branches."""
    n = qs.size
    lower = 3 * n // 4
    mus = np.empty((n, len(pencil.inverse_masses(qs[0]))), dtype=complex)
    mus[0] = pencil.inverse_masses(qs[0])
    for k in range(1, lower):
        mus[k] = pencil.inverse_masses(qs[k])
    for k in range(lower, n):  # the mirror image, Eq. (S14)
        mus[k] = mus[3 * n // 2 - 1 - k].conj()
    for k in range(1, n):
        mus[k] = match_branches(mus[k - 1], mus[k])
    return mus


def _polish(
    pencil: InverseMasses, a: float, b: float, mu_a: complex, mu_b: complex
) -> tuple[float, complex] | None:
    """The zero of Im mu on the branch through mu_a (at a) and mu_b (at b), by Brent's method; the branch at
    q is the eigenvalue nearest the straight line between them. None when Im mu has no sign change, or
    when Brent's method has not converged in POLISH_ITER steps: then the sign change is a jump from one
    branch to another (two branches that pass close to each other), which it bisects without end."""

    def pick(q: float) -> complex:
        t = (q - a) / (b - a)
        guess = (1 - t) * mu_a + t * mu_b
        mus = pencil.inverse_masses(q)
        return complex(mus[np.argmin(np.abs(mus - guess))])

    def f(q: float) -> float:
        return pick(q).imag

    fa, fb = f(a), f(b)
    if fa == 0 or fb == 0 or np.sign(fa) == np.sign(fb):
        return None
    xtol = 1e-11 * max(1.0, abs(b))
    q, out = brentq(f, a, b, xtol=xtol, rtol=1e-12, maxiter=POLISH_ITER, full_output=True, disp=False)
    return (float(q), pick(float(q))) if out.converged else None


def _follow(pencil: MassPencil, q0: float, mu0: complex, a: float, b: float) -> tuple[float, complex] | None:
    """The crossing of ``pencil`` near the crossing (q0, mu0) of a pencil with one harmonic fewer: the
    secant method on Im mu of the eigenvalue nearest the last one, from q0, until 1 / mu is real to
    REAL_TOL / 1000; Brent's method on [a, b] (:func:`_polish`) when it leaves [a, b] or stalls."""

    def at(q: float, near: complex) -> complex:
        mus = pencil.inverse_masses(q)
        return complex(mus[np.argmin(np.abs(mus - near))])

    q1, mu1 = q0, at(q0, mu0)
    if abs(mu1.imag) <= 1e-3 * REAL_TOL * abs(mu1):
        return q1, mu1
    q2 = q0 + 1e-3 * (b - a) * (1 if q0 - a < b - q0 else -1)
    mu2 = at(q2, mu1)
    for _ in range(8):
        if abs(mu2.imag) <= 1e-3 * REAL_TOL * abs(mu2):
            return q2, mu2
        if mu2.imag == mu1.imag:
            break
        q1, q2, mu1 = q2, q2 - mu2.imag * (q2 - q1) / (mu2.imag - mu1.imag), mu2
        if not a <= q2 <= b:
            break
        mu2 = at(q2, mu1)
    return _polish(pencil, a, b, mu0, mu0)


def match_branches(previous: np.ndarray, current: np.ndarray) -> np.ndarray:
    """``current`` reordered to follow ``previous`` (least total distance)."""
    _, order = linear_sum_assignment(np.abs(previous[:, None] - current[None, :]))
    return current[order]


def _resolve(
    pencil: InverseMasses, a: float, b: float, mus_a: np.ndarray, j: int, depth: int = 0
) -> tuple[list[tuple[float, complex, int, float, float]], bool]:
    """The real crossings of branch j between samples a and b: ([(q, mu, change, a', b')], resolved).

    The interval is cut in three (never at its middle, where Omega_0 / 2 may sit) and the branch matched
    through the new samples; a sign change of Im mu is polished on its third once the branch moves less
    than half its distance to the others there, else cut again (at most 4 times): two branches that pass
    close to each other (a complex pair meeting on Re q = Omega_0 / 2) are told apart by finer samples.
    """
    qs = np.linspace(a, b, 4)
    rows = [mus_a]
    for q in qs[1:]:
        rows.append(match_branches(rows[-1], pencil.inverse_masses(q)))
    branch = np.array([r[j] for r in rows])
    out: list[tuple[float, complex, int, float, float]] = []
    resolved = True
    for k in np.nonzero(np.sign(branch.imag[:-1]) * np.sign(branch.imag[1:]) < 0)[0]:
        others = np.delete(rows[k], j)
        gap = np.min(np.abs(others - branch[k]), initial=np.inf)
        # polished once the branch moves less between the samples than it is from the others
        hit = None
        if depth == 4 or abs(branch[k + 1] - branch[k]) < 0.5 * gap:
            hit = _polish(pencil, qs[k], qs[k + 1], branch[k], branch[k + 1])
        if hit is not None and abs(hit[1].imag) <= REAL_TOL * abs(hit[1]):
            out.append((hit[0], hit[1], 1 if branch[k].imag > 0 else -1, qs[k], qs[k + 1]))
        elif depth < 4:
            more, ok = _resolve(pencil, qs[k], qs[k + 1], rows[k], j, depth + 1)
            out += more
            resolved = resolved and ok
        else:
            resolved = False
    return out, resolved


def real_crossings(
    pencil: InverseMasses, qs: np.ndarray, mus: np.ndarray, eta_max: float
) -> tuple[list[tuple[float, complex, int, float, float]], list[str]]:
    """Every polished crossing (q, mu, change, bracket) with 0 < 1 / mu <= eta_max, and the notes."""
    found: list[tuple[float, complex, int, float, float]] = []
    notes: list[str] = []
    for j in range(mus.shape[1]):
        im = mus[:, j].imag
        for k in np.nonzero(np.sign(im[:-1]) * np.sign(im[1:]) < 0)[0]:
            if min(mus[k, j].real, mus[k + 1, j].real) * eta_max < 0.5:  # eta_M beyond 2 eta_max (or < 0)
                continue
            hits, resolved = _resolve(pencil, qs[k], qs[k + 1], mus[k], j)
            if not resolved:
                notes.append(
                    f"a sign change of Im(1 / eta_M) at q in [{qs[k]:.6g}, {qs[k + 1]:.6g}] was not resolved"
                )
            found += [h for h in hits if 0 < 1 / h[1].real <= eta_max]
    return found, notes


def d_column(
    pencil: MassPencil, *, eta_max: float, samples: int = 32, check_harmonics: bool = True
) -> DColumn:
    """Every real crossing with 0 < eta_M <= eta_max at the pencil's velocity (module docstring)."""
    if samples % 4 or samples < 8:
        raise ValueError("samples: a multiple of 4, at least 8")
    omega0 = pencil.track.Omega0
    start = pencil.evaluations[0]
    qs = strip_samples(omega0, samples)
    hits, notes = real_crossings(pencil, qs, _branches(pencil.but(tol=SCAN_TOL), qs), eta_max)
    finer = pencil.but(N=pencil.N + 1)
    found: list[DCrossing] = []
    for q, mu, change, a, b in hits:
        moved = np.nan
        if check_harmonics:
            fine = _follow(finer, q, mu, a, b)
            if fine is not None and abs(fine[1].imag) <= REAL_TOL * abs(fine[1]):
                moved = abs(1 / fine[1].real - 1 / mu.real) * mu.real
        found.append(DCrossing(q, float(1 / mu.real), change, float(moved)))
    found.sort(key=lambda c: c.eta_M)
    if check_harmonics and any(not (c.moved < MOVE_TOL) for c in found):
        worst = max((c.moved for c in found), key=lambda m: np.inf if np.isnan(m) else m)
        notes.append(
            f"the crossings have not converged in the harmonics: one more harmonic moves eta_M by "
            f"{worst:.2g} (relative; N = {pencil.N})"
        )
    total = np.cumsum([c.change for c in found])
    if total.size and total.min() < 0:
        notes.append("the signed crossings give a negative count: a crossing is missing")
    return DColumn(
        pencil.track.alpha,
        omega0,
        tuple(found),
        pencil.N,
        samples,
        pencil.evaluations[0] - start,
        tuple(notes),
    )
