"""Several parameter sets of one model in one call of :class:`SweepCharacteristic`'s vectorised kernels.

The panels of a stability figure differ in a few parameters (eta_f, cf2, eta_v, S, r) of the same track
and vehicle. E_chr, its kernel K and their derivatives are evaluated point by point (every operation of
:meth:`SweepCharacteristic.kernel` and of the generated functions acts elementwise), so a point may as well
carry its own parameter values: :meth:`StackedSweep.at` returns a :class:`SweepCharacteristic` whose track
and vehicle arguments are arrays, one value per point, taken from the member each point belongs to. One
call then serves points of every member, which matters when each member has few points per call (the
continuation of instability lines).
"""

from __future__ import annotations

import copy
from collections.abc import Hashable, Sequence
from typing import Any

import numpy as np

from moving_bogie.kernels.sweep_characteristic import SweepCharacteristic

__all__ = ["StackedSweep", "stack_key"]


def stack_key(sweep: SweepCharacteristic) -> Hashable:
    """Sweeps with equal keys can be stacked: same track and vehicle modules, same swept parameter, the
    closed form of Eq. (38) (no block system), same limit on the cut and the same held groups."""
    followers = tuple((group, depends) for group, _, _, depends in sweep.followers)
    return (
        sweep.foundation,
        sweep.module,
        sweep.parameter,
        sweep.blocks is None,
        sweep.below,
        sweep.held,
        followers,
        tuple(sorted(sweep.track_args)),
        tuple(sorted(sweep.base)),
    )


class StackedSweep:
    """The members (sweeps of one :func:`stack_key`) evaluated together, each point with its member's
    parameters."""

    def __init__(self, members: Sequence[SweepCharacteristic]) -> None:
        keys = {stack_key(m) for m in members}
        if len(keys) != 1 or members[0].blocks is not None:
            raise ValueError("only sweeps of one model with the closed form of Eq. (38) can be stacked")
        self.members = list(members)
        self._track = {k: _column([m.track_args[k] for m in members]) for k in members[0].track_args}
        self._base = {k: _column([m.base[k] for m in members]) for k in members[0].base}
        self._values = [
            _column([m.followers[j][2] for m in members]) for j in range(len(members[0].followers))
        ]

    def at(self, member: np.ndarray) -> SweepCharacteristic:
        """A sweep whose parameters at point k are those of ``members[member[k]]``."""
        if len(self.members) == 1:
            return self.members[0]
        sweep = copy.copy(self.members[0])
        sweep.track_args = {k: _pick(v, member) for k, v in self._track.items()}
        sweep.base = {k: _pick(v, member) for k, v in self._base.items()}
        sweep.followers = [
            (group, set_by, _pick(values, member), depends)
            for (group, set_by, _, depends), values in zip(self.members[0].followers, self._values)
        ]
        return sweep


def _column(values: list[Any]) -> Any:
    """The members' values of one argument: an array, or the common value when they all agree."""
    first = values[0]
    if all(v is first or v == first for v in values):
        return first
    return np.asarray(values)


def _pick(values: Any, member: np.ndarray) -> Any:
    return values[member] if isinstance(values, np.ndarray) else values
