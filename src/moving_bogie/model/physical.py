"""Physical (SI) parameters and the exact scaling of Eqs. (15)-(17), (59) between SI and dimensionless form.

The scaling of every group, the SI names and units come from the generated metadata
(``generated/parameters.py``, derived from ``derivations/symbols.py``); nothing here names a parameter
beyond the scale parameters the metadata lists.
"""

from __future__ import annotations

from fractions import Fraction
from typing import TYPE_CHECKING, Any

import mpmath

from moving_bogie.errors import ParameterError, suggestion
from moving_bogie.model.catalogue import DEFAULT_MODEL, Model, default_catalogue
from moving_bogie.model.exact import (
    NumberLike,
    fraction_to_mpf,
    fraction_to_text,
    nonnegative,
    positive,
)
from moving_bogie.model.scales import (
    Scales,
    call_scaling,
    catalogue_values,
    group_from_si,
    rounded_fraction,
    scales_mp,
)
from moving_bogie.model.values import ModelValues

if TYPE_CHECKING:
    from moving_bogie.model.params import DimensionlessParams

__all__ = ["DIMENSIONLESS_OF", "PER_RAIL_CONVENTION", "PHYSICAL_UNITS", "PhysicalParams", "Scales"]

#: What the SI parameters describe: one rail and the half vehicle on it, and how to convert a whole vehicle.
PER_RAIL_CONVENTION = (
    "SI inputs are per rail, as in STEM and ROSE: the beam is one rail (EI, m, GA, r_g of one rail), the "
    "foundation the support of that rail per metre of track (k_f, c_f, k_s and the layers), and the "
    "vehicle the half carried by it: M one wheel (half a wheelset), M_b and J_b the half of the bogie frame "
    "on that rail, k_v and c_v the primary suspension of one wheel, P one wheel's static load (half the "
    "axle load). A whole vehicle on a combined beam (both rails as one) converts by halving everything: "
    "EI, m and the foundation per rail are half of the combined beam's, and M, M_b, J_b, k_v, c_v and P "
    "half of the whole vehicle's; lengths and the speed (v, d, r_g) stay. This halving leaves every "
    "dimensionless group unchanged (Eqs. (15)-(17), (59)), so both descriptions give the same frequencies "
    "and verdicts; only a mix of the two (a whole vehicle on one rail) is wrong."
)

_META = default_catalogue().parameters
#: SI unit of each SI parameter of the packaged catalogue (scale parameters first), on every track.
PHYSICAL_UNITS = {name: meta["unit"] for name, meta in _META.SCALE_PARAMETERS.items()} | {
    meta["si"]: meta["unit"] for meta in _META.PARAMETERS.values()
}
#: The dimensionless group each SI parameter (other than the scale parameters) scales to.
DIMENSIONLESS_OF = {meta["si"]: name for name, meta in _META.PARAMETERS.items()}
for _model in default_catalogue().models():
    PHYSICAL_UNITS |= {name: meta["unit"] for name, meta in _model.scale_parameters.items()}
    PHYSICAL_UNITS |= {spec.si: spec.unit for spec in _model.specs.values()}
    DIMENSIONLESS_OF |= {spec.si: name for name, spec in _model.specs.items()}
del _model


