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

import inspect
from collections.abc import Callable, Sequence
from fractions import Fraction
from typing import Any, cast

import numpy as np

from moving_bogie.errors import ParameterError
from moving_bogie.kernels.bound import BoundModel
from moving_bogie.kernels.sweep_characteristic import SweepCharacteristic
from moving_bogie.stability.lines.continuation import PathTracer, evaluate
from moving_bogie.stability.lines.line_ends import find_folds, line_end
from moving_bogie.stability.lines.line_results import InstabilityBranch, InstabilityLines
from moving_bogie.stability.lines.seeds import report, seed_groups
from moving_bogie.stability.lines.undamped_lines import undamped_lines
from moving_bogie.stability.lines.walkers import trace_all_many
from moving_bogie.stability.maps.column import at_theta
from moving_bogie.stability.maps.undamped import regime
from moving_bogie.typing import FloatArray

__all__ = ["InstabilityBranch", "InstabilityLines", "instability_lines", "instability_lines_many"]

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
    held: tuple[str, ...] = (),
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
    held : tuple of str
        Groups that keep their values instead of following ``parameter`` (the bar's mu_v, J_b under the
        rule ``"fixed"`` of :mod:`~moving_bogie.model.bar`; default none, Eq. (63)); not with an
        undamped foundation.
    """
    options: dict[str, Any] = dict(spacings=spacings, parameter=parameter, alpha_range=alpha_range)
    options |= dict(theta_max=theta_max, q_max=q_max, q_max_cap=q_max_cap, alpha_step=alpha_step)
    options |= dict(q_step=q_step, h_max=h_max)
    options |= dict(tol=tol, verify=verify, progress=progress, held=held)
    return instability_lines_many([(bound, options)])[0]


def instability_lines_many(requests: Sequence[tuple[BoundModel, dict[str, Any]]]) -> list[InstabilityLines]:
    """:func:`instability_lines` of several parameter sets at once (the panels of a figure), each
    ``(bound, keyword arguments of instability_lines)``.

    Each result is the one :func:`instability_lines` returns for its request alone; the continuations of
    all requests advance together (:func:`~moving_bogie.stability.lines.walkers.trace_all_many`), the
    points of requests of one track and vehicle model in shared calls.
    """
    parameters = inspect.signature(instability_lines).parameters
    defaults = {name: p.default for name, p in parameters.items() if name != "bound"}
    panels = []
    for bound, options in requests:
        if unknown := sorted(set(options) - set(defaults)):
            raise TypeError(f"instability_lines() got unexpected keyword arguments {unknown}")
        panels.append(_Panel(bound, **(defaults | options)))
    todo = [panel for panel in panels if panel.result is None]
    while todo:
        jobs = [panel.seed() for panel in todo]
        for panel, traced in zip(todo, trace_all_many(jobs)):
            panel.traced(traced)
        todo = [panel for panel in todo if panel.result is None]
    return [cast(InstabilityLines, panel.result) for panel in panels]


class _Panel:
    """One request of :func:`instability_lines_many` while its lines are traced: seeds and continuation
    up to ``q_max``, doubled (up to the cap) while a line reaches it."""

    def __init__(
        self,
        bound: BoundModel,
        spacings: Sequence[float] | None,
        parameter: str | None,
        alpha_range: tuple[float, float],
        theta_max: float,
        q_max: float,
        q_max_cap: float | None,
        alpha_step: float,
        q_step: float,
        h_max: float,
        tol: float,
        verify: bool,
        progress: Callable[[float], None] | None,
        held: tuple[str, ...],
    ) -> None:
        params = bound.params
        self.bound, self.verify, self.progress, self.held = bound, verify, progress, tuple(held)
        self.parameter = parameter or params.model.wheel_mass
        self.ds = [float(params.d)] if spacings is None else [float(d) for d in spacings]
        self.alpha_range = (float(alpha_range[0]), float(alpha_range[1]))
        self.theta_max, self.q_max = theta_max, q_max
        self.result: InstabilityLines | None = None
        if regime(params.eta_f) != "damped":
            if self.held:
                raise ParameterError(
                    "bar", "the bar held fixed is not available for the lines of an undamped foundation"
                )
            step = max(alpha_step, 0.02)
            self.result = undamped_lines(
                bound,
                self.ds,
                self.parameter,
                self.alpha_range,
                theta_max,
                alpha_step=step,
                progress=progress,
            )
            return
        self.sweep = SweepCharacteristic(bound, self.parameter, held=self.held)
        self.cap = 8 * q_max if q_max_cap is None else q_max_cap
        self.grid = dict(alpha_step=alpha_step, q_step=q_step, h_max=h_max, tol=tol)

    def seed(self) -> tuple[PathTracer, list[tuple[float, FloatArray]]]:
        """The tracer and the seeds up to the current ``q_max``."""
        progress = self.progress
        groups, box = seed_groups(
            self.sweep, self.ds, self.alpha_range, self.theta_max, self.q_max, self.grid, progress
        )
        self.tracer = PathTracer(
            self.sweep,
            self.theta_max,
            box,
            self.grid["h_max"],
            self.grid["tol"],
            progress=lambda x: report(progress, 0.3 + 0.7 * x),
        )
        return self.tracer, groups

    def traced(self, traced: list[tuple[float, FloatArray, tuple[str, str]]]) -> None:
        """The branches of the traced curves: the result, or ``q_max`` doubled while a line reaches it."""
        a0, a1 = self.alpha_range
        values = _path_values(self.sweep, traced, self.theta_max)
        branches = [
            _branch(self.sweep, d, path, self.theta_max, ends, a1 - a0, value)
            for (d, path, ends), value in zip(traced, values)
        ]
        branches.sort(key=lambda b: (b.d, b.alpha.min()))
        warnings = list(self.tracer.warnings)
        reaches = any(e.reason == "q_max" for b in branches for e in b.ends)
        if reaches and 2 * self.q_max <= self.cap:
            self.q_max *= 2
            return
        if reaches:
            warnings.insert(0, f"a line reaches q_max={self.q_max:g} (the cap); raise q_max_cap")
        if self.verify:
            branches = [_verify(self.bound, self.parameter, b, self.held) for b in branches]
        report(self.progress, 1.0)
        params = self.bound.params
        self.result = InstabilityLines(
            params,
            params.vehicle,
            self.parameter,
            self.alpha_range,
            float(self.theta_max),
            tuple(branches),
            tuple(dict.fromkeys(warnings)),
            float(self.q_max),
        )


def _verify(
    bound: BoundModel, parameter: str, branch: InstabilityBranch, held: tuple[str, ...] = ()
) -> InstabilityBranch:
    """Unstable counts by induced_frequencies just below and above the branch's middle point."""
    from dataclasses import replace

    from moving_bogie.roots.frequencies import induced_frequencies

    k = len(branch.alpha) // 2
    a, theta = branch.alpha[k], branch.theta[k]
    base = bound.replace(alpha=_exact(a), d=_exact(branch.d))
    counts = []
    for t in (theta * 0.98, theta * 1.02):
        res = induced_frequencies(at_theta(base, parameter, _exact(t), held), dps=20)
        counts.append(len(res.unstable_roots))
    return replace(
        branch, verified=(float(a), float(theta * 0.98), counts[0], float(theta * 1.02), counts[1])
    )


