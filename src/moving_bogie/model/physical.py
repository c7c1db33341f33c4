"""Physical (SI) parameters and the scaling of Eqs. (15)-(17) and (59) between SI and dimensionless form."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from fractions import Fraction
from types import SimpleNamespace
from typing import TYPE_CHECKING, Any

import mpmath

from moving_bogie.errors import ParameterError
from moving_bogie.model.exact import (
    NumberLike,
    dataclass_repr,
    fraction_to_mpf,
    fraction_to_text,
    map_fractions,
    nonnegative,
    positive,
)

if TYPE_CHECKING:  # params imports this module at run time; the reverse import stays local
    from moving_bogie.model.params import DimensionlessParams

__all__ = ["DIMENSIONLESS_OF", "PHYSICAL_UNITS", "PhysicalParams", "Scales"]

#: SI unit of each field of :class:`PhysicalParams`.
PHYSICAL_UNITS = {
    "EI": "N m^2",
    "m": "kg/m",
    "k_f": "N/m^2",
    "c_f": "N s/m^2",
    "M": "kg",
    "M_b": "kg",
    "J_b": "kg m^2",
    "k_v": "N/m",
    "c_v": "N s/m",
    "d": "m",
    "v": "m/s",
    "P": "N",
    "k_s": "N",
    "GA": "N",
    "r_g": "m",
}

#: The dimensionless parameter each SI field (other than the track EI, m, k_f and load P) scales to.
DIMENSIONLESS_OF = {
    "c_f": "eta_f",
    "M": "eta_M",
    "M_b": "mu_v",
    "J_b": "J_b",
    "k_v": "kappa_v",
    "c_v": "eta_v",
    "d": "d",
    "v": "alpha",
    "k_s": "eta_s",
    "GA": "S",
    "r_g": "r",
}
_POSITIVE = frozenset({"EI", "m", "k_f", "M", "M_b", "J_b", "k_v", "d", "P", "GA"})
_TIMOSHENKO = ("GA", "r_g")


def _rounded(x: mpmath.mpf, digits: int) -> Fraction:
    """`x` rounded to `digits` significant decimal digits, as an exact decimal Fraction."""
    return Fraction(mpmath.nstr(x, digits))


def _scales_mp(EI: Fraction, m: Fraction, k_f: Fraction, P: Fraction) -> SimpleNamespace:
    """Scales of Eqs. (15)-(16) as mpf at the current precision."""
    EI_, m_, k_f_, P_ = (fraction_to_mpf(x) for x in (EI, m, k_f, P))
    chi = mpmath.root(k_f_ / (4 * EI_), 4)
    return SimpleNamespace(
        chi=chi,
        v_ref=mpmath.sqrt(k_f_ / m_) / chi,
        w_st=P_ * chi / (2 * k_f_),
        t_scale=mpmath.sqrt(m_ / k_f_),
    )


@dataclass(frozen=True)
class Scales:
    """Reference scales of Eqs. (15)-(16), as floats in SI units.

    Attributes
    ----------
    chi : float
        ``(k_f / (4 EI))**(1/4)`` [1/m]; ``xi = chi * r``.
    v_ref : float
        ``(4 k_f EI / m**2)**(1/4)`` [m/s]; ``alpha = v / v_ref``.
    w_st : float
        ``P chi / (2 k_f)`` [m], the static deflection under one wheel load.
    t_scale : float
        ``sqrt(m / k_f)`` [s]; ``tau = t / t_scale = chi v_ref t``.

    The methods take dimensionless values (floats, numpy arrays or mpf) and return SI values.
    """

    chi: float
    v_ref: float
    w_st: float
    t_scale: float

    def position(self, xi: Any) -> Any:
        """Moving coordinate ``r = xi / chi`` [m], Eq. (16)."""
        return xi / self.chi

    def deflection(self, w: Any) -> Any:
        """Beam deflection ``w = w~ w_st`` [m], Eq. (16)."""
        return w * self.w_st

    def displacement(self, u: Any) -> Any:
        """Bogie-bar mass-centre displacement ``u_v = u~ w_st`` [m], Eq. (16)."""
        return u * self.w_st

    def rotation(self, theta: Any) -> Any:
        """Bogie-bar rotation ``theta = theta~ w_st chi`` [rad], Eq. (16)."""
        return theta * self.w_st * self.chi

    def time(self, tau: Any) -> Any:
        """Time ``t = tau t_scale`` [s], Eq. (16)."""
        return tau * self.t_scale

    def velocity(self, alpha: Any) -> Any:
        """Velocity ``v = alpha v_ref`` [m/s], Eq. (16)."""
        return alpha * self.v_ref

    def angular_frequency(self, q: Any) -> Any:
        """Angular frequency [rad/s] of an induced frequency `q`, the conjugate of `tau`: ``q / t_scale``."""
        return q / self.t_scale


@dataclass(frozen=True)
class PhysicalParams:
    """Physical parameters in SI units, Eqs. (1)-(4), (55)-(56); stored exactly as Fractions.

    Numeric fields accept what :class:`~moving_bogie.model.params.DimensionlessParams` accepts.

    Parameters
    ----------
    EI : NumberLike
        Beam bending stiffness [N m^2]; > 0.
    m : NumberLike
        Beam mass per unit length [kg/m]; > 0.
    k_f : NumberLike
        Foundation (Winkler) stiffness [N/m^2]; > 0.
    c_f : NumberLike
        Foundation viscous damping [N s/m^2]; >= 0 and below ``2 sqrt(m k_f)`` (``eta_f < 1``).
    M : NumberLike
        Mass of each wheel [kg]; > 0.
    M_b : NumberLike
        Bogie-bar mass [kg]; > 0.
    J_b : NumberLike
        Bogie-bar mass moment of inertia about its mass centre [kg m^2]; > 0.
    k_v : NumberLike
        Primary suspension stiffness of each support [N/m]; > 0.
    c_v : NumberLike
        Primary suspension damping of each support [N s/m]; >= 0.
    d : NumberLike
        Wheel spacing [m]; > 0.
    v : NumberLike
        Bogie velocity [m/s]; >= 0.
    P : NumberLike
        Constant load on each wheel [N]; > 0.
    k_s : NumberLike, optional
        Foundation shear (Pasternak) stiffness [N]; >= 0, default 0.
    GA : NumberLike or None, optional
        Timoshenko shear stiffness ``G Abar`` [N], > 0; given together with `r_g` it selects the
        Timoshenko-Rayleigh beam of Eqs. (55)-(56).
    r_g : NumberLike or None, optional
        Radius of gyration of the cross-section [m], >= 0 (``J = m r_g**2`` in Eq. 56).

    Raises
    ------
    ParameterError
        Naming the first offending field.
    """

    EI: Fraction
    m: Fraction
    k_f: Fraction
    c_f: Fraction
    M: Fraction
    M_b: Fraction
    J_b: Fraction
    k_v: Fraction
    c_v: Fraction
    d: Fraction
    v: Fraction
    P: Fraction
    k_s: Fraction = Fraction(0)
    GA: Fraction | None = None
    r_g: Fraction | None = None

    def __post_init__(self) -> None:
        for name in PHYSICAL_UNITS:
            value = getattr(self, name)
            if name in _TIMOSHENKO:
                other = _TIMOSHENKO[1 - _TIMOSHENKO.index(name)]
                if value is None:
                    if getattr(self, other) is not None:
                        raise ParameterError(
                            name, f"{name} is required with {other} (Timoshenko-Rayleigh beam; r_g may be 0)"
                        )
                    continue
            check = positive if name in _POSITIVE else nonnegative
            object.__setattr__(self, name, check(name, value))

    __repr__ = dataclass_repr

    @property
    def beam(self) -> str:
        """``"tr"`` (Timoshenko-Rayleigh) when `GA` is given, else ``"eb"`` (Euler-Bernoulli)."""
        return "eb" if self.GA is None else "tr"

    def to_dict(self) -> dict[str, str | None]:
        """JSON-ready dict of the fields, numbers as decimal strings (see ``DimensionlessParams.to_dict``)."""
        return map_fractions(self, fraction_to_text)

    def scales(self) -> Scales:
        """Reference scales chi, v_ref, w_st and the time scale, Eqs. (15)-(16), as floats."""
        with mpmath.workdps(30):
            s = _scales_mp(self.EI, self.m, self.k_f, self.P)
            return Scales(
                chi=float(s.chi), v_ref=float(s.v_ref), w_st=float(s.w_st), t_scale=float(s.t_scale)
            )

    def to_dimensionless(self, *, digits: int = 20) -> DimensionlessParams:
        """Dimensionless parameters, Eqs. (15)-(17) and (59).

        ``eta_M = M chi/m``, ``mu_v = M_b chi/m``, ``J_b~ = chi**3 J_b/m``, ``kappa_v = k_v chi/k_f``,
        ``eta_v = c_v chi/(2 sqrt(m k_f))``, ``eta_f = c_f/(2 sqrt(m k_f))``,
        ``eta_s = k_s/(2 sqrt(k_f EI))``, ``alpha = v/v_ref``, ``d~ = d chi``, and for the
        Timoshenko-Rayleigh beam ``S = G Abar/(2 sqrt(k_f EI))``, ``r~ = r_g chi``.

        Parameters
        ----------
        digits : int, optional
            The scaling involves fourth roots, so the results are irrational: each is rounded to this
            many significant decimal digits (computed with 10 more) and stored exactly.

        Raises
        ------
        ParameterError
            Naming ``c_f`` when the foundation is at or above critical damping (``eta_f >= 1``).
        """
        from moving_bogie.model.params import DimensionlessParams

        with mpmath.workdps(digits + 10):
            s = _scales_mp(self.EI, self.m, self.k_f, self.P)
            f = SimpleNamespace(**map_fractions(self, fraction_to_mpf))
            damping = 2 * mpmath.sqrt(f.m * f.k_f)
            shear = 2 * mpmath.sqrt(f.k_f * f.EI)
            values = {
                "eta_f": f.c_f / damping,
                "eta_M": f.M * s.chi / f.m,
                "d": f.d * s.chi,
                "mu_v": f.M_b * s.chi / f.m,
                "J_b": s.chi**3 * f.J_b / f.m,
                "kappa_v": f.k_v * s.chi / f.k_f,
                "eta_v": f.c_v * s.chi / damping,
                "alpha": f.v / s.v_ref,
                "eta_s": f.k_s / shear,
            }
            if self.beam == "tr":
                values.update(S=f.GA / shear, r=f.r_g * s.chi)
            exact = {name: _rounded(value, digits) for name, value in values.items()}
        if exact["eta_f"] >= 1:
            raise ParameterError(
                "c_f",
                f"c_f = {fraction_to_text(self.c_f)} N s/m^2 reaches the critical foundation damping "
                f"2*sqrt(m*k_f); eta_f = c_f/(2*sqrt(m*k_f)) must be < 1",
            )
        return DimensionlessParams(beam=self.beam, **exact)

    @classmethod
    def from_dimensionless(
        cls,
        params: DimensionlessParams,
        *,
        EI: NumberLike,
        m: NumberLike,
        k_f: NumberLike,
        P: NumberLike,
        digits: int = 20,
    ) -> PhysicalParams:
        """Invert Eqs. (15)-(17) and (59) for a given track (`EI`, `m`, `k_f`) and wheel load `P`.

        Results are rounded to `digits` significant decimal digits, as in :meth:`to_dimensionless`.
        """
        track = {
            name: positive(name, value) for name, value in (("EI", EI), ("m", m), ("k_f", k_f), ("P", P))
        }
        with mpmath.workdps(digits + 10):
            s = _scales_mp(**track)
            p = params.as_mp()
            mass, stiffness = fraction_to_mpf(track["m"]), fraction_to_mpf(track["k_f"])
            damping = 2 * mpmath.sqrt(mass * stiffness)
            shear = 2 * mpmath.sqrt(stiffness * fraction_to_mpf(track["EI"]))
            values = {
                "c_f": p.eta_f * damping,
                "M": p.eta_M * mass / s.chi,
                "M_b": p.mu_v * mass / s.chi,
                "J_b": p.J_b * mass / s.chi**3,
                "k_v": p.kappa_v * stiffness / s.chi,
                "c_v": p.eta_v * damping / s.chi,
                "d": p.d / s.chi,
                "v": p.alpha * s.v_ref,
                "k_s": p.eta_s * shear,
            }
            if params.beam == "tr":
                values.update(GA=p.S * shear, r_g=p.r / s.chi)
            exact = {name: _rounded(value, digits) for name, value in values.items()}
        return cls(**track, **exact)

    def with_dimensionless(self, params: DimensionlessParams, *, digits: int = 20) -> PhysicalParams:
        """The SI parameters of `params` on this track (``EI``, ``m``, ``k_f``) under this wheel load ``P``.

        Each SI field depends on one dimensionless parameter (:data:`DIMENSIONLESS_OF`); a field whose
        parameter equals this instance's own dimensionless value keeps its exact SI value, the
        others are recomputed as in :meth:`from_dimensionless`.
        """
        own = self.to_dimensionless(digits=digits)
        new = PhysicalParams.from_dimensionless(
            params, EI=self.EI, m=self.m, k_f=self.k_f, P=self.P, digits=digits
        )
        kept = {
            field: getattr(self, field)
            for field, name in DIMENSIONLESS_OF.items()
            if getattr(params, name) == getattr(own, name)
        }
        return dataclasses.replace(new, **kept)
