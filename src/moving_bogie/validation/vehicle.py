"""The vehicle of the finite-beam validation, read from its generated matrices (any vehicle, n contacts).

``python -m derivations`` writes, for every declared vehicle, its contact positions ``xi_j`` (rear wheel at
0), its static wheel loads ``s_j`` and its symmetric mass, damping and stiffness matrices ``M, C, K`` over its
degrees of freedom ``DOFS`` (the ``n`` wheel deflections first, in contact order, then the bodies' bounce and
pitch), in the scaling of Eqs. (15)-(17). The force that wheel ``j`` exerts on the rail is

    F_j = s_j - (M x'' + C x' + K x)_j    (j < n),    and    (M x'' + C x' + K x)_i = 0    (i >= n).

The paper's bogie (Eqs. (2)-(4), (19)-(20)) is one such vehicle, two masses (Figure 1a) another.
:class:`Vehicle` holds the matrices as floats for one set of parameters; :meth:`Vehicle.loads_only` is the
same vehicle with its matrices zeroed (constant moving forces ``F_j = s_j``).
"""

from __future__ import annotations

from dataclasses import dataclass
from types import ModuleType
from typing import Any

import numpy as np

from moving_bogie.errors import MovingBogieError
from moving_bogie.model.catalogue import DEFAULT_MODEL, default_catalogue

__all__ = ["Vehicle", "vehicle_kernels"]


def vehicle_kernels(params: Any, vehicle: ModuleType | None = None) -> ModuleType:
    """The generated module of the vehicle: `vehicle` (a module) or the parameters' own.

    ``params`` are parameters, a bound model (their model's own catalogue) or a namespace of numbers that
    names its ``vehicle`` (the packaged catalogue's; the paper's bogie when it names none).

    Raises
    ------
    MovingBogieError
        For a name that no generated vehicle module has, listing those that exist.
    """
    if vehicle is not None:
        return vehicle
    model = getattr(params, "model", None)
    if model is not None and not isinstance(model, str):
        return model.vehicle_kernels
    catalogue = default_catalogue()
    name = getattr(params, "vehicle", None) or DEFAULT_MODEL["vehicle"]
    declared = dict(getattr(catalogue.index, "DECLARED_VEHICLES", {}), **catalogue.index.VEHICLES)
    if name not in declared:
        raise MovingBogieError(f"vehicle must be one of {', '.join(declared)} (got {name!r})")
    return catalogue.module(f"vehicle_{name}")


def _matrix(rows: Any) -> np.ndarray:
    return np.array([[float(x) for x in row] for row in rows], dtype=float)


@dataclass(frozen=True)
class Vehicle:
    """A vehicle's matrices for one set of parameters (floats) and its motion along the beam.

    Attributes
    ----------
    dofs : tuple of str
        Names of the degrees of freedom (``DOFS`` of the generated module): the ``contacts`` wheel
        deflections first.
    contacts : int
        Number of wheels ``n``.
    offsets : ndarray, shape (n,)
        Contact positions ``xi_j`` relative to the rear wheel.
    loads : ndarray, shape (n,)
        Static wheel loads ``s_j`` (2 for the paper's load P).
    mass, damping, stiffness : ndarray, shape (n + m, n + m)
        ``M``, ``C``, ``K`` (all zero for constant moving forces).
    alpha : float
        Velocity ratio, Eq. (16).
    entry : float
        Rear-wheel position ``x0`` at ``tau = 0``.
    """

    dofs: tuple[str, ...]
    contacts: int
    offsets: np.ndarray
    loads: np.ndarray
    mass: np.ndarray
    damping: np.ndarray
    stiffness: np.ndarray
    alpha: float
    entry: float

    @classmethod
    def of(cls, params: Any, entry: float, vehicle: ModuleType | None = None) -> Vehicle:
        """The vehicle of `params` (or the given generated module), its groups read from `params`."""
        module = vehicle_kernels(params, vehicle)
        args = {}
        for name in module.MATRIX_ARGUMENTS:
            value = getattr(params, name, None)
            if value is None:
                raise MovingBogieError(f"the vehicle needs the parameter {name} (not given)")
            args[name] = float(value)
        return cls(
            dofs=tuple(module.DOFS),
            contacts=int(module.CONTACTS),
            offsets=np.array([float(x) for x in module.contact_positions(**args)]),
            loads=np.array([float(x) for x in module.static_loads(**args)]),
            mass=_matrix(module.mass_matrix(**args)),
            damping=_matrix(module.damping_matrix(**args)),
            stiffness=_matrix(module.stiffness_matrix(**args)),
            alpha=float(params.alpha),
            entry=float(entry),
        )

    def loads_only(self) -> Vehicle:
        """The same wheels as constant moving forces: the contacts only, all matrices zero."""
        n = self.contacts
        zero = np.zeros((n, n))
        return Vehicle(
            self.dofs[:n], n, self.offsets, self.loads, zero, zero, zero.copy(), self.alpha, self.entry
        )

    @property
    def forces_only(self) -> bool:
        """Whether the vehicle is loads only (all matrices zero)."""
        return not (self.mass.any() or self.damping.any() or self.stiffness.any())

    @property
    def size(self) -> int:
        """Degrees of freedom ``n + m``."""
        return len(self.dofs)

    @property
    def length(self) -> float:
        """Distance from the rear to the front contact."""
        return float(np.max(self.offsets) - np.min(self.offsets))

    def positions(self, tau: float) -> np.ndarray:
        """Contact positions ``x0 + alpha tau + xi_j`` at `tau`."""
        return self.entry + self.alpha * tau + self.offsets
