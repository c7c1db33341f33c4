"""Critical velocity of a constant moving force, Eqs. (65)-(66), checked against the dispersion relation.

A constant force moving at alpha excites a steady wave of wavenumber p wherever N(p, 0) = 0 has a real
root (undamped track, q = 0 in the moving frame): the force travels with the phase speed of a free wave.
The critical velocity is the smallest such alpha, the minimum over real p of the phase speed
c(p) (the smallest positive alpha with N(p, 0; alpha) = 0); at the minimum N(p, 0) has a real double root
in p, so (p_cr, alpha_cr) solves N = dN/dp = 0. The minimum is located in double precision on a grid of p
and polished with mpmath's Newton on that 2x2 system, at ``dps`` digits, and confirmed at a higher
precision.

Closed forms: Euler-Bernoulli with the Pasternak layer, Eq. (65), alpha_cr = sqrt(1 + eta_s) (at p^2 = 2,
independent of eta_s); Timoshenko-Rayleigh, Eq. (66) as printed (without eta_s).
"""

from __future__ import annotations

from dataclasses import dataclass

import mpmath
import numpy as np

from moving_bogie.errors import MovingBogieError, ParameterError
from moving_bogie.kernels.track import foundation_module

__all__ = ["CriticalVelocity", "critical_velocity", "formula_eb", "formula_tr", "phase_speed"]


@dataclass(frozen=True)
class CriticalVelocity:
    """Critical velocity alpha_cr, the wavenumber p_cr of the resonant wave and the closed form."""

    beam: str
    eta_s: float
    S: float | None
    r: float | None
    alpha_cr: mpmath.mpf
    p_cr: mpmath.mpf
    formula: mpmath.mpf | None  # Eq. (65) or (66); None where the paper gives none (TR with eta_s > 0)
    digits: int  # digits of alpha_cr and p_cr confirmed at two precisions
    method: str = "minimum phase speed of free waves: real double root of N(p, 0) in p (N = dN/dp = 0)"

    @property
    def agrees(self) -> bool | None:
        """Whether the closed form equals the numerical value to the confirmed digits."""
        if self.formula is None:
            return None
        return abs(self.formula - self.alpha_cr) <= mpmath.mpf(10) ** (-self.digits + 1)

    def to_dict(self) -> dict:
        digits = min(self.digits, 20)
        return {
            "beam": self.beam,
            "eta_s": self.eta_s,
            "S": self.S,
            "r": self.r,
            "alpha_cr": mpmath.nstr(self.alpha_cr, digits),
            "p_cr": mpmath.nstr(self.p_cr, digits),
            "alpha_cr_formula": None if self.formula is None else mpmath.nstr(self.formula, digits),
            "formula": "Eq. (65)" if self.beam == "eb" else "Eq. (66)",
            "agrees": self.agrees,
            "digits": self.digits,
            "method": self.method,
        }


def formula_eb(eta_s=0):
    """Eq. (65): alpha_cr = sqrt(1 + eta_s) (alpha_ref = 1)."""
    return mpmath.sqrt(1 + mpmath.mpf(eta_s))


def formula_tr(S, r):
    """Eq. (66) as printed: sqrt(r^2 - S - 8 r^2 S^2 + 4 S^(3/2) sqrt(4 r^4 S - r^2 + S)) / (2 (S - r^2))."""
    S, r = mpmath.mpf(S), mpmath.mpf(r)
    r2 = r * r
    inner = mpmath.sqrt(4 * r2 * r2 * S - r2 + S)
    return mpmath.sqrt(r2 - S - 8 * r2 * S * S + 4 * S**1.5 * inner) / (2 * (S - r2))


def _n_values(module, args, p, alpha):
    """N(p, 0; alpha) and dN/dp for the undamped track (mpmath or numpy arguments)."""
    args = {k: v for k, v in args.items() if k in module.ARGUMENTS}
    cs = module.n_coeffs(0, alpha=alpha, eta_f=0, **args)
    N, dN = 0, 0
    for c in cs:
        dN = dN * p + N
        N = N * p + c
    return N, dN


