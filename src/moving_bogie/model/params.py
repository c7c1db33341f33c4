"""Dimensionless parameters of the moving-bogie model, stored exactly and validated.

The model (paper, Section 2) is an infinite beam on a viscoelastic foundation traversed at constant
velocity by a bogie: a rigid bar (mass, mass moment of inertia) on a primary suspension over two
wheel masses in permanent contact with the beam. Its dimensionless form, Eqs. (18)-(20) and for the
Timoshenko-Rayleigh beam Eqs. (60)-(61), depends only on the parameters of Eqs. (15)-(17) and (59),
collected in :class:`DimensionlessParams`. The SI counterpart is :class:`PhysicalParams`.
"""

from __future__ import annotations

import dataclasses
import importlib
from collections.abc import Mapping
from dataclasses import dataclass
from fractions import Fraction
from types import SimpleNamespace
from typing import Any

from moving_bogie import generated as _generated
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
from moving_bogie.model.physical import PhysicalParams, Scales

__all__ = ["BEAMS", "DimensionlessParams", "PhysicalParams", "Scales"]

#: Track models with generated kernels: Euler-Bernoulli (Eq. 18), Timoshenko-Rayleigh (Eqs. 60-61), and any
#: model added in derivations/foundations.py (``python -m derivations`` lists it in generated.FOUNDATIONS).
BEAMS = _generated.FOUNDATIONS


def _model_parameters(beam: str) -> tuple[str, ...]:
    """Dimensionless groups a track model adds (S, r for Timoshenko-Rayleigh), from its generated kernel."""
    return importlib.import_module(f"moving_bogie.generated.foundation_{beam}").MODEL_PARAMETERS


_NUMERIC_FIELDS = ("eta_f", "eta_M", "d", "mu_v", "J_b", "kappa_v", "eta_v", "alpha", "eta_s", "S", "r")
#: Table 1 coefficients of Eq. (63) and the field each one sets.
_COEFFICIENTS = {"cf1": "mu_v", "cf2": "J_b"}
_POSITIVE = frozenset({"eta_M", "d", "mu_v", "J_b", "kappa_v", "S", "cf1", "cf2"})


def _parse(name: str, value: object) -> Fraction:
    """Convert one numeric parameter exactly and check its range (names `name` on failure)."""
    if name in _POSITIVE:
        return positive(name, value)
    x = nonnegative(name, value)
    if name == "eta_f" and x >= 1:
        raise ParameterError(
            "eta_f",
            f"eta_f must satisfy 0 <= eta_f < 1 (got {fraction_to_text(x)}): the runtime assumes an "
            "under-damped foundation, c_f < 2*sqrt(m*k_f), and its search for induced frequencies "
            "relies on it",
        )
    return x


