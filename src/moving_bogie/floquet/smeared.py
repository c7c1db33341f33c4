"""The continuous track of the same smeared support as a sleeper file (docs/sleepers.md, (S2) and (S22)).

For ``track = "sleepers"`` the limit l -> 0 with the support per unit length held fixed is the paper's
one-layer track with k_f = k_sup / l + k_f and c_f = c_sup / l + c_f: the same rail, vehicle and load.
"""

from __future__ import annotations

from moving_bogie.errors import ParameterError
from moving_bogie.floquet.inputs import SleeperInput
from moving_bogie.model.physical import PhysicalParams

__all__ = ["smeared_physical"]


def smeared_physical(data: SleeperInput) -> PhysicalParams:
    """The one-layer track's SI parameters of a ``sleepers`` file (a ParameterError for another track)."""
    if data.track != "sleepers":
        raise ParameterError(
            "track", f"the continuous counterpart is the one-layer track of 'sleepers' (not {data.track!r})"
        )
    si = dict(data.physical)
    bay = si.pop("l")
    si["k_f"] = si.pop("k_sup") / bay + si.get("k_f", 0.0)
    si["c_f"] = si.pop("c_sup", 0.0) / bay + si.get("c_f", 0.0)
    return PhysicalParams(beam=data.beam, track="one-layer", vehicle=data.vehicle, **si)
