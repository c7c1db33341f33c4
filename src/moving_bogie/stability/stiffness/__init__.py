"""The critical stiffness of the primary suspension (Section 3.8, Figure 16) and the D-decomposition at fixed
velocity (ref. [48]), its independent cross-check.
"""

from moving_bogie.stability.stiffness.critical_stiffness import CriticalStiffness
from moving_bogie.stability.stiffness.d_decomposition import DCrossing, DDecomposition

__all__ = [
    "CriticalStiffness",
    "DCrossing",
    "DDecomposition",
]
