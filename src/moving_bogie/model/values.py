"""Exact values of one model, immutable: what dimensionless and SI parameters have in common."""

from __future__ import annotations

from fractions import Fraction
from typing import Any

from moving_bogie.model.catalogue import Model
from moving_bogie.model.exact import fraction_to_exact_text

__all__ = ["ModelValues"]

_MODEL_KEYS = ("beam", "track", "vehicle")


class ModelValues:
    """Named exact values (``Fraction``) of a :class:`~moving_bogie.model.catalogue.Model`.

    Immutable and hashable; equal when the class, the model and every value are equal. The repr is exact and
    evaluable (``DimensionlessParams(alpha='0.4', ..., beam='eb', track='one-layer', vehicle='bogie')``).
    """

    __slots__ = ("_model", "_values")
    _model: Model
    _values: dict[str, Fraction]

    def _set(self, model: Model, values: dict[str, Fraction]) -> None:
        object.__setattr__(self, "_model", model)
        object.__setattr__(self, "_values", values)

    @property
    def model(self) -> Model:
        """The :class:`~moving_bogie.model.catalogue.Model` these values belong to."""
        return self._model

    @property
    def beam(self) -> str:
        return self._model.beam

    @property
    def track(self) -> str:
        return self._model.track

    @property
    def vehicle(self) -> str:
        return self._model.vehicle

    def values(self) -> dict[str, Fraction]:
        """Name -> exact value, in the catalogue's order."""
        return dict(self._values)

    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError(
            f"{type(self).__name__} is immutable: use replace({name}=...) or build a new one"
        )

    def __eq__(self, other: object) -> bool:
        if type(other) is not type(self):
            return NotImplemented
        return self._key() == other._key()

    def __hash__(self) -> int:
        return hash(self._key())

    def _key(self) -> tuple:
        return (self._model, tuple(self._values.items()))

    def __repr__(self) -> str:
        items = [f"{k}={fraction_to_exact_text(v)!r}" for k, v in self._values.items()]
        items += [f"{k}={getattr(self, k)!r}" for k in _MODEL_KEYS]
        return f"{type(self).__name__}({', '.join(items)})"