class PhysicalParams(ModelValues):
    """Physical parameters of a model in SI units, stored exactly as Fractions.

    Per rail (:data:`PER_RAIL_CONVENTION`): one rail and the half vehicle on it. The scale parameters
    ``EI`` [N m^2], ``m`` [kg/m], ``k_f`` [N/m^2] and the wheel load ``P`` [N], and the
    SI counterpart of each of the model's dimensionless groups (``moving-bogie models`` lists them with their
    units: for the paper's bogie ``c_f, M, M_b, J_b, k_v, c_v, d, v`` and optionally ``k_s``; ``GA, r_g``
    for a Timoshenko-Rayleigh beam). Numeric values accept what
    :class:`~moving_bogie.model.params.DimensionlessParams` accepts.

    Parameters
    ----------
    beam, track, vehicle : str, optional
        The model. When left out, it is the one whose SI parameters are exactly those given (so ``GA`` and
        ``r_g`` select the Timoshenko-Rayleigh beam), the paper's choice where several fit.
    model : Model, optional
        Instead of the names.
    **values
        The SI parameters.

    Raises
    ------
    ParameterError
        Naming the first offending parameter.

    Examples
    --------
    Table 1's Case 7 on a rail with EI = 6.42e6 N m^2 and m = 60.21 kg/m on k_f = 1.2e8 N/m^2 under an
    80 kN wheel: Eqs. (15)-(17) inverted, then applied again.

    >>> from moving_bogie.model.cases import table1_case
    >>> si = PhysicalParams.from_dimensionless(table1_case(7), EI="6.42e6", m="60.21", k_f="1.2e8", P="8e4")
    >>> round(si.scales().v_ref, 1), round(float(si.v), 1)
    (960.2, 384.1)
    >>> si.to_dimensionless().alpha
    Fraction(2, 5)
    """

    __slots__ = ()

    def __init__(
        self,
        *,
        beam: str | None = None,
        track: str | None = None,
        vehicle: str | None = None,
        model: Model | None = None,
        **values: Any,
    ) -> None:
        values = {k: v for k, v in values.items() if v is not None}
        if model is None:
            model = _infer_model(values, beam, track, vehicle)
        scale_parameters = model.scale_parameters
        scale_names = tuple(scale_parameters)
        si_of = {spec.si: spec for spec in model.specs.values()}
        exact = {}
        for name in values:
            if name not in scale_names and name not in si_of:
                hint = suggestion(name, [*scale_names, *si_of], listing="known:")
                raise ParameterError(
                    name, f"unknown SI parameter {name!r} for the model {model.name}; {hint}"
                )
        for name in scale_names:
            if name not in values:
                raise ParameterError(
                    name, f"missing SI parameter {name!r} ({scale_parameters[name]['unit']})"
                )
            exact[name] = positive(name, values[name])
        for si, spec in si_of.items():
            if si not in values:
                if spec.default is None:
                    raise ParameterError(si, f"missing SI parameter {si!r} ({spec.si_meaning}, {spec.unit})")
                if spec.default != 0:
                    raise ParameterError(si, f"missing SI parameter {si!r} ({spec.si_meaning}, {spec.unit})")
                exact[si] = Fraction(0)
                continue
            check = positive if spec.constraint == "positive" else nonnegative
            exact[si] = check(si, values[si])
        self._set(model, exact)

    def __getattr__(self, name: str) -> Any:
        if name.startswith("_"):
            raise AttributeError(name)
        if name in self._values:
            return self._values[name]
        raise AttributeError(f"PhysicalParams of {self._model.name} has no SI parameter {name!r}")

    def units(self) -> dict[str, str]:
        """SI name -> unit."""
        out = {name: m["unit"] for name, m in self._model.scale_parameters.items()}
        return out | {spec.si: spec.unit for spec in self._model.specs.values()}

    def to_dict(self) -> dict[str, str | None]:
        """JSON-ready dict of the model's names and the SI values as decimal strings."""
        out: dict[str, str | None] = {k: getattr(self, k) for k in ("beam", "track", "vehicle")}
        return out | {k: fraction_to_text(v) for k, v in self._values.items()}

    def _scale_values(self) -> dict:
        return {name: self._values[name] for name in self._model.scale_parameters}

    def scales(self) -> Scales:
        """Reference scales chi, v_ref, w_st and the time scale, Eqs. (15)-(16), as floats."""
        with mpmath.workdps(30):
            chi, v_ref, w_st, t_scale = scales_mp(self._model, self._scale_values())
            load = fraction_to_mpf(self._values["P"]) / 2
            return Scales(
                chi=float(chi), v_ref=float(v_ref), w_st=float(w_st), t_scale=float(t_scale), load=float(load)
            )

    def to_dimensionless(self, *, digits: int = 20) -> DimensionlessParams:
        """Dimensionless parameters, Eqs. (15)-(17) and (59), by the generated exact scaling.

        Parameters
        ----------
        digits : int, optional
            The scaling involves fourth roots, so the results are irrational: each is rounded to this
            many significant decimal digits (computed with 10 more) and stored exactly.

        Raises
        ------
        ParameterError
            Naming the SI parameter whose group is out of range (``c_f`` at or above critical damping).
        """
        from moving_bogie.model.params import DimensionlessParams, check_value

        exact: dict[str, Any] = {}  # Fractions, passed as DimensionlessParams' **values
        with mpmath.workdps(digits + 10):
            mp_values = {k: fraction_to_mpf(v) for k, v in self._values.items()}
            for name, spec in self._model.specs.items():
                value = rounded_fraction(group_from_si(self._model, name, mp_values), digits)
                try:
                    exact[name] = check_value(spec, value)
                except ParameterError as exc:
                    raise ParameterError(
                        spec.si,
                        f"{spec.si} = {fraction_to_text(self._values[spec.si])} {spec.unit} gives {exc}",
                    ) from None
        return DimensionlessParams(model=self._model, **exact)

    def group_value(self, si: str, value: NumberLike, *, digits: int = 20) -> tuple[str, Fraction]:
        """The group the SI parameter ``si`` scales to, at ``value``, the rest of ``self`` fixed.

        Eqs. (15)-(17), (59) by the generated exact scaling, rounded as in :meth:`to_dimensionless` (so
        ``si`` at its own value gives exactly the group of :meth:`to_dimensionless`).

        Returns
        -------
        (str, Fraction)
            The group's name and its value.

        Raises
        ------
        ParameterError
            Naming ``si`` when it is not the SI counterpart of one of the model's groups (a scale
            parameter changes every group) or when the value is out of range.
        """
        from moving_bogie.model.params import check_value

        specs = {spec.si: (name, spec) for name, spec in self._model.specs.items()}
        if si not in specs:
            raise ParameterError(
                si,
                f"{si!r} is not the SI counterpart of a dimensionless group of {self._model.name} "
                f"(known: {', '.join(specs)})",
            )
        name, spec = specs[si]
        check = positive if spec.constraint == "positive" else nonnegative
        exact = check(si, value)
        with mpmath.workdps(digits + 10):
            values = {k: fraction_to_mpf(v) for k, v in (self._values | {si: exact}).items()}
            group = rounded_fraction(group_from_si(self._model, name, values), digits)
        try:
            return name, check_value(spec, group)
        except ParameterError as exc:
            raise ParameterError(si, f"{si} = {fraction_to_text(exact)} {spec.unit} gives {exc}") from None

    def si_factor(self, group: str) -> float:
        """The SI value of ``group`` = 1 at this track's scales (every group is proportional to its SI
        counterpart, Eqs. (15)-(17), (59)): SI value = group x factor, by the generated scaling."""
        if self._model.periodic:
            return self._periodic_si_factor(group)
        meta = self._model.catalogue.parameters
        with mpmath.workdps(30):
            values = catalogue_values(
                self._model, {k: fraction_to_mpf(v) for k, v in self._scale_values().items()}
            )
            one = call_scaling(getattr(meta, f"physical_{group}"), values | {group: mpmath.mpf(1)})
            two = call_scaling(getattr(meta, f"physical_{group}"), values | {group: mpmath.mpf(2)})
            if abs(two - 2 * one) > abs(one) * mpmath.mpf(10) ** -25:
                raise ParameterError(group, f"the SI counterpart of {group} is not proportional to it")
            return float(one)

    def _periodic_si_factor(self, group: str) -> float:
        """:meth:`si_factor` on periodic supports: the SI value over the group at 1 of the SI unit (each
        group is proportional to its SI counterpart; docs/sleepers.md (S2))."""
        spec = self._model.specs[group]
        with mpmath.workdps(30):
            values = {k: fraction_to_mpf(v) for k, v in self._values.items()} | {spec.si: mpmath.mpf(1)}
            return float(1 / group_from_si(self._model, group, values))

    @classmethod
    def from_dimensionless(
        cls,
        params: DimensionlessParams,
        *,
        digits: int = 20,
        **scales: NumberLike,
    ) -> PhysicalParams:
        """Invert Eqs. (15)-(17) and (59) for a given track and wheel load.

        Parameters
        ----------
        params : DimensionlessParams
        **scales
            The model's scale parameters (:attr:`Model.scale_parameters`): ``EI``, ``m``, ``k_f``, ``P``
            on the one-layer track; ``EI``, ``m``, ``k_1``, ``P`` on a layered track.
        digits : int
            Results are rounded to `digits` significant decimal digits, as in :meth:`to_dimensionless`.

        Raises
        ------
        ParameterError
            Naming a missing or unknown scale parameter.
        """
        model = params.model
        if model.periodic:
            raise ParameterError(
                "track", f"the SI parameters of {model.name} are given as such (a [physical] table)"
            )
        for name in scales:
            if name not in model.scale_parameters:
                known = ", ".join(model.scale_parameters)
                raise ParameterError(
                    name, f"{name!r} is not a scale parameter of {model.name}; known: {known}"
                )
        track: dict[str, Any] = {}  # Fractions, passed as **values
        for name, meta in model.scale_parameters.items():
            if scales.get(name) is None:
                raise ParameterError(name, f"missing SI parameter {name!r} ({meta['unit']})")
            track[name] = positive(name, scales[name])
        formulas = model.catalogue.parameters
        exact: dict[str, Any] = {}  # Fractions, passed as **values
        with mpmath.workdps(digits + 10):
            mp_values = catalogue_values(model, {k: fraction_to_mpf(v) for k, v in track.items()})
            mp_values |= {k: fraction_to_mpf(v) for k, v in params.values().items()}
            for name, spec in model.specs.items():
                exact[spec.si] = rounded_fraction(
                    call_scaling(getattr(formulas, f"physical_{name}"), mp_values), digits
                )
        return cls(model=model, **track, **exact)

    def with_dimensionless(self, params: DimensionlessParams, *, digits: int = 20) -> PhysicalParams:
        """The SI parameters of `params` on this track (``EI``, ``m``, ``k_f``) under this wheel load ``P``.

        An SI parameter whose group equals this instance's own dimensionless value keeps its exact SI
        value; the others are recomputed as in :meth:`from_dimensionless`.
        """
        own = self.to_dimensionless(digits=digits)
        new = PhysicalParams.from_dimensionless(params, **self._scale_values(), digits=digits)
        values: dict[str, Any] = new.values()  # Fractions, passed as **values
        for name, spec in params.model.specs.items():
            if getattr(own, name) == getattr(params, name) and spec.si in self._values:
                values[spec.si] = self._values[spec.si]
        return PhysicalParams(model=params.model, **values)


