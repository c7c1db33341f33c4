"""Pseudo-arclength continuation with every walker on its own schedule (Section 3.5, instability lines).

Each seed starts two *walkers*, one along each direction of the curve's tangent. A walker repeats the
step of :class:`~moving_bogie.stability.lines.continuation.PathTracer`: Euler predictor ``y = x + h t``,
Newton corrector on the bordered 3x3 system ``(Re E, Im E, t . (y - x) - h) = 0`` (at most 6 iterations,
to ``tol``), acceptance test, step control, box faces and closed loops. What differs from advancing all
walkers in lockstep (one step of all of them, the corrector iterating until the slowest one converges) is
only the schedule: one call of :meth:`~moving_bogie.kernels.sweep_characteristic.SweepCharacteristic.
derivatives` serves every walker at whatever stage it is (first corrector iteration of a new step, or
the fifth of a hard one), so the calls number the corrector iterations of the longest walker instead of
the sum over the steps of the slowest iteration count. The end points on the box faces of the walkers
leaving the box in the same call are placed together.

Several tracers (the panels of a figure) advance together: their walkers share the calls, one per group
of tracers whose sweeps stack (:class:`~moving_bogie.kernels.stacked_sweep.StackedSweep`).

A walker's sequence of points is that of the lockstep tracer (each point's arithmetic is its own); the
tangent of an accepted step is taken from the Jacobian of the walker's last corrector iteration. When a
walker closes a loop at its step ``s``, its partner (the other direction of the same seed) stops after its
own step ``s``: as in lockstep, of two walkers closing, the one closing at the earlier step wins (the
forward one on a tie).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from moving_bogie.kernels.stacked_sweep import StackedSweep, stack_key
from moving_bogie.kernels.sweep_characteristic import SweepCharacteristic
from moving_bogie.typing import FloatArray

if TYPE_CHECKING:
    from moving_bogie.stability.lines.continuation import PathTracer, TracedPath

__all__ = ["trace_walkers_many"]

#: Newton iterations of the corrector per step.
CORRECTOR_ITERATIONS = 6

#: A tracing job: the tracer, the seeds (m, 3) and their spacings (m,).
Job = tuple["PathTracer", FloatArray, FloatArray]


class _Walkers:
    """The walkers of every job: job k's seed c starts walker o_k + c forward and o_k + m_k + c backward."""

    def __init__(self, jobs: list[Job], T0: FloatArray) -> None:
        sizes = [len(starts) for _, starts, _ in jobs]
        self.offsets = np.concatenate([[0], np.cumsum([2 * m for m in sizes])]).astype(int)
        self.tracers = [tracer for tracer, _, _ in jobs]
        starts = [np.concatenate([s, s]) for _, s, _ in jobs]
        self.X = np.concatenate(starts)  # the last accepted point
        self.D = np.concatenate([np.concatenate([d, d]) for _, _, d in jobs])
        T = np.split(T0, np.cumsum(sizes)[:-1])
        self.T = np.concatenate([np.concatenate([t, -t]) for t in T])
        self.job = np.repeat(np.arange(len(jobs)), [2 * m for m in sizes])
        self.pair = np.concatenate(
            [o + (np.arange(2 * m) + m) % (2 * m) for o, m in zip(self.offsets, sizes)]
        )
        self.scale = np.array([self.tracers[j].scale for j in self.job], dtype=float)
        self.H = np.array([0.25 * self.tracers[j].h_max for j in self.job], dtype=float)
        self.Y = self.X + self.H[:, None] * self.T  # the corrector's iterate of the current step
        n = len(self.X)
        self.iters = np.zeros(n, dtype=int)  # corrector iterations done in the current step
        self.steps = np.zeros(n, dtype=int)  # steps attempted (accepted or not)
        self.active = np.all(np.isfinite(self.T), axis=-1)
        self.reason = ["max_steps" if ok else "stalled" for ok in self.active]
        self.walked = np.zeros(n)
        self.closed_at = np.full(n, _NEVER)  # the step at which the walker closed its loop
        self.ended_at = np.full(n, _NEVER)  # the step at which it left the box or stalled
        self.pts: list[list[FloatArray]] = [[x.copy()] for x in self.X]

    def end(self, i: int, reason: str) -> None:
        """Walker ``i`` stops by itself at its current step (box face, stalled or closed loop)."""
        self.active[i] = False
        self.reason[i] = reason
        if reason == "closed":
            self.closed_at[i] = self.steps[i]
        else:
            self.ended_at[i] = self.steps[i]


