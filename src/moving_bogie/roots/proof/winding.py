"""Proven root counts: the argument principle on a rectangle (or a region with axis-parallel edges) with
ball arithmetic.

The rectangle's boundary (corners are exact binary floats) is cut into segments [a, b]. On each segment:

1. E_chr is analytic: the ball evaluation (:mod:`balls`) proves that no p-root of N(p, q) is real for any q
   of the segment, i.e. the segment does not meet the cut of K.
2. E_chr has no zero and turns by less than pi: with B the segment's ball, the mean-value forms
   E(q) in E(c) + E'(B) (B - c) (Eq. (40) for E') around c = a and c = b, intersected, enclose E on the
   whole segment in an axis-parallel rectangle (E(q) - E(c) is (q - c) times the mean of E' over the
   segment from c to q, which lies in the convex E'(B)). When that does not exclude 0, the segment is
   split at its midpoint m (a point of it: the edges are axis-parallel) and E on [a, m] enclosed by
   E(a) + E'(B) (H(a, m) - a), on [m, b] by E(b) + E'(B) (H(m, b) - b) (H(u, v) the ball holding u and v;
   no new value of E is needed), a rectangle holding both intersected with the first; when that does not
   exclude 0 either, the form around m, E(m) + E'(B) (B - m), too. When the rectangle excludes 0 it lies
   in an open half-plane through 0, so the continuous change of arg E along the segment is the principal
   value Arg(E(b) / E(a)), computed as a ball.

Along each edge a proven segment lets the next one grow (or shrink, when 0 was close to leaving the
enclosure: the step's length only, :func:`_growth`, never what is proven), and a segment where either test
fails is halved
(down to a relative length ``min_length``, then the count is reported unproven); the values at the ends
are kept, so neighbouring segments share them, and a halved segment ends at the midpoint of the failed
one. The total change of arg divided by 2 pi is a ball containing an integer, the number of
zeros inside; it is proven when the ball holds exactly one integer.

Why the interior is free of the cut too: each branch q(p), p real, of the cut is a connected curve that
goes to infinity (for bounded q the real roots p of N are bounded, as N's leading coefficient in p does not
vanish, which :func:`balls.isolate_roots` checks), so a branch entering the rectangle would cross its
boundary, which step 1 excludes. E_chr is therefore analytic inside and the winding number counts its zeros.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from flint import acb, arb, ctx

from moving_bogie.errors import MovingBogieError
from moving_bogie.roots.count.contour import Rectangle
from moving_bogie.roots.proof.balls import BallCharacteristic, Undecided
from moving_bogie.roots.proof.proof_tiling import Staircase
from moving_bogie.typing import Acb, Arb

#: Factor by which a boundary segment grows after a proven one (a failing one is halved). Slow growth
#: costs fewer evaluations than fast: a failed try costs as much as a proven segment, and along most edges
#: the longest provable segment changes slowly (1.1 against 1.2, 1.5 and 2 on Table 2's counts).
GROWTH = 1.1
#: Room (:func:`_growth`) below which the next segment is not longer than the last (0.6 against 0.3, 0.5,
#: 0.7 and 1 on Table 2's counts: about a sixth fewer evaluations of E_chr, most of the failed tries gone).
ROOM = 0.6


class NotProven(MovingBogieError):
    """The count could not be proven (a zero on or too near the boundary, or the boundary meets the cut)."""


@dataclass(frozen=True)
class ProvenCount:
    """Proven number of zeros inside ``rect``; ``segments`` boundary pieces were needed."""

    rect: Rectangle | Staircase
    count: int
    segments: int


def proven_count(
    bc: BallCharacteristic,
    rect: Rectangle | Staircase,
    *,
    initial: int = 8,
    min_length: float = 1e-10,
    max_segments: int = 200_000,
) -> ProvenCount:
    """Number of zeros of E_chr inside ``rect`` (a :class:`~moving_bogie.roots.count.contour.Rectangle`, or a
    region with axis-parallel edges and exact ``corners`` counterclockwise, such as
    :class:`~moving_bogie.roots.proof.proof_tiling.Staircase`), proven.

    Parameters
    ----------
    bc : BallCharacteristic
        E_chr and E_chr' on balls.
    initial : int
        The first segment of an edge is 1/``initial`` of it; along the edge, a proven segment lets the
        next one grow by :data:`GROWTH` (less, or shrink, with little room: :func:`_growth`), a failing
        one is halved.
    min_length : float
        Relative length (to the rectangle's longer side) below which a segment is not halved any more.
    max_segments : int
        Work limit: more segments than this make the count unproven.

    Raises
    ------
    NotProven
        Naming the place where the boundary could not be certified.
    """
    corners = (
        list(rect.corners)
        if isinstance(rect, Staircase)
        else [
            complex(rect.x0, rect.y0),
            complex(rect.x1, rect.y0),
            complex(rect.x1, rect.y1),
            complex(rect.x0, rect.y1),
        ]
    )
    size = max(rect.width, rect.height)
    values: dict[complex, Acb] = {}

    def value(z: complex) -> Acb:
        if z not in values:
            values[z] = bc.value(z)
        return values[z]

    with ctx.workprec(bc.prec):
        total = arb(0)
        segments = 0
        for a, b in zip(corners, corners[1:] + corners[:1]):
            # walk from a to b: a proven segment lets the next one grow by GROWTH, a failing one is halved
            # (its midpoint, whose value is kept, becomes the end of the next try)
            x, step, edge = 0.0, 1.0 / initial, abs(b - a)
            while x < 1.0:
                y = 1.0 if x + step * 1.25 >= 1.0 else x + step
                h = x + 0.5 * (y - x)
                s = _point(a, b, x)
                try:
                    change, room = _argument_change(bc, s, _point(a, b, y), _point(a, b, h), value)
                except Undecided as exc:
                    if (y - x) * edge < min_length * size or segments > max_segments:
                        where = f"boundary of {rect} not certified near q = {s:.12g}"
                        raise NotProven(f"{where}: {exc}") from None
                    step = 0.5 * (y - x)
                    continue
                total += change
                segments += 1
                x, step = y, max((y - x) * _growth(room), min_length * size / edge)
        turns = total / (2 * arb.pi())
        n = int(round(float(turns.mid())))
        if not (turns.contains(n) and turns.rad() < 0.5):
            raise NotProven(f"winding number of {rect} not an isolated integer: {turns}")
        return ProvenCount(rect, n, segments)


def _point(a: complex, b: complex, u: float) -> complex:
    """The point at fraction ``u`` of the edge from a to b (b itself at 1, a at 0)."""
    return b if u == 1.0 else a + (b - a) * u


def _growth(room: float) -> float:
    """Factor from a proven segment's length to the next one's: :data:`GROWTH`, or less where the segment
    had little room, ``room`` = min |E| / (max |E'| length) below :data:`ROOM` (the next one, as long, would
    likely fail: E_chr's zero or K's branch point ahead), down to 1/2."""
    return GROWTH if room >= ROOM else max(0.5, room / ROOM)


def _argument_change(
    bc: BallCharacteristic, a: complex, b: complex, m: complex, value: Callable[[complex], Acb]
) -> tuple[Arb, float]:
    """Change of arg E_chr along [a, b] (``m`` near its midpoint) as a ball, and the segment's room
    min(|E(a)|, |E(b)|) / (max |E'| |b - a|) (a lower bound, for the next segment's length only); raises
    Undecided if the change cannot be determined.

    E on the segment is enclosed by the mean-value forms around a and b (their intersection), and only
    when that does not exclude 0, by those around a on [a, m] and around b on [m, b] (the hull of the
    two), and then by the one around m too: E(q) in E(c) + E'(B) (H - c) for every q of the segment, or
    of the half of it that H holds, B the box of a, b and m (so that the segment from c to q lies in it).
    """
    ball = acb(a).union(acb(b)).union(acb(m))
    dE = bc.derivative(ball)
    Ea, Eb = value(a), value(b)
    enclosure = _intersection(Ea + dE * (ball - acb(a)), Eb + dE * (ball - acb(b)))
    if enclosure.contains(0) and _between(a, m, b):
        halves = (Ea + dE * (acb(a).union(acb(m)) - acb(a))).union(Eb + dE * (acb(m).union(acb(b)) - acb(b)))
        enclosure = _intersection(enclosure, halves)
    if enclosure.contains(0):
        enclosure = _intersection(enclosure, value(m) + dE * (ball - acb(m)))
        if enclosure.contains(0):
            raise Undecided("E_chr not bounded away from 0 on the segment")
    change = (Eb / Ea).arg()
    if not change.is_finite() or change.rad() > 0.5:
        raise Undecided("arg E_chr not resolved on the segment")
    room = min(Ea.abs_lower(), Eb.abs_lower()) / (dE.abs_upper() * abs(b - a))
    return change, float(room.lower()) if room.is_finite() else 0.0


def _between(a: complex, m: complex, b: complex) -> bool:
    """m lies on the axis-parallel segment from a to b (so that [a, m] and [m, b] cover it)."""
    if a.imag == m.imag == b.imag:
        return min(a.real, b.real) <= m.real <= max(a.real, b.real)
    if a.real == m.real == b.real:
        return min(a.imag, b.imag) <= m.imag <= max(a.imag, b.imag)
    return False


def _intersection(u: Acb, v: Acb) -> Acb:
    """The intersection of two rectangles that both enclose one set (it encloses the set too)."""
    return acb(u.real.intersection(v.real), u.imag.intersection(v.imag))
