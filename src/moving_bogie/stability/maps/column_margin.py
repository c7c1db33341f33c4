"""The stability margin of the stable cells of a column: the smallest decay rate of the induced frequencies.

A stable cell has no root of E_chr (Eq. (38)) with Im q < 0; how far it is from instability is the
smallest Im q of its roots (a vibration decays like exp(-Im q tau), Eq. (35)). Its roots lie above the
real axis, below or above the cut of K. Below the cut E_chr is analytic, so the argument principle and
the Delves-Lyness power sums (:func:`~moving_bogie.stability.maps.column_roots.delves_lyness`) of the
rectangle -X <= Re q <= X, -Y <= Im q <= h (the column's window, its top h below the cut) count and
locate every root there; each is polished by Newton's method and the located roots must add up to the
count (a pair q, -conj(q) counts twice, a root on the imaginary axis once). Then:

- roots in the rectangle: the margin is their smallest Im q, earned by the count;
- no root in it: every root of the window lies above h (or above the cut), and the margin is at least h:
  a lower bound, flagged ``bound``;
- the count is not an integer or the roots do not add up: the margin is undetermined (NaN).

Like the column count it speaks about the column's window (the scale of the natural frequencies,
:func:`~moving_bogie.stability.maps.column.column_window`), not about roots beyond it.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from moving_bogie.stability.maps.column_roots import delves_lyness, polish_roots

if TYPE_CHECKING:
    from moving_bogie.kernels.sweep_characteristic import SweepCharacteristic

__all__ = ["ColumnMargin", "column_margin", "strip_top"]

#: Largest number of roots (both members of each pair) whose power sums locate them.
MAX_STRIP_ROOTS = 16


@dataclass(frozen=True)
class ColumnMargin:
    """Per cell: the smallest Im q of the roots below the rectangle's top (that top where ``bound``, the top
    having been lowered from ``h`` for a cell with a root near it; NaN: undetermined)."""

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


def _mirrored(roots: np.ndarray, x: float) -> int:
    """Roots counted as the argument principle counts them: a pair twice, one on the imaginary axis once."""
    return int(sum(1 if abs(r.real) <= 1e-9 * max(1.0, x) else 2 for r in roots))


def column_margin(
    sweep: SweepCharacteristic,
    alpha: float,
    thetas: np.ndarray,
    coeffs: Callable,
    window: tuple[float, float],
    h: float | None,
    cells: np.ndarray,
    polish: int = 10,
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
        Its top (:func:`strip_top`); None leaves every margin undetermined.
    cells : ndarray of int
        The cells to measure (the stable, certain ones).
    polish : int
        Newton steps on each Delves-Lyness root.
    """
    margin = np.full(len(thetas), np.nan)
    bound = np.zeros(len(thetas), dtype=bool)
    if h is None or not len(cells):
        return ColumnMargin(margin, bound, np.nan if h is None else h)
    X, Y = window
    t = np.asarray(thetas, dtype=float) / float(np.max(thetas))
    todo = np.asarray(cells, dtype=int)
    for top, panel in ((h, 0.05), (0.75 * h, 0.05), (0.5 * h, 0.02)):  # a root near the top: a lower top
        found = delves_lyness(
            coeffs, t[todo], X, Y, top, panel=panel, max_roots=MAX_STRIP_ROOTS, with_empty=True
        )
        for j, roots in zip(todo, found):
            if roots is not None:
                margin[j], bound[j] = _smallest(sweep, alpha, thetas[j], roots, (X, Y, top), polish)
        todo = todo[np.isnan(margin[todo])]
        if not todo.size:
            break
    return ColumnMargin(margin, bound, h)


def _smallest(
    sweep: SweepCharacteristic, alpha: float, theta: float, roots: list, box: tuple, polish: int
) -> tuple[float, bool]:
    """(margin, bound) of one cell from the Delves-Lyness roots of the rectangle ``box`` = (X, Y, top):
    ``top`` where it holds no root, the smallest Im q of the polished roots where they add up to the
    count and none lies below the real axis, else NaN."""
    X, Y, top = box
    if not roots:
        return top, True
    q = polish_roots(sweep, np.asarray(roots, dtype=complex), alpha, np.full(len(roots), theta), polish)
    keep: list[complex] = []
    for x in q[np.isfinite(q)]:
        x = -np.conj(x) if x.real < 0 else x
        inside = -Y < x.imag < top and abs(x.real) < X
        if inside and all(abs(x - y) > 1e-7 * max(1.0, abs(x)) for y in keep):
            keep.append(x)
    if _mirrored(np.array(keep), X) != len(roots) or min(x.imag for x in keep) < 0:
        return np.nan, False
    return min(x.imag for x in keep), False
