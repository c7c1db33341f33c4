"""The speed regime: the critical velocity of a constant moving force (Eqs. (65)-(66)) on any track, and
whether a vehicle moves above it.
"""

from moving_bogie.stability.velocity.critical_velocity import (
    CriticalVelocity,
    PhaseSpeedMinimum,
    dispersion_branches,
    phase_speed,
)
from moving_bogie.stability.velocity.supercritical import SUPERCRITICAL_MEANING, SpeedRegime, speed_regime

__all__ = [
    "CriticalVelocity",
    "PhaseSpeedMinimum",
    "SUPERCRITICAL_MEANING",
    "SpeedRegime",
    "dispersion_branches",
    "phase_speed",
    "speed_regime",
]
