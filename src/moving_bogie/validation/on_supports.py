"""The finite-rail check of a model on periodic supports from its parameters, shared by the public API and
the command line (docs/sleepers.md, "The finite rail on sleepers").

:func:`check_on_supports` assembles the sleeper track, the vehicle's matrices and its static loads from the
parameters (a :class:`~moving_bogie.model.sleeper_input.SleeperInput`, :func:`sleeper_input_of` of the one
catalogue's parameters) and runs :func:`~moving_bogie.validation.sleepers_check.check_sleepers`;
:func:`check_summary` gives its summary with the SI values beside the dimensionless ones.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from moving_bogie.errors import ParameterError
from moving_bogie.kernels.hill import VehicleMatrices
from moving_bogie.kernels.sleeper_track import SleeperTrack
from moving_bogie.model.sleeper_input import SleeperInput
from moving_bogie.response.steady_bay import static_loads
from moving_bogie.validation.sleepers_check import SleeperCheck, check_sleepers

__all__ = ["check_on_supports", "check_summary"]


def check_on_supports(
    data: SleeperInput, *, tol: float = 0.01, progress: Callable[[float], None] | None = None
) -> SleeperCheck:
    """The finite rail against the Floquet theory for the vehicle and track of ``data``.

    Raises
    ------
    ParameterError
        Naming ``v`` when the vehicle does not move, ``beam`` for a rail other than Euler-Bernoulli (the
        finite rail's elements), before any computation.
    """
    if data.groups["alpha"] <= 0:
        raise ParameterError("v", "v must be positive on a sleeper track (the vehicle must cross the bays)")
    track = SleeperTrack(data.foundation, data.groups)
    try:
        track.rail_foundation()  # the finite rail's elements: Euler-Bernoulli
    except ValueError:
        why = f"the finite rail on sleepers has Euler-Bernoulli elements (got {data.beam!r})"
        raise ParameterError("beam", why) from None
    module = data.vehicle_kernels
    vehicle = VehicleMatrices.from_module(module, data.vehicle_groups)
    loads = static_loads(module, data.vehicle_groups)
    return check_sleepers(track, vehicle, loads, tol=tol, time_scale=data.t_scale, progress=progress)


def check_summary(result: SleeperCheck, data: SleeperInput) -> dict[str, Any]:
    """The check's summary with SI values beside the dimensionless ones (rates and frequencies in 1/s and
    rad/s, forces in N: the static load 2 is P)."""
    out = {"model": f"{data.beam}/{data.track}/{data.vehicle}", **result.to_dict()}
    to_si = {"growth rate -Im q": 1 / data.t_scale, "dominant frequency": 1 / data.t_scale}
    force = data.physical.get("P", 2.0) / 2
    for item in out["comparisons"]:
        scale = to_si.get(item["quantity"], force)
        item["unit_si"] = (
            "N"
            if item["quantity"].startswith("steady")
            else ("1/s" if "rate" in item["quantity"] else "rad/s")
        )
        item["floquet_si"], item["finite_beam_si"] = item["floquet"] * scale, item["finite_beam"] * scale
    out["finite_beam"]["dt_s"] = out["finite_beam"]["dt"] * data.t_scale
    return out
