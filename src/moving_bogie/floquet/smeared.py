"""The continuous track with the same smeared supports as a sleeper track (docs/sleepers.md (S2)).

With the support groups per unit length of rail held fixed, ``l -> 0`` turns ``sleepers`` into the paper's
one-layer track with ``k_f = k_sup / l + k_f`` and ``c_f = c_sup / l + c_f``, and ``sleepers-two-layer``
(without a continuous foundation along the rail) into the two-layer track with ``k_1 = k_pad / l``,
``c_1 = c_pad / l``, ``m_2 = m_sl / l``, ``k_2 = k_bal / l``, ``c_2 = c_bal / l``. Its steady deflection
under each wheel of a vehicle moving at ``v`` is the steady part of the closed form, ``n_X(0) / E_chr(0)``
(the paper's Eq. (39)), evaluated by the continuous model's own code.
"""

from __future__ import annotations

import mpmath
import numpy as np

from moving_bogie.floquet.inputs import SleeperInput
from moving_bogie.model.physical import PhysicalParams

__all__ = ["continuous_steady_deflection", "smeared_track"]

#: the sleeper track's own SI inputs (not passed on to the continuous track as they are)
_SUPPORT_KEYS = frozenset({"l", "k_sup", "c_sup", "k_pad", "c_pad", "m_sl", "k_bal", "c_bal", "k_f", "c_f"})


def smeared_track(data: SleeperInput) -> PhysicalParams | None:
    """The continuous track with the same smeared supports in SI (None: the track has no such limit).

    ``sleepers-two-layer`` with a continuous foundation along the rail (``k_f`` or ``c_f`` > 0) has none: the
    two-layer track puts every spring under its mass layer.
    """
    si = data.physical
    values = {k: v for k, v in si.items() if k not in _SUPPORT_KEYS}
    bay = si["l"]
    if data.track == "sleepers":
        track = "one-layer"
        values |= {"k_f": si["k_sup"] / bay + si["k_f"], "c_f": si["c_sup"] / bay + si["c_f"]}
    elif data.track == "sleepers-two-layer" and si["k_f"] == 0 and si["c_f"] == 0:
        track = "two-layer"
        values |= {"k_f": si["k_pad"] / bay, "c_1": si["c_pad"] / bay, "m_2": si["m_sl"] / bay}
        values |= {"k_2": si["k_bal"] / bay, "c_2": si["c_bal"] / bay}
    else:
        return None
    return PhysicalParams(beam=data.beam, track=track, vehicle=data.vehicle, **values)


def continuous_steady_deflection(params: PhysicalParams, dps: int = 30) -> np.ndarray:
    """The steady rail deflection under each wheel [m]: n_X(0) / E_chr(0) (the paper's Eq. (39)) times w_st.

    The wheels are the vehicle's contacts, in the order of its generated module.
    """
    from moving_bogie.kernels.bound import bind
    from moving_bogie.kernels.characteristic import Characteristic

    chr_ = Characteristic(bind(params.to_dimensionless()))
    contacts = chr_.system.contacts
    with mpmath.workdps(dps):
        zero = mpmath.mpc(0)
        kv = chr_.kernel_values(zero)
        E0 = chr_.system.e_chr(zero, kv.K)
        n0 = chr_.numerators(zero, kv)
        steady = [complex(n0[name] / E0) for name in chr_.names[:contacts]]
    return np.array([s.real for s in steady]) * params.scales().w_st
