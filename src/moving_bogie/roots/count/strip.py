"""The strip just below the cut of K: counted when the cut lies on or above the real axis.

The search of :mod:`frequencies` keeps its contours a small distance away from the cut of K, so a thin
sliver around the cut is not searched. When that sliver reaches below the real axis, a root with Im q < 0
could hide there and the verdict would be UNDETERMINED. Two situations are common and decided here:

* **eta_f = 0** (Table 1's Cases 2-4, 9, 10): the cut lies on the real axis, Re q >= q_c (the branch point
  q_c, and any other branch point of K on the axis). Below the axis K is analytic, and its values on the
  axis are the limit from below (the paper's convention: eta_f -> 0+ moves the cut up to Im q > 0, so the
  real axis lies below it). This limit continues analytically across the axis away from the branch points
  (each real p-root of N(p, q) is an analytic function of q there), so the argument principle holds on a
  rectangle whose top edge is the real axis, with E_chr evaluated from below
  (:class:`~moving_bogie.kernels.sweep_characteristic.SweepCharacteristic` ``below=True``).
* **0 < eta_f, cut above the axis**: the rectangle from the sliver's bottom up to Im q = 0 does not meet
  the cut, and the ordinary E_chr counts there.

The rectangles are split at every branch point of K on the real axis, where K is infinite (it grows like
the inverse square root of the distance): a square of half-side :data:`NOTCH` under each branch point is
left out, and ``notches`` says so. E_chr is infinite there with K: |E_chr| sqrt|q - q_c| is checked to be
about constant (within a factor 1.5) at 1e-5, 1e-7 and 1e-9 below each branch point (Case 2: 1.83e4 at
1e-3, 1.94e4 at 1e-9), so no root sits next to it; otherwise the strip is not counted and the reason says
so. This is a numerical check, not a proof: ``roots/proof/certify.py`` proves everything but the notch.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from moving_bogie.kernels.bound import BoundModel
from moving_bogie.kernels.characteristic import CharacteristicArray
from moving_bogie.kernels.cut import CutLocus, cut_locus
from moving_bogie.kernels.sweep_characteristic import SweepCharacteristic
from moving_bogie.roots.count.contour import ContourFunction, EdgeZeroError, Rectangle, winding_number
from moving_bogie.typing import ComplexArray

if TYPE_CHECKING:
    from moving_bogie.roots.search.cut_cells import Sliver

#: Half-side of the square left out under a branch point of K on the real axis (where K is infinite).
NOTCH = 1e-9
#: Distances below a branch point at which the growth of E_chr is checked (down to the notch).
GROWTH_PROBES = (1e-5, 1e-7, NOTCH)
#: |Im q| below which the cut counts as lying on the real axis.
ON_AXIS = 1e-12


@dataclass(frozen=True)
class StripCount:
    """Roots with Im q < 0 in the sliver below the cut (``count``), or why they could not be counted.

    ``rects`` were counted; ``mode`` is "from below" (cut on the real axis, eta_f = 0) or "below the cut"
    (cut above the axis); ``notches`` are the Re q of the branch points under which a square of half-side
    ``notch`` is left out; ``reason`` is non-empty when the count failed (``count`` is None then).
    """

    count: int | None
    rects: tuple[Rectangle, ...]
    mode: str
    notches: tuple[float, ...] = ()
    notch: float = NOTCH
    reason: str = ""
    growth: tuple[tuple[float, ...], ...] = ()  # per notch: |E_chr| sqrt(distance) at GROWTH_PROBES below it

    @property
    def decided(self) -> bool:
        return self.count is not None

    def statement(self) -> str:
        """One sentence: what was counted and the result."""
        if not self.decided:
            return f"strip below the cut not counted: {self.reason}"
        lo = min(r.y0 for r in self.rects)
        where = f"{min(r.x0 for r in self.rects):.6g} <= Re q <= {max(r.x1 for r in self.rects):.6g}"
        text = f"strip {lo:.1e} <= Im q < 0, {where}: {self.count} root(s) (argument principle"
        if self.mode == "from below":
            text += ", K on the real axis as the limit from below, eta_f -> 0+"
        text += ")"
        if self.notches:
            where = branch_point_text(self.notches)
            text += f"; a square of half-side {self.notch:.0e} under {where} is left out"
            if self.growth:
                c = ", ".join(f"{g[-1]:.3g}" for g in self.growth)
                text += f" (E_chr is infinite there: |E_chr| sqrt|q - q_c| -> {c})"
        return text

    def to_dict(self) -> dict[str, Any]:
        return {
            "count": self.count,
            "mode": self.mode,
            "rects": [{"re": [r.x0, r.x1], "im": [r.y0, r.y1]} for r in self.rects],
            "branch_points": list(self.notches),
            "notch": self.notch,
            "reason": self.reason,
            "growth": [list(g) for g in self.growth],
        }


def strip_below_cut(bound: BoundModel, window: Rectangle, unsearched: Sequence[Sliver]) -> StripCount | None:
    """Count the roots with Im q < 0 in the unsearched sliver(s) that reach below the real axis.

    Returns None when no sliver reaches below the axis, or when the cut there is neither on the real axis
    nor above it (nothing is decided then; the verdict keeps its reason).
    """
    low = [u for u in unsearched if u.y0 < 0]
    if not low:
        return None
    cut = cut_locus(bound, window.x0, window.x1)
    if not cut.points.size:
        return None
    f: ContourFunction
    points: list[float]
    if abs(cut.im_low) <= ON_AXIS and abs(cut.im_high) <= ON_AXIS:
        mode = "from below"
        sweep = SweepCharacteristic(bound, below=True)
        alpha = float(bound.params.alpha)

        def from_below(z: ComplexArray) -> ComplexArray:
            z = np.asarray(z, dtype=complex)
            return sweep(z, np.full(z.shape, alpha))

        f = from_below

        points = branch_points_on_axis(cut)
        misplaced = [x for x in points if not _located(sweep, alpha, x)]
        if misplaced:
            reason = f"branch point near q = {misplaced[0]:.9g} not located to within {NOTCH:.0e}"
            return StripCount(None, (), mode, reason=reason)
    elif cut.im_low > 0:
        mode = "below the cut"
        f = CharacteristicArray(bound)
        points = []
    else:
        return None
    rects: list[Rectangle] = []
    for u in low:
        rects += pieces_below_axis(Rectangle(u.x0, u.x1, u.y0, 0.0), [x for x in points if u.x0 < x < u.x1])
    notches = tuple(x for x in points if any(r.x0 <= x + NOTCH and x - NOTCH <= r.x1 for r in rects))
    growth = tuple(_growth(f, x) for x in notches)
    for x, g in zip(notches, growth):
        if not (max(g) < 1.5 * min(g) and min(g) > 0):
            reason = (
                f"|E_chr| does not grow like the inverse square root of the distance at the branch point "
                f"q = {x:.9g} (|E| sqrt(distance) = {', '.join(f'{v:.3g}' for v in g)} at "
                f"{', '.join(f'{d:.0e}' for d in GROWTH_PROBES)} below it): a root may sit next to it"
            )
            return StripCount(None, tuple(rects), mode, notches, reason=reason, growth=growth)
    try:
        count = sum(winding_number(f, r) for r in rects)
    except EdgeZeroError as exc:
        return StripCount(None, tuple(rects), mode, notches, reason=f"{exc} (a root on or next to the axis)")
    return StripCount(count, tuple(rects), mode, notches, growth=growth)


def _growth(f: ContourFunction, x: float) -> tuple[float, ...]:
    """|E_chr(x - i delta)| sqrt(delta) for delta in GROWTH_PROBES: about constant when E_chr is infinite at
    the branch point x like K (no root next to it)."""
    d = np.array(GROWTH_PROBES)
    return tuple(float(v) for v in np.abs(f(x - 1j * d)) * np.sqrt(d))


def branch_point_text(points: Sequence[float]) -> str:
    """ "the branch point q = x" for one, "each branch point q = x, y" for several."""
    values = ", ".join(f"{x:.9g}" for x in points)
    return f"{'each' if len(points) > 1 else 'the'} branch point q = {values}"


def branch_points_on_axis(cut: CutLocus) -> list[float]:
    """Re q of the branch points of K on the real axis: the cut's start and its folds there."""
    xs = [float(f.q.real) for f in cut.folds if abs(f.q.imag) <= 1e-9]
    if np.isfinite(cut.x_start):
        xs.append(float(cut.x_start))
    return sorted(set(xs))


