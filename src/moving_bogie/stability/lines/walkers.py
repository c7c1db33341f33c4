"""Pseudo-arclength continuation of several tracers at once (Section 3.5, the panels of a figure).

Each tracer (:class:`~moving_bogie.stability.lines.continuation.PathTracer`, one panel) advances its
curves in lockstep, exactly as it does alone: every step, the Euler predictor ``y = x + h t`` of all its
walkers (a seed, one direction of the curve's tangent), then the Newton corrector on the bordered 3x3
system ``(Re E, Im E, t . (y - x) - h) = 0`` iterating until all of them have converged or failed (at most
6 iterations), then acceptance, step control, box faces and closed loops walker by walker. What the
tracers share is the calls: one call of
:meth:`~moving_bogie.kernels.sweep_characteristic.SweepCharacteristic.derivatives` per corrector iteration
serves the current iterate of every tracer whose sweep stacks with the others
(:class:`~moving_bogie.kernels.stacked_sweep.StackedSweep`), and the end points on the box faces of all
walkers leaving the box in that iteration are placed together. Every point's arithmetic is its own, so each
tracer's curves are those it traces alone, to rounding (the quartics of a call of at most eight points are
solved on Python complex numbers, larger batches with numpy: :func:`~moving_bogie.kernels.polyroots.
quartic_roots`); the calls number the corrector iterations of the slowest tracer instead of their sum over
the tracers.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

import numpy as np

from moving_bogie.kernels.stacked_sweep import StackedSweep, stack_key
from moving_bogie.kernels.sweep_characteristic import SweepCharacteristic
from moving_bogie.stability.lines.continuation import (
    END_REASONS,
    PathTracer,
    TracedPath,
    evaluate,
    newton_fixed,
    tangent,
)
from moving_bogie.typing import FloatArray

__all__ = ["trace_all_many", "trace_walkers_many"]

#: Newton iterations of the corrector per step.
CORRECTOR_ITERATIONS = 6

#: A tracing job: the tracer, the seeds (m, 3) and their spacings (m,).
Job = tuple[PathTracer, FloatArray, FloatArray]

#: An end point to place: (the lockstep, walker, last point x, first point outside y, box coordinate, face).
EndRequest = tuple["_Lockstep", int, FloatArray, FloatArray, int, float]


class _Calls:
    """One call per group of jobs whose sweeps stack: (E, E_q, E_alpha, E_theta) of walkers or points."""

    def __init__(self, tracers: list[PathTracer]) -> None:
        groups: dict[object, list[int]] = {}
        for k, tracer in enumerate(tracers):
            key = stack_key(tracer.sweep) if tracer.sweep.blocks is None else ("alone", k)
            groups.setdefault(key, []).append(k)
        self.groups = list(groups.values())
        self.stacks = [
            StackedSweep([tracers[k].sweep for k in g]) if len(g) > 1 else None for g in self.groups
        ]
        self.tracers = tracers
        self.member = {k: (gi, j) for gi, g in enumerate(self.groups) for j, k in enumerate(g)}

    def split(self, job: np.ndarray) -> list[tuple[SweepCharacteristic, np.ndarray]]:
        """For each group: (its sweep for these points, the positions of its points in ``job``)."""
        out = []
        for gi, g in enumerate(self.groups):
            where = np.nonzero(np.isin(job, g))[0]
            if len(where):
                stack = self.stacks[gi]
                if stack is None:
                    out.append((self.tracers[g[0]].sweep, where))
                else:
                    member = np.array([self.member[int(k)][1] for k in job[where]])
                    out.append((stack.at(member), where))
        return out


def trace_all_many(
    jobs: Sequence[tuple[PathTracer, Iterable[tuple[float, FloatArray]]]],
) -> list[list[TracedPath]]:
    """Trace curves until every seed of every tracer lies on one (the panels of a figure, or one panel
    alone), their rounds together: the walkers of every tracer's current round advance in
    shared calls (:func:`trace_walkers_many`); each tracer's rounds, curves and warnings are those it has
    alone."""
    tracers = [tracer for tracer, _ in jobs]
    for tracer, groups in jobs:
        tracer.begin(groups)
    while todo := [tracer for tracer in tracers if tracer.pending]:
        rounds = [(tracer, *tracer.start_round()) for tracer in todo]
        for (tracer, _, _), new in zip(rounds, trace_walkers_many(rounds)):
            tracer.end_round(new)
    return [tracer.paths for tracer in tracers]


def trace_walkers_many(jobs: list[Job]) -> list[list[TracedPath]]:
    """Trace the curves through the seeds of every job (tracer, seeds, spacings) both ways, each tracer in
    lockstep: per job, a list of (d, path, (start, end))."""
    calls = _Calls([tracer for tracer, _, _ in jobs])
    states: list[_Lockstep] = []
    for k, (tracer, starts, ds) in enumerate(jobs):
        state = _Lockstep(tracer, k, starts, ds)
        state.start_step(tangent(_evaluated(calls, [state], evaluate, starts)[0][1]))
        states.append(state)
    while running := [s for s in states if not s.finished]:
        ends: list[EndRequest] = []
        for state, (F, J) in zip(running, _evaluated(calls, running, evaluate)):
            if state.correct(F, J):
                ends += state.finish_step()
        _place_ends(calls, ends)
        for state in running:
            if state.done_step:
                state.start_step()
    return [state.paths() for state in states]


def _evaluated(
    calls: _Calls, states: list[_Lockstep], evaluate: object, points: FloatArray | None = None
) -> list[tuple[FloatArray, FloatArray]]:
    """(F, J) at the current iterate of every state (or at ``points`` of the only state), shared calls."""
    ys = [s.y if points is None else points for s in states]
    ds = [s.d if points is None else s.ds for s in states]
    sizes = [len(y) for y in ys]
    y, d = np.concatenate(ys), np.concatenate(ds)
    job = np.repeat([s.job for s in states], sizes)
    scale = np.repeat([s.tracer.scale for s in states], sizes).astype(float)
    F, J = np.empty((len(y), 2)), np.empty((len(y), 2, 3))
    for sweep, where in calls.split(job):
        F[where], J[where], *_ = evaluate(sweep, y[where], d[where], scale[where])  # type: ignore[operator]
    cuts = np.cumsum(sizes)[:-1]
    return list(zip(np.split(F, cuts), np.split(J, cuts)))


def _place_ends(calls: _Calls, ends: list[EndRequest]) -> None:
    """End points on the box faces (Newton with the box coordinate held, from the linear guess between
    the last point and the first outside), all requests at once per box coordinate and group of sweeps."""
    for k in sorted({e[4] for e in ends}):
        mine = [e for e in ends if e[4] == k]
        x, y = np.array([e[2] for e in mine]), np.array([e[3] for e in mine])
        value = np.array([e[5] for e in mine])
        d = np.array([e[0].D[e[1]] for e in mine])
        scale = np.array([e[0].tracer.scale for e in mine], dtype=float)
        tol = np.array([e[0].tracer.tol for e in mine], dtype=float)
        guess = x + ((value - x[:, k]) / (y[:, k] - x[:, k]))[:, None] * (y - x)
        for sweep, where in calls.split(np.array([e[0].job for e in mine])):
            w = where
            end, conv = newton_fixed(sweep, guess[w], d[w], k, value[w], scale[w], tol[w])
            near = np.linalg.norm(end - guess[w], axis=-1) < 2 * np.linalg.norm(y[w] - x[w], axis=-1) + 1e-9
            for j, n in enumerate(w):
                if conv[j] and near[j]:
                    state, i = mine[n][0], mine[n][1]
                    state.pts[i].append(end[j])


class _Lockstep:
    """One tracer's walkers advancing one step at a time: seed c starts walkers c (forward) and c + m."""

    def __init__(self, tracer: PathTracer, job: int, starts: FloatArray, ds: FloatArray) -> None:
        m = len(starts)
        self.tracer, self.job, self.m, self.ds = tracer, job, m, ds
        self.X = np.concatenate([starts, starts])
        self.D = np.concatenate([ds, ds])
        self.H = np.full(2 * m, 0.25 * tracer.h_max)
        self.walked = np.zeros(2 * m)
        self.loop = np.zeros(2 * m, dtype=bool)
        self.pts: list[list[FloatArray]] = [[x.copy()] for x in self.X]
        self.taken = 0  # steps started
        self.finished = False
        self.done_step = False

    def start_step(self, T0: FloatArray | None = None) -> None:
        """The predictor of the next step of the active walkers (the first step: their tangents ``T0``)."""
        if T0 is not None:
            self.T = np.concatenate([T0, -T0])
            self.active = np.all(np.isfinite(self.T), axis=-1)
            self.reason = ["max_steps" if ok else "stalled" for ok in self.active]
        if self.taken == self.tracer.max_steps:
            self.tracer.warnings.append("continuation stopped at max_steps")
            self.finished = True
        if self.finished or not np.any(self.active):
            self.finished = True
            return
        self.taken += 1
        self.idx = np.nonzero(self.active)[0]
        self.x, self.t, self.h, self.d = (
            self.X[self.idx],
            self.T[self.idx],
            self.H[self.idx],
            self.D[self.idx],
        )
        self.y = self.x + self.h[:, None] * self.t
        self.conv = np.zeros(len(self.idx), dtype=bool)
        self.iters = np.zeros(len(self.idx), dtype=int)
        self.k = 0
        self.done_step = False

    def correct(self, F: FloatArray, Jy: FloatArray) -> bool:
        """One corrector iteration from (F, J) at the iterate; True when the step's corrector is done."""
        x, y, t, h, conv = self.x, self.y, self.t, self.h, self.conv
        A = np.concatenate([Jy, t[:, None, :]], axis=1)
        rhs = np.concatenate([F, (np.sum((y - x) * t, axis=-1) - h)[:, None]], axis=-1)
        with np.errstate(all="ignore"):
            dy = -np.linalg.solve(A, rhs[..., None])[..., 0]
        size = np.max(np.abs(dy), axis=-1)
        ok = np.isfinite(size)
        self.y = np.where((ok & ~conv)[:, None], y + np.where(ok[:, None], dy, 0), y)
        self.iters += ~conv
        conv |= ok & (size < self.tracer.tol)
        self.k += 1
        self.Jy = Jy
        self.done_step = bool(np.all(conv | ~ok)) or self.k == CORRECTOR_ITERATIONS
        return self.done_step

    def finish_step(self) -> list[EndRequest]:
        """Accept or refuse every walker's step (step control, box faces, closed loops); the end points to
        place on the box faces."""
        tracer, m, x, y, t, h = self.tracer, self.m, self.x, self.y, self.t, self.h
        tn = tangent(self.Jy, t)  # at the last corrector iterate: the final correction is below tol
        good = (
            self.conv
            & np.all(np.isfinite(tn), axis=-1)
            & (np.sum(tn * t, axis=-1) > np.cos(0.5))
            & (np.linalg.norm(y - x, axis=-1) < 2 * h)
        )
        ends: list[EndRequest] = []
        for j, i in enumerate(self.idx):
            if not good[j]:
                self.H[i] *= 0.5
                if self.H[i] < tracer.h_min:
                    self.active[i] = False
                    self.reason[i] = "stalled"
                continue
            out = tracer.outside(y[j])
            if out is not None:
                ends.append((self, int(i), x[j], y[j], out[0], out[1]))
                self.active[i] = False
                self.reason[i] = END_REASONS[(out[0], int(out[1] == tracer.box[out[0], 1]))]
                continue
            self.walked[i] += np.linalg.norm(y[j] - x[j])
            self.pts[i].append(y[j].copy())
            self.X[i], self.T[i] = y[j], tn[j]
            self.H[i] = min(self.H[i] * (1.5 if self.iters[j] <= 3 else 1.0), tracer.h_max)
            if self.walked[i] > 4 * tracer.h_max and np.linalg.norm(y[j] - self.pts[i][0]) < 0.75 * self.H[i]:
                self.pts[i].append(self.pts[i][0].copy())
                partner = i + m if i < m else i - m
                self.active[i] = self.active[partner] = False
                self.loop[i] = True
                self.reason[i] = self.reason[partner] = "closed"
        return ends

    def paths(self) -> list[TracedPath]:
        """One path per seed (a closed loop: the walker's that closed it), with why each end is there."""
        m, pts, reason = self.m, self.pts, self.reason
        paths: list[TracedPath] = []
        for c in range(m):
            if self.loop[c] or self.loop[c + m]:
                path = np.array(pts[c] if self.loop[c] else pts[c + m])
            else:
                path = np.array(pts[c + m][::-1] + pts[c][1:])
            if len(path) >= 2:
                paths.append((float(self.ds[c]), path, (reason[c + m], reason[c])))
        return paths