def phase_speed(beam: str = "eb", p=None, *, eta_s=0.0, S=None, r=None, alpha_max: float = 20.0):
    """Phase speed c(p) of free waves (smallest alpha > 0 with N(p, 0; alpha) = 0), vectorised in p.

    N(p, 0; alpha) is a polynomial of degree <= 4 in alpha; its coefficients follow from five evaluations.
    Returns inf where no positive real alpha below ``alpha_max`` exists.
    """
    module = foundation_module(beam)
    args = {"eta_s": eta_s, "S": S, "r": r}
    p = np.atleast_1d(np.asarray(p, dtype=float))
    nodes = np.linspace(0.0, 2.0, 5)
    vals = np.stack(
        [np.real(_n_values(module, args, p.astype(complex), a)[0]) * np.ones_like(p) for a in nodes]
    )
    coeffs = np.linalg.solve(np.vander(nodes, 5), vals).T  # (n, 5) in alpha, highest first
    out = np.full(p.shape, np.inf)
    for k, c in enumerate(coeffs):
        c = np.trim_zeros(c, "f")
        if len(c) < 2:
            continue
        roots = np.roots(c)
        real = roots[(np.abs(roots.imag) <= 1e-9 * np.maximum(1, np.abs(roots))) & (roots.real > 0)].real
        real = real[real <= alpha_max]
        if real.size:
            out[k] = real.min()
    return out


def critical_velocity(
    beam: str = "eb", *, eta_s=0, S=None, r=None, dps: int = 30, p_max: float = 20.0, samples: int = 4001
) -> CriticalVelocity:
    """Critical velocity of a constant moving force, Eq. (65) (EB) / Eq. (66) (TR), computed numerically.

    Parameters
    ----------
    beam : {"eb", "tr"}
    eta_s : float
        Pasternak shear layer.
    S, r : float
        Timoshenko-Rayleigh parameters of Eq. (59) (required for ``beam="tr"``).
    dps : int
        Working precision of the polished minimum; digits are confirmed at ``dps + 15``.
    p_max, samples : float, int
        Grid of wavenumbers 0 < p <= p_max on which the minimum of c(p) is bracketed.

    Raises
    ------
    ParameterError
        For a missing or invalid parameter.
    MovingBogieError
        If no free wave has a real phase speed (no critical velocity).
    """
    if beam not in ("eb", "tr"):
        raise ParameterError("beam", f"beam must be eb or tr (got {beam!r})")
    if beam == "tr" and (S is None or r is None):
        raise ParameterError("S", "the Timoshenko-Rayleigh beam needs S and r")
    if beam == "eb":
        S = r = None
    if float(eta_s) < 0 or (S is not None and float(S) <= 0) or (r is not None and float(r) < 0):
        raise ParameterError("eta_s", "eta_s, r must be >= 0 and S > 0")
    fargs = {
        "eta_s": float(eta_s),
        "S": None if S is None else float(S),
        "r": None if r is None else float(r),
    }
    ps = np.linspace(p_max / samples, p_max, samples)
    speeds = phase_speed(beam, ps, **fargs)
    if not np.any(np.isfinite(speeds)):
        raise MovingBogieError("no free wave with a real phase speed: no critical velocity")
    k = int(np.argmin(speeds))
    p0, a0 = ps[k], speeds[k]
    module = foundation_module(beam)

    def polish(digits):
        with mpmath.workdps(digits):
            args = {
                "eta_s": mpmath.mpf(str(eta_s)),
                "S": None if S is None else mpmath.mpf(str(S)),
                "r": None if r is None else mpmath.mpf(str(r)),
            }

            def system(p, a):
                N, dN = _n_values(module, args, p, a)
                return mpmath.re(N), mpmath.re(dN)

            # start slightly off the grid minimum: findroot can stop at once on a start that is exact
            # to double precision in alpha but not in p
            start = (mpmath.mpf(p0) * (1 + mpmath.mpf(1e-6)), mpmath.mpf(a0) * (1 + mpmath.mpf(1e-6)))
            p, a = mpmath.findroot(system, start, tol=mpmath.mpf(10) ** (-2 * digits))
            return abs(p), +a

    p_lo, a_lo = polish(dps)
    p_hi, a_hi = polish(dps + 15)
    with mpmath.workdps(dps + 15):
        err = max(abs(a_hi - a_lo) / abs(a_lo), abs(p_hi - p_lo) / abs(p_lo))
        digits = dps if err == 0 else max(0, min(dps, int(-mpmath.log10(2 * err))))
    formula = None
    with mpmath.workdps(dps):
        if beam == "eb":
            formula = formula_eb(mpmath.mpf(str(eta_s)))
        elif float(eta_s) == 0:
            formula = formula_tr(mpmath.mpf(str(S)), mpmath.mpf(str(r)))
    return CriticalVelocity(beam, float(eta_s), fargs["S"], fargs["r"], a_lo, p_lo, formula, digits)