def _located(sweep: SweepCharacteristic, alpha: float, x: float) -> bool:
    """The number of real p-roots of N changes between x - NOTCH and x + NOTCH: the branch point lies in
    the notch (a real pair of p-roots is about sqrt(NOTCH) apart next to it, far above rounding)."""
    q = np.array([x - NOTCH, x + NOTCH], dtype=complex)
    P = sweep.p_roots(q, np.full(2, alpha))
    real = np.sum(np.abs(P.imag) <= 1e-7 * np.maximum(1.0, np.abs(P)), axis=-1)
    return bool(real[0] != real[1])


def pieces_below_axis(rect: Rectangle, points: Iterable[float]) -> list[Rectangle]:
    """``rect`` (top edge on Im q = 0) split at each branch point x: the columns between them reach the
    axis, and under each x a column [x - NOTCH, x + NOTCH] stops at Im q = -NOTCH."""
    out, x0 = [], rect.x0
    for x in sorted(points):
        out.append(Rectangle(x0, x - NOTCH, rect.y0, rect.y1))
        out.append(Rectangle(x - NOTCH, x + NOTCH, rect.y0, -NOTCH))
        x0 = x + NOTCH
    out.append(Rectangle(x0, rect.x1, rect.y0, rect.y1))
    return [r for r in out if r.x1 > r.x0 and r.y1 > r.y0]
