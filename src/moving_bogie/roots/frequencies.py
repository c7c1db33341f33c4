"""Induced frequencies: every root of E_chr(q) = 0 (Eq. (48)) in a window, found with no starting guesses.

1. Count: the window (Re q >= 0 half, pairs q, -conj(q) are reported once) is tiled into rectangles that
   never meet the cut of K (:mod:`search_regions`); the argument principle counts the roots in each
   (:mod:`contour`), in double precision.
2. Locate: rectangles holding roots are bisected (each half counted) until a cell holds one root and is
   small enough for Newton's method to stay inside it.
3. Polish and confirm at high precision (:mod:`polish`): digits are those that agree at two precisions.
4. Check: the roots found must add up to the count, or the result says so (``count_ok``) and the CLI
   exits non-zero. The window is also compared with a window twice as large: a root outside the default
   window is reported, never silently dropped. When the window holds the lower half-disc of the far-field
   radius R, roots found there lie beyond R, so Im q >= 0 (``decaying_outside``): they are reported and do
   not change the verdict or the count (the Timoshenko-Rayleigh sequence along the real axis beyond
   sqrt(S)/r); otherwise they fail the count.

Stability: the motion is unstable when some induced frequency has Im q < 0 (Eq. (35) with e^{i q tau}).
The default window contains the lower half-disc of the radius R beyond which E_chr has no root with
Im q < 0 (:mod:`far_field`), so the verdict (:mod:`verdict`) speaks about every root, or says UNDETERMINED.
The search region is the bound model's track's: on a track whose region is one strip of width Omega_0
(periodic supports), :mod:`strip_frequencies` searches that strip and returns the same result.
"""

from __future__ import annotations

import dataclasses
import functools
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import mpmath
import numpy as np

from moving_bogie.kernels.bound import BoundModel
from moving_bogie.kernels.characteristic import CharacteristicArray
from moving_bogie.kernels.cut import CutLocus, cut_loci, side_of_cut
from moving_bogie.roots.ball_polish import BallPrecise
from moving_bogie.roots.count.contour import Rectangle, Region
from moving_bogie.roots.count.far_field import FarField, far_field_radius
from moving_bogie.roots.count.lattice import NEAR
from moving_bogie.roots.count.outcomes import Note, Reason, Unlocated, count_mismatch
from moving_bogie.roots.count.strip import strip_below_cut
from moving_bogie.roots.count.window import default_window, far_field_window  # noqa: F401  (public here too)
from moving_bogie.roots.frequency_result import FrequencyResult, InducedFrequency
from moving_bogie.roots.refine.locate import LocatedCell, locate
from moving_bogie.roots.refine.polish import (
    PolishError,
    PreciseCharacteristic,
    polish_and_confirm,
    split_cluster,
)
from moving_bogie.roots.search.continuation import ContinuedRegion
from moving_bogie.roots.search.counting import TilingCount, count_tiling, frame
from moving_bogie.roots.strip_frequencies import strip_frequencies


