"""Instability boundaries in the (alpha, theta) plane on an undamped or near-undamped foundation.

With eta_f = 0 the instability lines of :mod:`instability_lines` degenerate (real induced frequencies fill
whole regions; :mod:`undamped` explains why and states the convention). What is computed instead, for
every alpha of a grid ``alpha_step`` apart: the values of theta where the number of unstable induced
frequencies changes, found by counts on a grid of theta and bisection (:func:`undamped.boundaries`), of
two kinds:

* ``"undamped"``: the boundary at eta_f = 0 exactly (K on the cut from below; real roots neutral);
* ``"limit"``: the boundary in the limit eta_f -> 0+ (real roots that small foundation damping
  destabilises count as unstable). For 0 < eta_f < :data:`~undamped.NEAR_UNDAMPED` it is the answer, to
  first order in eta_f.

Boundary points of one kind at neighbouring alphas with the same counts on both sides and theta values
closer than ``join`` times theta_max are joined into branches (polylines through exact boundary points;
between two alphas of the grid the polyline is an interpolation). Each point carries the counts at the two
ends of its bisection bracket (``verified``) and the unstable side.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from moving_bogie.kernels.bound import BoundModel
from moving_bogie.stability.lines.line_results import InstabilityBranch, InstabilityLines
from moving_bogie.stability.maps.column import exact
from moving_bogie.stability.maps.undamped import (
    Boundary,
    UndampedCounter,
    boundaries,
    parameter_grid,
    regime,
    uncertain_warning,
)
from moving_bogie.typing import FloatArray

__all__ = ["KIND_TEXT", "undamped_branches", "undamped_lines"]

#: One sentence per kind of undamped boundary (text output, JSON, legend).
KIND_TEXT = {
    "crossing": "a real induced frequency (E_chr = 0 with q real)",
    "undamped": "boundary of instability at eta_f = 0 exactly",
    "limit": "boundary of instability in the limit eta_f -> 0+ (real roots destabilised by small eta_f)",
}


def undamped_branches(
    bound: BoundModel,
    ds: Sequence[float],
    parameter: str,
    alpha_range: tuple[float, float],
    theta_max: float,
    *,
    alpha_step: float = 0.02,
    grid_points: int = 40,
    tol: float = 1e-3,
    join: float = 0.5,
    progress: Callable[[float], None] | None = None,
) -> tuple[list[InstabilityBranch], list[str], str]:
    """Branches of undamped boundaries (module text); returns ``(branches, warnings, method)``.

    ``grid_points`` values of theta (and 5 geometric ones down to theta_max / 1000) are counted at every
    alpha; changes are bisected to ``tol * theta_max``.
    """
    a0, a1 = float(alpha_range[0]), float(alpha_range[1])
    alphas = np.linspace(a0, a1, max(2, int(round((a1 - a0) / alpha_step)) + 1))
    grid = parameter_grid(theta_max, grid_points)
    params = bound.params
    kinds = ("undamped", "limit") if regime(params.eta_f) == "undamped" else ("limit",)
    branches: list[InstabilityBranch] = []
    warnings: list[str] = []
    total = len(ds) * len(alphas)
    for j, d in enumerate(ds):
        margin = 100 * float(params.eta_f)
        counter = UndampedCounter(bound.replace(d=exact(d)), parameter, margin=margin)
        points: list[Boundary] = []
        unsure: dict[float, int] = {}
        for i, a in enumerate(alphas):
            bounds, _, unsure[float(a)] = boundaries(counter, float(a), grid, tol=tol * theta_max)
            points += [b for b in bounds if b.kind in kinds]
            if progress is not None:
                progress((j * len(alphas) + i + 1) / total)
        warnings += uncertain_warning(f"d={d:g}: ", unsure, margin)
        for kind in kinds:
            for chain in _join([b for b in points if b.kind == kind], alphas, join * theta_max):
                branches.append(_branch(float(d), kind, chain))
    branches.sort(key=lambda b: (b.d, b.kind, b.alpha.min()))
    method = (
        f"counts of unstable induced frequencies (argument principle, K on the cut from below) on "
        f"{len(grid)} values of {parameter} at {len(alphas)} velocities {alphas[1] - alphas[0]:.3g} apart, "
        f"every change bisected to {tol * theta_max:.2g}; branches join the boundary points of neighbouring "
        "velocities (features narrower than one velocity step, or two changes within one grid step, can be "
        "missed)"
    )
    return branches, warnings, method


def undamped_lines(
    bound: BoundModel,
    ds: Sequence[float],
    parameter: str,
    alpha_range: tuple[float, float],
    theta_max: float,
    **options: Any,
) -> InstabilityLines:
    """:class:`~moving_bogie.stability.lines.line_results.InstabilityLines` of undamped boundaries (``q_max``
    None); ``options`` go to :func:`undamped_branches`."""
    branches, warnings, method = undamped_branches(bound, ds, parameter, alpha_range, theta_max, **options)
    params = bound.params
    a0, a1 = (float(a) for a in alpha_range)
    unique = tuple(dict.fromkeys(warnings))
    return InstabilityLines(
        params, params.vehicle, parameter, (a0, a1), float(theta_max), tuple(branches), unique, None, method
    )


def _join(points: list[Boundary], alphas: FloatArray, jump: float) -> list[list[Boundary]]:
    """Chains of boundary points: same counts on both sides, consecutive alphas, theta within ``jump``."""
    index = {float(a): i for i, a in enumerate(alphas)}
    open_: list[list[Boundary]] = []
    done: list[list[Boundary]] = []
    for i in range(len(alphas)):
        here = sorted((b for b in points if index[b.alpha] == i), key=lambda b: b.theta)
        still = []
        free = list(here)
        for chain in open_:
            last = chain[-1]
            options = [
                b
                for b in free
                if (b.count_below, b.count_above) == (last.count_below, last.count_above)
                and abs(b.theta - last.theta) <= jump
            ]
            if index[last.alpha] == i - 1 and options:
                best = min(options, key=lambda b: abs(b.theta - last.theta))
                free.remove(best)
                chain.append(best)
                still.append(chain)
            else:
                done.append(chain)
        open_ = still + [[b] for b in free]
    return done + open_


def _branch(d: float, kind: str, chain: list[Boundary]) -> InstabilityBranch:
    """The :class:`InstabilityBranch` of one chain of boundary points (kind "undamped" or "limit")."""
    n = len(chain)
    k = n // 2
    mid = chain[k]
    return InstabilityBranch(
        d=d,
        alpha=np.array([b.alpha for b in chain]),
        theta=np.array([b.theta for b in chain]),
        q=np.full(n, np.nan),
        unstable_above=np.array([b.count_above > b.count_below for b in chain]),
        residual=np.full(n, np.nan),
        verified=(mid.alpha, mid.low, mid.count_below, mid.high, mid.count_above),
        kind=kind,
        mechanism=tuple(b.mechanism for b in chain),
    )
