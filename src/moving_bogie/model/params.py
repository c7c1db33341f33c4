"""Dimensionless parameters of a model, stored exactly and validated from the generated metadata.

The dimensionless form of every model (paper, Eqs. (18)-(20); Timoshenko-Rayleigh Eqs. (60)-(61)) depends
only on the groups of Eqs. (15)-(17), (59) and those any further model declares in ``derivations/``.
Which groups a model needs, their ranges and defaults come from the generated catalogue
(:mod:`moving_bogie.model.catalogue`); no parameter name is written here.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from fractions import Fraction
from types import SimpleNamespace
from typing import Any

from moving_bogie.errors import ParameterError, suggestion
from moving_bogie.model.catalogue import (
    DEFAULT_MODEL,
    Model,
    ParameterSpec,
    default_catalogue,
    get_model,
)
from moving_bogie.model.exact import (
    fraction_to_exact_text,
    fraction_to_mpf,
    fraction_to_text,
    nonnegative,
    positive,
)
from moving_bogie.model.values import ModelValues

__all__ = ["BEAMS", "DimensionlessParams"]

#: Beam theories with generated kernels (Euler-Bernoulli Eq. (1), Timoshenko-Rayleigh Eqs. (55)-(56), and
#: any beam added in derivations/).
BEAMS = tuple(default_catalogue().beams)
_MODEL_KEYS = ("beam", "track", "vehicle")


def check_value(spec: ParameterSpec, value: object) -> Fraction:
    """Convert one value exactly and check the range its metadata states; the error names the group."""
    if spec.constraint == "positive":
        return positive(spec.name, value)
    x = nonnegative(spec.name, value)
    if spec.constraint == "underdamped" and x >= 1:
        raise ParameterError(
            spec.name,
            f"{spec.name} must satisfy {spec.range_text.replace('x', spec.name)} "
            f"(got {fraction_to_text(x)}): the runtime assumes an under-damped foundation, "
            "and its search for induced frequencies relies on it",
        )
    return x


class DimensionlessParams(ModelValues):
    """Dimensionless parameters of one model (beam x track x vehicle), Eqs. (15)-(17), (59), (63).

    Every group accepts an int, a Fraction, decimal text (``"0.1"``, converted exactly), a Decimal or a
    finite float (read by its shortest decimal text: ``0.1`` is 1/10), and is stored as a
    :class:`~fractions.Fraction`. Instances are immutable and hashable; :meth:`replace` varies a parameter.
    Read a group as an attribute (``p.alpha``); a group of the catalogue that this model does not use reads
    as None (``p.S`` of an Euler-Bernoulli beam). ``moving-bogie models`` lists every model's groups.

    Parameters
    ----------
    beam, track, vehicle : str, optional
        The model (default: the paper's Euler-Bernoulli beam, one-layer track, bogie).
    model : Model, optional
        Instead of the three names (e.g. a model of a catalogue loaded with
        :func:`~moving_bogie.model.catalogue.load_catalogue`).
    **values
        The groups: required ones must be given, those with a default may be; None counts as not given.

    Raises
    ------
    ParameterError
        Naming the first offending parameter.

    Examples
    --------
    >>> p = DimensionlessParams.from_coefficients(
    ...     eta_f="0.05", eta_M=30, d=2, cf1="1.7", cf2="0.01", kappa_v="0.2", eta_v="0.05", alpha="0.4")
    >>> p.mu_v, p.J_b, p.cf1
    (Fraction(51, 1), Fraction(6, 5), Fraction(17, 10))
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
        if model is None:
            model = get_model(beam, track, vehicle)
        elif any(x is not None for x in (beam, track, vehicle)):
            model = get_model(
                beam or model.beam, track or model.track, vehicle or model.vehicle, model.catalogue
            )
        specs = model.catalogue.specs
        exact = {}
        for name, value in values.items():
            if name not in specs:
                known = [*model.parameters, *model.alternatives, *_MODEL_KEYS]
                raise ParameterError(
                    name, f"unknown parameter {name!r}; {suggestion(name, known, listing='known:')}"
                )
            if value is None:
                continue
            if name not in model.parameters:
                raise ParameterError(
                    name, f"{name} is not a parameter of the model {model.name} (got {value!r})"
                )
        own = model.specs
        for name in model.parameters:
            spec = own[name]
            value = values.get(name)
            if value is None:
                if spec.default is None:
                    raise ParameterError(
                        name, f"missing parameter {name!r} ({spec.meaning}) for {model.name}"
                    )
                value = spec.default
            exact[name] = check_value(spec, value)
        self._set(model, exact)

    # --- reading ------------------------------------------------------------------------------------

    def __getattr__(self, name: str) -> Any:
        if name.startswith("_"):
            raise AttributeError(name)
        values = self._values
        if name in values:
            return values[name]
        model = self._model
        alternatives = model.alternatives
        if name in alternatives:
            meta = alternatives[name]
            func = getattr(model.catalogue.parameters, f"alternative_{name}")
            return func(**{k: values[k] for k in (meta["sets"], *meta["depends"])})
        if name in model.catalogue.specs or name in model.catalogue.parameters.ALTERNATIVES:
            return None  # a group or coefficient of another model
        raise AttributeError(f"{type(self).__name__} of {model.name} has no parameter {name!r}")

    def __reduce__(self) -> tuple[Callable[..., DimensionlessParams], tuple[Any, ...]]:
        return (_rebuild, (self._model.beam, self._model.track, self._model.vehicle, self.to_exact_dict()))

    # --- building -----------------------------------------------------------------------------------

    @classmethod
    def from_mapping(cls, values: Mapping[str, Any], *, model: Model | None = None) -> DimensionlessParams:
        """Build from a mapping of names: the groups, the model keys and the alternatives (Eq. (63)).

        An alternative (``cf1``, ``cf2`` of Table 1) sets the group it stands for from the other groups:
        ``mu_v = cf1 eta_M`` and ``J_b = cf2 eta_M d**2``. This is the one entry point for parameters read
        from files and command lines.

        Raises
        ------
        ParameterError
            For an unknown or missing name, an alternative given with the group it sets, or an invalid
            value; the message names the parameter.
        """
        values = dict(values)
        keys = {k: values.pop(k) for k in _MODEL_KEYS if k in values}
        if model is None:
            model = get_model(**keys)
        elif keys:
            model = get_model(
                **({k: getattr(model, k) for k in _MODEL_KEYS} | keys), catalogue=model.catalogue
            )
        catalogue_alternatives = model.catalogue.parameters.ALTERNATIVES
        for name, meta in model.alternatives.items():
            if values.get(name) is None:
                values.pop(name, None)
                continue
            if values.get(meta["sets"]) is not None:
                raise ParameterError(name, f"give either {name} or {meta['sets']}, not both")
            depends = {}
            for dep in meta["depends"]:
                if values.get(dep) is None:
                    raise ParameterError(dep, f"missing parameter {dep!r} (needed by {name})")
                depends[dep] = check_value(model.catalogue.specs[dep], values[dep])
            alt = check_value_named(name, values.pop(name))
            values[meta["sets"]] = getattr(model.catalogue.parameters, f"set_by_{name}")(alt, **depends)
        for name in list(values):
            if name in catalogue_alternatives and name not in model.alternatives:
                if values[name] is None:
                    del values[name]
                else:
                    raise ParameterError(name, f"{name} is not a parameter of the model {model.name}")
        for name in model.parameters:
            if values.get(name) is None and model.specs[name].default is None:
                alt_name = next((a for a, m in model.alternatives.items() if m["sets"] == name), None)
                hint = f" (or {alt_name!r})" if alt_name else ""
                meaning = model.specs[name].meaning
                raise ParameterError(alt_name or name, f"missing parameter {name!r}{hint} ({meaning})")
        return cls(model=model, **values)

    @classmethod
    def from_coefficients(cls, **values: Any) -> DimensionlessParams:
        """Build from the coefficients of Table 1: ``mu_v = cf1 eta_M``, ``J_b = cf2 eta_M d**2`` (Eq. 63)."""
        return cls.from_mapping(values)

    def replace(self, **changes: Any) -> DimensionlessParams:
        """Return a copy with some parameters (or the model) changed, validated again.

        The alternatives (``cf1``, ``cf2``) are accepted too. When a group an alternative depends on
        changes (``eta_M`` or ``d``) and neither the alternative nor the group it sets is given, the
        alternative is kept fixed, as in Table 1: the bar's mass and inertia scale with the wheel mass
        (Eq. 64). Changing the model (``beam``, ``track``, ``vehicle``) drops the groups the new model does
        not use and requires those it adds.

        Examples
        --------
        >>> p = DimensionlessParams.from_coefficients(
        ...     eta_f=0, eta_M=20, d=2, cf1=2, cf2="0.1", kappa_v="0.2", eta_v=0, alpha="0.5")
        >>> q = p.replace(eta_M=40)
        >>> (q.mu_v, q.cf1), (q.J_b, q.cf2)
        ((Fraction(80, 1), Fraction(2, 1)), (Fraction(16, 1), Fraction(1, 10)))
        """
        model = self._model
        keys = {k: changes.pop(k) for k in _MODEL_KEYS if k in changes and changes[k] is not None}
        if keys:
            model = get_model(
                **({k: getattr(model, k) for k in _MODEL_KEYS} | keys), catalogue=model.catalogue
            )
        values: dict[str, Any] = {k: v for k, v in self._values.items() if k in model.parameters}
        for name, meta in model.alternatives.items():
            affected = any(dep in changes for dep in meta["depends"])
            if name in changes or (
                affected and meta["sets"] not in changes and name in self._model.alternatives
            ):
                values.pop(meta["sets"], None)
                if name not in changes:
                    values[name] = getattr(self, name)
        return type(self).from_mapping(values | changes, model=model)

    # --- conversions --------------------------------------------------------------------------------

    def as_mp(self) -> SimpleNamespace:
        """Every group of the catalogue as ``mpmath.mpf`` at the current ``mp`` precision (None if unused).

        Call it inside ``mpmath.workdps(n)`` to get the parameters at `n` digits.
        """
        return self._namespace(fraction_to_mpf)

    def as_float(self) -> SimpleNamespace:
        """Every group of the catalogue as a float (None if unused), plus the model names."""
        return self._namespace(float)

    def _namespace(self, convert: Callable[[Fraction], Any]) -> SimpleNamespace:
        out = {name: None for name in self._model.catalogue.specs}
        out |= {name: convert(value) for name, value in self._values.items()}
        out |= {k: getattr(self, k) for k in _MODEL_KEYS}
        return SimpleNamespace(**out)

    def to_exact_dict(self) -> dict[str, str]:
        """The groups as exact text that ``Fraction`` reads back (``'1/3'`` where no decimal is exact)."""
        return {k: fraction_to_exact_text(v) for k, v in self._values.items()}

    def to_dict(self) -> dict[str, str | None]:
        """JSON-ready dict: the model's names, its groups and its alternatives (``cf1``, ``cf2``).

        Numbers are strings: the exact decimal when the Fraction has a finite decimal expansion
        (``"0.05"``), else the repr of the nearest float (``"0.3333333333333333"``).
        """
        out: dict[str, str | None] = {k: getattr(self, k) for k in _MODEL_KEYS}
        out |= {k: fraction_to_text(v) for k, v in self._values.items()}
        out |= {name: fraction_to_text(getattr(self, name)) for name in self._model.alternatives}
        return out


def check_value_named(name: str, value: object) -> Fraction:
    """An alternative input (cf1, cf2 of Eq. (63)): exact and > 0."""
    return positive(name, value)


def _rebuild(beam: str, track: str, vehicle: str, values: dict[str, Any]) -> DimensionlessParams:
    """Unpickle: the model's names and the exact texts of :meth:`DimensionlessParams.to_exact_dict`."""
    return DimensionlessParams(beam=beam, track=track, vehicle=vehicle, **values)


__all__ += ["DEFAULT_MODEL"]
