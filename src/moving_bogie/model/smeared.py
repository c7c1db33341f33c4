"""The continuous track with the same smeared supports as a sleeper track (docs/sleepers.md (S2)).

With the support groups per unit length of rail held fixed, ``l -> 0`` turns ``sleepers`` into the paper's
one-layer track with ``k_f = k_sup / l + k_f`` and ``c_f = c_sup / l + c_f``, and ``sleepers-two-layer``
(without a continuous foundation along the rail) into the two-layer track with ``k_1 = k_pad / l``,
``c_1 = c_pad / l``, ``m_2 = m_sl / l``, ``k_2 = k_bal / l``, ``c_2 = c_bal / l``. Its steady deflection
under each wheel of a vehicle moving at ``v`` is the steady part of the closed form, ``n_X(0) / E_chr(0)``
(the paper's Eq. (39)), evaluated by the continuous model's own code
(:mod:`moving_bogie.response.smeared_deflection`); its critical velocity is the speed regime on the
supports (:mod:`moving_bogie.stability.velocity.smeared_regime`).
"""

from __future__ import annotations

from moving_bogie.model.physical import PhysicalParams
from moving_bogie.model.sleeper_input import SleeperInput

__all__ = ["smeared_physical", "smeared_track", "smeared_values"]

#: the sleeper track's own SI inputs (not passed on to the continuous track as they are)
_SUPPORT_KEYS = frozenset({"l", "k_sup", "c_sup", "k_pad", "c_pad", "m_sl", "k_bal", "c_bal", "k_f", "c_f"})


def smeared_track(data: SleeperInput) -> PhysicalParams | None:
    """The continuous track with the same smeared supports in SI (None: the track has no such limit).

    ``sleepers-two-layer`` with a continuous foundation along the rail (``k_f`` or ``c_f`` > 0) has none: the
    two-layer track puts every spring under its mass layer.
    """
    return smeared_values(data.beam, data.track, data.vehicle, data.physical)


def smeared_physical(physical: PhysicalParams) -> PhysicalParams | None:
    """:func:`smeared_track` of the SI parameters of a model on periodic supports."""
    model = physical.model
    values = {k: float(v) for k, v in physical.values().items()}
    return smeared_values(model.beam, model.track, model.vehicle, values)


def smeared_values(beam: str, track: str, vehicle: str, si: dict) -> PhysicalParams | None:
    """:func:`smeared_track` of the model's names and its SI values (floats)."""
    si = {"k_f": 0.0, "c_f": 0.0} | {k: v for k, v in si.items() if v is not None}
    values = {k: v for k, v in si.items() if k not in _SUPPORT_KEYS}
    bay = si["l"]
    if track == "sleepers":
        limit = "one-layer"
        values |= {"k_f": si["k_sup"] / bay + si["k_f"], "c_f": si.get("c_sup", 0.0) / bay + si["c_f"]}
    elif track == "sleepers-two-layer" and si["k_f"] == 0 and si["c_f"] == 0:
        limit = "two-layer"
        values |= {"k_f": si["k_pad"] / bay, "c_1": si.get("c_pad", 0.0) / bay, "m_2": si["m_sl"] / bay}
        values |= {"k_2": si["k_bal"] / bay, "c_2": si.get("c_bal", 0.0) / bay}
    else:
        return None
    return PhysicalParams(beam=beam, track=limit, vehicle=vehicle, **values)