@dataclass(frozen=True)
class DimensionlessParams:
    """Dimensionless parameters of the moving bogie, Eqs. (15)-(17), (59) and (63).

    Every numeric field accepts an int, a Fraction, decimal text (``"0.1"``, converted exactly), a
    Decimal or a finite float (converted to its exact binary value), and is stored as a
    :class:`~fractions.Fraction`. Instances are immutable; use :meth:`replace` to vary a parameter.

    Parameters
    ----------
    eta_f : NumberLike
        Foundation damping ratio ``c_f / (2 sqrt(m k_f))``, Eq. (17); ``0 <= eta_f < 1``. The
        under-damped bound is relied on by the runtime's search for induced frequencies.
    eta_M : NumberLike
        Wheel mass ratio ``M chi / m``, Eq. (17); > 0.
    d : NumberLike
        Wheel spacing ``d chi``, Eq. (16); > 0.
    mu_v : NumberLike
        Bogie-bar mass ratio ``M_b chi / m``, Eq. (17); > 0. Equals ``cf1 * eta_M``, Eq. (63).
    J_b : NumberLike
        Bogie-bar mass moment of inertia ``chi**3 J_b / m``, Eq. (17); > 0. Equals
        ``cf2 * eta_M * d**2``, Eq. (63).
    kappa_v : NumberLike
        Primary suspension stiffness ``k_v chi / k_f``, Eq. (17); > 0.
    eta_v : NumberLike
        Primary suspension damping ``c_v chi / (2 sqrt(m k_f))``, Eq. (17); >= 0.
    alpha : NumberLike
        Velocity ratio ``v / v_ref``, Eq. (16); >= 0. ``alpha = sqrt(1 + eta_s)`` is the critical
        velocity of a constant force on the Euler-Bernoulli beam, Eq. (65).
    eta_s : NumberLike, optional
        Pasternak shear layer ``k_s / (2 sqrt(k_f EI))``; >= 0, default 0.
    beam : {"eb", "tr"}, optional
        Euler-Bernoulli (default) or Timoshenko-Rayleigh beam.
    S : NumberLike or None
        Timoshenko shear parameter ``G Abar / (2 sqrt(k_f EI))``, Eq. (59); > 0, required for
        ``beam="tr"`` and None for ``beam="eb"``.
    r : NumberLike or None
        Radius of gyration ``r chi``, Eq. (59); >= 0, required for ``beam="tr"`` and None for
        ``beam="eb"``.

    Raises
    ------
    ParameterError
        Naming the first offending field.

    Examples
    --------
    >>> p = DimensionlessParams.from_coefficients(
    ...     eta_f="0.05", eta_M=30, d=2, cf1="1.7", cf2="0.01", kappa_v="0.2", eta_v="0.05", alpha="0.4")
    >>> p.mu_v, p.J_b, p.cf1
    (Fraction(51, 1), Fraction(6, 5), Fraction(17, 10))
    """

    eta_f: Fraction
    eta_M: Fraction
    d: Fraction
    mu_v: Fraction
    J_b: Fraction
    kappa_v: Fraction
    eta_v: Fraction
    alpha: Fraction
    eta_s: Fraction = Fraction(0)
    beam: str = "eb"
    S: Fraction | None = None
    r: Fraction | None = None

    def __post_init__(self) -> None:
        if self.beam not in BEAMS:
            raise ParameterError("beam", f"beam must be one of {', '.join(BEAMS)} (got {self.beam!r})")
        extra = _model_parameters(self.beam)
        for name in _NUMERIC_FIELDS:
            value = getattr(self, name)
            if name in ("S", "r"):
                if name not in extra:
                    if value is not None:
                        raise ParameterError(
                            name, f"{name} is not a parameter of beam={self.beam!r} (got {value!r})"
                        )
                    continue
                if value is None:
                    raise ParameterError(name, f"{name} is required with beam={self.beam!r}")
            object.__setattr__(self, name, _parse(name, value))

    __repr__ = dataclass_repr  # exact and evaluable: DimensionlessParams(eta_f='0.05', ...)

    @property
    def cf1(self) -> Fraction:
        """Bar-to-wheel mass coefficient ``mu_v / eta_M = M_b / M``, Eqs. (63)-(64)."""
        return self.mu_v / self.eta_M

    @property
    def cf2(self) -> Fraction:
        """Inertia coefficient ``J_b / (eta_M d**2)``, dimensional ``J_b / (M d**2)``, Eqs. (63)-(64)."""
        return self.J_b / (self.eta_M * self.d**2)

    @classmethod
    def from_mapping(cls, values: Mapping[str, Any]) -> DimensionlessParams:
        """Build from a mapping of field names; ``cf1`` may replace ``mu_v`` and ``cf2`` may replace ``J_b``.

        ``mu_v = cf1 eta_M`` and ``J_b = cf2 eta_M d**2``, Eq. (63). This is the one entry point for
        parameters read from files and command lines.

        Raises
        ------
        ParameterError
            For an unknown or missing name, for both ``cf1`` and ``mu_v`` (or ``cf2`` and ``J_b``),
            or an invalid value; the message names the parameter.
        """
        values = dict(values)
        known = [field.name for field in dataclasses.fields(cls)]
        for name in values:
            if name not in known and name not in _COEFFICIENTS:
                raise ParameterError(
                    name, f"unknown parameter {name!r}; known: {', '.join([*known, *_COEFFICIENTS])}"
                )
        for coefficient, field in _COEFFICIENTS.items():
            if coefficient in values and field in values:
                raise ParameterError(coefficient, f"give either {coefficient} or {field}, not both")
        for field in dataclasses.fields(cls):
            if field.default is dataclasses.MISSING and field.name not in values:
                coefficient = next((c for c, f in _COEFFICIENTS.items() if f == field.name), None)
                if coefficient is None:
                    raise ParameterError(field.name, f"missing parameter {field.name!r}")
                if coefficient not in values:
                    raise ParameterError(
                        coefficient, f"missing parameter {coefficient!r} (or {field.name!r})"
                    )
        cf1, cf2 = values.pop("cf1", None), values.pop("cf2", None)
        if cf1 is not None or cf2 is not None:
            eta_M, d = _parse("eta_M", values["eta_M"]), _parse("d", values["d"])
            if cf1 is not None:
                values["mu_v"] = _parse("cf1", cf1) * eta_M
            if cf2 is not None:
                values["J_b"] = _parse("cf2", cf2) * eta_M * d**2
        return cls(**values)

    @classmethod
    def from_coefficients(
        cls,
        *,
        eta_f: NumberLike,
        eta_M: NumberLike,
        d: NumberLike,
        cf1: NumberLike,
        cf2: NumberLike,
        kappa_v: NumberLike,
        eta_v: NumberLike,
        alpha: NumberLike,
        eta_s: NumberLike = 0,
        beam: str = "eb",
        S: NumberLike | None = None,
        r: NumberLike | None = None,
    ) -> DimensionlessParams:
        """Build from the coefficients of Table 1: ``mu_v = cf1 eta_M``, ``J_b = cf2 eta_M d**2`` (Eq. 63)."""
        return cls.from_mapping(
            dict(
                eta_f=eta_f,
                eta_M=eta_M,
                d=d,
                cf1=cf1,
                cf2=cf2,
                kappa_v=kappa_v,
                eta_v=eta_v,
                alpha=alpha,
                eta_s=eta_s,
                beam=beam,
                S=S,
                r=r,
            )
        )

    def replace(self, **changes: Any) -> DimensionlessParams:
        """Return a copy with some parameters changed, validated again.

        Besides the fields, ``cf1`` and ``cf2`` are accepted: they set ``mu_v = cf1 eta_M`` and
        ``J_b = cf2 eta_M d**2`` (Eq. 63) with the new ``eta_M`` and ``d``. When ``eta_M`` or ``d``
        changes and neither the coefficient nor the field it sets is given, ``cf1`` and ``cf2`` are
        kept fixed, as in Table 1: the bar's mass and inertia scale with the wheel mass (Eq. 64).
        Changing ``beam`` to ``"eb"`` drops ``S`` and ``r`` unless they are given.

        Raises
        ------
        ParameterError
            As :meth:`from_mapping`.

        Examples
        --------
        >>> p = DimensionlessParams.from_coefficients(
        ...     eta_f=0, eta_M=20, d=2, cf1=2, cf2="0.1", kappa_v="0.2", eta_v=0, alpha="0.5")
        >>> q = p.replace(eta_M=40)
        >>> (q.mu_v, q.cf1), (q.J_b, q.cf2)
        ((Fraction(80, 1), Fraction(2, 1)), (Fraction(16, 1), Fraction(1, 10)))
        """
        values: dict[str, Any] = {field.name: getattr(self, field.name) for field in dataclasses.fields(self)}
        rescaled = "eta_M" in changes or "d" in changes
        for coefficient, field in _COEFFICIENTS.items():
            if coefficient in changes or (rescaled and field not in changes):
                del values[field]
                values.setdefault(coefficient, getattr(self, coefficient))
        if changes.get("beam") == "eb":
            values.update(S=None, r=None)
        return type(self).from_mapping(values | changes)

    def as_mp(self) -> SimpleNamespace:
        """All fields as ``mpmath.mpf`` rounded once at the current ``mp`` precision (beam a str, None kept).

        Call it inside ``mpmath.workdps(n)`` to get the parameters at `n` digits.
        """
        return SimpleNamespace(**map_fractions(self, fraction_to_mpf))

    def as_float(self) -> SimpleNamespace:
        """All fields as floats (beam a str, None kept)."""
        return SimpleNamespace(**map_fractions(self, float))

    def to_dict(self) -> dict[str, str | None]:
        """JSON-ready dict of all fields plus ``cf1`` and ``cf2``.

        Numbers are strings: the exact decimal when the Fraction has a finite decimal expansion
        (``"0.05"``), else the repr of the nearest float (``"0.3333333333333333"``).
        """
        out = map_fractions(self, fraction_to_text)
        out["cf1"] = fraction_to_text(self.cf1)
        out["cf2"] = fraction_to_text(self.cf2)
        return out

    def to_physical(
        self, EI: NumberLike, m: NumberLike, k_f: NumberLike, P: NumberLike, *, digits: int = 20
    ) -> PhysicalParams:
        """SI parameters for a track (`EI`, `m`, `k_f`) and wheel load `P`: Eqs. (15)-(17), (59) inverted.

        Parameters
        ----------
        EI, m, k_f, P : NumberLike
            Bending stiffness [N m^2], beam mass per length [kg/m], foundation stiffness [N/m^2] and
            wheel load [N], all > 0.
        digits : int, optional
            The results are rounded to this many significant decimal digits (computed with 10 more).

        Returns
        -------
        PhysicalParams
            ``PhysicalParams(...).to_dimensionless()`` gives back these parameters to about `digits`.
        """
        return PhysicalParams.from_dimensionless(self, EI=EI, m=m, k_f=k_f, P=P, digits=digits)
