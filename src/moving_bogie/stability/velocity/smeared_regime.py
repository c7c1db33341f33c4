"""The speed regime of a model on periodic supports: that of its smeared continuous track (docs/sleepers.md
(S2)).

The smeared track (:mod:`moving_bogie.model.smeared`) is a model of the paper's kind, whose critical
velocity :func:`~moving_bogie.stability.velocity.supercritical.speed_regime` computes; the periodic track's
speed is compared with it in the periodic track's own scaling.
"""

from __future__ import annotations

from moving_bogie.model.params import DimensionlessParams
from moving_bogie.model.physical import PhysicalParams
from moving_bogie.model.smeared import smeared_physical
from moving_bogie.stability.velocity.supercritical import SpeedRegime, speed_regime

__all__ = ["smeared_regime"]


def smeared_regime(params: DimensionlessParams, physical: PhysicalParams | None) -> SpeedRegime:
    """The speed of a model on periodic supports against the critical velocity of its smeared track.

    The smeared track's v_cr (m/s, :func:`~moving_bogie.stability.velocity.supercritical.speed_regime` of
    :func:`smeared_physical`) in the periodic track's own scaling: alpha_cr = v_cr / v_ref (docs/sleepers.md
    (S2)). Without SI parameters, or for a track with no smeared limit, alpha_cr is None and the note says
    why.
    """
    alpha = float(params.alpha)
    smeared = None if physical is None else smeared_physical(physical)
    if physical is None or smeared is None:
        why = (
            "no SI parameters" if physical is None else f"{params.model.name} has no smeared continuous track"
        )
        return SpeedRegime(
            alpha, None, None, note=f"the smeared track's critical velocity is unknown ({why})"
        )
    regime = speed_regime(smeared.to_dimensionless(), smeared)
    v_ref = physical.scales().v_ref
    alpha_cr = None if regime.v_cr is None else regime.v_cr / v_ref
    supercritical = None if alpha_cr is None else alpha > alpha_cr
    note = f"v_cr of the smeared {smeared.model.track} track (the supports spread along the rail)"
    if regime.note:
        note += f"; {regime.note}"
    return SpeedRegime(alpha, alpha_cr, supercritical, v=alpha * v_ref, v_cr=regime.v_cr, note=note)
