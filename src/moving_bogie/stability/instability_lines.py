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
   itself. Seeds lying on a traced curve are used up; duplicates are dropped.

Which side is unstable follows from the implicit function theorem: at fixed alpha, the real root moves
as dq/dtheta = -E_theta / E_q, so the side of larger theta is the unstable one (one more root with
Im q < 0) when Im(dq/dtheta) < 0. This is the D-decomposition rule of hatching written pointwise; the
tests confirm it with :func:`~moving_bogie.roots.frequencies.induced_frequencies` on both sides.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from fractions import Fraction

import contourpy
import numpy as np

from moving_bogie.errors import ParameterError
from moving_bogie.kernels.sweep_characteristic import SweepCharacteristic, poly_roots

__all__ = ["InstabilityBranch", "InstabilityLines", "instability_lines"]

_ALPHA_STEP_FD = 1e-6


@dataclass(frozen=True)
class InstabilityBranch:
    """One connected piece of an instability line.

    Attributes
    ----------
    d : float
        Wheel spacing.
    alpha, theta, q : ndarray
        Points of the line: velocity, parameter value (eta_M unless stated), and the real induced
        frequency there.
    unstable_above : ndarray of bool
        At each point, True if increasing theta at fixed alpha makes the real root unstable.
    residual : ndarray
        |E_chr / E_chr'| at each point: distance in q to the exact real root (double precision).
    """

    d: float
    alpha: np.ndarray
    theta: np.ndarray
    q: np.ndarray
    unstable_above: np.ndarray
    residual: np.ndarray
    verified: tuple | None = None  # (alpha, eta below, count, eta above, count) by induced_frequencies

    @property
    def unstable_side(self) -> str:
        """ "above" (larger theta) or "below" at fixed alpha along the whole branch, else "mixed"."""
        if np.all(self.unstable_above):
            return "above"
        if not np.any(self.unstable_above):
            return "below"
        return "mixed"

    def to_dict(self, parameter: str = "eta_M") -> dict:
        return {
            "d": self.d,
            "unstable_side": self.unstable_side,
            "verified": None
            if self.verified is None
            else dict(
                zip(("alpha", "theta_below", "count_below", "theta_above", "count_above"), self.verified)
            ),
            "points": [
                {"alpha": float(a), parameter: float(t), "q": float(q), "unstable_above": bool(u)}
                for a, t, q, u in zip(self.alpha, self.theta, self.q, self.unstable_above)
            ],
        }


@dataclass(frozen=True)
class InstabilityLines:
    """All instability lines of one parameter set (for one or several wheel spacings)."""

    params: object
    model: str
    parameter: str
    alpha_range: tuple
    theta_max: float
    branches: tuple
    warnings: tuple = field(default=())

    def for_spacing(self, d: float) -> tuple:
        return tuple(b for b in self.branches if abs(b.d - d) < 1e-12)

    def to_dict(self) -> dict:
        return {
            "params": self.params.to_dict(),
            "model": self.model,
            "parameter": self.parameter,
            "alpha_range": list(self.alpha_range),
            "theta_max": self.theta_max,
            "branches": [b.to_dict(self.parameter) for b in self.branches],
            "warnings": list(self.warnings),
        }


