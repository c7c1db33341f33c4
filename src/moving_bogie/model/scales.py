"""The reference scales of Eqs. (15)-(16) and the calls of the generated scaling functions.

:class:`Scales` converts dimensionless values to SI; the helpers below evaluate the generated scaling
(``generated/parameters.py`` and each model's own) exactly in mpmath, for
:class:`~moving_bogie.model.physical.PhysicalParams`.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import mpmath

from moving_bogie.model.catalogue import Model
from moving_bogie.model.exact import fraction_to_mpf
from moving_bogie.typing import Mpf

__all__ = [
    "Scales",
    "call_scaling",
    "catalogue_values",
    "group_from_si",
    "rounded_fraction",
    "scales_mp",
]


def rounded_fraction(x: Mpf, digits: int) -> Fraction:
    """`x` rounded to `digits` significant decimal digits, as an exact decimal Fraction."""
    return Fraction(mpmath.nstr(x, digits))


def call_scaling(func: Callable[..., Any], values: Mapping[str, Any]) -> Mpf:
    """Call a generated scaling function with the arguments it names, ``sqrt`` being mpmath's."""
    names = func.__code__.co_varnames[: func.__code__.co_argcount]
    return func(**{name: (mpmath.sqrt if name == "sqrt" else values[name]) for name in names})


def catalogue_values(model: Model, values: Mapping[str, Any]) -> dict[str, Any]:
    """SI values keyed by the catalogue's names (the arguments of the generated scaling functions).

    A track that renames SI parameters (a layered track's ``k_1`` for the reference stiffness ``k_f``)
    lists the renames in its generated ``SI_NAMES``; the scaling is the same expression.
    """
    catalogue_name = {track: generic for generic, track in model.si_names.items()}
    return {catalogue_name.get(k, k): v for k, v in values.items()}


def scales_mp(model: Model, scale_values: Mapping[str, Fraction]) -> tuple[Mpf, Mpf, Mpf, Mpf]:
    """(chi, v_ref, w_st, t_scale) of Eqs. (15)-(16) as mpf at the current precision (on periodic
    supports those of docs/sleepers.md (S2), the track's own)."""
    if model.periodic:
        mp_values = {k: fraction_to_mpf(v) for k, v in scale_values.items()}
        chi, v_ref, w_st, t_scale = model.foundation.scales(mp_values, mpmath.sqrt)
        return chi, v_ref, w_st, t_scale
    values = catalogue_values(model, {k: fraction_to_mpf(v) for k, v in scale_values.items()})
    return call_scaling(model.catalogue.parameters.scales, values)


def group_from_si(model: Model, name: str, values: Mapping[str, Any]) -> Mpf:
    """The group ``name`` of ``model`` from SI ``values`` (mpf, by the model's SI names), exactly: the
    generated scaling of Eqs. (15)-(17), (59), or a periodic track's own (docs/sleepers.md (S2))."""
    if model.periodic:
        value: Mpf = model.foundation.dimensionless(name, values, mpmath.sqrt)
        return value
    scaling = getattr(model.catalogue.parameters, f"dimensionless_{name}")
    return call_scaling(scaling, catalogue_values(model, values))


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
    load : float
        ``P / 2 = k_f w_st / chi`` [N], the unit of force: a wheel's static load is 2.

    The methods take dimensionless values (floats, numpy arrays or mpf) and return SI values.
    """

    chi: float
    v_ref: float
    w_st: float
    t_scale: float
    load: float

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

    @property
    def mass(self) -> float:
        """``m / chi = (P / 2) t_scale^2 / w_st`` [kg], the unit of the vehicle's masses (Eq. (17):
        eta_M = M chi / m)."""
        return self.load * self.t_scale**2 / self.w_st

    def force(self, f: Any) -> Any:
        """Force ``F = f P / 2`` [N] (a contact force; a wheel's static load is f = 2)."""
        return f * self.load

    def time(self, tau: Any) -> Any:
        """Time ``t = tau t_scale`` [s], Eq. (16)."""
        return tau * self.t_scale

    def velocity(self, alpha: Any) -> Any:
        """Velocity ``v = alpha v_ref`` [m/s], Eq. (16)."""
        return alpha * self.v_ref

    def angular_frequency(self, q: Any) -> Any:
        """Angular frequency [rad/s] of an induced frequency `q`, the conjugate of `tau`: ``q / t_scale``."""
        return q / self.t_scale
