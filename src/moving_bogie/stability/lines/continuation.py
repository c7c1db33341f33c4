"""Pseudo-arclength continuation of the curves E_chr(q; alpha, theta) = 0 with q real (Section 3.5).

The curves live in (alpha, q, t = theta / theta_max); their tangent is the cross product of the gradients
of Re E and Im E, the corrector is Newton on the bordered 3x3 system, and many curves advance together
(vectorised numpy; each curve carries its own wheel spacing d). dE/dalpha comes from residues like dE/dq
(:meth:`~moving_bogie.kernels.sweep_characteristic.SweepCharacteristic.derivatives`).

Every traced curve records why each of its two ends is where it is (:data:`END_REASONS`): it left the box
``alpha_range x (0, q_max] x (0, theta_max]`` through one of its faces (the end point is placed on the face),
it closed on itself, or the continuation stalled (the step fell below ``h_min``: a singular point, where two
lines cross or the curve has a double point).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import TypeAlias

import numpy as np

from moving_bogie.kernels.sweep_characteristic import SweepCharacteristic
from moving_bogie.typing import ComplexArray, FloatArray

__all__ = ["END_REASONS", "PathTracer", "covered", "evaluate", "gauss_newton"]

#: A traced curve: its wheel spacing d, its points (k, 3) in (alpha, q, t) and why each end is there.
TracedPath: TypeAlias = tuple[float, FloatArray, tuple[str, str]]

#: Why a traced curve ends, by box face (coordinate, low/high) or event.
END_REASONS = {
    (0, 0): "alpha_min",
    (0, 1): "alpha_max",
    (1, 0): "q_zero",
    (1, 1): "q_max",
    (2, 0): "theta_zero",
    (2, 1): "theta_max",
}


def evaluate(
    sweep: SweepCharacteristic, x: FloatArray, d: FloatArray, scale: float | FloatArray
) -> tuple[FloatArray, FloatArray, ComplexArray, ComplexArray, ComplexArray]:
    """F = (Re E, Im E) and the 2x3 real Jacobian in (alpha, q, t = theta/scale) at points x (n, 3),
    with E, dE/dq and dE/dtheta there."""
    E, E_q, E_a, E_t = sweep.derivatives(x[:, 1].astype(complex), x[:, 0], x[:, 2] * scale, d=d)
    assert E_t is not None  # theta is given

    cols = np.stack([E_a, E_q, E_t * scale], axis=-1)
    F = np.stack([E.real, E.imag], axis=-1)
    J = np.stack([cols.real, cols.imag], axis=-2)
    return F, J, E, E_q, E_t


def gauss_newton(
    sweep: SweepCharacteristic,
    x: FloatArray,
    d: FloatArray,
    scale: float | FloatArray,
    tol: float | FloatArray,
    max_iter: int = 12,
) -> tuple[FloatArray, np.ndarray]:
    """Minimum-norm Gauss-Newton onto the curve Re E = Im E = 0; returns (x, converged)."""
    x = np.array(x, dtype=float)
    conv = np.zeros(len(x), dtype=bool)
    for _ in range(max_iter):
        F, J, *_ = evaluate(sweep, x, d, scale)
        with np.errstate(all="ignore"):
            y = np.linalg.solve(J @ np.swapaxes(J, -1, -2), F[..., None])
            step = -(np.swapaxes(J, -1, -2) @ y)[..., 0]
        size = np.max(np.abs(step), axis=-1)
        step = np.where(
            (size > 0.05)[:, None], step * (0.05 / np.where(size > 0.05, size, 1.0))[:, None], step
        )
        x = np.where(conv[:, None], x, x + step)
        conv |= size < tol
        if np.all(conv | ~np.isfinite(size)):
            break
    return x, conv & np.all(np.isfinite(x), axis=-1)


def newton_fixed(
    sweep: SweepCharacteristic,
    x: FloatArray,
    d: FloatArray,
    k: int,
    value: float,
    scale: float | FloatArray,
    tol: float | FloatArray,
    max_iter: int = 12,
) -> tuple[FloatArray, np.ndarray]:
    """Newton in the two coordinates other than ``k`` with x[k] = value (end points on the box)."""
    x = np.array(x, dtype=float)
    x[:, k] = value
    free = [i for i in range(3) if i != k]
    conv = np.zeros(len(x), dtype=bool)
    for _ in range(max_iter):
        F, J, *_ = evaluate(sweep, x, d, scale)
        with np.errstate(all="ignore"):
            step = -np.linalg.solve(J[..., free], F[..., None])[..., 0]
        size = np.max(np.abs(step), axis=-1)
        step = np.where(
            (size > 0.05)[:, None], step * (0.05 / np.where(size > 0.05, size, 1.0))[:, None], step
        )
        x[:, free] = np.where(conv[:, None], x[:, free], x[:, free] + step)
        conv |= size < tol
        if np.all(conv | ~np.isfinite(size)):
            break
    return x, conv & np.all(np.isfinite(x), axis=-1)


def tangent(J: FloatArray, previous: FloatArray | None = None) -> FloatArray:
    """Unit tangent of the curves (cross product of the rows of J), oriented along ``previous``."""
    T = np.cross(J[:, 0, :], J[:, 1, :])
    T /= np.linalg.norm(T, axis=-1, keepdims=True)
    if previous is not None:
        T *= np.sign(np.sum(T * previous, axis=-1, keepdims=True) + 1e-300)
    return T


class PathTracer:
    """Pseudo-arclength continuation of many curves at once (vectorised over the curves).

    Each curve carries its own wheel spacing d, so that all spacings of a figure advance together.
    It holds one panel's settings, its rounds of seeds (:meth:`begin`, :meth:`start_round`,
    :meth:`end_round`) and the curves traced; the steps themselves are taken by
    :func:`~moving_bogie.stability.lines.walkers.trace_all_many`, alone or with the tracers of other panels
    (sharing their calls, each tracer's curves the same).
    """

    def __init__(
        self,
        sweep: SweepCharacteristic,
        scale: float,
        box: FloatArray,
        h_max: float,
        tol: float,
        *,
        h_min: float = 1e-6,
        max_steps: int = 4000,
        progress: Callable[[float], None] | None = None,
    ) -> None:
        self.sweep, self.scale, self.box = sweep, scale, box
        self.h_max, self.tol, self.h_min, self.max_steps = h_max, tol, h_min, max_steps
        self.progress = progress
        self.warnings: list[str] = []
        self.paths: list[TracedPath] = []  # the curves traced (end_round)
        self.pending: list[tuple[float, FloatArray]] = []  # (d, seeds) not yet on a traced curve
        self.total = 1  # seeds at the start

    def begin(self, groups: Iterable[tuple[float, FloatArray]]) -> None:
        """Start tracing the seed ``groups`` (d, seeds): no curve yet, every seed pending."""
        self.paths, self.pending = [], list(groups)
        self.total = max(1, sum(len(g) for _, g in self.pending))

    def start_round(self) -> tuple[FloatArray, FloatArray]:
        """The seeds of the next round: the middle seed of every group not yet on a traced curve."""
        starts = np.array([g[len(g) // 2] for _, g in self.pending])
        return starts, np.array([d for d, _ in self.pending])

    def end_round(self, new: list[TracedPath]) -> None:
        """Keep the new curves not already traced; use up the seeds lying on a traced curve."""
        paths, pending = self.paths, self.pending
        for d, path, ends in sorted(new, key=lambda item: -len(item[1])):
            if not any(
                od == d and covered(path, other, 0.3 * self.h_max).mean() > 0.9 for od, other, _ in paths
            ):
                paths.append((d, path, ends))
        remaining = []
        for d, g in pending:
            hit = [covered(g, p, 0.3 * self.h_max) for od, p, _ in paths if od == d]
            left = g[~np.any(hit, axis=0)] if hit else g
            if len(left):
                remaining.append((d, left))
        self.pending = remaining
        if sum(len(g) for _, g in remaining) >= sum(len(g) for _, g in pending):
            self.warnings.append(f"{sum(len(g) for _, g in remaining)} seed point(s) could not be traced")
            self.pending = []
        elif self.progress is not None:
            self.progress(1 - sum(len(g) for _, g in remaining) / self.total)

    def outside(self, y: FloatArray) -> tuple[int, float] | None:
        """(coordinate, bound value) of the first box face crossed, or None."""
        for k in range(3):
            lo, hi = self.box[k]
            if y[k] < lo:
                return k, lo
            if y[k] > hi:
                return k, hi
        return None


def covered(points: FloatArray, path: FloatArray, radius: float) -> np.ndarray:
    """Boolean mask: points within ``radius`` of the polyline ``path`` (both (n, 3))."""
    if len(path) < 2:
        return np.linalg.norm(points - path[0], axis=-1) < radius
    a, b = path[:-1], path[1:]
    ab = b - a
    L2 = np.maximum(np.sum(ab * ab, axis=-1), 1e-300)
    ap = points[:, None, :] - a[None, :, :]
    s = np.clip(np.sum(ap * ab[None], axis=-1) / L2[None], 0, 1)
    dist = np.linalg.norm(ap - s[..., None] * ab[None], axis=-1)
    return dist.min(axis=-1) < radius
