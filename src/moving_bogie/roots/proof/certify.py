"""Certified induced frequencies: ball arithmetic proves each root, the count and the stability verdict.

Given the numerical result of :func:`~moving_bogie.roots.frequencies.induced_frequencies`:

1. **Each root** (and its mirror -conj(q) when that lies in the window) is enclosed in a square ball B of
   half-side ``radius`` around the polished value in which the Krawczyk operator

       K(B) = c - Y E(c) + (1 - Y E'(B)) (B - c),      Y ~ 1/E'(c),

   lands in the interior of B (E = E_chr of Eq. (38), E' its derivative Eq. (40), both as balls from
   :mod:`balls`). Then B holds exactly one root of E_chr, and it is simple.
2. **No other root**: the window is tiled away from the cut of K (:func:`proof_tiling.proof_tiling` with a
   margin ``margin``) and the number of roots in every tile is proven (:mod:`winding`). All roots are proven
   when every tile holds exactly as many enclosures as its proven count.
3. **What is not searched** is the strip of half-height ``margin`` along the cut (and around the branch
   point), listed in ``unsearched``; a root there, if any, would sit within ``margin`` of the cut.
4. **Verdict**: unstable when some enclosure lies entirely in Im q < 0 (a proof needing no count); stable
   when all roots are proven, every enclosure lies in Im q > 0 and the unsearched strip lies in Im q > 0;
   marginal when, instead, some enclosures meet Im q = 0 (|Im q| <= radius); otherwise not proven, with the
   reason. Everything is "in the window": roots outside it are excluded by the asymptotics of E_chr and a
   numerical count in a window twice as large (see docs/frequencies.md), not by this proof.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from enum import StrEnum
from typing import Any

import mpmath
from flint import acb, arb, ctx

from moving_bogie.kernels.cut import CutLocus, cut_locus
from moving_bogie.roots.count.contour import Rectangle
from moving_bogie.roots.count.strip import branch_point_text
from moving_bogie.roots.proof.balls import BallCharacteristic, Undecided, square_ball
from moving_bogie.roots.proof.proof_tiling import Staircase, proof_tiling
from moving_bogie.roots.proof.strip_proof import StripProof, strip_from_below
from moving_bogie.roots.proof.winding import NotProven, ProvenCount, proven_count
from moving_bogie.roots.refine.polish import fixed_text
from moving_bogie.roots.search_record import LocatedRoot, SearchRecord
from moving_bogie.typing import Acb, Arb, Mpc, Mpf

#: Tilings tried in turn when a tile edge passes too close to a root (margin factor, gap fraction).
TILINGS = ((1.0, 0.1), (1.7, 0.113), (0.6, 0.087))


@dataclass(frozen=True)
class Enclosure:
    """A square ball ``ball`` (acb) around ``q``; ``certified`` when it provably holds exactly one root."""

    q: Mpc
    ball: Acb
    radius: str
    certified: bool
    reason: str = ""

    def contains(self, q: Mpc | complex) -> bool:
        """Whether the ball contains the point q (an mpc or complex, read at 256 bits)."""
        with ctx.workprec(256):
            return bool(self.ball.contains(_acb_from_mp(q)))

    @property
    def below_axis(self) -> bool:
        """Im q < 0 for every point of the ball (proven)."""
        return bool(self.ball.imag < 0)

    @property
    def above_axis(self) -> bool:
        return bool(self.ball.imag > 0)

    def bounds(self) -> tuple[tuple[Mpf, Mpf], tuple[Mpf, Mpf]]:
        """((re_low, re_high), (im_low, im_high)) of the ball as exact mpmath numbers."""
        with ctx.workprec(max(256, self.ball.real.mid().bits() + 64)):
            r, i = self.ball.real, self.ball.imag
            lows, highs = (r.lower(), i.lower()), (r.upper(), i.upper())
            if not all(x.is_exact() for x in lows + highs):
                raise ArithmeticError("ball ends not exact")  # pragma: no cover (precision set above)
            return (_mpf(lows[0]), _mpf(highs[0])), (_mpf(lows[1]), _mpf(highs[1]))

    def rounds_to(self, re_text: str, im_text: str, decimals: int) -> bool:
        """Every point of the ball rounds to ``re_text``, ``im_text`` at ``decimals`` places."""
        (rl, rh), (il, ih) = self.bounds()
        return all(fixed_text(x, decimals) == _norm(re_text) for x in (rl, rh)) and all(
            fixed_text(y, decimals) == _norm(im_text) for y in (il, ih)
        )


class ProofVerdict(StrEnum):
    """The proven verdict in the window (module docstring, 4.); the value is the word printed for it."""

    STABLE = "stable"
    UNSTABLE = "unstable"
    MARGINAL = "marginal"
    NOT_PROVEN = "not proven"


@dataclass(frozen=True)
class Certificate:
    """The proof attached to a FrequencyResult (see the module docstring)."""

    roots: tuple[Enclosure, ...]  # per result root, same order
    mirrors: tuple[Enclosure, ...]  # of the mirrors -conj(q) that lie in the window's Re q < 0 strip
    tiles: tuple[ProvenCount, ...]  # per tile, or empty when a tile could not be counted
    unsearched: tuple[Rectangle, ...]  # along the cut, not covered by the tiles
    count: int | None  # proven number of roots with Re q >= 0 in the tiles (pairs once), None if unproven
    all_proven: bool
    verdict: ProofVerdict
    reason: str  # what the verdict rests on, or what is not proven
    seconds: float
    margin: float
    problems: tuple[str, ...] = field(default=())
    below: StripProof | None = None  # the strip below a cut on the real axis, proven with K from below

    @property
    def proven_roots(self) -> int:
        return sum(e.certified for e in self.roots)

    def to_dict_for(self, result: SearchRecord) -> dict[str, Any]:
        """Fields added to ``result.to_dict()``: per-root ``radius`` and ``certified``, and ``certified``."""
        roots = [
            r.to_dict() | {"radius": e.radius, "certified": e.certified}
            for r, e in zip(result.roots, self.roots)
        ]
        return {"roots": roots, "certified": self.to_dict()}

    def to_dict(self) -> dict[str, Any]:
        return {
            "count": self.count,
            "roots": self.proven_roots,
            "all": self.all_proven,
            "verdict": self.verdict,
            "reason": self.reason,
            "margin": self.margin,
            "unsearched": [{"re": [u.x0, u.x1], "im": [u.y0, u.y1]} for u in self.unsearched],
            "seconds": round(self.seconds, 3),
            "problems": list(self.problems),
            "strip_below": None if self.below is None else self.below.to_dict(),
        }


def _mpf(x: Arb) -> Mpf:
    """The midpoint of ``x`` as an exact mpmath number (its mantissa kept in full)."""
    man, exp = (int(v) for v in x.mid().man_exp())
    with mpmath.workprec(max(mpmath.mp.prec, abs(man).bit_length() + 8)):
        return mpmath.ldexp(mpmath.mpf(man), exp)


def _norm(text: str) -> str:
    return text[1:] if text.startswith("-") and set(text[1:]) <= set("0.") else text


def _full(q: Mpc | complex, prec: int) -> Mpc:
    """``q`` as an mpc of at least ``prec`` bits (not rounded to the current mpmath precision)."""
    with mpmath.workprec(max(mpmath.mp.prec, prec)):
        return mpmath.mpc(q)


def _acb_from_mp(q: Mpc | complex) -> Acb:
    with mpmath.workdps(max(mpmath.mp.dps, 60)):
        q = mpmath.mpc(q)
        return acb(arb(mpmath.nstr(q.real, 60)), arb(mpmath.nstr(q.imag, 60)))


def krawczyk(bc: BallCharacteristic, q: Mpc, radius: float = 1e-26) -> Enclosure:
    """Prove that the square ball of half-side ``radius`` around ``q`` holds exactly one root of E_chr.

    Parameters
    ----------
    bc : BallCharacteristic
        At a precision well beyond ``radius`` (e.g. 200 bits for 1e-26).
    q : mpmath.mpc
        The candidate (a polished root).
    radius : float
        Half-side of the ball.
    """
    q = _full(q, bc.prec)
    with ctx.workprec(bc.prec):
        c = _acb_from_mp(q).mid()
        B = square_ball(c, arb(radius))
        text = f"{radius:.0e}"
        try:
            E_c, dE_c = bc.taylor(c, 1)
            dE_B = bc.taylor(B, 1)[1]
        except Undecided as exc:
            return Enclosure(q, B, text, False, str(exc))
        if dE_c.contains(0):
            return Enclosure(q, B, text, False, "E_chr' not bounded away from 0")
        Y = (1 / dE_c).mid()
        K = c - Y * E_c + (1 - Y * dE_B) * (B - c)
        if B.contains_interior(K):
            return Enclosure(q, B, text, True)
        return Enclosure(q, B, text, False, "Krawczyk image not inside the ball")


def refine(bc: BallCharacteristic, q: Mpc, steps: int = 3) -> Mpc:
    """``q`` after ``steps`` Newton steps on E_chr at the ball precision (midpoints only: a better centre
    for :func:`krawczyk`, whatever the precision the root was polished at)."""
    with ctx.workprec(bc.prec):
        c = _acb_from_mp(q).mid()
        try:
            for _ in range(steps):
                E, dE = bc.taylor(c, 1)
                c = (c - E / dE).mid()
        except (Undecided, ZeroDivisionError):
            return _full(q, bc.prec)
        if not c.is_finite():
            return _full(q, bc.prec)
        with mpmath.workprec(bc.prec + 8):
            return mpmath.mpc(_mpf(c.real), _mpf(c.imag))


def certify(
    result: SearchRecord,
    *,
    radius: float = 1e-26,
    margin: float = 1e-3,
    prec: int = 200,
    count_prec: int = 96,
) -> Certificate:
    """The :class:`Certificate` of a FrequencyResult (roots, proven count, verdict)."""
    start = time.perf_counter()
    bound, window = result.bound, result.window
    problems: list[str] = []
    precise = BallCharacteristic(bound, prec=prec)
    centres = [refine(precise, r.q) for r in result.roots]
    roots = tuple(krawczyk(precise, q, radius) for q in centres)
    mirrors = tuple(
        krawczyk(precise, -mpmath.conj(q), radius)
        for q in centres
        if mpmath.re(-mpmath.conj(q)) >= window.x0 and mpmath.re(q) > 4 * radius
    )
    for e in roots + mirrors:
        if not e.certified:
            problems.append(f"root {mpmath.nstr(e.q, 12)}: not proven ({e.reason})")
    counter = BallCharacteristic(bound, prec=count_prec)
    cut = cut_locus(bound, window.x0, window.x1)
    pinches = pinches_around_roots(margin, cut, result.roots)
    tiles: tuple[ProvenCount, ...] = ()
    unsearched: tuple[Rectangle, ...] = ()
    used_margin = margin
    for factor, fraction in TILINGS:
        used_margin = margin * factor
        gap_height = fraction * max(window.width, window.height)
        tiling = proof_tiling(window, cut, margin=used_margin, gap_height=gap_height, pinches=pinches)
        try:
            tiles = tuple(proven_count(counter, rect) for rect in tiling.regions)
            unsearched = tiling.unsearched
            break
        except NotProven as exc:
            last = str(exc)
    else:
        problems.append(f"count: {last}")
    count, all_proven = _match(tiles, roots, mirrors, problems)
    if tiles and count != result.count:
        problems.append(
            f"count: proven {count} root(s) in the tiles, the numerical search counts {result.count}"
        )
    below = strip_from_below(bound, cut, unsearched, count_prec) if tiles else None
    verdict, reason = _verdict(roots + mirrors, all_proven, unsearched, problems, below)
    return Certificate(
        roots, mirrors, tiles, unsearched, count, all_proven, verdict, reason,
        time.perf_counter() - start, used_margin, tuple(problems), below,
    )  # fmt: skip


def pinches_around_roots(
    margin: float, cut: CutLocus, roots: Sequence[LocatedRoot], floor: float = 1e-6
) -> list[tuple[float, float, float]]:
    """Where the strip along the cut must be thinner than ``margin`` so that it leaves out no root found
    numerically: for a root closer to the cut than 2 ``margin`` (beyond the branch point), the stretch of
    Re q within 50 times its distance d (at least 1e-5) gets the margin max(``floor``, d / 4), a pinch of
    :func:`proof_tiling.proof_tiling`. Only there do the tile edges come that close to the cut (an edge at
    distance h from it needs segments shorter than about h, so a margin thin all along would cost
    millions of segments)."""
    out: list[tuple[float, float, float]] = []
    if not cut.points.size:
        return out
    for r in roots:
        x, y = float(mpmath.re(r.q)), float(mpmath.im(r.q))
        if x < cut.x_start - 2 * margin:
            continue
        near = cut.im_range_between(x - 2 * margin, x + 2 * margin) or (cut.im_low, cut.im_high)
        distance = max(near[0] - y, y - near[1], 0.0)
        if distance < 2 * margin:
            half = max(50 * distance, 1e-5)
            out.append((x - half, x + half, max(floor, distance / 4)))
    return out


def _match(
    tiles: Sequence[ProvenCount],
    roots: tuple[Enclosure, ...],
    mirrors: tuple[Enclosure, ...],
    problems: list[str],
) -> tuple[int | None, bool]:
    """Proven count (pairs once) and whether every root in the tiles is one of the proven enclosures."""
    if not tiles:
        return None, False
    enclosures = [e for e in roots + mirrors if e.certified]
    ok = all(e.certified for e in roots + mirrors)
    for pc in tiles:
        inside = sum(_in_tile(e.ball, pc.rect) for e in enclosures)
        if inside != pc.count:
            ok = False
            problems.append(f"tile {pc.rect}: {pc.count} root(s) proven, {inside} enclosure(s) inside")
    loose = [e for e in enclosures if not any(_in_tile(e.ball, pc.rect) for pc in tiles)]
    if loose:
        ok = False
        problems.append(f"{len(loose)} enclosure(s) not inside a counted tile")
    total = sum(pc.count for pc in tiles)
    return total - sum(e.certified for e in mirrors), ok


def _in_tile(ball: Acb, rect: Rectangle | Staircase) -> bool:
    """The ball lies in the interior of the tile (of one member rectangle, for a staircase: a ball across
    two members' shared edge is reported as outside, never counted wrongly)."""
    if isinstance(rect, Staircase):
        return any(_in_tile(ball, r) for r in rect.rects)
    return bool(ball.real > rect.x0 and ball.real < rect.x1 and ball.imag > rect.y0 and ball.imag < rect.y1)


def _verdict(
    enclosures: Sequence[Enclosure],
    all_proven: bool,
    unsearched: Sequence[Rectangle],
    problems: Sequence[str],
    below: StripProof | None = None,
) -> tuple[ProofVerdict, str]:
    """The verdict and its reason (module docstring, 4.)."""
    unstable = [e for e in enclosures if e.certified and e.below_axis]
    if unstable:
        worst = min(unstable, key=lambda e: mpmath.im(e.q))
        return ProofVerdict.UNSTABLE, f"a root is proven in Im q < 0 (q = {mpmath.nstr(worst.q, 10)})"
    if below is not None and below.count:
        return (
            ProofVerdict.UNSTABLE,
            f"{below.count} root(s) proven in the strip below the cut on the real axis",
        )
    if not all_proven:
        return ProofVerdict.NOT_PROVEN, "; ".join(problems) or "not every root is proven"
    low = [u for u in unsearched if u.y0 <= 0]
    if low and below is not None:
        floor = min(u.y0 for u in low)
        if below.count is None:
            return ProofVerdict.NOT_PROVEN, (
                f"the strip {floor:.1e} <= Im q < 0 below the cut on the real axis (eta_f = 0) could not be "
                f"counted with K from below: {below.reason}"
            )
        return ProofVerdict.NOT_PROVEN, (
            f"every root in the window is proven and the strip {floor:.1e} <= Im q < 0 below the cut on the "
            f"real axis holds none (K from below, eta_f -> 0+), except in a square of half-side "
            f"{below.notch:.0e} under {branch_point_text(below.notches)}, where K is infinite: only that "
            "square remains"
        )
    if low:
        floor = min(u.y0 for u in low)
        return ProofVerdict.NOT_PROVEN, (
            f"no root with Im q < {floor:.1e} in the window (proven), but the unsearched strip along the "
            f"cut reaches Im q = {floor:.1e} <= 0"
        )
    if all(e.above_axis for e in enclosures):
        return ProofVerdict.STABLE, "every root in the window is proven and lies in Im q > 0"
    marginal = sum(not e.above_axis for e in enclosures)
    return ProofVerdict.MARGINAL, (
        f"no root in Im q < 0 beyond the enclosures; {marginal} enclosure(s) meet Im q = 0 (real to within "
        f"the radius)"
    )