def induced_frequencies(
    bound: BoundModel,
    *,
    dps: int = 30,
    extra_dps: int | None = None,
    window: Rectangle | None = None,
    check_window: bool = True,
    eps: float = 2e-11,
    eps_branch: float = 1e-9,
    newton_cell: float = 0.25,
    progress: Callable[[float], None] | None = None,
    certify: bool = False,
    starts: Sequence[complex] | None = None,
    balls: bool = False,
    **strip: Any,
) -> FrequencyResult:
    """Every induced frequency of the bound model in ``window`` (default :func:`far_field_window`).

    Count (:func:`count_tiling`), locate (:func:`locate`), polish and confirm (:func:`polish_and_confirm`),
    then compare the roots found with the count (module docstring).

    Parameters
    ----------
    bound : BoundModel
        The parameters bound to their model: the vehicle and the track (another vehicle:
        ``bound.replace(vehicle=...)``; the public :func:`moving_bogie.induced_frequencies` binds).
    dps : int
        Working precision (decimal digits) of the polished roots.
    extra_dps : int, optional
        Extra digits of the confirming recomputation (default max(10, dps // 2)).
    window : Rectangle, optional
        Search window in the q-plane (Re q >= 0 half); default :func:`far_field_window`. A window that does
        not contain the lower half-disc of the far-field radius makes the verdict UNDETERMINED.
    check_window : bool
        Also count roots in a window twice as large; more roots there make the result fail loudly.
    eps : float
        Distance kept from the cut of K by the contours that follow it: the unsearched sliver around the
        cut is 2 eps high, at most 5 eps where two cut curves meet (default: at most 1e-10).
    eps_branch : float
        Half-width of the box left out around a branch point of K (where K is infinite like the inverse
        square root of the distance; the contours next to it are refined down to that scale).
    newton_cell : float
        Side of a single-root cell below which Newton's method is tried from its centre.
    progress : callable, optional
        Called with the fraction of work done (0..1).
    certify : bool
        Also prove every root, the count and the verdict in ball arithmetic (:mod:`certify`).
    starts : sequence of complex, optional
        Roots located by other means (double precision): a tile holding exactly its count of them takes
        them instead of its bisection (:func:`_locate_counted`; :mod:`moving_bogie.response.axis_law`).
    balls : bool
        Polish in Arb's balls too (:class:`BallPrecise`; the digits are confirmed there in any case).
    **strip
        The options of :func:`strip_frequencies`, on a track searched in one strip (:func:`_on_a_strip`).
    """
    if _on_a_strip(bound, strip, window=window, certify=certify, starts=starts, balls=balls):
        return strip_frequencies(bound, progress=progress, **strip)
    window, far = _window_and_far_field(bound, window)
    fast, in_balls = CharacteristicArray(bound, remember=NEAR), BallPrecise(bound)  # NEAR: the lattice's
    polishing = (in_balls if balls else in_balls.precise, in_balls)  # (polish, confirm at higher precision)
    report = _reporter(progress)
    counted, beyond = _count(fast, bound, window, eps, eps_branch, newton_cell, check_window, report)
    notes: list[Note] = [*counted.notes, *(beyond.notes(window, far) if beyond else ())]
    report(0.2)
    args = (counted, newton_cell, dps, extra_dps, notes, report, starts)
    roots, cells, unlocated = _confirmed_roots(fast, polishing, *args)
    count = sum(counted.counts) - _mirrors_counted(cells)
    _compare_with_count(count, roots, notes)
    unsearched = counted.tiling.unsearched
    result = FrequencyResult(
        *(bound, bound.params.vehicle, dps, window, tuple(roots), count, unsearched),
        fast.evaluations + in_balls.evaluations,  # BallPrecise's own and those of its mpmath path
        *(tuple(notes), far),
        strip=strip_below_cut(bound, window, [u for u in unsearched if not u.reason]),
        unlocated=tuple(unlocated),
        decaying_outside=beyond.decaying(window, far) if beyond else 0,
    )
    result = _certified(result) if certify else result
    report(1.0)
    return result


def _on_a_strip(bound: BoundModel, strip: dict[str, Any], **window_only: Any) -> bool:
    """Whether the bound model's track is searched in one strip (periodic supports); TypeError for an option
    of the other search given (``window``, ``certify``, ``starts``, ``balls`` on a strip; a strip's own
    options on a window)."""
    if bound.track.search_region().periodic:
        if any(value is not None and value is not False for value in window_only.values()):
            raise TypeError(f"{', '.join(window_only)}: a search of one strip takes none of them")
        return True
    if strip:
        raise TypeError(f"induced_frequencies() got unexpected keyword arguments {sorted(strip)}")
    return False


def _certified(result: FrequencyResult) -> FrequencyResult:
    """The result with the proof of every root, the count and the verdict in ball arithmetic."""
    from moving_bogie.roots.proof.certify import certify as prove

    return dataclasses.replace(result, certificate=prove(result))


def _compare_with_count(count: int, roots: list[InducedFrequency], notes: list[Note]) -> None:
    """The roots found must add up to the count (with multiplicity), or a note says they do not."""
    found = sum(r.multiplicity for r in roots)
    if found != count:
        notes.append(count_mismatch(count, found))


def _window_and_far_field(bound: BoundModel, window: Rectangle | None) -> tuple[Rectangle, FarField]:
    """The window searched (default :func:`far_field_window`) and the far-field check of the bound model."""
    if window is None:
        return far_field_window(bound)
    return window, _far_field(bound)


@functools.lru_cache(maxsize=16)
def _far_field(bound: BoundModel) -> FarField:
    """The far-field check from the default window's scale (:func:`far_field_radius`), once per bound model:
    the strips of a search along the real axis (:mod:`moving_bogie.response.axis_sequence`) share it."""
    return far_field_radius(bound, default_window(bound).x1)


