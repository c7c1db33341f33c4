"""Search cells whose edges follow the cut of K at a fixed distance (curved counting contours).

A cell is a closed curve made of pieces: straight segments and offset arcs q(p) + side delta n(p) of a
cut arm (:class:`~moving_bogie.kernels.cut.CutArm`), computed exactly at every sample (Newton on
N(p, q) = 0), so that an edge is never closer than delta to the cut and the part of the plane left out
is exactly the band of half-width delta around the cut. Cells expose the interface of
:class:`~moving_bogie.roots.count.contour.Rectangle` that counting and locating use: ``boundary_parameters``
and ``points_at`` (the argument principle refines along the curve itself, not along chords), ``width``,
``height``, ``center``, ``contains`` and ``split``.

Two shapes occur: a *column* cell over x0 <= Re q <= x1 between two edges (a horizontal line or an offset
arm; the arms are graphs over Re q there), and a *tip* cell around a fold of the cut (the inside or the
outside of the lens that opens at a fold), closed by the vertical line Re q = x_tip.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from moving_bogie.kernels.cut import CutArm, clearance
from moving_bogie.kernels.cut_curves import Fold
from moving_bogie.roots.count.contour import BoundingBox, Rectangle, Region
from moving_bogie.typing import FloatArray

#: A piece of a cell's boundary: u in [0, 1] (an array) -> its points.
Piece = Callable[[np.ndarray], np.ndarray]

__all__ = ["Edge", "ColumnCell", "TipCell", "Sliver"]


@dataclass(frozen=True)
class Sliver:
    """A part of the window no contour enters: the band |Im q - cut| <= height/2 over x0..x1.

    ``y0``, ``y1`` bound it; ``height`` is its thickness at every Re q (the cut may slope in between).
    ``reason`` is empty for the band the tiling leaves out by design; otherwise it says why a search cell
    was left out (its count failed however its edges were moved and it was split), and the sliver is that
    cell's bounding box.
    """

    x0: float
    x1: float
    y0: float
    y1: float
    height: float
    reason: str = ""
    #: a region whose area is the band left out (``covers`` empty), or that holds it together with the
    #: search cells ``covers`` (the tip cells of a fold): it can be counted through the cut instead
    #: (:mod:`~moving_bogie.roots.search.continuation`)
    cell: Region | None = field(default=None, repr=False, compare=False)
    covers: tuple[Region, ...] = field(default=(), repr=False, compare=False)


@dataclass(frozen=True)
class Edge:
    """A horizontal line Im q = ``y`` (``arm`` None) or the offset of a cut arm by ``side`` * ``delta``."""

    y: float = 0.0
    arm: CutArm | None = None
    side: int = 0
    delta: float = 0.0

    def points(self, x: ArrayLike) -> np.ndarray:
        """Points of the edge above (near) Re q = x, for an array x."""
        x = np.asarray(x, dtype=float)
        if self.arm is None:
            return x + 1j * self.y
        return self.arm.offset(self.arm.p_at(x), self.side, self.delta)

    def along(self, x0: float, x1: float, u: ArrayLike) -> np.ndarray:
        """Points from Re q ~ x0 (u = 0) to x1 (u = 1), uniform in the arm parameter p."""
        u = np.asarray(u, dtype=float)
        if self.arm is None:
            return x0 + (x1 - x0) * u + 1j * self.y
        p0, p1 = self.arm.p_at(np.array([x0, x1]))
        return self.arm.offset(p0 + (p1 - p0) * u, self.side, self.delta)


def _samples(z_of_u: Piece, spacing: float) -> FloatArray:
    """Uniform parameters in [0, 1) of one piece, about ``spacing`` apart (at least 8)."""
    probe = z_of_u(np.linspace(0.0, 1.0, 17))
    length = float(np.abs(np.diff(probe)).sum())
    n = max(8, int(np.ceil(length / spacing)))
    return np.arange(n) / n


class _Curve(BoundingBox):
    """A closed curve from pieces u -> z(u), u in [0, 1]; global parameter t = piece index + u.

    The pieces may be listed in either sense: :meth:`_orient` (called once the pieces are set) reverses the
    parameter when the curve as listed runs clockwise (negative signed area), so that the boundary is
    always counter-clockwise, as the argument principle needs.
    """

    pieces: tuple[Piece, ...]
    _clockwise: bool = False

    def _orient(self) -> None:
        self._clockwise = False
        t = self.boundary_parameters(np.inf)
        z = self.points_at(t[:-1])
        area = 0.5 * float(np.sum(z.real * np.roll(z.imag, -1) - np.roll(z.real, -1) * z.imag))
        self._clockwise = area < 0

    def points_at(self, t: ArrayLike) -> np.ndarray:
        t = np.asarray(t, dtype=float)
        if self._clockwise:
            t = len(self.pieces) - t
        k = np.minimum(np.floor(t).astype(int), len(self.pieces) - 1)
        out = np.empty(t.shape, dtype=complex)
        for j, piece in enumerate(self.pieces):
            sel = k == j
            if np.any(sel):
                out[sel] = piece(t[sel] - j)
        return out

    def boundary_parameters(self, spacing: float) -> FloatArray:
        s = np.concatenate([j + _samples(piece, spacing) for j, piece in enumerate(self.pieces)])
        n = float(len(self.pieces))
        if self._clockwise:  # the same samples, run backwards (t = n - s)
            s = np.concatenate(([0.0], np.sort(n - s[1:])))
        return np.append(s, n)

    def boundary(self, spacing: float) -> np.ndarray:
        t = self.boundary_parameters(spacing)
        z = self.points_at(t[:-1])
        return np.append(z, z[0])


def _segment(a: complex | np.ndarray, b: complex | np.ndarray) -> Piece:
    """The straight piece from ``a`` (u = 0) to ``b`` (u = 1)."""

    def piece(u: np.ndarray) -> np.ndarray:
        return a + (b - a) * u

    return piece


class ColumnCell(_Curve):
    """x0 <= Re q <= x1 between the edges ``lower`` and ``upper`` (counter-clockwise boundary)."""

    def __init__(self, x0: float, x1: float, lower: Edge, upper: Edge) -> None:
        self.x0, self.x1, self.lower, self.upper = float(x0), float(x1), lower, upper
        lo = lower.points(np.array([x0, 0.5 * (x0 + x1), x1]))
        hi = upper.points(np.array([x0, 0.5 * (x0 + x1), x1]))
        self.y0, self.y1 = float(lo.imag.min()), float(hi.imag.max())
        self._mid = complex(0.5 * (x0 + x1), 0.5 * (lo[1].imag + hi[1].imag))
        self.pieces = (
            lambda u: lower.along(x0, x1, u),
            _segment(lo[2], hi[2]),
            lambda u: upper.along(x1, x0, u),
            _segment(hi[0], lo[0]),
        )

    def _piece(self, lower: Edge, upper: Edge) -> Rectangle | ColumnCell:
        """The cell over the same columns between other edges (a Rectangle when both are straight)."""
        if lower.arm is None and upper.arm is None:
            return Rectangle(self.x0, self.x1, lower.y, upper.y)
        return ColumnCell(self.x0, self.x1, lower, upper)

    def __repr__(self) -> str:
        return f"ColumnCell({self.x0:.9g}..{self.x1:.9g}, {self.y0:.9g}..{self.y1:.9g})"

    @property
    def center(self) -> complex:
        return self._mid

    def contains(self, z: complex, margin: float = 0.0) -> bool:
        if not (self.x0 - margin <= z.real <= self.x1 + margin):
            return False
        x = np.array([min(max(z.real, self.x0), self.x1)])
        lo = self.lower.points(x)[0].imag
        hi = self.upper.points(x)[0].imag
        return bool(lo - margin <= z.imag <= hi + margin)

    def split(self, fraction: float = 0.5) -> tuple[Rectangle | ColumnCell, Rectangle | ColumnCell]:
        """Two cells: across Re q, or (taller than twice its width, with a horizontal line passing between
        its edges) along that line, so that a tall cell shrinks in height too (a lens between two arms)."""
        if self.height > 2 * self.width:
            xs = np.linspace(self.x0, self.x1, 33)
            top = float(self.lower.points(xs).imag.max())
            bottom = float(self.upper.points(xs).imag.min())
            if bottom > top:
                ym = top + fraction * (bottom - top)
                return self._piece(self.lower, Edge(y=ym)), self._piece(Edge(y=ym), self.upper)
        xm = self.x0 + fraction * self.width
        return ColumnCell(self.x0, xm, self.lower, self.upper), ColumnCell(
            xm, self.x1, self.lower, self.upper
        )


class TipCell(_Curve):
    """The inside (``inner``) or outside of the lens that opens at a fold of the cut, up to Re q = x_tip.

    The lens opens towards larger Re q (``fold.opens`` = +1, x_tip right of the fold) or towards smaller
    Re q (-1, x_tip left of it). ``fold_arms`` = (lower arm, upper arm) as seen at x_tip; the offset runs
    from one arm around the fold to the other. The outer cell is closed by the frame between x_far (the
    side away from the opening) and x_tip, y_low <= Im q <= y_high. The boundary is made counter-clockwise
    whichever way the lens opens (:meth:`_Curve._orient`).
    """

    def __init__(
        self,
        fold: Fold,
        lower: CutArm,
        upper: CutArm,
        x_tip: float,
        delta: float,
        inner: bool,
        frame: tuple[float, float, float] | None = None,
    ) -> None:
        self.fold, self.lower, self.upper = fold, lower, upper
        self.x_tip, self.delta, self.inner, self.frame = float(x_tip), delta, inner, frame
        p_lo = float(lower.p_at(np.array([x_tip]))[0])
        p_hi = float(upper.p_at(np.array([x_tip]))[0])
        self._p = (p_lo, p_hi)
        around = self._offset_curve(p_lo, p_hi)
        a, b = around(0.0), around(1.0)
        if inner:
            # around the lens: from the upper arm's point, round the fold, to the lower one
            self.pieces = (lambda u: around(1.0 - u), _segment(a, b))
            self.x0, self.x1 = sorted((float(fold.q.real), self.x_tip))
            self.y0, self.y1 = float(a.imag), float(b.imag)
        else:
            assert frame is not None  # the outer cell is closed by its frame
            x_far, y_low, y_high = frame
            c0, c1 = complex(x_far, y_low), complex(self.x_tip, y_low)
            c2, c3 = complex(self.x_tip, y_high), complex(x_far, y_high)
            self.pieces = (
                _segment(c0, c1),
                _segment(c1, a),
                around,
                _segment(b, c2),
                _segment(c2, c3),
                _segment(c3, c0),
            )
            self.x0, self.x1 = sorted((float(x_far), self.x_tip))
            self.y0, self.y1 = y_low, y_high
        self._orient()

    def _offset_curve(self, p_lo: float, p_hi: float) -> Callable[[float | np.ndarray], np.ndarray]:
        """u -> offset point from p_lo (u = 0, lower arm) to p_hi (u = 1, upper arm), through the fold."""
        fold, lower, upper, delta = self.fold, self.lower, self.upper, self.delta
        sign = 1 if self.inner else -1

        def curve(u: float | np.ndarray) -> np.ndarray:
            u = np.asarray(u, dtype=float)
            p = p_lo + (p_hi - p_lo) * u
            on_lower = (p - fold.p) * (p_lo - fold.p) > 0
            arm_q = np.where(on_lower, lower.q_at(p), upper.q_at(p))
            t = lower.tracer.dq_dp(p, arm_q)
            return arm_q + sign * clearance(p, t, delta) * self._inward_normal(1j * t / np.abs(t))

        return curve

    def _inward_normal(self, n: np.ndarray) -> np.ndarray:
        """The unit normal n = i t/|t| (t = dq/dp, continuous through the fold) turned into the lens."""
        t = complex(self.lower.tracer.dq_dp(np.array([self.fold.p]), np.array([self.fold.q]))[0])
        return n if (1j * t).real * self.fold.opens > 0 else -n

    def __repr__(self) -> str:
        return f"TipCell({'inner' if self.inner else 'outer'}, x <= {self.x_tip:.9g})"

    def contains(self, z: complex, margin: float = 0.0) -> bool:
        if not (
            self.x0 - margin <= z.real <= self.x1 + margin and self.y0 - margin <= z.imag <= self.y1 + margin
        ):
            return False
        inside_lens = self._in_lens(z)
        return inside_lens if self.inner else not inside_lens

    def _in_lens(self, z: complex) -> bool:
        x = (z.real - self.fold.q.real) * self.fold.opens
        if x <= 0:
            return False
        lo = self.lower.y_at(np.array([z.real]))[0]
        hi = self.upper.y_at(np.array([z.real]))[0]
        return bool(lo <= z.imag <= hi)

    def split(self, fraction: float = 0.5) -> tuple[Region, ...]:
        """The tip cell up to a Re q nearer the fold, and column cells for the rest."""
        x_new = self.fold.q.real + fraction * (self.x_tip - self.fold.q.real)
        c0, c1 = sorted((x_new, self.x_tip))
        if self.inner:
            rest = ColumnCell(
                c0,
                c1,
                Edge(arm=self.lower, side=1, delta=self.delta),
                Edge(arm=self.upper, side=-1, delta=self.delta),
            )
            return TipCell(self.fold, self.lower, self.upper, x_new, self.delta, True), rest
        assert self.frame is not None  # the outer cell is closed by its frame
        x_far, y_low, y_high = self.frame
        tip = TipCell(self.fold, self.lower, self.upper, x_new, self.delta, False, (x_far, y_low, y_high))
        below = ColumnCell(c0, c1, Edge(y=y_low), Edge(arm=self.lower, side=-1, delta=self.delta))
        above = ColumnCell(c0, c1, Edge(arm=self.upper, side=1, delta=self.delta), Edge(y=y_high))
        return tip, below, above