def _exact(x: float) -> Fraction:
    return Fraction(str(x))


def _at_cut(sweep: SweepCharacteristic, reason: str, q: float, alpha: float) -> str:
    """A stalled end where a p-root of N is real (to 1e-6) lies on the cut of K: reason "cut"."""
    if reason != "stalled":
        return reason
    p = sweep.p_roots(np.array([complex(q)]), np.array([float(alpha)]))[0]
    return "cut" if np.min(np.abs(p.imag) / np.maximum(1.0, np.abs(p))) < 1e-6 else reason


def _path_values(
    sweep: SweepCharacteristic, traced: list[tuple[float, FloatArray, tuple[str, str]]], theta_max: float
) -> list[tuple[np.ndarray, ...]]:
    """(E, E_q, E_theta) at the points of every traced path (all paths in one batch)."""
    if not traced:
        return []
    points = np.concatenate([path for _, path, _ in traced])
    d = np.concatenate([np.full(len(path), d) for d, path, _ in traced])
    _, _, *values = evaluate(sweep, points, d, theta_max)
    spans = np.split(np.arange(len(points)), np.cumsum([len(path) for _, path, _ in traced])[:-1])
    return [tuple(v[span] for v in values) for span in spans]


def _branch(
    sweep: SweepCharacteristic,
    d: float,
    path: FloatArray,
    theta_max: float,
    ends: tuple[str, str],
    alpha_span: float,
    values: tuple[np.ndarray, ...],
) -> InstabilityBranch:
    """The branch of one traced path; ``values`` are (E, E_q, E_theta) at its points (the residual
    |E / E_q| and the unstable side from dq/dtheta = -E_theta / E_q)."""
    E, E_q, E_t = values
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
