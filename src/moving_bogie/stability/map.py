"""Stability maps: the degree of instability over an (alpha, theta) grid, in vectorised double precision.

The degree of instability is the most negative Im q over the induced frequencies (0 when stable, Eq. (35):
a root with Im q < 0 grows like exp(|Im q| tau)). For each alpha the whole column of theta values (theta =
eta_M by default) is done at once, using that E_chr is a polynomial in theta at fixed (q, alpha)
(:mod:`stability_kernel`): the track kernel is evaluated once on a contour in the lower half q-plane, and
E_chr, E_chr' on that contour for every theta are polynomial evaluations.

Counting (argument principle). Let R be the rectangle -X <= Re q <= X, -Y <= Im q <= 0 (below the cut
of K, which lies at Im q = eta_f > 0). Because E(-conj q) = conj E(q), the change of arg E around R is
twice its change along the right half of the boundary, from -iY to X - iY to X to 0; both ends lie on
the imaginary axis, where E is real, so the change is a multiple of pi and R holds N_R = change / pi roots.
Pairs q, -conj(q) are counted once in the paper (and by
:func:`~moving_bogie.roots.frequencies.induced_frequencies`),
roots on the negative imaginary axis (their own mirror) once too; the latter are the sign changes of the
real function E(iy), -Y < y < 0. So the number of unstable induced frequencies is (N_R + N_axis) / 2.

Locating (Delves-Lyness). The power sums s_n = (1/2 pi i) contour-integral of q^n E'/E dq, n <= N_R, over
the boundary of R (trapezoidal rule), give the roots inside as the zeros of a polynomial (Newton's
identities); each is polished by Newton's method on E_chr. The sampling of the real axis (the edge the
roots approach) is refined wherever a phase step of E exceeds ``max_step`` for some theta; cells where it
still does at the finest spacing (a root within ~1e-7 of the real axis: on an instability line) are
flagged ``uncertain``.

The columns are independent and are spread over ``workers`` processes.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass

import numpy as np

from moving_bogie.kernels.cut import cut_locus
from moving_bogie.kernels.sweep_characteristic import SweepCharacteristic
from moving_bogie.roots.frequencies import default_window

__all__ = ["ColumnResult", "StabilityMap", "stability_column", "stability_map"]


@dataclass(frozen=True)
class ColumnResult:
    """Unstable induced frequencies along one column (fixed alpha) of theta values."""

    alpha: float
    thetas: np.ndarray
    count: np.ndarray  # unstable induced frequencies (pairs once)
    degree: np.ndarray  # most negative Im q (0 where stable)
    uncertain: np.ndarray  # the count could not be resolved (a root on or next to the real axis)
    roots: list  # per theta: the unstable roots (Re q >= 0 member of each pair)


@dataclass(frozen=True)
class StabilityMap:
    """Degree of instability ``degree[j, i]`` at (alphas[i], thetas[j]) and the unstable count."""

    params: object
    model: str
    parameter: str
    alphas: np.ndarray
    thetas: np.ndarray
    degree: np.ndarray
    count: np.ndarray
    uncertain: np.ndarray

    def save_npz(self, path) -> None:
        """Write the arrays (and the parameters as JSON text) to ``path`` (numpy .npz)."""
        import json

        np.savez_compressed(
            path,
            alphas=self.alphas,
            thetas=self.thetas,
            degree=self.degree,
            count=self.count,
            uncertain=self.uncertain,
            params=json.dumps(self.params.to_dict()),
            model=self.model,
            parameter=self.parameter,
        )

    def summary(self) -> dict:
        return {
            "params": self.params.to_dict(),
            "model": self.model,
            "parameter": self.parameter,
            "alpha_range": [float(self.alphas[0]), float(self.alphas[-1]), len(self.alphas)],
            "theta_range": [float(self.thetas[0]), float(self.thetas[-1]), len(self.thetas)],
            "unstable_fraction": float(np.mean(self.count > 0)),
            "max_degree": float(-self.degree.min()) if self.degree.size else 0.0,
            "uncertain_cells": int(self.uncertain.sum()),
        }


def _edge(a, b, h):
    n = max(8, int(np.ceil(abs(b - a) / h)))
    return a + (b - a) * np.arange(n) / n


@dataclass
class _Box:
    """Right half of the boundary of the rectangle -X..X x -Y..top, sampled, with E for every t."""

    path: np.ndarray  # base samples: -iY -> X - iY -> X + i top -> i top
    n_outer: int  # samples before the top edge
    E: np.ndarray  # (n_t, len(path)) at the base samples
    n_rect: np.ndarray  # (change of arg E along the path) / pi = roots in the rectangle
    n_axis: np.ndarray  # sign changes of E(iy) on the imaginary-axis edge
    uncertain: np.ndarray  # some phase step still above max_step at the finest spacing
    near_axis: list  # per t: places on the top edge where refinement went deepest (roots nearby)


def _box(coeffs, t, X, Y, top, spacing, coarse, max_step, min_spacing) -> _Box:
    """Sample the right half-boundary and count the roots in the rectangle for every t.

    The top edge is refined per row (per t) only: a segment whose phase step exceeds ``max_step`` for
    some row is halved (the new point's track kernel is shared by all rows), and only the rows that need
    it are evaluated there. The change of arg E is then the sum of the steps over each row's leaves.
    """
    outer = np.concatenate(
        [_edge(complex(0, -Y), complex(X, -Y), coarse), _edge(complex(X, -Y), complex(X, top), coarse)]
    )
    z0 = np.append(_edge(complex(X, top), complex(0, top), spacing), complex(0, top))
    axis = np.append(_edge(complex(0, top), complex(0, -Y), coarse), complex(0, -Y))
    path = np.concatenate([outer, z0])
    T = t[:, None]
    c_path, _ = coeffs(path)
    E = _ev(c_path, T)
    steps = np.angle(E[:, 1:] / E[:, :-1])
    n_rect = steps.sum(axis=1)
    # per-row refinement of the top edge: pending (row, left, right) with the step across them
    base = len(outer)
    z_all = path.copy()
    c_all = c_path
    rows, seg = np.nonzero(np.abs(steps[:, base:]) > max_step)
    seg = seg + base
    lo, hi = seg, seg + 1
    st = steps[rows, seg]
    near = [[] for _ in t]
    uncertain = np.zeros(len(t), dtype=bool)
    for _ in range(60):
        if rows.size == 0:
            break
        fine = np.abs(z_all[hi] - z_all[lo]) <= min_spacing
        if np.any(fine):
            uncertain[rows[fine]] = True
            for r_, a_ in zip(rows[fine], lo[fine]):
                near[r_].append(z_all[a_])
            rows, lo, hi, st = rows[~fine], lo[~fine], hi[~fine], st[~fine]
            if rows.size == 0:
                break
        keys, inverse = np.unique(lo * len(z_all) * 4 + hi, return_inverse=True)
        first = np.zeros(len(keys), dtype=int)
        first[inverse] = np.arange(len(inverse))
        mids = 0.5 * (z_all[lo[first]] + z_all[hi[first]])
        cm, _ = coeffs(mids)
        mi = len(z_all) + np.arange(len(mids))
        z_all = np.concatenate([z_all, mids])
        c_all = np.concatenate([c_all, cm])
        m = mi[inverse]
        Ea = _ev_rows(c_all, lo, t[rows])
        Em = _ev_rows(c_all, m, t[rows])
        Eb = _ev_rows(c_all, hi, t[rows])
        s1, s2 = np.angle(Em / Ea), np.angle(Eb / Em)
        np.add.at(n_rect, rows, s1 + s2 - st)
        for r_, z_ in zip(rows, z_all[m]):
            if len(near[r_]) < 64:
                near[r_].append(z_)
        r2 = np.concatenate([rows, rows])
        l2, h2, s12 = np.concatenate([lo, m]), np.concatenate([m, hi]), np.concatenate([s1, s2])
        keep = np.abs(s12) > max_step
        rows, lo, hi, st = r2[keep], l2[keep], h2[keep], s12[keep]
    n_rect = n_rect / np.pi
    uncertain |= np.abs(n_rect - np.rint(n_rect)) > 1e-3
    c_axis, _ = coeffs(axis)
    Ea = _ev(c_axis, T).real
    n_axis = np.sum(np.sign(Ea[:, 1:]) * np.sign(Ea[:, :-1]) < 0, axis=1)
    return _Box(path, base, E, n_rect, n_axis, uncertain, near)


def _ev_rows(c, idx, t):
    """E at points ``idx`` (coefficient rows of c) for the matching t values (1-d arrays)."""
    cc = c[idx]
    acc = cc[:, 0].copy()
    for k in range(1, cc.shape[-1]):
        acc = acc * t + cc[:, k]
    return acc


def _delves_lyness(coeffs, t, X, Y, top, *, panel=0.05, nodes=16, max_roots=8) -> list:
    """Roots inside -X..X x -Y..top for each t (Delves-Lyness), or an empty list where that fails.

    Power sums s_m = (1/2 pi i) contour-integral of z^m E'/E dz by 16-point Gauss-Legendre panels on the
    right half of the boundary; the left half follows from E(-conj z) = conj E(z). The roots are the
    zeros of the polynomial with these power sums (Newton's identities): starting points for Newton.
    """
    x, w = np.polynomial.legendre.leggauss(nodes)
    zs, ws = [], []
    for a, b in (
        (complex(0, -Y), complex(X, -Y)),
        (complex(X, -Y), complex(X, top)),
        (complex(X, top), complex(0, top)),
    ):
        n = max(1, int(np.ceil(abs(b - a) / panel)))
        for k in range(n):
            pa, pb = a + (b - a) * k / n, a + (b - a) * (k + 1) / n
            zs.append(pa + (pb - pa) * (x + 1) / 2)
            ws.append((pb - pa) / 2 * w)
    z, wz = np.concatenate(zs), np.concatenate(ws)
    c, dc = coeffs(z)
    E, dE = _ev(c, t[:, None]), _ev(dc, t[:, None])
    g = dE / E
    out = []
    for j in range(len(t)):

        def s(m, j=j):
            right = np.sum(z**m * g[j] * wz)
            left = np.sum((-np.conj(z)) ** m * (-np.conj(g[j])) * np.conj(wz))
            return (right + left) / (2j * np.pi)

        n = s(0).real
        if abs(n - round(n)) > 1e-3 or not 0 < round(n) <= max_roots:
            out.append([])
            continue
        out.append(list(_from_power_sums(np.array([s(m) for m in range(1, int(round(n)) + 1)]))))
    return out


def stability_column(
    sweep: SweepCharacteristic,
    alpha: float,
    thetas: np.ndarray,
    *,
    window: tuple[float, float] | None = None,
    top: float = 0.0,
    moment_top: float | None = None,
    spacing: float = 0.006,
    coarse: float = 0.03,
    max_step: float = np.pi / 3,
    min_spacing: float = 1e-7,
    polish: int = 10,
    guesses: Sequence | None = None,
) -> ColumnResult:
    """Unstable induced frequencies for every theta of ``thetas`` at one alpha (see the module text).

    Parameters
    ----------
    sweep : SweepCharacteristic
    alpha : float
    thetas : ndarray
        Values of ``sweep.parameter`` (> 0).
    window : (X, Y), optional
        Half-width and depth of the counting rectangle (default: the search window of
        :func:`~moving_bogie.roots.frequencies.default_window` for the largest theta).
    top : float
        Im q of the counting rectangle's upper edge (0; slightly negative when eta_f = 0 puts the cut on
        the axis).
    moment_top : float, optional
        Im q of the upper edge of the rectangle whose power sums locate the roots (default 0.4 eta_f,
        between the real axis and the cut): roots near the real axis, where the power sums over the
        counting rectangle would be inaccurate, are then well inside. Roots found above the real axis
        are stable and discarded.
    spacing, coarse : float
        Initial sampling of the top edges and of the other edges.
    max_step : float
        Largest accepted phase step of E between samples (radians).
    min_spacing : float
        Finest sampling of the real axis; a phase step still too large there flags the cell ``uncertain``.
    polish : int
        Largest number of Newton steps on each candidate (a candidate that has not converged to 1e-11
        by then is dropped).
    guesses : sequence of arrays, optional
        Extra starting points per theta (the unstable roots of the neighbouring column).
    """
    thetas = np.asarray(thetas, dtype=float)
    scale = float(thetas.max())
    t = thetas / scale
    if window is None:
        w = default_window(sweep.params.replace(**{sweep.parameter: _frac(scale)}), sweep.model)
        window = (w.x1, -w.y0)
    X, Y = window
    if moment_top is None:
        moment_top = top + 0.4 * float(sweep.params.eta_f)

    def coeffs(z):
        K, dK, _ = sweep.kernel(z, alpha, derivative=True)
        return sweep.coefficients(z, K, scale=scale, dK=dK)

    def count_coeffs(z):  # the counting needs E only
        K, _, _ = sweep.kernel(z, alpha)
        return sweep.coefficients(z, K, scale=scale), None

    box = _box(count_coeffs, t, X, Y, top, spacing, coarse, max_step, min_spacing)
    total = np.rint(box.n_rect).astype(int) + box.n_axis
    uncertain = box.uncertain | ((total % 2) != 0)
    count = np.maximum(total // 2, 0)
    # Newton from, in turn: the neighbouring column's roots (continuation in alpha), the places on the
    # real axis where a root just below (or above) it shows (|E| dips, the refinement goes deep), the
    # neighbouring theta's roots (inside _locate), and the Delves-Lyness roots of a taller rectangle
    unstable = np.nonzero(count > 0)[0]
    roots = [np.zeros(0, dtype=complex) for _ in t]

    def short():
        return np.array([j for j in unstable if len(roots[j]) < count[j]], dtype=int)

    def merge(more):
        for j in range(len(t)):
            if len(more[j]) > len(roots[j]):
                roots[j] = more[j]

    if guesses is not None:
        cands = [list(guesses[j]) if count[j] else [] for j in range(len(t))]
        merge(_locate(sweep, alpha, thetas, cands, count, polish, spread=False))
    todo = short()
    if todo.size:
        cands = [[] for _ in t]
        for j in todo:
            cands[j] = _dip_candidates(box, j) + list(roots[j])
        merge(_locate(sweep, alpha, thetas, cands, count, polish, spread=False))
    todo = short()
    if todo.size:
        cands = [list(roots[j]) for j in range(len(t))]
        merge(_locate(sweep, alpha, thetas, cands, count, polish))
    # Delves-Lyness, on a taller rectangle (roots near the real axis well inside), then on one whose top
    # lies a little below the axis (only the deeper roots inside)
    for box_top in (max(moment_top, top), top - 0.005, top - 0.02):
        todo = short()
        if not todo.size:
            break
        cands = [[] for _ in t]
        for j, r in zip(todo, _delves_lyness(coeffs, t[todo], X, Y, box_top)):
            cands[j] = r + list(roots[j])
        merge(_locate(sweep, alpha, thetas, cands, count, polish, spread=False))
    degree = np.array([min(0.0, float(np.min(r.imag))) if len(r) else 0.0 for r in roots])
    uncertain |= np.array([len(r) != c for r, c in zip(roots, count)])
    return ColumnResult(float(alpha), thetas, count, degree, uncertain, roots)


def _ev(c, T):
    """E at every contour point for every t: c (M, deg+1), T (n, 1) -> (n, M) (Horner, in place)."""
    acc = np.empty((T.shape[0], c.shape[0]), dtype=complex)
    acc[:] = c[None, :, 0]
    for k in range(1, c.shape[-1]):
        acc *= T
        acc += c[None, :, k]
    return acc


def _from_power_sums(s):
    """Roots of the monic polynomial whose roots have power sums s[0..n-1] (Newton's identities)."""
    n = len(s)
    e = [1.0 + 0j]
    for k in range(1, n + 1):
        e.append(sum((-1) ** (i - 1) * e[k - i] * s[i - 1] for i in range(1, k + 1)) / k)
    coeffs = [(-1) ** k * e[k] for k in range(n + 1)]
    return np.roots(coeffs) if n > 0 else np.zeros(0, dtype=complex)


def _dip_candidates(box, j, limit=10):
    """Starting points below the places of the top edge where a root near the real axis shows."""
    zr = box.path[box.n_outer :]
    mag = np.abs(box.E[j, box.n_outer :])
    inner = np.nonzero((mag[1:-1] < mag[:-2]) & (mag[1:-1] < mag[2:]))[0] + 1
    chosen, out = [], []
    for z_ in list(zr[inner[np.argsort(mag[inner])][:limit]]) + box.near_axis[j][::-1]:
        if len(chosen) >= limit:
            break
        if all(abs(z_ - c) > 0.002 for c in chosen):
            chosen.append(z_)
            out += [z_ - 0.002j, z_ - 0.01j, z_ - 1e-4j]
    return out


def _locate(sweep, alpha, thetas, cands, count, steps, spread=True):
    """Polish the candidates of every cell at once; with ``spread``, cells still short of roots then
    borrow the roots of the nearest complete cell (continuation in theta), front by front."""
    roots = [np.zeros(0, dtype=complex) for _ in thetas]
    tried: dict = {}
    for _ in range(len(thetas) + 1):
        owner = np.concatenate([np.full(len(c), j) for j, c in enumerate(cands)]).astype(int)
        flat = np.array([x for c in cands for x in c], dtype=complex)
        if flat.size:
            flat = _polish(sweep, flat, alpha, thetas[owner], steps)
        for j in set(owner.tolist()):
            r = list(roots[j]) + [x for x in flat[owner == j] if np.isfinite(x) and x.imag < 0]
            keep = []
            for x in r:
                x = -np.conj(x) if x.real < 0 else x
                if all(abs(x - y) > 1e-7 * max(1.0, abs(x)) for y in keep):
                    keep.append(x)
            roots[j] = np.array(sorted(keep, key=lambda x: x.imag), dtype=complex)
        complete = np.array([len(r) >= c for r, c in zip(roots, count)])
        cands = [[] for _ in thetas]
        for j in np.nonzero(~complete)[0]:
            for nb in (j - 1, j + 1):
                if 0 <= nb < len(thetas) and complete[nb] and count[nb] > 0 and nb not in tried.get(j, ()):
                    cands[j] += list(roots[nb])
                    tried.setdefault(j, set()).add(nb)
        if not spread or not any(cands):
            break
    return roots


def _polish(sweep, q, alpha, thetas, steps, tol=1e-11):
    """Newton on E_chr for every (q, theta) pair; non-converged entries come back as nan."""
    q = q.astype(complex)
    done = np.zeros(q.shape, dtype=bool)
    for _ in range(steps):
        todo = ~done & np.isfinite(q)
        if not np.any(todo):
            break
        E, dE = sweep.e_and_dq(q[todo], np.full(int(todo.sum()), alpha), thetas[todo])
        with np.errstate(all="ignore"):
            step = E / dE
        ok = np.isfinite(step) & (np.abs(step) < 0.1)
        qt = np.where(ok, q[todo] - step, np.nan)
        q[todo] = qt
        done[todo] = ok & (np.abs(step) < tol * np.maximum(1.0, np.abs(qt)))
    return np.where(done, q, np.nan)


def _frac(x):
    from fractions import Fraction

    return Fraction(str(float(x)))


def _column_task(args):
    params, model, parameter, alphas, thetas, options = args
    sweep = SweepCharacteristic(params, model, parameter)
    out = []
    for a in alphas:
        guesses = out[-1].roots if out else None  # continuation from the neighbouring column
        out.append(stability_column(sweep, a, thetas, guesses=guesses, **options))
    return out


def stability_map(
    params,
    model: str | None = None,
    *,
    parameter: str = "eta_M",
    alphas: Sequence[float] | None = None,
    thetas: Sequence[float] | None = None,
    workers: int | None = None,
    chunk: int = 8,
    progress: Callable[[float], None] | None = None,
    **options,
) -> StabilityMap:
    """Degree of instability over the grid ``alphas x thetas`` (beyond the paper).

    Parameters
    ----------
    params : DimensionlessParams
        Everything but alpha and ``parameter`` (cf1, cf2 kept fixed when the parameter is eta_M).
    model : {"bogie", "masses"}
    parameter : {"eta_M", "kappa_v", "eta_v"}
    alphas, thetas : sequence of float
        Grid (default 0..1.2 and 0..200 in 200 steps each, theta > 0).
    workers : int, optional
        Processes (default: the number of CPUs, at most 2 columns chunks each); 1 runs in-process.
    chunk : int
        Columns per task.
    progress : callable, optional
        Called with the fraction of columns done.
    **options
        Passed to :func:`stability_column`.
    """
    model = model or params.vehicle
    alphas = np.asarray(np.linspace(0.0, 1.2, 200) if alphas is None else alphas, dtype=float)
    thetas = np.asarray(np.linspace(1.0, 200.0, 200) if thetas is None else thetas, dtype=float)
    if "top" not in options:
        options["top"] = _top_edge(params, alphas)
    chunks = [alphas[i : i + chunk] for i in range(0, len(alphas), chunk)]
    tasks = [(params, model, parameter, c, thetas, options) for c in chunks]
    workers = workers or min(len(chunks), os.cpu_count() or 1)
    columns = []
    if workers <= 1:
        for k, task in enumerate(tasks):
            columns += _column_task(task)
            if progress is not None:
                progress((k + 1) / len(tasks))
    else:
        with ProcessPoolExecutor(max_workers=workers) as pool:
            for k, result in enumerate(pool.map(_column_task, tasks)):
                columns += result
                if progress is not None:
                    progress((k + 1) / len(tasks))
    degree = np.stack([c.degree for c in columns], axis=1)
    count = np.stack([c.count for c in columns], axis=1)
    uncertain = np.stack([c.uncertain for c in columns], axis=1)
    return StabilityMap(params, model, parameter, alphas, thetas, degree, count, uncertain)


def _top_edge(params, alphas) -> float:
    """Im q of the counting rectangle's top: 0, or just below the cut where it reaches the real axis."""
    lowest = np.inf
    for a in (float(np.min(alphas)), float(np.max(alphas))):
        cut = cut_locus(params.replace(alpha=_frac(a)), -3.0, 3.0, samples=2001)
        if cut.points.size:
            lowest = min(lowest, cut.im_low)
    return 0.0 if lowest > 1e-6 else min(0.0, lowest) - 1e-7
