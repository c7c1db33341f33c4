"""The track model of a computation: a generated foundation module and the values of the groups it takes.

The functions of a generated foundation module (``N(p, q)`` and ``Q(p, q)`` of Eq. (24) as coefficient lists
in p, their q-derivatives) take the dimensionless groups of the track as keyword arguments. A
:class:`Foundation` names the module and, for groups the parameters do not carry, their values; a bound
model holds one (:attr:`~moving_bogie.kernels.bound.BoundModel.foundation_model`).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from fractions import Fraction
from types import SimpleNamespace
from typing import Any

import mpmath

__all__ = ["Foundation"]


@dataclass(frozen=True)
class Foundation:
    """A generated foundation module and the values of the groups its functions take.

    ``module`` is any object with the generated interface: ``n_coeffs``, ``n_coeffs_dq``, ``q_coeffs``,
    ``q_coeffs_dq``, ``n_coeffs_in_q``, ``ARGUMENTS``, ``DEGREE_N``, ``DEGREE_Q`` (a module of
    ``moving_bogie.generated`` or one generated elsewhere and loaded with importlib). ``values`` maps
    group names to numbers (floats, Fractions or decimal strings) for groups the parameters object does
    not carry; they take precedence over the parameters' own values.
    """

    module: Any
    values: Mapping[str, Any] = field(default_factory=dict)

    @property
    def names(self) -> tuple[str, ...]:
        """The groups the generated functions take besides q (or p)."""
        return tuple(self.module.ARGUMENTS[1:])

    def float_arguments(self, numbers: SimpleNamespace | None) -> dict[str, float | None]:
        """Keyword arguments in double precision from a namespace of the groups (``BoundModel.floats``).

        Groups neither in ``values`` nor in ``numbers`` are None.
        """
        out: dict[str, float | None] = {}
        for name in self.names:
            value = self.values[name] if name in self.values else getattr(numbers, name, None)
            out[name] = None if value is None else float(value)
        return out

    def mp_arguments(self, numbers: SimpleNamespace | None) -> dict[str, Any]:
        """Keyword arguments at the current mpmath precision from the groups as mpf (``params.as_mp()``)."""
        out = {}
        for name in self.names:
            if name in self.values:
                out[name] = _to_mp(self.values[name])
            else:
                out[name] = getattr(numbers, name, None)
        return out


def _to_mp(value: Any) -> Any:
    if value is None:
        return None
    if isinstance(value, Fraction):
        return mpmath.mpf(value.numerator) / value.denominator
    return mpmath.mpf(str(value)) if isinstance(value, (int, float, str)) else mpmath.mpf(value)
