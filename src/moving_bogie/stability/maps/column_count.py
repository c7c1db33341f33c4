"""Argument-principle count of the roots below the real axis, for a whole column of theta values at once.

Let R be the rectangle -X <= Re q <= X, -Y <= Im q <= top (top = 0, or just below the cut of K where it
reaches the real axis). Because E(-conj q) = conj E(q) (Eq. (38) with real parameters), the change of
arg E around R is twice its change along the right half of the boundary, from -iY to X - iY to X + i top
to i top; both ends lie on the imaginary axis, where E is real, so the change is a multiple of pi and R
holds N_R = change / pi roots. Roots on the negative imaginary axis (their own mirror) are the sign
changes of the real function E(iy), -Y < y < top (N_axis). Pairs q, -conj(q) are counted once by
:func:`~moving_bogie.roots.frequencies.induced_frequencies`, so the number of unstable induced frequencies
is (N_R + N_axis) / 2.

At fixed (q, alpha), E_chr is a polynomial in theta (:mod:`~moving_bogie.kernels.sweep_characteristic`):
the track kernel is evaluated once per contour point and E for every theta is a Horner evaluation.

Sampling. The top edge (the real axis, which roots on instability lines approach) is refined per theta
row. A segment is halved while the change of log E across it (its phase step or its change of log|E|)
exceeds ``max_step`` in size, or while log|E| at its midpoint departs from the mean of its ends by more
than ``max_bend``: two roots close to the axis and to each other turn the phase by about 2 pi across one
segment, which a phase test alone reads as a small step, but they change log|E| strongly across it (a
segment is accepted only where |E'/E| times its length is small, i.e. it is short compared with its
distance to every root). The base samples are screened the same way (and by the second difference of
log|E|). A row
whose refinement reaches ``min_spacing`` (a root within about that distance of the real axis) or whose
count is not an integer is flagged ``uncertain``.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from moving_bogie.kernels.polynomial import horner

__all__ = ["BoxCount", "count_box", "edge_samples", "horner_pairs", "horner_rows"]


def edge_samples(a: complex, b: complex, h: float) -> np.ndarray:
    """Points from ``a`` (included) towards ``b`` (excluded), at most ``h`` apart (at least 8)."""
    n = max(8, int(np.ceil(abs(b - a) / h)))
    return a + (b - a) * np.arange(n) / n


def horner_rows(c: np.ndarray, T: np.ndarray) -> np.ndarray:
    """E at every contour point for every t: c (M, deg+1) complex, T (n, 1) -> (n, M) (:func:`horner`)."""
    return _broadcast(horner(np.moveaxis(c, -1, 0), T), np.broadcast_shapes(T.shape, c.shape[:-1]))


def horner_pairs(c: np.ndarray, idx: np.ndarray, t: np.ndarray) -> np.ndarray:
    """E at points ``idx`` (coefficient rows of c) for the matching t values (1-d arrays; :func:`horner`)."""
    return _broadcast(horner(np.moveaxis(c[idx], -1, 0), t), np.broadcast_shapes(t.shape, c[idx].shape[:-1]))


def _broadcast(values: np.ndarray, shape: tuple[int, ...]) -> np.ndarray:
    """``values`` with the shape of the points and t values (a polynomial of degree 0 is constant in t)."""
    return values if values.shape == shape else np.broadcast_to(values, shape).copy()


@dataclass
class BoxCount:
    """Right half of the boundary of the rectangle -X..X x -Y..top, sampled, with E for every t."""

    path: np.ndarray  # base samples: -iY -> X - iY -> X + i top -> i top
    n_outer: int  # samples before the top edge
    E: np.ndarray  # (n_t, len(path)) at the base samples
    n_rect: np.ndarray  # (change of arg E along the path) / pi = roots in the rectangle
    n_axis: np.ndarray  # sign changes of E(iy) on the imaginary-axis edge
    uncertain: np.ndarray  # refinement reached min_spacing, or a non-integer count
    near_axis: list  # per t: places on the top edge where refinement went deepest (roots nearby)


def _bent(E: np.ndarray, max_bend: float) -> np.ndarray:
    """Segments (rows, k) next to a base sample where log|E| bends by more than ``max_bend``."""
    with np.errstate(divide="ignore", invalid="ignore"):
        L = 0.5 * np.log(E.real**2 + E.imag**2)
        bend = np.abs(L[:, 2:] - 2 * L[:, 1:-1] + L[:, :-2])
    bad = ~(bend <= max_bend)
    out = np.zeros((E.shape[0], E.shape[1] - 1), dtype=bool)
    out[:, 1:] |= bad
    out[:, :-1] |= bad
    return out


def count_box(
    coeffs: Callable[[np.ndarray], tuple[np.ndarray, Any]],
    t: np.ndarray,
    X: float,
    Y: float,
    top: float,
    spacing: float,
    coarse: float,
    max_step: float,
    min_spacing: float,
    max_bend: float = 0.5,
    fine_until: float | None = None,
    extra: Sequence[float] | np.ndarray | None = None,
) -> BoxCount:
    """Sample the right half-boundary and count the roots in the rectangle for every t (module text).

    ``coeffs(z)`` returns the coefficients of E in t at the points z (first element of a pair). The top
    edge is sampled at ``spacing`` for Re q <= ``fine_until`` (default X) and at ``coarse`` beyond, where
    the refinement alone resolves roots near the axis. ``extra`` (values of Re q) are added to the top
    edge's samples: dense samples around a branch point of K lying on or just above it (eta_f = 0), where
    K grows like its inverse square root and E changes on the scale of the distance. The new point of a
    halved segment has its track kernel computed once for every row that needs it; the change of arg E is
    the sum of the steps over each row's leaves.
    """
    outer, z0, axis = _half_boundary(X, Y, top, spacing, coarse, min_spacing, fine_until, extra)
    path = np.concatenate([outer, z0])
    T = t[:, None]
    c_path, _ = coeffs(path)
    E = horner_rows(c_path, T)
    steps = np.angle(E[:, 1:] / E[:, :-1])
    n_rect = steps.sum(axis=1)
    base = len(outer)
    z_all = path.copy()
    c_all = c_path
    rows, lo, hi, st = _flagged_segments(E, steps, base, max_step, max_bend)
    near: list[list[Any]] = [[] for _ in t]
    uncertain = np.zeros(len(t), dtype=bool)
    for _ in range(80):
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
        Ea = horner_pairs(c_all, lo, t[rows])
        Em = horner_pairs(c_all, m, t[rows])
        Eb = horner_pairs(c_all, hi, t[rows])
        s1, s2 = np.angle(Em / Ea), np.angle(Eb / Em)
        np.add.at(n_rect, rows, s1 + s2 - st)
        with np.errstate(divide="ignore", invalid="ignore"):
            la, lm, lb = np.log(np.abs(Ea)), np.log(np.abs(Em)), np.log(np.abs(Eb))
            bend = np.abs(lm - 0.5 * (la + lb))
            jump = np.concatenate([np.abs(lm - la), np.abs(lb - lm)])
        bent = ~(bend <= max_bend)
        for r_, z_ in zip(rows, z_all[m]):
            if len(near[r_]) < 64:
                near[r_].append(z_)
        r2 = np.concatenate([rows, rows])
        l2, h2, s12 = np.concatenate([lo, m]), np.concatenate([m, hi]), np.concatenate([s1, s2])
        keep = (np.abs(s12) > max_step) | ~(jump <= max_step) | np.concatenate([bent, bent])
        rows, lo, hi, st = r2[keep], l2[keep], h2[keep], s12[keep]
    n_rect = n_rect / np.pi
    uncertain |= np.abs(n_rect - np.rint(n_rect)) > 1e-3
    c_axis, _ = coeffs(axis)
    Ea = horner_rows(c_axis, T).real
    n_axis = np.sum(np.sign(Ea[:, 1:]) * np.sign(Ea[:, :-1]) < 0, axis=1)
    return BoxCount(path, base, E, n_rect, n_axis, uncertain, near)


def _flagged_segments(
    E: np.ndarray, steps: np.ndarray, base: int, max_step: float, max_bend: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The segments of the path after its first ``base`` samples (the top edge) to halve, row by row: a
    phase step of E or a jump of log|E| over ``max_step``, or a bend of log|E| over ``max_bend``. Returns
    (rows, first sample, second sample, phase step) of each."""
    with np.errstate(divide="ignore", invalid="ignore"):
        log_mod = np.log(np.abs(E[:, base:]))
        jumps = np.abs(np.diff(log_mod, axis=1))
    flagged = (np.abs(steps[:, base:]) > max_step) | ~(jumps <= max_step)
    flagged |= _bent(E[:, base:], max_bend)
    rows, seg = np.nonzero(flagged)
    seg = seg + base
    return rows, seg, seg + 1, steps[rows, seg]


