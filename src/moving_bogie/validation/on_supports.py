"""The finite-rail check of a model on periodic supports from its bound model, shared by the public API and
the command line (docs/sleepers.md, "The finite rail on sleepers").

:func:`check_on_supports` takes what the continuous tracks' check takes, the bound model (on its
:class:`~moving_bogie.kernels.periodic_track.PeriodicTrack`) and the SI scales of its parameters, and runs
:func:`~moving_bogie.validation.sleepers_check.check_sleepers` on its sleeper track, vehicle and static
loads, and gives what the continuous tracks' check gives, a
:class:`~moving_bogie.validation.verdict.ValidationResult`: each compared quantity, the verdict, the wall
times, and in its ``supports`` the :class:`~moving_bogie.validation.sleeper_verdict.SleeperCheck` (the
runs, the fits, the Floquet side), which names the model and gives its values in SI beside the
dimensionless ones (``to_dict()``).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import replace
from typing import TYPE_CHECKING

from moving_bogie.errors import ParameterError
from moving_bogie.kernels.bound import BoundModel
from moving_bogie.kernels.hill import VehicleMatrices
from moving_bogie.kernels.periodic_track import PeriodicTrack
from moving_bogie.response.steady_bay import static_loads
from moving_bogie.validation.sleeper_verdict import Comparison, SleeperCheck
from moving_bogie.validation.sleepers_check import check_sleepers
from moving_bogie.validation.verdict import QuantityComparison, ValidationResult

if TYPE_CHECKING:
    from moving_bogie.model.scales import Scales

__all__ = ["check_on_supports"]


def check_on_supports(
    bound: BoundModel,
    scales: Scales | None = None,
    *,
    tol: float = 0.01,
    progress: Callable[[float], None] | None = None,
) -> ValidationResult:
    """The finite rail against the Floquet theory for the vehicle and track of ``bound``.

    Parameters
    ----------
    bound : BoundModel
        Parameters on periodic supports bound to their track (``moving_bogie.bind``).
    scales : Scales, optional
        The SI scales of the parameters (``PhysicalParams.scales()``): the notes, the figure and
        ``to_dict()`` then give SI values too.
    tol : float
        Relative tolerance of each comparison.
    progress : callable, optional
        Called with the fraction of the work done (0..1).

    Raises
    ------
    ParameterError
        Naming ``track`` for a track without periodic supports, ``v`` when the vehicle does not move,
        ``beam`` for a rail other than Euler-Bernoulli (the finite rail's elements), before any computation.
    """
    track = bound.track
    if not isinstance(track, PeriodicTrack):
        raise ParameterError("track", f"{bound.name}: the finite rail on sleepers needs periodic supports")
    sleepers = track.sleepers
    if sleepers.alpha <= 0:
        raise ParameterError("v", "v must be positive on a sleeper track (the vehicle must cross the bays)")
    try:
        sleepers.rail_foundation()  # the finite rail's elements: Euler-Bernoulli
    except ValueError:
        why = f"the finite rail on sleepers has Euler-Bernoulli elements (got {sleepers.beam!r})"
        raise ParameterError("beam", why) from None
    vehicle = VehicleMatrices.of(bound)
    loads = static_loads(bound.vehicle, bound.vehicle_values(bound.floats))
    time_scale = None if scales is None else scales.t_scale
    result = check_sleepers(sleepers, vehicle, loads, tol=tol, time_scale=time_scale, progress=progress)
    return validation_result(replace(result, model=bound.name, scales=scales, params=bound.params), tol)


def _quantity(c: Comparison) -> QuantityComparison:
    """A comparison as the continuous check's: the difference (``relative`` times the Floquet value, the
    force's peak-to-peak for the steady force) against that Floquet value as the amplitude."""
    amplitude = abs(c.floquet)
    diff = c.relative * amplitude if math.isfinite(c.relative) else abs(c.finite - c.floquet)
    return QuantityComparison(c.quantity, diff, amplitude, c.relative, c.tolerance)


def validation_result(check: SleeperCheck, tol: float) -> ValidationResult:
    """The check on supports as the one result type of a check (its ``supports``; the free run's times as
    ``tau``, its fit window as ``window``)."""
    assert check.params is not None and check.model is not None  # named by check_on_supports
    return ValidationResult(
        model=check.model,
        params=check.params,
        tau=check.free.tau,
        finite=None,
        reference=None,
        closed=None,
        window=check.fit.window,
        quantities={c.quantity: _quantity(c) for c in check.comparisons},
        finite_beam_s=check.finite_s,
        reference_s=0.0,
        closed_form_s=check.floquet_s,
        tolerance=tol,
        reflection_level=math.nan,
        notes=check.notes,
        supports=check,
    )
