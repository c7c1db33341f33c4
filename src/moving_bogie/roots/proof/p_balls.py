"""Root balls of N(p, q) (Eq. (24)), a polynomial in p with ball coefficients: at a point and over a q-ball.

Root isolation at a point q (Smith 1970, "Error bounds for zeros of a polynomial based upon Gerschgorin's
theorems"): for approximations z_1..z_n of the roots of a polynomial of degree n with leading coefficient
a_n, every root lies in the union of the discs |z - z_k| <= n |w_k|, w_k = P(z_k) / (a_n prod_{j != k}
(z_k - z_j)), and a disc disjoint from all others holds exactly one root. The approximations come from
Newton's method on the midpoint polynomial started at given points (the roots at a neighbouring point q,
:func:`point_root_balls`), or from Arb's ``acb_poly.roots`` on it when those fail to give disjoint discs.

Over a ball of q (the direct method, :func:`direct_root_balls`), each root ball at the centre is widened by
a Krawczyk test in p that holds for every q of the ball: with Y ~ 1 / N_p(p_m, m),

    p_m - Y N(p_m, q) + (1 - Y N_p(P, q)) (P - p_m)  inside P   =>  one root in P for every q of the ball,

N(p_m, q) by the mean-value form in q around the centre m. The test proves P for any point p_m in it and
any Y; p_m only has to be near the root for P to be small. The points p_m are the midpoints of the Smith
discs at the centre, or, cheaper, given approximations (the roots at a point of the ball: a boundary
segment's end) after one Newton step on N(., m), the Smith discs at the centre serving only when those
fail. The image K holds the root for every q; it is narrowed by the same operator applied to K itself
(K(X) holds every root in X when X holds p_m, the segment from p_m to the root then lying in X), each
image intersected with the ball it came from, while that shrinks it: the term (1 - Y N_p(P, q)) (P - p_m)
is of second order in the ball's radius, and over a long segment the first, square P costs much. It
evaluates N on the wide ball, which is cheap and tight for the quartic N of the one-layer beams;
:mod:`~moving_bogie.roots.proof.p_discs` serves the layered tracks.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from types import ModuleType
from typing import Any

from flint import acb, acb_poly, arb

from moving_bogie.errors import MovingBogieError
from moving_bogie.kernels.polynomial import derivative_coefficients, horner
from moving_bogie.typing import Acb, AcbPoly

__all__ = ["Undecided", "derivative_coefficients", "direct_root_balls", "horner", "isolate_roots"]


class Undecided(MovingBogieError):
    """Ball arithmetic could not decide a fact at this ball size (a p-root meets the real axis, or the
    root discs of N(p, q) overlap): subdivide the q-ball or raise the precision."""


def isolate_roots(coeffs: Iterable[Acb], tol: float | None = None) -> list[Acb]:
    """Balls, one per root, of the polynomial with acb ``coeffs`` (highest power first).

    ``tol`` is the accuracy asked of the approximations (default: just enough to isolate them); the balls
    are the Smith discs around them, whatever the accuracy.

    Raises
    ------
    Undecided
        If the Smith discs of two roots overlap (roots too close for the width of the coefficients).
    """
    coeffs = _leading(list(coeffs))
    if len(coeffs) < 2:
        return []
    mid_poly = acb_poly([c.mid() for c in reversed(coeffs)])
    try:
        approx = [z.mid() for z in mid_poly.roots(tol=tol)]
    except ValueError as exc:
        raise Undecided(f"root isolation of N(p, q) failed: {exc}") from None
    return smith_discs(coeffs, approx)


def _leading(coeffs: list[Acb]) -> list[Acb]:
    """``coeffs`` without leading exact zeros; Undecided when the leading one left may be 0."""
    while len(coeffs) > 1 and coeffs[0].is_zero():
        coeffs = coeffs[1:]
    if len(coeffs) > 1 and coeffs[0].contains(0):
        raise Undecided("leading coefficient of N(p, q) not bounded away from 0")
    return coeffs


def smith_discs(coeffs: Sequence[Acb], approx: Sequence[Acb]) -> list[Acb]:
    """The Smith discs (module text) of the polynomial with acb ``coeffs`` (highest power first, leading
    one bounded away from 0) around the exact points ``approx``, one per root, as square balls; they hold
    one root each when pairwise disjoint, which is checked.

    Raises
    ------
    Undecided
        If two discs overlap (approximations not close enough to distinct roots).
    """
    n = len(coeffs) - 1
    low_first = acb_poly(list(reversed(coeffs)))
    lead = coeffs[0]
    balls = []
    for k, zk in enumerate(approx):
        den = lead
        for j, zj in enumerate(approx):
            if j != k:
                den *= zk - zj
        w = low_first(zk) / den
        radius = arb(n) * abs(w)
        balls.append(acb(arb(zk.real, radius.upper()), arb(zk.imag, radius.upper())))
    for k in range(n):
        for j in range(k + 1, n):
            if balls[k].overlaps(balls[j]):
                raise Undecided("root discs of N(p, q) overlap")
    return balls


def point_root_balls(coeffs: list[Acb], tol: float, approx: Sequence[Acb] | None = None) -> list[Acb]:
    """Root balls of N(p, q) at a point q (acb ``coeffs``, highest power first): the Smith discs around
    ``approx`` (e.g. the roots at a neighbouring point) after Newton steps on N(., q) until the last step
    s is below sqrt(``tol``) / 100 relative to the root (the error after it, about |N''/2N'| s^2, is far
    below ``tol``); :func:`isolate_roots` when that does not converge in 12 steps or the discs overlap (the
    discs hold one root each whatever the approximations, :func:`smith_discs`)."""
    coeffs = _leading(coeffs)
    if approx is None or len(approx) != len(coeffs) - 1:
        return isolate_roots(coeffs, tol)
    mid = [c.mid() for c in coeffs]
    value, slope = _poly(mid), _poly(derivative_coefficients(mid))
    enough = 1e-2 * math.sqrt(tol)
    points = []
    for z in approx:
        z = acb(z).mid()
        for _ in range(12):
            step = (value(z) / slope(z)).mid()
            z = (z - step).mid()
            if not step.is_finite() or step.abs_upper() <= enough * max(1.0, float(z.abs_upper())):
                break
        else:
            return isolate_roots(coeffs, tol)
        if not z.is_finite():
            return isolate_roots(coeffs, tol)
        points.append(z)
    try:
        return smith_discs(coeffs, points)
    except Undecided:
        return isolate_roots(coeffs, tol)


def direct_root_balls(
    foundation: ModuleType,
    args: dict[str, Any],
    q: Acb,
    tol: float,
    prec: int,
    approx: Sequence[Acb] | None = None,
) -> list[Acb]:
    """Root balls of N(p, xi), each holding exactly one root for every xi in the ball q (module text).

    ``approx``, exact points near the roots at the ball's centre (one per root), are where the Krawczyk
    tests start; without them, or when they fail, the Smith discs at the centre. At a point (radius 0),
    the Smith discs of :func:`point_root_balls` from ``approx``.

    Raises
    ------
    Undecided
        When the leading coefficient may vanish over the ball, a Krawczyk test fails or two balls overlap.
    """
    n_mid = [acb(c) for c in foundation.n_coeffs(q.mid(), **args)]
    if q.rad() == 0:
        return point_root_balls(n_mid, tol, approx)
    n = [acb(c) for c in foundation.n_coeffs(q, **args)]
    if n[0].contains(0):  # the degree in p must not drop anywhere in the q ball
        raise Undecided("leading coefficient of N(p, q) not bounded away from 0 over the q ball")
    nq = [acb(c) for c in foundation.n_coeffs_dq(q, **args)]
    polys = tuple(_poly(c) for c in (n_mid, derivative_coefficients(n_mid), derivative_coefficients(n), nq))
    if approx is not None and len(approx) == len(n_mid) - 1:
        try:
            return _krawczyk_balls(polys, q, _newton_step(polys[0], polys[1], approx), prec)
        except Undecided:
            pass
    return _krawczyk_balls(polys, q, isolate_roots(n_mid, tol), prec)


def _poly(coeffs: Sequence[Acb]) -> AcbPoly:
    """The polynomial with ``coeffs`` (highest power first) as an ``acb_poly``: evaluated by Arb's Horner
    scheme, the same balls as :func:`horner` gives (the same operations, each rounded alike)."""
    return acb_poly(list(reversed(coeffs)))


def _narrowed(K: Acb, pm: Acb, Y: Acb, shift: Acb, n1: AcbPoly, steps: int = 8) -> Acb:
    """The Krawczyk image K of a proven ball, narrowed: K(X) = p_m - Y shift + (1 - Y N_p(X, q)) (X - p_m)
    holds the root for every q of the ball whenever X does and holds p_m (the mean-value form of N around
    p_m over X), so X is replaced by K(X) intersected with X while that holds p_m and shrinks the radius by
    a tenth or more (at most ``steps`` times)."""
    for _ in range(steps):
        if not K.contains(pm):
            break
        image = pm - Y * shift + (1 - Y * n1(K)) * (K - pm)
        narrower = acb(K.real.intersection(image.real), K.imag.intersection(image.imag))
        shrunk = narrower.rad() < 0.9 * K.rad()
        K = narrower
        if not shrunk:
            break
    return K


def _newton_step(n_mid: AcbPoly, n1_mid: AcbPoly, approx: Sequence[Acb]) -> list[Acb]:
    """One Newton step on N(., m) from each of ``approx``, in midpoints (exact points)."""
    out = []
    for z in approx:
        z = acb(z).mid()
        out.append((z - n_mid(z) / n1_mid(z)).mid())
    return out


def _krawczyk_balls(polys: tuple[AcbPoly, ...], q: Acb, centre: Sequence[Acb], prec: int) -> list[Acb]:
    """The Krawczyk test of the module text around each ball of ``centre`` (at q's midpoint m; points or
    Smith discs), with ``polys`` = (N(., m), N_p(., m), N_p over q, N_q over q); the balls K it proves,
    checked pairwise disjoint (so that, one per root of N, they hold every root)."""
    n_mid, n1_mid, n1, nq = polys
    balls = []
    for p_ball in centre:
        pm = p_ball.mid()
        Y = (1 / n1_mid(pm)).mid()
        shift = n_mid(p_ball) + nq(p_ball) * (q - q.mid())
        rho = 2 * (Y * shift).abs_upper() + p_ball.rad() + arb(2) ** (-prec)
        for _ in range(3):
            P = acb(arb(pm.real, rho), arb(pm.imag, rho))
            K = pm - Y * shift + (1 - Y * n1(P)) * (P - pm)
            if P.contains_interior(K):
                balls.append(_narrowed(K, pm, Y, shift, n1))
                break
            rho = 4 * rho
        else:
            raise Undecided("no isolating ball for a root of N(p, q) over the q ball")
    for k in range(len(balls)):
        for j in range(k + 1, len(balls)):
            if balls[k].overlaps(balls[j]):
                raise Undecided("root balls of N(p, q) overlap over the q ball")
    return balls
