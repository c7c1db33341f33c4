"""A model bound to its parameters: built once at an entry point and passed down (Eqs. (24), (29), (38)).

The entry points (the Python API of :mod:`moving_bogie.api`, the commands, the paper's recipes) call
:func:`bind` once; every function and kernel of ``kernels/``, ``roots/``, ``response/``, ``validation/``,
``stability/`` and ``sweep/`` takes the :class:`BoundModel` (``bound: BoundModel``) and never binds again.
Another vehicle or track is another bound model: ``bound.replace(vehicle=...)``, a foundation module
given beside the parameters (``BoundModel(params, foundation=Foundation(module, values))``), or another
kind of track (``BoundModel(params, track=MyTrack)``, :mod:`moving_bogie.kernels.track_model`). It plays the
part of PyBaMM's ``Simulation``, which binds a model to its parameter values once.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from fractions import Fraction
from types import ModuleType, SimpleNamespace
from typing import TYPE_CHECKING, Any, cast

import mpmath
import numpy as np

from moving_bogie.errors import ParameterError
from moving_bogie.kernels.continuous_track import ContinuousTrack
from moving_bogie.kernels.foundation import Foundation
from moving_bogie.kernels.track_model import Track
from moving_bogie.kernels.vehicle import VehicleSystem

if TYPE_CHECKING:
    from moving_bogie.model.catalogue import Model
    from moving_bogie.model.params import DimensionlessParams
    from moving_bogie.model.physical import PhysicalParams

__all__ = ["BoundModel", "Foundation", "TrackFactory", "bind"]

#: How a bound model makes its track: a callable of the bound model (a track class, ``MyTrack(bound)``).
TrackFactory = Callable[["BoundModel"], Track]


class BoundModel:
    """One parameter set bound to its model's generated kernels: what every computation on it needs.

    It holds (set once, read-only):

    - ``params``: the exact :class:`~moving_bogie.model.params.DimensionlessParams`; their ``model`` (beam x
      track x vehicle of a catalogue) names the kernels;
    - ``foundation_model``: the track as a :class:`~moving_bogie.kernels.foundation.Foundation`, the
      generated foundation module of the parameters' OWN catalogue (a catalogue loaded with
      :func:`~moving_bogie.model.catalogue.load_catalogue` reaches its own kernels; no name is looked up),
      or the one given as ``foundation`` with the values of the groups the parameters do not carry;
    - ``track_factory``: what makes :attr:`track` of the bound model (the ``track`` given, else
      :class:`~moving_bogie.kernels.continuous_track.ContinuousTrack`).

    It caches (computed on first use, kept for its life):

    - ``floats``: every group as a float (``params.as_float()``);
    - ``foundation``, ``vehicle``: the generated foundation module (N(p, q), Q(p, q) of Eq. (24)) and vehicle
      module (matrices, contacts, loads; Eqs. (30)-(38));
    - ``float_system``: the vehicle's :class:`~moving_bogie.kernels.vehicle.VehicleSystem` in double
      precision, and :meth:`vehicle_system` one per mpmath precision;
    - ``positions``, ``offsets``: the contact positions xi_j and their distinct differences (floats);
    - ``track``: the :class:`~moving_bogie.kernels.track_model.Track` that gives the rail-side receptance,
      the search region, the far field, the cuts and the smeared track (made once by ``track_factory``);
    - ``kernel_decay``, ``polynomial_degrees``: gamma of K = O(|q|^-gamma) (``KERNEL_DECAY`` of the track)
      and the degrees of E_chr in the vehicle's groups (``POLYNOMIAL_DEGREES``).

    Parameters
    ----------
    params : DimensionlessParams
        Exact parameters.
    foundation : Foundation or module, optional
        The track model when it is not that of ``params.model`` (a generated module, or a module with the
        values of its extra groups).
    track : callable, optional
        The kind of track, a callable of the bound model that returns its
        :class:`~moving_bogie.kernels.track_model.Track` (default: a continuous track on ``foundation``).

    Examples
    --------
    >>> from moving_bogie import table1_case
    >>> bound = BoundModel(table1_case(1))
    >>> bound.names[:2], bound.span
    (('w_rear', 'w_front'), 2.0)
    """

    params: DimensionlessParams
    foundation_model: Foundation
    track_factory: TrackFactory

    def __init__(
        self,
        params: DimensionlessParams,
        *,
        foundation: Foundation | ModuleType | None = None,
        track: TrackFactory | None = None,
    ) -> None:
        if not hasattr(params, "model") or not hasattr(params, "as_float"):
            raise ParameterError(
                "params",
                f"expected DimensionlessParams, PhysicalParams or a BoundModel (got {type(params).__name__})",
            )
        if track is None and getattr(params.model, "periodic", False):
            raise ParameterError(
                "track",
                f"{params.model.name} is a track on periodic supports: bind it with moving_bogie.bind, which "
                "gives it its track (kernels/track_model.py)",
            )
        self.params = params
        self._override = foundation
        if foundation is None:
            self.foundation_model = Foundation(params.model.foundation)
        else:
            self.foundation_model = (
                foundation if isinstance(foundation, Foundation) else Foundation(foundation)
            )
        self.track_factory = ContinuousTrack if track is None else track
        self._systems: dict[int, VehicleSystem] = {}

    def __repr__(self) -> str:
        extra = "" if self._override is None else f", foundation={self._override!r}"
        if self.track_factory is not ContinuousTrack:
            extra += f", track={getattr(self.track_factory, '__qualname__', self.track_factory)!r}"
        return f"BoundModel({self.params!r}{extra})"

    def __eq__(self, other: object) -> bool:
        return (
            isinstance(other, BoundModel)
            and other.params == self.params
            and other.foundation_model == self.foundation_model
            and other.track_factory == self.track_factory
        )

    def __hash__(self) -> int:
        return hash(self.params)

    def __reduce__(self) -> tuple[Any, ...]:
        options = self._options()
        if not options:
            return (BoundModel, (self.params,))
        return (functools.partial(BoundModel, **options), (self.params,))

    def _options(self, keep_foundation: bool = True) -> dict[str, Any]:
        """The keyword arguments given at construction beside the parameters (None ones left out)."""
        out: dict[str, Any] = {}
        if self._override is not None and keep_foundation:
            out["foundation"] = self._override
        if self.track_factory is not ContinuousTrack:
            out["track"] = self.track_factory
        return out

    # --- the model ----------------------------------------------------------------------------------
    @property
    def model(self) -> Model:
        """The :class:`~moving_bogie.model.catalogue.Model` (beam x track x vehicle + catalogue)."""
        return self.params.model

    @property
    def name(self) -> str:
        """``beam/track/vehicle``, for output only."""
        return self.model.name

    @property
    def foundation(self) -> ModuleType:
        """The generated kernel of the beam on its track (N(p, q), Q(p, q) of Eq. (24))."""
        return self.foundation_model.module

    @functools.cached_property
    def vehicle(self) -> ModuleType:
        """The generated kernel of the vehicle (matrices, contacts, loads; Eqs. (30)-(38)), own catalogue."""
        return self.model.vehicle_kernels

    def replace(self, **changes: Any) -> BoundModel:
        """A new bound model with some parameters (or the model's names) changed, as ``params.replace``.

        A foundation given at construction is kept, unless the beam or the track changes (then the new
        model's own); the kind of track (``track``) is kept.
        """
        options = self._options(keep_foundation=not {"beam", "track"} & set(changes))
        return BoundModel(self.params.replace(**changes), **options)

    def with_foundation(self, foundation: Foundation | ModuleType) -> BoundModel:
        """The same parameters on another track model (a generated module, with values of its groups)."""
        return BoundModel(self.params, **(self._options(keep_foundation=False) | {"foundation": foundation}))

    @functools.cached_property
    def track(self) -> Track:
        """The track (:mod:`moving_bogie.kernels.track_model`): the rail-side receptance, the search
        region, the far field, the cuts and the smeared track; made once by ``track_factory``."""
        return self.track_factory(self)

    # --- numbers ------------------------------------------------------------------------------------
    @functools.cached_property
    def floats(self) -> SimpleNamespace:
        """Every group as a float (``params.as_float()``), computed once."""
        return self.params.as_float()

    def vehicle_values(self, numbers: SimpleNamespace) -> dict[str, Any]:
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

    def foundation_floats(self) -> dict[str, float | None]:
        """Keyword arguments of the foundation functions in double precision."""
        return self.foundation_model.float_arguments(self.floats)

    def foundation_mp(self) -> dict[str, Any]:
        """Keyword arguments of the foundation functions at the current mpmath precision."""
        return self.foundation_model.mp_arguments(self.params.as_mp())

    @property
    def names(self) -> tuple[str, ...]:
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
    def polynomial_degrees(self) -> dict[str, int]:
        """Degree of E_chr in each vehicle parameter it is a polynomial in (``POLYNOMIAL_DEGREES``)."""
        return dict(getattr(self.vehicle, "POLYNOMIAL_DEGREES", {}))


def bind(params: DimensionlessParams | PhysicalParams | BoundModel) -> BoundModel:
    """The bound model of ``params``: a :class:`BoundModel` itself, else ``BoundModel(params)``.

    Called once by each entry point; SI parameters are made dimensionless first (``to_dimensionless()``).
    """
    if isinstance(params, BoundModel):
        return params
    dimensionless = params.to_dimensionless() if hasattr(params, "to_dimensionless") else params
    return BoundModel(cast("DimensionlessParams", dimensionless))
