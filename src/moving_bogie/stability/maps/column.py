"""Unstable induced frequencies along one column (fixed alpha, a vector of theta values) of a stability map.

The degree of instability is the most negative Im q over the induced frequencies (0 when stable, Eq. (35):
a root with Im q < 0 grows like exp(|Im q| tau)). A whole column of theta values (theta = eta_M, kappa_v or
eta_v, in which E_chr is a polynomial at fixed q and alpha) is counted at once by the argument principle
(:mod:`column_count`), then its roots are located by Newton's method (:mod:`column_roots`). Cells the
column count cannot settle (a root within ~1e-7 of the real axis, a count that is not an integer, or fewer
roots found than counted) are settled by :func:`settle_cells`: a full count at that point by
:func:`~moving_bogie.roots.frequencies.induced_frequencies`, the judge of every verdict.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, replace
from fractions import Fraction
from typing import Any

import mpmath
import numpy as np

from moving_bogie.errors import MovingBogieError
from moving_bogie.kernels.bound import BoundModel
from moving_bogie.kernels.cut import cut_locus
from moving_bogie.kernels.sweep_characteristic import SweepCharacteristic
from moving_bogie.roots.count.window import default_window
from moving_bogie.stability.maps.column_count import BoxCount, count_box
from moving_bogie.stability.maps.column_margin import column_margin, strip_top
from moving_bogie.stability.maps.column_roots import delves_lyness, dip_candidates, locate_roots

__all__ = [
    "ColumnResult",
    "at_theta",
    "branch_points",
    "branch_samples",
    "column_window",
    "exact",
    "settle_cells",
    "stability_column",
    "top_edge",
]


@dataclass(frozen=True)
class ColumnResult:
    """Unstable induced frequencies along one column (fixed alpha) of theta values.

    ``uncertain`` marks cells whose count is not certified; ``settled`` those whose verdict comes from a
    full count (:func:`settle_cells`) instead of the column count. ``margin`` is the smallest Im q of the
    induced frequencies (:mod:`~moving_bogie.stability.maps.column_margin`): the degree where unstable,
    the smallest decay rate where stable, NaN where undetermined, and a lower bound where ``margin_bound``.
    """

    alpha: float
    thetas: np.ndarray
    count: np.ndarray  # unstable induced frequencies (pairs once)
    degree: np.ndarray  # most negative Im q (0 where stable)
    uncertain: np.ndarray  # the count could not be certified
    roots: list[np.ndarray]  # per theta: the unstable roots (Re q >= 0 member of each pair)
    settled: np.ndarray | None = None
    margin: np.ndarray | None = None  # smallest Im q (the degree where unstable; NaN: undetermined)
    margin_bound: np.ndarray | None = None  # the margin is only a lower bound (no root below it)


def exact(x: float | str | Fraction) -> Fraction:
    """The shortest decimal text of a float, read exactly (as the command line reads its options)."""
    return Fraction(str(float(x)))


def at_theta(
    bound: BoundModel, parameter: str, theta: Fraction | float, held: Iterable[str] = ()
) -> BoundModel:
    """``bound`` with ``parameter = theta`` (exact), the groups of ``held`` kept at their values instead of
    following it (:class:`~moving_bogie.kernels.sweep_characteristic.SweepCharacteristic`)."""
    params = bound.params
    return bound.replace(**{name: getattr(params, name) for name in held}, **{parameter: theta})


def column_window(
    bound: BoundModel, parameter: str, thetas: np.ndarray, held: Iterable[str] = ()
) -> tuple[float, float, float]:
    """(X, Y) covering :func:`~moving_bogie.roots.count.window.default_window` (the scale of the induced
    frequencies) at the smallest and at the largest theta of the column, and the smaller of the two X (the
    part of the real axis every cell's window holds).

    Not the far-field window of :func:`~moving_bogie.roots.frequencies.induced_frequencies` (whose radius R
    can be hundreds of times larger, too long a contour to sample at this spacing): a root with Im q < 0
    between the two would be missed here; the full counts of the per-chunk check of a sweep would see it.
    """
    windows = [
        default_window(at_theta(bound, parameter, exact(theta), held))
        for theta in (float(np.min(thetas)), float(np.max(thetas)))
    ]
    return max(w.x1 for w in windows), max(-w.y0 for w in windows), min(w.x1 for w in windows)


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
    max_bend: float = 0.2,
    min_spacing: float = 1e-10,
    polish: int = 10,
    guesses: Sequence[Sequence[complex] | np.ndarray] | None = None,
    extra: Sequence[float] | np.ndarray | None = None,
    margin: bool = True,
) -> ColumnResult:
    """Unstable induced frequencies for every theta of ``thetas`` at one alpha (see the module text).

    Parameters
    ----------
    sweep : SweepCharacteristic
    alpha : float
    thetas : ndarray
        Values of ``sweep.parameter`` (> 0).
    window : (X, Y), optional
        Half-width and depth of the counting rectangle (default :func:`column_window`; the real axis is
        then sampled at ``spacing`` up to the X every cell's own window reaches, at ``coarse`` beyond).
    top : float
        Im q of the counting rectangle's upper edge (0; slightly negative when the cut reaches the axis).
    moment_top : float, optional
        Im q of the upper edge of the rectangle whose power sums locate the roots (default 0.4 eta_f,
        between the real axis and the cut). Roots found above the real axis are stable and discarded.
    spacing, coarse : float
        Initial sampling of the top edges and of the other edges.
    max_step, max_bend : float
        Largest accepted phase step of E between samples (radians), and bend of log|E| at a midpoint.
    min_spacing : float
        Finest sampling of the real axis; refinement still wanted there flags the cell ``uncertain``.
    polish : int
        Largest number of Newton steps on each candidate (a candidate that has not converged to 1e-11
        by then is dropped).
    guesses : sequence of arrays, optional
        Extra starting points per theta (the unstable roots of the neighbouring column).
    extra : sequence of float, optional
        Extra samples (values of Re q) of the counting rectangle's top edge. Default: when ``top`` < 0 (the
        cut of K reaches the real axis), :func:`branch_samples` around the branch points of K on the axis.
    margin : bool
        Measure the margin of the stable cells (:mod:`~moving_bogie.stability.maps.column_margin`).
    """
    thetas = np.asarray(thetas, dtype=float)
    scale = float(thetas.max())
    t = thetas / scale
    X, Y, fine_until = (
        column_window(sweep.bound, sweep.parameter, thetas, sweep.held) if window is None else (*window, None)
    )
    if extra is None and top < 0:
        extra = branch_samples(branch_points(sweep.bound, alpha))
    moment_top = top + 0.4 * float(sweep.params.eta_f) if moment_top is None else moment_top

    coeffs, count_coeffs = _column_coefficients(sweep, alpha, thetas)
    box = count_box(
        count_coeffs, t, X, Y, top, spacing, coarse, max_step, min_spacing, max_bend, fine_until, extra
    )
    total = np.rint(box.n_rect).astype(int) + box.n_axis
    uncertain = box.uncertain | ((total % 2) != 0)
    count = np.maximum(total // 2, 0)
    tops = (max(moment_top, top), top - 0.005, top - 0.02)  # the rectangles whose power sums locate roots
    roots = _unstable_roots(sweep, alpha, thetas, box, count, guesses, coeffs, (X, Y), tops, polish)
    degree = np.array([min(0.0, float(np.min(r.imag))) if len(r) else 0.0 for r in roots])
    uncertain |= np.array([len(r) != c for r, c in zip(roots, count)])
    stable = np.nonzero((count == 0) & ~uncertain)[0]
    h = strip_top(float(sweep.params.eta_f), _cut_low(sweep.bound, alpha, X), top) if margin else None
    cells = stable if margin else stable[:0]
    found = column_margin(sweep, alpha, thetas, coeffs, (X, Y), h, cells, polish, base=top)
    margins = np.where(count > 0, degree, found.margin)
    margins[uncertain] = np.nan
    settled = np.zeros(len(t), dtype=bool)
    return ColumnResult(float(alpha), thetas, count, degree, uncertain, roots, settled, margins, found.bound)


def _column_coefficients(
    sweep: SweepCharacteristic, alpha: float, thetas: np.ndarray
) -> tuple[Callable[[np.ndarray], Any], Callable[[np.ndarray], Any]]:
    """The coefficients of E_chr in theta / max(thetas) at the points z and ``alpha``: with their
    q-derivative (to locate roots), and alone (the counting needs E only).

    A column of one value needs no polynomial: its coefficients are E itself (degree 0), evaluated at that
    value, a ninth of the work for a car (degree 8 in the wheel mass).
    """
    scale = float(thetas.max())
    one = float(thetas[0]) if len(thetas) == 1 else None

    def coeffs(z: np.ndarray) -> Any:
        K, dK, _ = sweep.kernel(z, alpha, derivative=True)
        if one is not None:
            E, E_q = sweep.e_and_dq_from(z, K, dK, one)
            return E[..., None], E_q[..., None]
        return sweep.coefficients(z, K, scale=scale, dK=dK)

    def count_coeffs(z: np.ndarray) -> Any:
        K, _, _ = sweep.kernel(z, alpha)
        if one is not None:
            return np.broadcast_to(sweep.e_chr(z, K, one), np.shape(z))[..., None], None
        return sweep.coefficients(z, K, scale=scale), None

    return coeffs, count_coeffs


def _unstable_roots(
    sweep: SweepCharacteristic,
    alpha: float,
    thetas: np.ndarray,
    box: BoxCount,
    count: np.ndarray,
    guesses: Sequence[Sequence[complex] | np.ndarray] | None,
    coeffs: Callable[[np.ndarray], Any],
    window: tuple[float, float],
    tops: tuple[float, ...],
    polish: int,
) -> list[np.ndarray]:
    """The unstable roots of every theta, ``count`` of them where found: Newton from the ``guesses``, from
    the dips of |E| on the counting rectangle's top edge, spread around those found, then from the
    Delves-Lyness roots of rectangles with the upper edges ``tops``."""
    t = thetas / float(thetas.max())
    X, Y = window
    unstable = np.nonzero(count > 0)[0]
    roots = [np.zeros(0, dtype=complex) for _ in t]

    def short() -> np.ndarray:
        return np.array([j for j in unstable if len(roots[j]) < count[j]], dtype=int)

    def merge(more: list[np.ndarray]) -> None:
        for j in range(len(t)):
            if len(more[j]) > len(roots[j]):
                roots[j] = more[j]

    if guesses is not None:
        cands = [list(guesses[j]) if count[j] else [] for j in range(len(t))]
        merge(locate_roots(sweep, alpha, thetas, cands, count, polish, spread=False))
    todo = short()
    if todo.size:
        cands = [[] for _ in t]
        for j in todo:
            cands[j] = dip_candidates(box, j) + list(roots[j])
        merge(locate_roots(sweep, alpha, thetas, cands, count, polish, spread=False))
    todo = short()
    if todo.size:
        cands = [list(roots[j]) for j in range(len(t))]
        merge(locate_roots(sweep, alpha, thetas, cands, count, polish))
    # Delves-Lyness, on a taller rectangle (roots near the real axis well inside), then on one whose top
    # lies a little below the axis (only the deeper roots inside)
    for box_top in tops:
        todo = short()
        if not todo.size:
            break
        cands = [[] for _ in t]
        for j, r in zip(todo, delves_lyness(coeffs, t[todo], X, Y, box_top)):
            cands[j] = (r or []) + list(roots[j])

        merge(locate_roots(sweep, alpha, thetas, cands, count, polish, spread=False))
    return roots


def _cut_low(bound: BoundModel, alpha: float, x: float) -> float | None:
    """The lowest Im q of the cut of K over 0 <= Re q <= x at ``alpha`` (None: it does not pass there)."""
    cut = cut_locus(bound.replace(alpha=exact(alpha)), 0.0, x, samples=401)
    return float(cut.im_low) if cut.points.size else None


def settle_cells(
    bound: BoundModel,
    parameter: str,
    column: ColumnResult,
    *,
    alpha: Fraction | None = None,
    thetas: list[Fraction | float] | None = None,
    dps: int = 15,
    held: Iterable[str] = (),
) -> ColumnResult:
    """Settle the ``uncertain`` cells of ``column`` by a full count at each (induced_frequencies).

    ``alpha`` and ``thetas`` are the exact values of the column (default: the shortest decimal text of
    its floats); the groups of ``held`` keep their values in ``bound`` (:func:`at_theta`). A cell stays
    uncertain only when the full count itself is not certified (``count_ok`` false, an UNDETERMINED
    verdict, or the search fails): its verdict is then never claimed.
    """
    from moving_bogie.roots.frequencies import induced_frequencies

    cells = np.nonzero(column.uncertain)[0]
    if not cells.size:
        return column
    count, degree = column.count.copy(), column.degree.copy()
    uncertain, settled = column.uncertain.copy(), np.zeros(len(count), dtype=bool)
    margin = np.full(len(count), np.nan) if column.margin is None else column.margin.copy()
    lower = np.zeros(len(count), dtype=bool) if column.margin_bound is None else column.margin_bound.copy()
    roots = list(column.roots)
    base = bound.replace(alpha=exact(column.alpha) if alpha is None else alpha)
    for j in cells:
        theta = exact(column.thetas[j]) if thetas is None else thetas[j]
        try:
            res = induced_frequencies(at_theta(base, parameter, theta, held), dps=dps)
        except MovingBogieError:
            continue
        unstable = [complex(r.q) for r in res.unstable_roots]
        count[j] = len(unstable)
        degree[j] = min([0.0, *(q.imag for q in unstable)])
        roots[j] = np.array(sorted(unstable, key=lambda q: q.imag), dtype=complex)
        uncertain[j] = not (res.count_ok and res.verdict.determined)
        settled[j] = True
        im = [float(mpmath.im(r.q)) for r in res.roots]  # every located root: the smallest decay rate
        margin[j] = np.nan if uncertain[j] or not im else min(im)
        lower[j] = False
    return replace(
        column,
        count=count,
        degree=degree,
        uncertain=uncertain,
        roots=roots,
        settled=settled,
        margin=margin,
        margin_bound=lower,
    )


def top_edge(bound: BoundModel, alphas: Sequence[float] | np.ndarray) -> float:
    """Im q of the counting rectangle's top: 0, or just below the cut where it reaches the real axis."""
    lowest = np.inf
    for a in (float(np.min(alphas)), float(np.max(alphas))):
        cut = cut_locus(bound.replace(alpha=exact(a)), -3.0, 3.0, samples=2001)
        if cut.points.size:
            lowest = min(lowest, cut.im_low)
    return 0.0 if lowest > 1e-6 else min(0.0, lowest) - 1e-7


def branch_points(bound: BoundModel, alpha: float) -> list[float]:
    """Re q > 0 of the branch points of K on the real axis (cusps and folds of the cut there), ascending."""
    cut = cut_locus(bound.replace(alpha=exact(alpha)), 0.0, 4.0, samples=801)
    xs = [f.q.real for f in cut.folds if f.q.real > 0 and abs(f.q.imag) < 1e-9]
    if np.isfinite(cut.x_start) and cut.x_start > 0 and abs(cut.im_low) < 1e-9:
        xs.append(cut.x_start)
    out: list[float] = []
    for x in sorted(xs):
        if not out or x - out[-1] > 1e-9:
            out.append(float(x))
    return out


def branch_samples(points: Sequence[float]) -> np.ndarray | None:
    """Top-edge samples 1e-8 to 1e-2 on both sides of each branch point: K grows like the inverse square
    root of the distance there, so E changes on the scale of the distance (a root 2e-4 below the axis next
    to one was missed with the regular samples alone)."""
    if not points:
        return None
    d = np.geomspace(1e-8, 1e-2, 25)
    return np.concatenate([np.concatenate([x - d[::-1], [x], x + d]) for x in points])
