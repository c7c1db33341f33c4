"""Seeds of the instability lines: step 1 of :mod:`~moving_bogie.stability.lines.instability_lines`.

At fixed (q, alpha), E_chr is a polynomial in theta, so its roots theta_k(q, alpha) are cheap on a whole
(alpha, q) grid. The product ``g = prod_k Im(theta_k) / (1 + |theta_k|)`` changes sign across the curves
where some theta_k is real; the vertices of its zero contour (marching squares, ``contourpy``), polished by
a minimum-norm Gauss-Newton iteration on Re E = Im E = 0 in (alpha, q, theta), are points on the curves.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import cast

import contourpy
import numpy as np

from moving_bogie.kernels.sweep_characteristic import SweepCharacteristic, poly_roots
from moving_bogie.stability.lines.continuation import gauss_newton
from moving_bogie.typing import FloatArray

__all__ = ["report", "seed_groups"]


def seed_groups(
    sweep: SweepCharacteristic,
    ds: Sequence[float],
    alpha_range: Sequence[float],
    theta_max: float,
    q_max: float,
    grid: dict[str, float],
    progress: Callable[[float], None] | None,
) -> tuple[list[tuple[float, FloatArray]], FloatArray]:
    """Seeds on an (alpha, q) grid up to ``q_max``: ((d, seed points (k, 3)) per contour polyline, the box
    ``alpha_range x (0, q_max] x (0, 1]`` in (alpha, q, theta / theta_max))."""
    a0, a1 = float(alpha_range[0]), float(alpha_range[1])
    alpha_step, q_step, tol = grid["alpha_step"], grid["q_step"], grid["tol"]
    alphas = np.linspace(a0, a1, max(3, int(round((a1 - a0) / alpha_step)) + 1))
    qs = np.linspace(q_step, q_max, max(3, int(round(q_max / q_step))))
    AA, QQ = np.meshgrid(alphas, qs, indexing="ij")
    Ks, _, _ = sweep.kernel(QQ, AA, spacings=ds)
    report(progress, 0.1)
    box = np.array([[a0, a1], [0.0, q_max], [0.0, 1.0]])
    steps = (alphas[1] - alphas[0], qs[1] - qs[0])
    lines_of: list[tuple[float, list[FloatArray]]] = []  # (d, its contour polylines)
    for j, d in enumerate(ds):
        roots = poly_roots(sweep.coefficients(QQ, Ks[j], scale=theta_max, d=d))
        g = np.prod(np.where(np.isfinite(roots), roots.imag / (1 + np.abs(roots)), 1.0), axis=-1)
        # line_type "Separate": the lines are a list of (k, 2) vertex arrays (contourpy types every line type)
        lines = cast(
            list[FloatArray],
            contourpy.contour_generator(x=alphas, y=qs, z=g.T, line_type="Separate").lines(0.0),
        )
        lines_of += [(d, lines)] if lines else []
        report(progress, 0.1 + 0.2 * (j + 1) / len(ds))

    return _seed_groups(sweep, lines_of, theta_max, tol, box, steps), box


def _seed_groups(
    sweep: SweepCharacteristic,
    lines_of: list[tuple[float, list[FloatArray]]],
    theta_max: float,
    tol: float,
    box: FloatArray,
    steps: tuple[float, float],
) -> list[tuple[float, FloatArray]]:
    """(d, seed points) per contour polyline: the vertices of every polyline of every spacing are polished
    in one batch (each vertex on its own, :func:`_seed_points`)."""
    if not lines_of:
        return []
    vertices = np.concatenate([v for _, lines in lines_of for v in lines])
    d = np.concatenate([np.full(len(v), d) for d, lines in lines_of for v in lines])
    points, inside = _seed_points(sweep, vertices, d, theta_max, tol, box, steps)
    sizes = [len(v) for _, lines in lines_of for v in lines]
    spacing = [d for d, lines in lines_of for _ in lines]
    groups = []
    for dd, span in zip(spacing, np.split(np.arange(len(points)), np.cumsum(sizes)[:-1])):
        seeds = points[span][inside[span]]
        if len(seeds):
            groups.append((dd, seeds))
    return groups


def report(progress: Callable[[float], None] | None, x: float) -> None:
    if progress is not None:
        progress(min(1.0, x))


def _seed_points(
    sweep: SweepCharacteristic,
    line: FloatArray,
    d: FloatArray,
    theta_max: float,
    tol: float,
    box: FloatArray,
    steps: tuple[float, float],
) -> tuple[FloatArray, np.ndarray]:
    """Points on the curves near the vertices of contour polylines (vertex k of spacing ``d[k]``): (points,
    inside), shapes (k, 3) in (alpha, q, t) and (k,), ``inside`` marking the polished points kept (in the
    box, theta > 0, q > 0).

    A vertex lies on a grid edge crossed by a curve, so its polished point must lie within about one
    grid cell: each candidate root theta_k (most nearly real first) is polished by Gauss-Newton, and the
    first one that converges that close is kept.
    """
    alpha0, q0 = line[:, 0].copy(), line[:, 1].copy()
    n = len(q0)
    K, _, _ = sweep.kernel(q0, alpha0, d=d)
    roots = poly_roots(sweep.coefficients(q0, K, scale=theta_max, d=d))
    with np.errstate(all="ignore"):
        score = np.abs(roots.imag) / np.abs(roots)
    score = np.where(np.isfinite(roots) & (roots.real > -0.05) & (roots.real < 1.5), score, np.inf)
    order = np.argsort(score, axis=-1)
    out = np.full((n, 3), np.nan)
    ok = np.zeros(n, dtype=bool)
    for rank in range(roots.shape[-1]):
        todo = ~ok & np.isfinite(score[np.arange(n), order[:, rank]])
        if not np.any(todo):
            break
        x = np.stack([alpha0[todo], q0[todo], roots[np.arange(n), order[:, rank]].real[todo]], axis=-1)
        x, conv = gauss_newton(sweep, x, d[todo], theta_max, tol)
        near = (np.abs(x[:, 0] - alpha0[todo]) <= 1.5 * steps[0]) & (
            np.abs(x[:, 1] - q0[todo]) <= 1.5 * steps[1]
        )
        good = conv & near
        idx = np.nonzero(todo)[0][good]
        out[idx], ok[idx] = x[good], True
    inside = ok & np.all((out >= box[:, 0]) & (out <= box[:, 1]), axis=-1) & (out[:, 2] > 0) & (out[:, 1] > 0)
    return out, inside
