"""The stability margin of the stable cells of a column: the smallest decay rate of the induced frequencies.

A stable cell has no root of E_chr (Eq. (38)) with Im q < 0; how far it is from instability is the
smallest Im q of its roots (a vibration decays like exp(-Im q tau), Eq. (35)). Its roots lie above the
real axis, below or above the cut of K. Below the cut E_chr is analytic, so the argument principle and
the Delves-Lyness power sums (:func:`~moving_bogie.stability.maps.column_roots.rectangle_sums`) of the
rectangle -X <= Re q <= X, -Y <= Im q <= t (the column's window, its top t at most h below the cut)
count and locate every root there:

- the top starts at h. A rectangle holding more roots than the power sums locate (``MAX_STRIP_ROOTS``)
  has its top halved towards the highest top known to hold none (0 at first), and one holding none
  (below h) has it raised half way to the lowest top known to hold too many; a count that is not an
  integer (a root on the edge) moves the top by a tenth of that interval. The lowest roots are in every
  rectangle that holds any, so the first rectangle holding 1 to ``MAX_STRIP_ROOTS`` roots holds them.
  Its panels are halved where E'/E is not resolved (a root near an edge), and when its power sums do not
  locate its roots (many small roots in a wide rectangle), its top is halved again;
- its roots are polished by Newton's method, and each distinct polished root is confirmed, with its
  multiplicity, by the argument principle on a small circle around it (radius at most 1e-6 |q|, and
  less than half the distance to any other root found or to the rectangle's edge): a pair of roots closer
  than Newton's method separates (the two rails of a car) counts twice there. The multiplicities must add
  up to the rectangle's count (a pair q, -conj(q) counts twice, a root on the imaginary axis once), so no
  root of the rectangle is missed; the margin is then the smallest Im q, to within the circles' radii.

The cells of a column whose rectangles share a top are measured together: their power sums come from one
set of panels, and their roots are polished and their circles counted in shared evaluations of E_chr
(elementwise, so each cell gets the roots it gets alone, to rounding).

With no root below h the margin is h, a lower bound flagged ``bound``; when the counts never settle or the
roots do not add up, it is undetermined (NaN).

Like the column count it speaks about the column's window (the scale of the natural frequencies,
:func:`~moving_bogie.stability.maps.column.column_window`), not about roots beyond it.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from moving_bogie.stability.maps.column_roots import located, polish_roots, rectangle_sums

if TYPE_CHECKING:
    from moving_bogie.kernels.sweep_characteristic import SweepCharacteristic

__all__ = ["ColumnMargin", "cluster_counts", "column_margin", "strip_top"]

#: Largest number of roots (both members of each pair) whose power sums locate them.
MAX_STRIP_ROOTS = 16


@dataclass(frozen=True)
class ColumnMargin:
    """Per cell: the smallest Im q of its roots (h where ``bound``: no root below h; NaN: undetermined)."""

    margin: np.ndarray
    bound: np.ndarray
    h: float


def strip_top(eta_f: float, cut_low: float | None, top: float) -> float | None:
    """Im q of the rectangle's top: 0.4 eta_f, at most half way up to the lowest point of the cut over the
    window (``cut_low``; None when the cut does not pass there); None when that leaves no room above
    ``top`` (the counting rectangle's top: the cut reaches the real axis)."""
    h = 0.4 * eta_f
    if cut_low is not None:
        h = min(h, 0.5 * cut_low)
    return h if h > max(top, 0.0) + 1e-9 else None


def column_margin(
    sweep: SweepCharacteristic,
    alpha: float,
    thetas: np.ndarray,
    coeffs: Callable,
    window: tuple[float, float],
    h: float | None,
    cells: np.ndarray,
    polish: int = 10,
    base: float | None = None,
) -> ColumnMargin:
    """The margin of the cells ``cells`` (indices into ``thetas``) of one column (see the module text).

    Parameters
    ----------
    sweep : SweepCharacteristic
    alpha : float
    thetas : ndarray
        The column's values of ``sweep.parameter``.
    coeffs : callable
        ``coeffs(z)`` -> the coefficients of E and dE/dq in the scaled theta at the points z, as
        :func:`~moving_bogie.stability.maps.column.stability_column` builds them (theta / max(thetas)).
    window : (X, Y)
        Half-width and depth of the rectangle.
    h : float or None
        Its highest top (:func:`strip_top`); None leaves every margin undetermined.
    cells : ndarray of int
        The cells to measure (the stable, certain ones).
    polish : int
        Newton steps on each Delves-Lyness root (three times as many are allowed near a cluster).
    base : float, optional
        Im q of the top of the rectangle where the column count found no root of these cells (the stable
        ones): the rectangle with top t then reaches down to ``base`` - t only, rather than to -Y (half
        the boundary, the roots at least t away from its bottom edge).
    """
    margin = np.full(len(thetas), np.nan)
    bound = np.zeros(len(thetas), dtype=bool)
    if h is None or not len(cells):
        return ColumnMargin(margin, bound, np.nan if h is None else h)
    X, Y = window
    t = np.asarray(thetas, dtype=float) / float(np.max(thetas))
    # per cell: (highest top known to hold no root, lowest top known to hold too many, the next top)
    state = {int(j): (0.0, h, h) for j in cells}
    for _ in range(_ROUNDS):
        groups: dict[float, list[int]] = {}
        for j, tops in state.items():
            groups.setdefault(tops[2], []).append(j)
        for top, group in sorted(groups.items()):
            depth = Y if base is None else min(Y, top - min(base, 0.0))
            s = rectangle_sums(coeffs, t[group], X, depth, top, adaptive=True)
            counts = [s(k, 0).real for k in range(len(group))]
            # the cells whose rectangle holds 1 to MAX_STRIP_ROOTS roots: located, then measured together
            measured = [k for k, n in enumerate(counts) if _locatable(n)]
            roots = [located(s, k, int(round(counts[k]))) for k in measured]
            cells_at = [thetas[group[k]] for k in measured]
            values = dict(
                zip(measured, _smallest_many(sweep, alpha, cells_at, roots, (X, depth, top), polish))
            )
            for k, j in enumerate(group):
                following = _next_top(state.pop(j), top, h, counts[k], values.get(k, np.nan))
                if following is not None:
                    state[j] = following
                else:  # settled: a margin, or h as a bound where no root lies below h
                    margin[j], bound[j] = (h, True) if round(counts[k]) == 0 else (values[k], False)
        if not state:
            break
    return ColumnMargin(margin, bound, h)


def _on_edge(n: float) -> bool:
    """A rectangle's count ``n`` that is not an integer: a root on its edge."""
    return abs(n - round(n)) > 1e-3


def _locatable(n: float) -> bool:
    """A count of 1 to MAX_STRIP_ROOTS roots, which the power sums locate."""
    return not _on_edge(n) and 0 < round(n) <= MAX_STRIP_ROOTS


def _next_top(
    tops: tuple[float, float, float], top: float, h: float, n: float, smallest: float
) -> tuple[float, float, float] | None:
    """The next (lo, hi, top) of a cell whose rectangle with this ``top`` counted ``n`` roots (the module
    text), or None when it is settled: no root below h (its margin the bound h), or ``smallest`` measured."""
    lo, hi, _ = tops
    if _on_edge(n):
        return (lo, hi, top - 0.1 * (top - lo))
    if round(n) > MAX_STRIP_ROOTS:
        return (lo, top, 0.5 * (lo + top))
    if round(n) == 0:
        return None if top == h else (top, hi, 0.5 * (top + hi))
    # not located (NaN; :func:`_locatable` counts only): fewer roots, in a lower rectangle
    return (lo, top, 0.5 * (lo + top)) if np.isnan(smallest) else None


#: Rectangles tried per cell before its margin is left undetermined.
_ROUNDS = 8


def _smallest_many(
    sweep: SweepCharacteristic, alpha: float, thetas: list, roots: list[list], box: tuple, polish: int
) -> list[float]:
    """Per cell (its theta and its Delves-Lyness roots in the rectangle ``box`` = (X, Y, top)): the smallest
    Im q of its polished roots, where their multiplicities on small circles add up to the count and none
    lies below the real axis; else NaN. Every cell's roots are polished, and its circles counted, in the
    same evaluations (elementwise: each cell gets what it gets alone)."""
    X, Y, top = box
    sizes = [len(r) for r in roots]
    if not sizes:
        return []
    flat = np.concatenate([np.asarray(r, dtype=complex) for r in roots])
    q = polish_roots(sweep, flat, alpha, np.repeat(np.asarray(thetas, dtype=float), sizes), 3 * polish)
    kept: list[np.ndarray | None] = []
    for cell in np.split(q, np.cumsum(sizes)[:-1]):
        keep: list[complex] = []  # the distinct polished roots of the cell, each once (Re q >= 0)
        for x in cell[np.isfinite(cell)]:
            x = -np.conj(x) if x.real < 0 else x
            inside = -Y < x.imag < top and abs(x.real) < X
            if inside and all(abs(x - y) > 1e-7 * max(1.0, abs(x)) for y in keep):
                keep.append(x)
        kept.append(np.array(keep) if keep and min(x.imag for x in keep) >= 0 else None)
    chosen = [k for k, keep in enumerate(kept) if keep is not None]
    counted = _counts_many(sweep, alpha, [thetas[k] for k in chosen], [kept[k] for k in chosen], box)
    out = [np.nan] * len(roots)
    for k, n in zip(chosen, counted):
        distinct = kept[k]
        assert distinct is not None  # chosen: a cell with roots kept
        if n == sizes[k]:
            out[k] = float(distinct.imag.min())
    return out


def cluster_counts(
    sweep: SweepCharacteristic, alpha: float, theta: float, keep: np.ndarray, box: tuple, nodes: int = 32
) -> int:
    """The roots of E_chr on small circles around the distinct roots ``keep`` (Re q >= 0), counted as the
    argument principle counts the rectangle ``box`` = (X, Y, top): a circle off the imaginary axis twice
    (its mirror -conj(q) holds as many), one on it once. -1 when a circle cannot be drawn (a root at the
    edge) or its count is not an integer.

    Each count is (1/2 pi i) of the contour integral of E'/E over the circle, by the trapezoidal rule on
    ``nodes`` points (exact to about (radius / distance of the nearest root outside)^nodes).
    """
    return _counts_many(sweep, alpha, [theta], [keep], box, nodes)[0]


def _circles(keep: np.ndarray, box: tuple) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
    """(centres, radii, on the imaginary axis) of the circles of :func:`cluster_counts`; None when one
    cannot be drawn."""
    X, Y, top = box
    on_axis = np.abs(keep.real) <= 1e-9 * max(1.0, X)
    centre = np.where(on_axis, 1j * keep.imag, keep)
    others = np.concatenate([centre, -np.conj(centre[~on_axis])])
    radius = np.empty(len(centre))
    for i, c in enumerate(centre):
        gaps = np.abs(others - c)
        gaps = gaps[gaps > 0]
        edge = min(X - abs(c.real), c.imag + Y, top - c.imag)
        radius[i] = min(1e-6 * max(1.0, abs(c)), 0.4 * float(gaps.min(initial=np.inf)), 0.5 * edge)
    if np.any(radius <= 1e-12 * np.maximum(1.0, np.abs(centre))):
        return None
    return centre, radius, on_axis


def _counts_many(
    sweep: SweepCharacteristic, alpha: float, thetas: list, keeps: list, box: tuple, nodes: int = 32
) -> list[int]:
    """:func:`cluster_counts` of several cells (their thetas and distinct roots), the circles of all of
    them in one evaluation of E_chr."""
    drawn = [(k, c) for k, c in enumerate(_circles(keep, box) for keep in keeps) if c is not None]
    out = [-1] * len(keeps)
    if not drawn:
        return out
    angles = np.exp(2j * np.pi * np.arange(nodes) / nodes)
    rings, centres, theta = [], [], []
    for k, (centre, radius, _) in drawn:
        rings.append(radius[:, None] * angles)
        centres.append(centre)
        theta.append(np.full(len(centre), float(thetas[k])))
    ring = np.concatenate(rings)
    z = np.concatenate(centres)[:, None] + ring
    E, dE = sweep.e_and_dq(
        z, np.full(z.shape, alpha), np.repeat(np.concatenate(theta), nodes).reshape(z.shape)
    )
    counts = np.mean(dE / E * ring, axis=1).real
    for (k, (_, _, on_axis)), n in zip(drawn, np.split(counts, np.cumsum([len(c) for c in centres])[:-1])):
        if (
            np.all(np.isfinite(n))
            and not np.any(np.abs(n - np.round(n)) > 1e-2)
            and not np.any(np.round(n) < 1)
        ):
            out[k] = int(np.sum(np.round(n) * np.where(on_axis, 1, 2)))
    return out