def _confirmed_roots(
    fast: CharacteristicArray,
    precise: tuple[PreciseCharacteristic, PreciseCharacteristic],
    counted: TilingCount,
    newton_cell: float,
    dps: int,
    extra_dps: int | None,
    notes: list[Note],
    report: Callable[[float], None],
    starts: Sequence[complex] | None = None,
) -> tuple[list[InducedFrequency], list[LocatedCell], list[Unlocated]]:
    """Locate the counted roots (from ``starts`` where they agree with the count of every tile), polish and
    confirm them (``precise``: the evaluations of E_chr for each, :func:`_polish_located`), keep one of each
    pair q, -conj(q) (largest Re q first); the roots, the located cells and the roots not located (notes
    appended; ``extra_dps`` None: max(10, dps // 2))."""
    extra_dps = max(10, dps // 2) if extra_dps is None else extra_dps
    cells, unlocated = _locate_counted(fast, counted, newton_cell, starts)
    notes += [missing.note for missing in unlocated]
    report(0.6)
    roots = _polish_located(precise, cells, counted.cut, dps, extra_dps, notes, report)
    roots, pair_notes = _fold_pairs(roots)
    notes += pair_notes
    roots.sort(key=lambda r: -float(mpmath.re(r.q)))
    return roots, cells, unlocated


def _reporter(progress: Callable[[float], None] | None) -> Callable[[float], None]:
    """Report the fraction of work done to ``progress`` (capped at 1), or nowhere."""

    def report(x: float) -> None:
        if progress is not None:
            progress(min(1.0, x))

    return report


def _count(
    fast: CharacteristicArray,
    bound: BoundModel,
    window: Rectangle,
    eps: float,
    eps_branch: float,
    newton_cell: float,
    check_window: bool,
    report: Callable[[float], None],
) -> tuple[TilingCount, _Beyond | None]:
    """Count the roots in the window tiled around the cut and, with ``check_window``, in the frame up to the
    window twice as large (the argument principle, :func:`count_tiling`)."""
    big = Rectangle(window.x0, window.x0 + 2 * window.width, 2 * window.y0, 2 * window.y1)
    parts = frame(window, big) if check_window else ()
    # the cut is traced once, over the p-range of the window twice as large, for the window and the frame
    cuts = cut_loci(bound, [(r.x0, r.x1) for r in (window, *parts)])
    counted = count_tiling(fast, bound, window, eps, eps_branch, cuts[0], newton_cell)
    report(0.1)
    if not check_window:
        return counted, None
    return counted, _count_twice_as_large(fast, bound, big, parts, cuts[1:], eps, eps_branch)


@dataclass(frozen=True)
class _Beyond:
    """The roots counted in the frame between the window and the window twice as large (``big``)."""

    big: Rectangle
    more: int  # roots counted in the frame
    lost: int  # cells of the frame that could not be counted
    below: int  # roots in the strip Im q <= window.y0 < 0

    def decaying(self, window: Rectangle, far: FarField | None) -> int:
        """Roots of the frame known to have Im q >= 0: it lies outside the far-field half-disc."""
        return self.more if self.more and not self.below and _holds_far_disc(window, far) else 0

    def notes(self, window: Rectangle, far: FarField | None) -> list[Note]:
        big, more = self.big, self.more
        where = f"(Re q <= {big.x1:g}, {big.y0:g} <= Im q <= {big.y1:g})"
        notes = []
        if self.lost:
            text = f"{self.lost} cell(s) of the window twice as large could not be counted {where}"
            notes.append(Note(Reason.WINDOW, text))
        if self.decaying(window, far):
            assert far is not None
            notes.append(
                Note(
                    Reason.BEYOND_WINDOW,
                    f"{more} root(s) in the window twice as large {where}, all with Im q >= 0 (no root "
                    f"with Im q < 0 beyond |q| = {far.radius:g}, the far-field check): they decay and do "
                    "not change the verdict; a time series adds them from strips along the real axis when "
                    "the cut runs along it, and refuses otherwise (pass a larger window to list them)",
                )
            )
        elif more:
            text = f"{more} more root(s) in the window twice as large {where}; pass a larger window"
            notes.append(Note(Reason.WINDOW, text))
        return notes


def _count_twice_as_large(
    fast: CharacteristicArray,
    bound: BoundModel,
    big: Rectangle,
    parts: tuple[Rectangle, ...],
    cuts: tuple[CutLocus, ...],
    eps: float,
    eps_branch: float,
) -> _Beyond:
    """Count the frame between the window and the window twice as large (a root outside is never lost)."""
    more, lost, below = 0, 0, 0
    for k, (part, part_cut) in enumerate(zip(parts, cuts)):
        part_count = count_tiling(fast, bound, part, eps, eps_branch, part_cut)
        more += sum(part_count.counts)
        lost += len(part_count.notes)
        below += sum(part_count.counts) if k == 0 else 0  # the strip Im q <= window.y0 < 0
    return _Beyond(big, more, lost, below)


def _holds(region: Region | ContinuedRegion, z: np.ndarray) -> np.ndarray:
    """Which points z lie inside a tile, by the tile's own :meth:`contains` (a rectangle, or a curved cell
    between its arms); a tile counted through the cut holds none (its roots are located already)."""
    if isinstance(region, ContinuedRegion):
        return np.zeros(z.shape, dtype=bool)
    return np.array([region.contains(complex(w)) for w in z], dtype=bool)


def _locate_counted(
    fast: CharacteristicArray,
    counted: TilingCount,
    newton_cell: float,
    starts: Sequence[complex] | None = None,
) -> tuple[list[LocatedCell], list[Unlocated]]:
    """Isolate the counted roots of each tile: cells (start, multiplicity, cell), the roots not located.

    A tile that holds exactly its count of the given ``starts`` (roots located by other means), none of
    them in another tile as well, takes them as its cells; any other tile is bisected."""
    cells: list[LocatedCell] = []
    unlocated: list[Unlocated] = []
    points = np.array([complex(z) for z in (() if starts is None else starts)], dtype=complex)
    regions = counted.tiling.regions
    held = np.array([_holds(rect, points) for rect in regions]).reshape(len(regions), points.size)
    once = held.sum(axis=0) == 1
    for k, (rect, n) in enumerate(zip(regions, counted.counts)):
        if isinstance(rect, ContinuedRegion):  # counted through the cut, its roots located already
            cells += rect.cells
        elif points.size and held[k].sum() == n and np.all(once[held[k]]):
            cells += [(complex(z), 1, rect) for z in points[held[k]]]
        elif n:
            found_cells, missing = locate(fast, rect, n, newton_cell)
            cells += found_cells
            if missing is not None:
                unlocated.append(missing)
    return cells, unlocated


def _polish_located(
    precise: tuple[PreciseCharacteristic, PreciseCharacteristic],
    cells: list[LocatedCell],
    cut: CutLocus,
    dps: int,
    extra_dps: int,
    notes: list[Note],
    report: Callable[[float], None],
) -> list[InducedFrequency]:
    """Polish each located root at ``dps`` digits and confirm its digits (notes appended for failures);
    ``precise``: the evaluations of E_chr for the polish and for the confirmation
    (:func:`polish_and_confirm`)."""
    polishing, confirming = precise
    roots = []
    for k, (q0, mult, rect) in enumerate(cells):
        try:
            confirmed = [
                (
                    polish_and_confirm(
                        polishing, q0, dps=dps, extra_dps=extra_dps, multiplicity=mult, confirming=confirming
                    ),
                    mult,
                )
            ]
        except PolishError as exc:
            confirmed = (
                split_cluster(polishing, q0, mult, rect, dps=dps, extra_dps=extra_dps, confirming=confirming)
                if mult > 1
                else []
            )
            if not confirmed:
                notes.append(Note(Reason.POLISH, str(exc)))
                continue
        for conf, m in confirmed:
            if not rect.contains(complex(conf.q), margin=1e-9 * max(1.0, abs(complex(conf.q)))):
                notes.append(
                    Note(Reason.POLISH, f"Newton left its cell {rect} (ended at {mpmath.nstr(conf.q, 8)})")
                )
                continue
            side = side_of_cut(conf.q, 10.0 ** (-conf.decimals), cut, float(polishing.params.eta_f))
            roots.append(InducedFrequency(conf.q, side, m, conf.step, conf.digits, conf.decimals))
        report(0.6 + 0.4 * (k + 1) / len(cells))
    return roots


def _holds_far_disc(window: Rectangle, far: FarField | None) -> bool:
    """The window contains the lower half-disc of the far-field radius R (every root with Im q < 0)."""
    return far is not None and far.radius is not None and window.x1 >= far.radius and window.y0 <= -far.radius


def _fold_pairs(roots: list[InducedFrequency]) -> tuple[list[InducedFrequency], list[Note]]:
    """Keep one member of each pair q, -conj(q): drop a root with Re q < 0 whose mirror was found."""
    keep: list[InducedFrequency] = []
    notes: list[Note] = []
    for r in roots:
        if mpmath.re(r.q) < 0 and abs(mpmath.re(r.q)) > mpmath.mpf(10) ** (-r.decimals):
            mirror = -mpmath.conj(r.q)
            if any(abs(o.q - mirror) < 1e-8 for o in roots if o is not r):
                continue
            notes.append(Note(Reason.PAIR, f"root {mpmath.nstr(r.q, 8)} found without its mirror -conj(q)"))
        keep.append(r)
    return keep, notes


def _mirrors_counted(cells: list[LocatedCell]) -> int:
    """Roots counted in the strip Re q < 0 of the window (mirrors of roots with Re q > 0)."""
    return sum(m for q, m, _ in cells if mpmath.re(q) < -1e-9)
