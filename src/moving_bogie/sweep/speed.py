"""The speed regime of every point of a sweep: above or below the critical velocity of its track.

alpha_cr depends on the track's groups only (:mod:`moving_bogie.stability.velocity.supercritical`), so it is
computed once per combination of the varied track groups (once in all when none varies), and the flag of
every point is a comparison: cheap enough to write with the store's metadata, before any block runs.
"""

from __future__ import annotations

import itertools
from fractions import Fraction

import numpy as np

from moving_bogie.stability.velocity.supercritical import speed_regime
from moving_bogie.sweep.design import SweepSpec

__all__ = ["MAX_TRACKS", "speed_arrays"]

#: Largest number of distinct tracks (combinations of varied track groups) whose alpha_cr is computed.
MAX_TRACKS = 64


def _track_axes(spec: SweepSpec) -> list[int]:
    """Indices of the axes that change the track (not alpha, not a damping group, not the vehicle)."""
    model = spec.params.model
    track = set(model.foundation.MODEL_PARAMETERS) - {"alpha"} - set(model.damping)
    return [k for k, a in enumerate(spec.axes) if a.name in track]


def speed_arrays(spec: SweepSpec) -> dict[str, np.ndarray] | None:
    """``alpha_cr`` and ``supercritical`` at every point of ``spec`` (arrays of its shape), or None when
    more than :data:`MAX_TRACKS` distinct tracks would need their critical velocity or one of them has
    none (:func:`~moving_bogie.stability.velocity.supercritical.speed_regime` says why)."""
    try:
        return _arrays(spec)
    except _Undetermined:
        return None


class _Undetermined(Exception):
    """A track of the sweep without a determined critical velocity."""


def _arrays(spec: SweepSpec) -> dict[str, np.ndarray] | None:
    names = [a.name for a in spec.axes]
    tracks = _track_axes(spec)
    if spec.design == "sobol":
        n = spec.shape[0]
        keys = [tuple(spec.axes[k].values[i] for k in tracks) for i in range(n)]
        if len(set(keys)) > MAX_TRACKS:
            return None
        cache: dict[tuple[Fraction, ...], float] = {}
        alpha_cr = np.empty(n)
        for i, key in enumerate(keys):
            if key not in cache:
                cache[key] = _alpha_cr(spec, {names[k]: v for k, v in zip(tracks, key)})
            alpha_cr[i] = cache[key]
        alpha = np.array([float(_value(spec, "alpha", (i,))) for i in range(n)])
        return {"alpha_cr": alpha_cr, "supercritical": alpha > alpha_cr}
    combos = list(itertools.product(*(range(len(spec.axes[k].values)) for k in tracks)))
    if len(combos) > MAX_TRACKS:
        return None
    alpha_cr = np.empty(spec.shape)
    for combo in combos:
        index: list[slice | int] = [slice(None)] * len(spec.axes)
        for k, i in zip(tracks, combo):
            index[k] = i
        alpha_cr[tuple(index)] = _alpha_cr(
            spec, {names[k]: spec.axes[k].values[i] for k, i in zip(tracks, combo)}
        )
    alpha = np.full(spec.shape, float(spec.params.alpha))
    if "alpha" in names:
        k = names.index("alpha")
        shape = [1] * len(names)
        shape[k] = -1
        alpha = np.broadcast_to(spec.axes[k].floats.reshape(shape), spec.shape)
    return {"alpha_cr": alpha_cr, "supercritical": alpha > alpha_cr}


def _alpha_cr(spec: SweepSpec, changes: dict[str, Fraction]) -> float:
    params = spec.params.replace(**(spec.fixed | changes)) if changes else spec.params
    alpha_cr = speed_regime(params).alpha_cr
    if alpha_cr is None:
        raise _Undetermined
    return alpha_cr


def _value(spec: SweepSpec, name: str, index: tuple[int, ...]) -> Fraction:
    for a in spec.axes:
        if a.name == name:
            return a.values[index[0]]
    return getattr(spec.params, name)