_NEVER = np.iinfo(np.int64).max


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


def trace_walkers_many(jobs: list[Job]) -> list[list[TracedPath]]:
    """Trace the curves through the seeds of every job (tracer, seeds, spacings) both ways: per job, a
    list of (d, path, (start, end))."""
    from moving_bogie.stability.lines.continuation import evaluate, tangent

    calls = _Calls([tracer for tracer, _, _ in jobs])
    job0 = np.repeat(np.arange(len(jobs)), [len(s) for _, s, _ in jobs])
    starts = np.concatenate([s for _, s, _ in jobs])
    ds = np.concatenate([d for _, _, d in jobs])
    scale0 = np.array([jobs[k][0].scale for k in job0], dtype=float)
    T0 = np.empty_like(starts)
    for sweep, where in calls.split(job0):
        _, J, *_ = evaluate(sweep, starts[where], ds[where], scale0[where])
        T0[where] = tangent(J)
    w = _Walkers(jobs, T0)
    tol = np.array([w.tracers[j].tol for j in w.job])
    while np.any(w.active):
        active = np.nonzero(w.active)[0]
        for sweep, where in calls.split(w.job[active]):
            _advance(w, calls, sweep, active[where], tol)
    paths = []
    for k, (tracer, _, d) in enumerate(jobs):
        mine = slice(w.offsets[k], w.offsets[k + 1])
        if np.any(w.steps[mine] >= tracer.max_steps):
            tracer.warnings.append("continuation stopped at max_steps")
        paths.append(_paths(w, w.offsets[k], d))
    return paths


def _advance(
    w: _Walkers, calls: _Calls, sweep: SweepCharacteristic, idx: np.ndarray, tol: FloatArray
) -> None:
    """One corrector iteration of the walkers ``idx`` (one call); finish the steps that are done."""
    from moving_bogie.stability.lines.continuation import evaluate

    y, x, t, h = w.Y[idx], w.X[idx], w.T[idx], w.H[idx]
    F, Jy, *_ = evaluate(sweep, y, w.D[idx], w.scale[idx])
    A = np.concatenate([Jy, t[:, None, :]], axis=1)
    rhs = np.concatenate([F, (np.sum((y - x) * t, axis=-1) - h)[:, None]], axis=-1)
    with np.errstate(all="ignore"):
        dy = -np.linalg.solve(A, rhs[..., None])[..., 0]
    size = np.max(np.abs(dy), axis=-1)
    ok = np.isfinite(size)
    w.Y[idx] = np.where(ok[:, None], y + np.where(ok[:, None], dy, 0), y)
    w.iters[idx] += 1
    conv = ok & (size < tol[idx])
    done = conv | ~ok | (w.iters[idx] >= CORRECTOR_ITERATIONS)
    if np.any(done):
        _finish_steps(w, calls, idx[done], conv[done], Jy[done])


