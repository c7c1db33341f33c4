"""The strip below a cut on the real axis (eta_f = 0), proven: the part of the strip that the proven count of
:mod:`~moving_bogie.roots.proof.certify` leaves out along the cut and that reaches below the real axis,
counted in ball arithmetic with K on the real axis as the limit from below
(:class:`~moving_bogie.roots.proof.balls.BallCharacteristic` ``below=True``), except a square of half-side
``NOTCH`` under each branch point, where K is infinite.

The pieces of one strip (columns reaching the axis between the notched columns under the branch points)
are counted together, on the boundary of their union (a :class:`~moving_bogie.roots.proof.proof_tiling.
Staircase`): the sides they share, which run up to a branch point, are not walked (K's derivative grows
without bound there, so they would need the most segments), and a root on one of them is counted, not an
obstacle to the proof.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from moving_bogie.kernels.bound import BoundModel
from moving_bogie.kernels.cut import CutLocus
from moving_bogie.roots.count.contour import Rectangle
from moving_bogie.roots.count.strip import NOTCH, ON_AXIS, branch_points_on_axis, pieces_below_axis
from moving_bogie.roots.proof.balls import BallCharacteristic
from moving_bogie.roots.proof.proof_tiling import Staircase, staircase
from moving_bogie.roots.proof.winding import NotProven, proven_count

__all__ = ["StripProof", "strip_from_below", "strip_region"]


@dataclass(frozen=True)
class StripProof:
    """The part of the unsearched strip below a cut on the real axis (eta_f = 0), counted in ball
    arithmetic with K from below (:class:`BallCharacteristic` ``below=True``): ``count`` roots in ``rects``
    (None when not proven, ``reason`` says why); ``notches`` the branch points under which a square of
    half-side ``notch`` is left out (K is infinite there)."""

    count: int | None
    rects: tuple[Rectangle, ...]
    notches: tuple[float, ...]
    notch: float = NOTCH
    reason: str = ""

    def to_dict(self) -> dict[str, Any]:
        return {
            "count": self.count,
            "rects": [{"re": [r.x0, r.x1], "im": [r.y0, r.y1]} for r in self.rects],
            "branch_points": list(self.notches),
            "notch": self.notch,
            "reason": self.reason,
        }


def strip_from_below(
    bound: BoundModel, cut: CutLocus, unsearched: Sequence[Rectangle], prec: int
) -> StripProof | None:
    """Prove the root count in the unsearched strip below a cut that lies on the real axis (None when the
    strip does not reach below the axis or the cut is not on it)."""
    low = [u for u in unsearched if u.y0 < 0]
    if not low or not cut.points.size or max(abs(cut.im_low), abs(cut.im_high)) > ON_AXIS:
        return None
    points = branch_points_on_axis(cut)
    rects: list[Rectangle] = []
    regions: list[Rectangle | Staircase] = []
    for u in low:
        pieces = pieces_below_axis(Rectangle(u.x0, u.x1, u.y0, 0.0), [x for x in points if u.x0 < x < u.x1])
        rects += pieces
        regions += strip_region(pieces)
    notches = tuple(x for x in points if any(r.x0 <= x + NOTCH and x - NOTCH <= r.x1 for r in rects))
    bc = BallCharacteristic(bound, prec=prec, below=True)
    try:
        count = sum(proven_count(bc, r, min_length=1e-14).count for r in regions)
    except NotProven as exc:
        return StripProof(None, tuple(rects), notches, reason=str(exc))
    return StripProof(count, tuple(rects), notches)


def strip_region(pieces: list[Rectangle]) -> list[Rectangle | Staircase]:
    """The pieces of one strip (:func:`pieces_below_axis`, left to right) as one region: the base below
    Im q = -NOTCH with the columns that reach the axis standing on it, when the pieces are side by side on
    one bottom edge and reach Im q = 0 or -NOTCH (as they are); otherwise the pieces themselves."""
    if len(pieces) < 2:
        return list(pieces)
    y0, x0, x1 = pieces[0].y0, pieces[0].x0, pieces[-1].x1
    tiled = all(r.x1 == s.x0 for r, s in zip(pieces, pieces[1:]))
    levels = all(r.y0 == y0 and r.y1 in (0.0, -NOTCH) for r in pieces)
    if not (tiled and levels and y0 < -NOTCH):
        return list(pieces)
    columns = [Rectangle(r.x0, r.x1, -NOTCH, 0.0) for r in pieces if r.y1 == 0.0]
    return [staircase(Rectangle(x0, x1, y0, -NOTCH), columns, on_top=True)]