def _half_boundary(
    X: float,
    Y: float,
    top: float,
    spacing: float,
    coarse: float,
    min_spacing: float,
    fine_until: float | None,
    extra: Sequence[float] | np.ndarray | None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The samples of the right half-boundary of the rectangle (see :func:`count_box`): the bottom and right
    edges (``outer``), the top edge from Re q = X to 0 (``z0``: ``spacing`` up to ``fine_until``, the
    ``extra`` values of Re q added) and the imaginary axis down to -Y (``axis``)."""
    outer = np.concatenate(
        [
            edge_samples(complex(0, -Y), complex(X, -Y), coarse),
            edge_samples(complex(X, -Y), complex(X, top), coarse),
        ]
    )
    split = X if fine_until is None else min(X, fine_until)
    z0 = np.concatenate(
        [
            edge_samples(complex(X, top), complex(split, top), coarse) if split < X else np.zeros(0, complex),
            edge_samples(complex(split, top), complex(0, top), spacing),
            [complex(0, top)],
        ]
    )
    if extra is not None and len(extra):
        x = np.asarray(extra, dtype=float)
        x = np.unique(np.concatenate([z0.real, x[(x > 0) & (x < X)]]))
        x = x[np.concatenate([[True], np.diff(x) > 10 * min_spacing])]  # no two closer than the finest
        z0 = x[::-1] + 1j * top
    axis = np.append(edge_samples(complex(0, top), complex(0, -Y), coarse), complex(0, -Y))
    return outer, z0, axis
