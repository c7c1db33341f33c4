"""Instability lines (Figures 3, 4, 7, 8): where an induced frequency is real.

In the plane of the velocity alpha and a vehicle parameter theta (the wheel mass eta_M in the paper;
kappa_v for Figure 16), the number of unstable induced frequencies (Im q < 0) can only change where a
root of E_chr(q) = 0 (Eq. (48)) crosses the real q-axis. With foundation damping (eta_f > 0) the cut of K
lies at Im q = eta_f > 0, so a real q is an ordinary point and every crossing changes the count by one
(Section 3.5). The instability lines are the curves

    E_chr(q; alpha, theta) = 0  with q real, q > 0, 0 < theta <= theta_max,

two real equations in three real unknowns (alpha, q, theta).

Method
------
1. Seeds. At fixed (q, alpha), E_chr is a polynomial in theta (:mod:`stability_kernel`), so its roots
   theta_k(q, alpha) are cheap on a whole grid. A real solution is a point where some theta_k is real:
   the product ``g = prod_k Im(theta_k) / (1 + |theta_k|)`` changes sign across these curves (no labelling
   of the roots needed), and the vertices of its zero contour (marching squares, ``contourpy``), polished
   by a minimum-norm Gauss-Newton iteration on Re E = Im E = 0 in (alpha, q, theta), are points on the
   curves. The contour alone is not enough: where a curve runs nearly parallel to the theta axis (a
   double root in theta; the nearly vertical pieces of the bogie's lines) its projection on the
   (alpha, q) grid degenerates into specks.
2. Tracing. From the seeds, every curve is followed in 3-D by pseudo-arclength continuation (tangent =
   cross product of the gradients of Re E and Im E, Newton corrector on the bordered 3x3 system, step
   control), all curves advancing together in vectorised numpy; dE/dalpha comes from residues like
   dE/dq (:meth:`SweepCharacteristic.derivatives`). A curve ends where it leaves the box
   ``alpha_range x (0, q_max] x (0, theta_max]`` (the end point is placed on the box face) or closes on
   itself. Seeds lying on a traced curve are used up; duplicates are dropped
   (:mod:`~moving_bogie.stability.lines.continuation`).
3. Ends. Every line records why it stops (:mod:`~moving_bogie.stability.lines.line_ends`): the plot's edge, or
   inside the plot (q_max, which is then raised automatically; q = 0; a singular point), and its folds
   (tips where the root touches the real axis and the line turns back).

Undamped and near-undamped foundations (eta_f = 0, or 0 < eta_f < 1e-5): the curves degenerate (real
induced frequencies fill whole regions); boundaries of instability located by root counts are returned
instead (:mod:`undamped_lines`; convention and kinds "undamped", "limit" in :mod:`undamped`).

Which side is unstable follows from the implicit function theorem: at fixed alpha, the real root moves
as dq/dtheta = -E_theta / E_q, so the side of larger theta is the unstable one (one more root with
Im q < 0) when Im(dq/dtheta) < 0. This is the D-decomposition rule of hatching written pointwise; the
tests confirm it with :func:`~moving_bogie.roots.frequencies.induced_frequencies` on both sides.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from fractions import Fraction
from typing import cast

import contourpy
import numpy as np

from moving_bogie.kernels.bound import BoundModel
from moving_bogie.kernels.sweep_characteristic import SweepCharacteristic, poly_roots
from moving_bogie.stability.lines.continuation import PathTracer, evaluate, gauss_newton
from moving_bogie.stability.lines.line_ends import find_folds, line_end
from moving_bogie.stability.lines.line_results import InstabilityBranch, InstabilityLines
from moving_bogie.stability.lines.undamped_lines import undamped_lines
from moving_bogie.stability.maps.undamped import regime
from moving_bogie.typing import FloatArray

__all__ = ["InstabilityBranch", "InstabilityLines", "instability_lines"]

_ALPHA_STEP_FD = 1e-6


def instability_lines(
    bound: BoundModel,
    *,
    spacings: Sequence[float] | None = None,
    parameter: str | None = None,
    alpha_range: tuple[float, float] = (0.0, 1.2),
    theta_max: float = 200.0,
    q_max: float = 1.5,
    q_max_cap: float | None = None,
    alpha_step: float = 0.01,
    q_step: float = 0.004,
    h_max: float = 0.01,
    tol: float = 1e-11,
    verify: bool = False,
    progress: Callable[[float], None] | None = None,
) -> InstabilityLines:
    """Instability lines in the (alpha, theta) plane, Section 3.5 (Figures 3, 4, 7, 8).

    Parameters
    ----------
    bound : BoundModel
        All parameters except alpha and ``parameter`` (their values in ``bound`` are ignored); with
        ``parameter="eta_M"``, mu_v = cf1 eta_M and J_b = cf2 eta_M d^2 (Eq. (63)) use the cf1, cf2 of
        ``bound``. With eta_f = 0 or 0 < eta_f < 1e-5 the lines degenerate and boundaries located by
        counts are returned instead (module text; ``alpha_step`` is then the step of the velocity grid,
        at least 0.02, and ``q_max``, ``q_step``, ``h_max``, ``tol``, ``verify`` are not used).
    spacings : sequence of float, optional
        Wheel spacings d to trace (default: the parameters' d); they share the track kernel of the scan.
    parameter : str, optional
        The vertical axis, a vehicle parameter E_chr is a polynomial in (eta_M, kappa_v, eta_v, ...;
        default the wheel mass, ``Model.wheel_mass``).
    alpha_range : (float, float)
        Velocity range.
    theta_max : float
        Upper end of the parameter range (the lower end is 0).
    q_max : float
        Largest real induced frequency searched at first; while a line reaches it, it is doubled (up to
        ``q_max_cap``) and the lines are traced again. A line still reaching it is reported in ``warnings``.
    q_max_cap : float
        Largest q_max tried (default 8 times ``q_max``).
    alpha_step, q_step : float
        Grid steps of the seed scan: features smaller than a grid cell in both alpha and q (and not
        connected to a larger one) can be missed.
    h_max : float
        Largest continuation step in the scaled coordinates (alpha, q, theta / theta_max).
    tol : float
        Newton tolerance (max norm of the correction in the same coordinates).
    verify : bool
        For every branch, count the unstable induced frequencies with
        :func:`~moving_bogie.roots.frequencies.induced_frequencies` 2 % below and above its middle point
        (in theta, at fixed alpha) and store them in ``verified`` (about one second per branch).
    progress : callable, optional
        Called with the fraction of work done.
    """
    params = bound.params
    parameter = parameter or params.model.wheel_mass
    ds = [float(params.d)] if spacings is None else [float(d) for d in spacings]
    a0, a1 = (float(a) for a in alpha_range)
    if regime(params.eta_f) != "damped":
        step = max(alpha_step, 0.02)
        return undamped_lines(bound, ds, parameter, (a0, a1), theta_max, alpha_step=step, progress=progress)
    sweep = SweepCharacteristic(bound, parameter)
    cap = 8 * q_max if q_max_cap is None else q_max_cap
    grid = dict(alpha_step=alpha_step, q_step=q_step, h_max=h_max, tol=tol)
    branches, warnings, q_max = _trace_up_to_cap(
        sweep, ds, alpha_range, theta_max, q_max, cap, grid, progress
    )
    if verify:
        branches = [_verify(bound, parameter, b) for b in branches]
    _report(progress, 1.0)
    return InstabilityLines(
        params,
        params.vehicle,
        parameter,
        (a0, a1),
        float(theta_max),
        tuple(branches),
        tuple(dict.fromkeys(warnings)),
        float(q_max),
    )


def _trace_up_to_cap(
    sweep: SweepCharacteristic,
    ds: list[float],
    alpha_range: tuple[float, float],
    theta_max: float,
    q_max: float,
    cap: float,
    grid: dict[str, float],
    progress: Callable[[float], None] | None,
) -> tuple[list[InstabilityBranch], list[str], float]:
    """:func:`_trace` up to ``q_max``, doubled (up to ``cap``) while a line reaches it: the branches, the
    warnings (first, that a line still reaches the cap) and the last ``q_max``."""
    while True:
        branches, warnings = _trace(sweep, ds, alpha_range, theta_max, q_max, grid, progress)
        reaches = any(e.reason == "q_max" for b in branches for e in b.ends)
        if not reaches or 2 * q_max > cap:
            break
        q_max *= 2
    if reaches:
        warnings.insert(0, f"a line reaches q_max={q_max:g} (the cap); raise q_max_cap")
    return branches, warnings, q_max


def _trace(
    sweep: SweepCharacteristic,
    ds: Sequence[float],
    alpha_range: Sequence[float],
    theta_max: float,
    q_max: float,
    grid: dict[str, float],
    progress: Callable[[float], None] | None,
) -> tuple[list[InstabilityBranch], list[str]]:
    """Seeds on an (alpha, q) grid, then continuation: the branches in the box up to ``q_max``."""
    a0, a1 = float(alpha_range[0]), float(alpha_range[1])
    alpha_step, q_step, tol = grid["alpha_step"], grid["q_step"], grid["tol"]
    alphas = np.linspace(a0, a1, max(3, int(round((a1 - a0) / alpha_step)) + 1))
    qs = np.linspace(q_step, q_max, max(3, int(round(q_max / q_step))))
    AA, QQ = np.meshgrid(alphas, qs, indexing="ij")
    Ks, _, _ = sweep.kernel(QQ, AA, spacings=ds)
    _report(progress, 0.1)
    box = np.array([[a0, a1], [0.0, q_max], [0.0, 1.0]])
    steps = (alphas[1] - alphas[0], qs[1] - qs[0])
    groups: list[tuple[float, FloatArray]] = []  # (d, seed points) per contour polyline
    for j, d in enumerate(ds):
        roots = poly_roots(sweep.coefficients(QQ, Ks[j], scale=theta_max, d=d))
        g = np.prod(np.where(np.isfinite(roots), roots.imag / (1 + np.abs(roots)), 1.0), axis=-1)
        # line_type "Separate": the lines are a list of (k, 2) vertex arrays (contourpy types every line type)
        lines = cast(
            list[FloatArray],
            contourpy.contour_generator(x=alphas, y=qs, z=g.T, line_type="Separate").lines(0.0),
        )
        if lines:  # every polyline's vertices polished in one batch (each vertex on its own)
            points, inside = _seed_points(sweep, np.concatenate(lines), d, theta_max, tol, box, steps)
            for span in np.split(np.arange(len(points)), np.cumsum([len(line) for line in lines])[:-1]):
                seeds = points[span][inside[span]]
                if len(seeds):
                    groups.append((d, seeds))
        _report(progress, 0.1 + 0.2 * (j + 1) / len(ds))
    tracer = PathTracer(
        sweep, theta_max, box, grid["h_max"], tol, progress=lambda x: _report(progress, 0.3 + 0.7 * x)
    )
    branches = [
        _branch(sweep, d, path, theta_max, ends, a1 - a0) for d, path, ends in tracer.trace_all(groups)
    ]
    branches.sort(key=lambda b: (b.d, b.alpha.min()))
    return branches, list(tracer.warnings)


def _verify(bound: BoundModel, parameter: str, branch: InstabilityBranch) -> InstabilityBranch:
    """Unstable counts by induced_frequencies just below and above the branch's middle point."""
    from dataclasses import replace

    from moving_bogie.roots.frequencies import induced_frequencies

    k = len(branch.alpha) // 2
    a, theta = branch.alpha[k], branch.theta[k]
    base = bound.replace(alpha=_exact(a), d=_exact(branch.d))
    counts = []
    for t in (theta * 0.98, theta * 1.02):
        res = induced_frequencies(base.replace(**{parameter: _exact(t)}), dps=20)
        counts.append(len(res.unstable_roots))
    return replace(
        branch, verified=(float(a), float(theta * 0.98), counts[0], float(theta * 1.02), counts[1])
    )


def _exact(x: float) -> Fraction:
    return Fraction(str(x))


def _report(progress: Callable[[float], None] | None, x: float) -> None:
    if progress is not None:
        progress(min(1.0, x))


def _seed_points(
    sweep: SweepCharacteristic,
    line: FloatArray,
    d: float,
    theta_max: float,
    tol: float,
    box: FloatArray,
    steps: tuple[float, float],
) -> tuple[FloatArray, np.ndarray]:
    """Points on the curves near the vertices of contour polylines: (points, inside), shapes (k, 3) in
    (alpha, q, t) and (k,), ``inside`` marking the polished points kept (in the box, theta > 0, q > 0).

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
        x, conv = gauss_newton(sweep, x, np.full(len(x), d), theta_max, tol)
        near = (np.abs(x[:, 0] - alpha0[todo]) <= 1.5 * steps[0]) & (
            np.abs(x[:, 1] - q0[todo]) <= 1.5 * steps[1]
        )
        good = conv & near
        idx = np.nonzero(todo)[0][good]
        out[idx], ok[idx] = x[good], True
    inside = ok & np.all((out >= box[:, 0]) & (out <= box[:, 1]), axis=-1) & (out[:, 2] > 0) & (out[:, 1] > 0)
    return out, inside


def _at_cut(sweep: SweepCharacteristic, reason: str, q: float, alpha: float) -> str:
    """A stalled end where a p-root of N is real (to 1e-6) lies on the cut of K: reason "cut"."""
    if reason != "stalled":
        return reason
    p = sweep.p_roots(np.array([complex(q)]), np.array([float(alpha)]))[0]
    return "cut" if np.min(np.abs(p.imag) / np.maximum(1.0, np.abs(p))) < 1e-6 else reason


def _branch(
    sweep: SweepCharacteristic,
    d: float,
    path: FloatArray,
    theta_max: float,
    ends: tuple[str, str],
    alpha_span: float,
) -> InstabilityBranch:

    _, _, E, E_q, E_t = evaluate(sweep, path, np.full(len(path), d), theta_max)
    dq_dtheta = -E_t / E_q
    alpha, theta, q = path[:, 0].copy(), path[:, 2] * theta_max, path[:, 1].copy()
    return InstabilityBranch(
        d=float(d),
        alpha=alpha,
        theta=theta,
        q=q,
        unstable_above=np.imag(dq_dtheta) < 0,
        residual=np.abs(E / E_q),
        ends=tuple(
            line_end(_at_cut(sweep, reason, q[k], alpha[k]), alpha[k], theta[k], q[k])
            for reason, k in zip(ends, (0, -1))
        ),
        folds=find_folds(alpha, theta, q, alpha_span, theta_max),
    )
