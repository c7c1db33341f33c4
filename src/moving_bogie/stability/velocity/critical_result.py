"""The outcome of :func:`~moving_bogie.stability.velocity.critical_velocity.critical_velocity`: the
critical velocity alpha_cr of a moving force (Eqs. (65)-(66)), every local minimum of the phase speed it
rests on, and their JSON form."""

from __future__ import annotations

from dataclasses import dataclass, field

import mpmath

from moving_bogie.typing import Mpf

__all__ = ["CriticalVelocity", "PhaseSpeedMinimum"]


@dataclass(frozen=True)
class PhaseSpeedMinimum:
    """A local minimum of the phase speed c_j(p) = Omega_j(p)/p: the load's line tangent to branch j."""

    branch: int  # 1 = lowest dispersion branch
    alpha: Mpf
    p: Mpf
    scan_alpha: float  # the grid minimum that bracketed it (double precision)
    scan_p: float
    digits: int  # digits of alpha and p confirmed at two precisions

    def to_dict(self, digits: int = 20) -> dict:
        d = min(self.digits, digits)
        return {
            "branch": self.branch,
            "alpha": mpmath.nstr(self.alpha, d),
            "p": mpmath.nstr(self.p, d),
            "scan_alpha": self.scan_alpha,
            "scan_p": self.scan_p,
            "digits": self.digits,
        }


@dataclass(frozen=True)
class CriticalVelocity:
    """Critical velocity alpha_cr (the smallest local minimum of the phase speed) and what it rests on.

    Attributes
    ----------
    model : str
        ``beam/track`` of the foundation.
    groups : dict
        The track's groups used (damping set to zero), as floats.
    alpha_cr, p_cr : mpf
        The smallest local minimum of c_j(p) over the branches, and its wavenumber.
    branch : int
        The branch it lies on (1 = lowest).
    minima : tuple of PhaseSpeedMinimum
        Every local minimum found on 0 < p <= p_max, ascending in alpha.
    branches : int
        The number of dispersion branches (the degree of N in q over 2).
    without_minimum : tuple of int
        Branches whose phase speed has no local minimum in the scanned range.
    unattained : float or None
        c_1(p_max) when the phase speed of the lowest branch still decreases at p_max: its infimum is
        approached as p grows and not attained (0 for a bounded branch, the shear wave speed of the
        lowest layer with a Pasternak layer); None when it does not.
    formula, formula_name
        A closed form to compare with, where the caller gave one for this track (the paper's Eqs.
        (65)-(66), ``paper/critical_velocity_formulas.py``), else None.
    """

    model: str
    groups: dict[str, float]
    alpha_cr: Mpf
    p_cr: Mpf
    branch: int
    minima: tuple[PhaseSpeedMinimum, ...]
    branches: int
    without_minimum: tuple[int, ...]
    unattained: float | None
    formula: Mpf | None
    formula_name: str | None
    digits: int
    p_max: float
    method: str = field(
        default="smallest local minimum of the phase speed Omega_j(p)/p of free waves over the dispersion "
        "branches: a real double root of N(p, 0) in p (N = dN/dp = 0)"
    )

    @property
    def beam(self) -> str:
        return self.model.split("/")[0]

    @property
    def agrees(self) -> bool | None:
        """Whether the closed form equals the numerical value to the confirmed digits."""
        if self.formula is None:
            return None
        return abs(self.formula - self.alpha_cr) <= mpmath.mpf(10) ** (-self.digits + 1)

    def to_dict(self) -> dict:
        digits = min(self.digits, 20)
        out = {
            "model": self.model,
            "beam": self.beam,
            **self.groups,
            "alpha_cr": mpmath.nstr(self.alpha_cr, digits),
            "p_cr": mpmath.nstr(self.p_cr, digits),
            "branch": self.branch,
            "branches": self.branches,
            "minima": [m.to_dict(digits) for m in self.minima],
            "branches_without_minimum": list(self.without_minimum),
            "lowest_branch_decreasing_to": self.unattained,
            "alpha_cr_formula": None if self.formula is None else mpmath.nstr(self.formula, digits),
            "formula": self.formula_name,
            "agrees": self.agrees,
            "digits": self.digits,
            "p_max": self.p_max,
            "method": self.method,
        }
        if self.unattained is not None:
            out["note"] = (
                f"the phase speed of branch 1 decreases to {self.unattained:.6g} at p = {self.p_max} and "
                "further as p grows (to 0 for a bounded branch): its infimum is no tangency and no "
                "critical velocity; alpha_cr is the smallest local minimum"
            )
        return out