def _finish_steps(w: _Walkers, calls: _Calls, idx: np.ndarray, conv: np.ndarray, Jy: FloatArray) -> None:
    """Accept or refuse the steps of the walkers ``idx`` whose corrector has finished; start the next."""
    from moving_bogie.stability.lines.continuation import END_REASONS, tangent

    x, y, t, h = w.X[idx], w.Y[idx], w.T[idx], w.H[idx]
    tn = tangent(Jy, t)  # at the last corrector iterate: the final correction is below tol
    good = (
        conv
        & np.all(np.isfinite(tn), axis=-1)
        & (np.sum(tn * t, axis=-1) > np.cos(0.5))
        & (np.linalg.norm(y - x, axis=-1) < 2 * h)
    )
    leaving: dict[tuple[int, float], list[int]] = {}  # walkers by box face, with their x and y
    for j, i in enumerate(idx):
        tracer = w.tracers[w.job[i]]
        w.steps[i] += 1
        if not good[j]:
            w.H[i] *= 0.5
            if w.H[i] < tracer.h_min:
                w.end(i, "stalled")
        elif (out := tracer._outside(y[j])) is not None:
            leaving.setdefault(out, []).append(j)
            w.end(i, END_REASONS[(out[0], int(out[1] == tracer.box[out[0], 1]))])
        else:
            w.walked[i] += np.linalg.norm(y[j] - x[j])
            w.pts[i].append(y[j].copy())
            w.X[i], w.T[i] = y[j], tn[j]
            w.H[i] = min(w.H[i] * (1.5 if w.iters[i] <= 3 else 1.0), tracer.h_max)
            if w.walked[i] > 4 * tracer.h_max and np.linalg.norm(y[j] - w.pts[i][0]) < 0.75 * w.H[i]:
                w.pts[i].append(w.pts[i][0].copy())
                w.end(i, "closed")
        p = w.pair[i]
        if w.active[p] and w.steps[p] >= w.closed_at[i]:  # a partner already past the closing step
            w.active[p] = False
        if w.active[i] and (w.steps[i] >= w.closed_at[p] or w.steps[i] >= tracer.max_steps):
            w.active[i] = False
        if w.active[i]:
            w.iters[i] = 0
            w.Y[i] = w.X[i] + w.H[i] * w.T[i]  # the predictor of the next step
    for (k, value), js in leaving.items():
        for sweep, where in calls.split(w.job[idx[js]]):
            _place_ends(w, sweep, idx[js][where], k, value, x[js][where], y[js][where])


def _place_ends(
    w: _Walkers,
    sweep: SweepCharacteristic,
    idx: np.ndarray,
    k: int,
    value: float,
    x: FloatArray,
    y: FloatArray,
) -> None:
    """End points on the box face x[k] = value (as :meth:`PathTracer._end_point`), walkers ``idx`` at once."""
    from moving_bogie.stability.lines.continuation import newton_fixed

    tol = np.array([w.tracers[j].tol for j in w.job[idx]])
    guess = x + ((value - x[:, k]) / (y[:, k] - x[:, k]))[:, None] * (y - x)
    end, conv = newton_fixed(sweep, guess, w.D[idx], k, value, w.scale[idx], tol)
    near = np.linalg.norm(end - guess, axis=-1) < 2 * np.linalg.norm(y - x, axis=-1) + 1e-9
    for j, i in enumerate(idx):
        if conv[j] and near[j]:
            w.pts[i].append(end[j])


def _paths(w: _Walkers, offset: int, ds: FloatArray) -> list[TracedPath]:
    """One path per seed of the job starting at walker ``offset``, with why each end is where it is.

    A closed loop is the path of the walker that closed it first (the forward one on a tie); the other
    walker's end is "closed" too, unless it left the box or stalled at that very step and is the
    backward one (lockstep processes the forward walker's closing first, then the backward one's step).
    """
    paths: list[TracedPath] = []
    m = len(ds)
    for c in range(offset, offset + m):
        b = c + m
        if min(w.closed_at[c], w.closed_at[b]) < _NEVER:
            winner, loser = (c, b) if w.closed_at[c] <= w.closed_at[b] else (b, c)
            path = np.array(w.pts[winner])
            w.reason[winner] = "closed"
            if not (loser == b and w.ended_at[b] == w.closed_at[c]):
                w.reason[loser] = "closed"
        else:
            path = np.array(w.pts[b][::-1] + w.pts[c][1:])
        if len(path) >= 2:
            paths.append((float(ds[c - offset]), path, (w.reason[b], w.reason[c])))
    return paths
