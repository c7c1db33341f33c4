"""The steady deflection of the continuous track with the same smeared supports as a sleeper track.

The smeared track (:mod:`moving_bogie.model.smeared`, docs/sleepers.md (S2)) is a model of the paper's
kind; its steady deflection under each wheel of a vehicle moving at ``v`` is the steady part of the closed
form, ``n_X(0) / E_chr(0)`` (the paper's Eq. (39)), evaluated by the continuous model's own code
(:mod:`moving_bogie.kernels.characteristic`). The steady bay response on the supports
(:mod:`moving_bogie.response.sleeper_series`) is compared with it.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import mpmath
import numpy as np

from moving_bogie.kernels.characteristic import Characteristic

if TYPE_CHECKING:
    from moving_bogie.kernels.bound import BoundModel

__all__ = ["continuous_steady_deflection"]


def continuous_steady_deflection(bound: BoundModel, dps: int = 30) -> np.ndarray:
    """The steady rail deflection under each wheel of the smeared track's bound model, n_X(0) / E_chr(0)
    (the paper's Eq. (39)), in units of its w_st (its scales give metres).

    The wheels are the vehicle's contacts, in the order of its generated module.
    """
    chr_ = Characteristic(bound)
    contacts = chr_.system.contacts
    with mpmath.workdps(dps):
        zero = mpmath.mpc(0)
        kv = chr_.kernel_values(zero)
        E0 = chr_.system.e_chr(zero, kv.K)
        n0 = chr_.numerators(zero, kv)
        steady = [complex(n0[name] / E0) for name in chr_.names[:contacts]]
    return np.array([s.real for s in steady])