def instability_lines(
    params,
    model: str | None = None,
    *,
    spacings: Sequence[float] | None = None,
    parameter: str = "eta_M",
    alpha_range: tuple[float, float] = (0.0, 1.2),
    theta_max: float = 200.0,
    q_max: float = 1.5,
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
    params : DimensionlessParams
        All parameters except alpha and ``parameter`` (their values in ``params`` are ignored); with
        ``parameter="eta_M"``, mu_v = cf1 eta_M and J_b = cf2 eta_M d^2 (Eq. (63)) use the cf1, cf2 of
        ``params``. Requires eta_f > 0.
    model : {"bogie", "masses"}
    spacings : sequence of float, optional
        Wheel spacings d to trace (default: ``params.d``); they share the track kernel of the scan.
    parameter : {"eta_M", "kappa_v", "eta_v"}
        The vertical axis.
    alpha_range : (float, float)
        Velocity range.
    theta_max : float
        Upper end of the parameter range (the lower end is 0).
    q_max : float
        Largest real induced frequency searched; a line reaching it is reported in ``warnings``.
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
        (in theta,
        at fixed alpha) and store them in ``verified`` (about one second per branch).
    progress : callable, optional
        Called with the fraction of work done.
    """
    model = model or params.vehicle
    if params.eta_f <= 0:
        raise ParameterError(
            "eta_f",
            "instability lines need eta_f > 0: without foundation damping the cut of K lies on the real "
            "q-axis and real induced frequencies fill whole regions (Cases 2-4)",
        )
    ds = [float(params.d)] if spacings is None else [float(d) for d in spacings]
    sweep = SweepCharacteristic(params, model, parameter)
    a0, a1 = float(alpha_range[0]), float(alpha_range[1])
    alphas = np.linspace(a0, a1, max(3, int(round((a1 - a0) / alpha_step)) + 1))
    qs = np.linspace(q_step, q_max, max(3, int(round(q_max / q_step))))
    AA, QQ = np.meshgrid(alphas, qs, indexing="ij")
    Ks, _, _ = sweep.kernel(QQ, AA, spacings=ds)
    _report(progress, 0.1)
    box = np.array([[a0, a1], [0.0, q_max], [0.0, 1.0]])
    steps = (alphas[1] - alphas[0], qs[1] - qs[0])
    groups = []  # (d, seed points) per contour polyline
    for j, d in enumerate(ds):
        roots = poly_roots(sweep.coefficients(QQ, Ks[j], scale=theta_max, d=d))
        g = np.prod(np.where(np.isfinite(roots), roots.imag / (1 + np.abs(roots)), 1.0), axis=-1)
        lines = contourpy.contour_generator(x=alphas, y=qs, z=g.T, line_type="Separate").lines(0.0)
        for line in lines:
            seeds = _seed_points(sweep, line, d, theta_max, tol, box, steps)
            if len(seeds):
                groups.append((d, seeds))
        _report(progress, 0.1 + 0.2 * (j + 1) / len(ds))
    tracer = _Tracer(sweep, theta_max, box, h_max, tol, progress=lambda x: _report(progress, 0.3 + 0.7 * x))
    branches, warnings = [], []
    for d, path in tracer.trace_all(groups):
        branch = _branch(sweep, d, path, theta_max)
        branches.append(branch)
        if np.any(branch.q >= q_max - 1e-9):
            warnings.append(f"d={d:g}: a line reaches q_max={q_max:g}; raise q_max")
    warnings += tracer.warnings
    branches.sort(key=lambda b: (b.d, b.alpha.min()))
    if verify:
        branches = [_verify(params, model, parameter, b) for b in branches]
    _report(progress, 1.0)
    return InstabilityLines(
        params, model, parameter, (a0, a1), float(theta_max), tuple(branches), tuple(dict.fromkeys(warnings))
    )


def _verify(params, model, parameter, branch) -> InstabilityBranch:
    """Unstable counts by induced_frequencies just below and above the branch's middle point."""
    from dataclasses import replace

    from moving_bogie.roots.frequencies import induced_frequencies

    k = len(branch.alpha) // 2
    a, theta = branch.alpha[k], branch.theta[k]
    base = params.replace(alpha=_exact(a), d=_exact(branch.d))
    counts = []
    for t in (theta * 0.98, theta * 1.02):
        res = induced_frequencies(base.replace(**{parameter: _exact(t)}), model, dps=20)
        counts.append(len(res.unstable_roots))
    return replace(
        branch, verified=(float(a), float(theta * 0.98), counts[0], float(theta * 1.02), counts[1])
    )


def _exact(x: float):
    return Fraction(str(x))


def _report(progress, x):
    if progress is not None:
        progress(min(1.0, x))


def _evaluate(sweep, x, d, scale):
    """F = (Re E, Im E) and the 2x3 real Jacobian in (alpha, q, t = theta/scale) at points x (n, 3)."""
    E, E_q, E_a, E_t = sweep.derivatives(x[:, 1].astype(complex), x[:, 0], x[:, 2] * scale, d=d)
    cols = np.stack([E_a, E_q, E_t * scale], axis=-1)
    F = np.stack([E.real, E.imag], axis=-1)
    J = np.stack([cols.real, cols.imag], axis=-2)
    return F, J, E, E_q, E_t


def _seed_points(sweep, line, d, theta_max, tol, box, steps):
    """Points on the curves near the vertices of one contour polyline, shape (k, 3) in (alpha, q, t).

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
        x, conv = _gauss_newton(sweep, x, np.full(len(x), d), theta_max, tol)
        near = (np.abs(x[:, 0] - alpha0[todo]) <= 1.5 * steps[0]) & (
            np.abs(x[:, 1] - q0[todo]) <= 1.5 * steps[1]
        )
        good = conv & near
        idx = np.nonzero(todo)[0][good]
        out[idx], ok[idx] = x[good], True
    inside = ok & np.all((out >= box[:, 0]) & (out <= box[:, 1]), axis=-1) & (out[:, 2] > 0) & (out[:, 1] > 0)
    return out[inside]


def _gauss_newton(sweep, x, d, scale, tol, max_iter=12):
    """Minimum-norm Gauss-Newton onto the curve Re E = Im E = 0; returns (x, converged)."""
    x = np.array(x, dtype=float)
    conv = np.zeros(len(x), dtype=bool)
    for _ in range(max_iter):
        F, J, *_ = _evaluate(sweep, x, d, scale)
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


def _newton_fixed(sweep, x, d, k, value, scale, tol, max_iter=12):
    """Newton in the two coordinates other than ``k`` with x[k] = value (end points on the box)."""
    x = np.array(x, dtype=float)
    x[:, k] = value
    free = [i for i in range(3) if i != k]
    conv = np.zeros(len(x), dtype=bool)
    for _ in range(max_iter):
        F, J, *_ = _evaluate(sweep, x, d, scale)
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


def _tangent(J, previous=None):
    T = np.cross(J[:, 0, :], J[:, 1, :])
    T /= np.linalg.norm(T, axis=-1, keepdims=True)
    if previous is not None:
        T *= np.sign(np.sum(T * previous, axis=-1, keepdims=True) + 1e-300)
    return T


class _Tracer:
    """Pseudo-arclength continuation of many curves at once (vectorised over the curves).

    Each curve carries its own wheel spacing d, so that all spacings of a figure advance together.
    """

    def __init__(self, sweep, scale, box, h_max, tol, *, h_min=1e-6, max_steps=4000, progress=None):
        self.sweep, self.scale, self.box = sweep, scale, box
        self.h_max, self.tol, self.h_min, self.max_steps = h_max, tol, h_min, max_steps
        self.progress = progress
        self.warnings = []

    def trace_all(self, groups):
        """Trace curves until every seed lies on one; returns a list of (d, path (k, 3))."""
        paths = []
        pending = list(groups)
        total = max(1, sum(len(g) for _, g in pending))
        while pending:
            starts = np.array([g[len(g) // 2] for _, g in pending])
            ds = np.array([d for d, _ in pending])
            new = self._trace(starts, ds)
            for d, path in sorted(new, key=lambda item: -len(item[1])):
                if not any(
                    od == d and _covered(path, other, 0.3 * self.h_max).mean() > 0.9 for od, other in paths
                ):
                    paths.append((d, path))
            remaining = []
            for d, g in pending:
                hit = [_covered(g, p, 0.3 * self.h_max) for od, p in paths if od == d]
                left = g[~np.any(hit, axis=0)] if hit else g
                if len(left):
                    remaining.append((d, left))
            if sum(len(g) for _, g in remaining) >= sum(len(g) for _, g in pending):
                self.warnings.append(f"{sum(len(g) for _, g in remaining)} seed point(s) could not be traced")
                break
            pending = remaining
            if self.progress is not None:
                self.progress(1 - sum(len(g) for _, g in pending) / total)
        return paths

    def _trace(self, starts, ds):
        m = len(starts)
        _, J, *_ = _evaluate(self.sweep, starts, ds, self.scale)
        T0 = _tangent(J)
        X = np.concatenate([starts, starts])
        D = np.concatenate([ds, ds])
        T = np.concatenate([T0, -T0])
        H = np.full(2 * m, 0.25 * self.h_max)
        active = np.all(np.isfinite(T), axis=-1)
        walked = np.zeros(2 * m)
        loop = np.zeros(2 * m, dtype=bool)
        pts = [[x.copy()] for x in X]
        for _ in range(self.max_steps):
            if not np.any(active):
                break
            idx = np.nonzero(active)[0]
            x, t, h, d = X[idx], T[idx], H[idx], D[idx]
            y = x + h[:, None] * t
            conv = np.zeros(len(idx), dtype=bool)
            iters = np.zeros(len(idx), dtype=int)
            for _k in range(6):
                F, Jy, *_ = _evaluate(self.sweep, y, d, self.scale)
                A = np.concatenate([Jy, t[:, None, :]], axis=1)
                rhs = np.concatenate([F, (np.sum((y - x) * t, axis=-1) - h)[:, None]], axis=-1)
                with np.errstate(all="ignore"):
                    dy = -np.linalg.solve(A, rhs[..., None])[..., 0]
                size = np.max(np.abs(dy), axis=-1)
                ok = np.isfinite(size)
                y = np.where((ok & ~conv)[:, None], y + np.where(ok[:, None], dy, 0), y)
                iters += ~conv
                conv |= ok & (size < self.tol)
                if np.all(conv | ~ok):
                    break
            tn = _tangent(Jy, t)  # at the last corrector iterate: the final correction is below tol
            good = (
                conv
                & np.all(np.isfinite(tn), axis=-1)
                & (np.sum(tn * t, axis=-1) > np.cos(0.5))
                & (np.linalg.norm(y - x, axis=-1) < 2 * h)
            )
            for j, i in enumerate(idx):
                if not good[j]:
                    H[i] *= 0.5
                    if H[i] < self.h_min:
                        active[i] = False
                    continue
                out = self._outside(y[j])
                if out is not None:
                    end = self._end_point(x[j], y[j], d[j], out)
                    if end is not None:
                        pts[i].append(end)
                    active[i] = False
                    continue
                walked[i] += np.linalg.norm(y[j] - x[j])
                pts[i].append(y[j].copy())
                X[i], T[i] = y[j], tn[j]
                H[i] = min(H[i] * (1.5 if iters[j] <= 3 else 1.0), self.h_max)
                if walked[i] > 4 * self.h_max and np.linalg.norm(y[j] - pts[i][0]) < 0.75 * H[i]:
                    pts[i].append(pts[i][0].copy())
                    active[i] = False
                    loop[i] = True
                    active[i + m if i < m else i - m] = False
        else:
            self.warnings.append("continuation stopped at max_steps")
        paths = []
        for i in range(m):
            if loop[i] or loop[i + m]:
                path = np.array(pts[i] if loop[i] else pts[i + m])
            else:
                path = np.array(pts[i + m][::-1] + pts[i][1:])
            if len(path) >= 2:
                paths.append((float(ds[i]), path))
        return paths

    def _outside(self, y):
        """(coordinate, bound value) of the first box face crossed, or None."""
        for k in range(3):
            lo, hi = self.box[k]
            if y[k] < lo:
                return k, lo
            if y[k] > hi:
                return k, hi
        return None

    def _end_point(self, x, y, d, face):
        k, value = face
        w = (value - x[k]) / (y[k] - x[k])
        guess = (x + w * (y - x))[None, :]
        end, conv = _newton_fixed(self.sweep, guess, np.array([d]), k, value, self.scale, self.tol)
        if conv[0] and np.linalg.norm(end[0] - guess[0]) < 2 * np.linalg.norm(y - x) + 1e-9:
            return end[0]
        return None


def _covered(points, path, radius):
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


def _branch(sweep, d, path, theta_max) -> InstabilityBranch:
    _, _, E, E_q, E_t = _evaluate(sweep, path, np.full(len(path), d), theta_max)
    dq_dtheta = -E_t / E_q
    return InstabilityBranch(
        d=float(d),
        alpha=path[:, 0].copy(),
        theta=path[:, 2] * theta_max,
        q=path[:, 1].copy(),
        unstable_above=np.imag(dq_dtheta) < 0,
        residual=np.abs(E / E_q),
    )
