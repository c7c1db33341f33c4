"""A model bound to its parameters: built once at an entry point and passed down (Eqs. (24), (29), (38)).

:class:`BoundModel` holds what every computation on one parameter set needs and would otherwise look up
again and again: the exact :class:`~moving_bogie.model.params.DimensionlessParams`, their
:class:`~moving_bogie.model.catalogue.Model`, the generated foundation and vehicle modules of the
parameters' OWN catalogue (a catalogue loaded with
:func:`~moving_bogie.model.catalogue.load_catalogue` reaches its own kernels and asymptotics; no name is
looked up), the vehicle's matrices (:class:`~moving_bogie.kernels.vehicle.VehicleSystem`) in double
precision and per mpmath precision, its contact positions and distinct offsets, and the large-|q| data of
the track (``KERNEL_DECAY``). It plays the part of PyBaMM's ``Simulation``, which binds a model to its
parameter values once.

Every function of the runtime that takes ``params`` accepts either the parameters or a bound model and calls
:func:`bind` (idempotent) on it; to analyse another vehicle or track, bind other parameters:
``bind(params.replace(vehicle=...))``.
"""

from __future__ import annotations

import functools
from fractions import Fraction
from types import ModuleType

import mpmath
import numpy as np

from moving_bogie.errors import ParameterError
from moving_bogie.kernels.vehicle import VehicleSystem

__all__ = ["BoundModel", "bind"]


class BoundModel:
    """One parameter set bound to its model's generated kernels (module docstring).

    Parameters
    ----------
    params : DimensionlessParams
        Exact parameters; their ``model`` (beam x track x vehicle of a catalogue) chooses the kernels.

    Examples
    --------
    >>> from moving_bogie import table1_case
    >>> bound = bind(table1_case(1))
    >>> bound.names[:2], bound.span
    (('w_rear', 'w_front'), 2.0)
    >>> bind(bound) is bound
    True
    """

    def __init__(self, params) -> None:
        if not hasattr(params, "model") or not hasattr(params, "as_float"):
            raise ParameterError(
                "params", f"expected DimensionlessParams or a bound model (got {type(params).__name__})"
            )
        self.params = params
        self._systems: dict[int, VehicleSystem] = {}

    def __repr__(self) -> str:
        return f"BoundModel({self.params!r})"

    def __eq__(self, other) -> bool:
        return isinstance(other, BoundModel) and other.params == self.params

    def __hash__(self) -> int:
        return hash(self.params)

    def __reduce__(self):
        return (bind, (self.params,))

    # --- the model ----------------------------------------------------------------------------------
    @property
    def model(self):
        """The :class:`~moving_bogie.model.catalogue.Model` (beam x track x vehicle + catalogue)."""
        return self.params.model

    @property
    def name(self) -> str:
        """``beam/track/vehicle``, for output only."""
        return self.model.name

    @functools.cached_property
    def foundation(self) -> ModuleType:
        """The generated kernel of the beam on its track (N(p, q), Q(p, q) of Eq. (24)), own catalogue."""
        return self.model.foundation

    @functools.cached_property
    def vehicle(self) -> ModuleType:
        """The generated kernel of the vehicle (matrices, contacts, loads; Eqs. (30)-(38)), own catalogue."""
        return self.model.vehicle_kernels

    def replace(self, **changes) -> BoundModel:
        """A new bound model with some parameters (or the model's names) changed, as ``params.replace``."""
        return BoundModel(self.params.replace(**changes))

    # --- numbers ------------------------------------------------------------------------------------
    @functools.cached_property
    def floats(self):
        """Every group as a float (``params.as_float()``), computed once."""
        return self.params.as_float()

    def vehicle_values(self, numbers) -> dict:
        """The vehicle's matrix arguments (``MATRIX_ARGUMENTS``) read from a namespace of numbers."""
        return {name: getattr(numbers, name) for name in self.vehicle.MATRIX_ARGUMENTS}

    @functools.cached_property
    def float_system(self) -> VehicleSystem:
        """The vehicle's matrices, contact positions and loads in double precision."""
        return VehicleSystem(self.vehicle, self.vehicle_values(self.floats))

    def vehicle_system(self) -> VehicleSystem:
        """The vehicle's matrices at the current mpmath precision (one per precision, kept)."""
        prec = mpmath.mp.prec
        if prec not in self._systems:
            self._systems[prec] = VehicleSystem(self.vehicle, self.vehicle_values(self.params.as_mp()))
        return self._systems[prec]

    @property
    def names(self) -> tuple:
        """The responses: every DOF of the vehicle, the wheels first (``DOFS`` of the generated module)."""
        return tuple(self.vehicle.DOFS)

    @functools.cached_property
    def positions(self) -> np.ndarray:
        """Contact positions xi_j of the wheels (floats; the rear wheel at 0)."""
        return np.array([float(x) for x in self.float_system.positions])

    @functools.cached_property
    def offsets(self) -> np.ndarray:
        """The distinct xi_i - xi_j of the contacts (floats, 0 first)."""
        return np.array([float(x) for x in self.float_system.offsets])

    @property
    def span(self) -> float:
        """Rear to front wheel."""
        return float(self.positions.max())

    # --- asymptotics --------------------------------------------------------------------------------
    @property
    def kernel_decay(self) -> Fraction | None:
        """gamma of K = O(|q|^-gamma) (``KERNEL_DECAY`` of the track's generated module; None if absent)."""
        value = getattr(self.foundation, "KERNEL_DECAY", None)
        return None if value is None else Fraction(value)

    @property
    def polynomial_degrees(self) -> dict:
        """Degree of E_chr in each vehicle parameter it is a polynomial in (``POLYNOMIAL_DEGREES``)."""
        return dict(getattr(self.vehicle, "POLYNOMIAL_DEGREES", {}))


def bind(params) -> BoundModel:
    """The bound model of ``params``: a :class:`BoundModel` itself, else ``BoundModel(params)``."""
    return params if isinstance(params, BoundModel) else BoundModel(params)