def _infer_model(values: dict[str, Any], beam: str | None, track: str | None, vehicle: str | None) -> Model:
    """The model whose SI parameters are exactly those given (the paper's choice where several fit)."""
    from moving_bogie.model.catalogue import get_model

    catalogue = default_catalogue()
    fixed = {"beam": beam, "track": track, "vehicle": vehicle}
    fits, covers = [], []
    for model in catalogue.models():
        if any(v is not None and getattr(model, k) != v for k, v in fixed.items()):
            continue
        specs = model.specs.values()
        names = {s.si for s in specs} | set(model.scale_parameters)
        required = {s.si for s in specs if s.default is None} | set(model.scale_parameters)
        given = set(values)
        if given <= names:
            covers.append(model)
            if required <= given:
                fits.append(model)
    # No exact fit: the model that knows every given name (its validation then names what is missing).
    fits = fits or covers
    if not fits:
        return get_model(beam, track, vehicle)  # its validation names what is wrong
    choice = {k: v if v is not None else DEFAULT_MODEL[k] for k, v in fixed.items()}
    preferred = [m for m in fits if all(getattr(m, k) == v for k, v in choice.items())]
    ranked = preferred or sorted(
        fits, key=lambda m: sum(getattr(m, k) != DEFAULT_MODEL[k] for k in DEFAULT_MODEL)
    )
    return ranked[0]
