"""Tracks whose cut of K is a straight half-line: q = alpha p + i c +- sqrt(R(p))/2 for real p (Eq. (24)).

The cut of K is where N(p, q) has a real root p (``kernels/cut.py``). When N is quadratic in q, its roots
for real p are q = m(p) +- sqrt(disc(p)); if m(p) = alpha p + i c with c free of p and real, and
R(p) = 4 disc(p) is a polynomial in p with real coefficients (free of alpha), then wherever R(p) >= 0 the
cut is the pair of half-lines Im q = c traced by Re q = alpha p +- sqrt(R(p))/2 (for the paper's
Euler-Bernoulli beam c = eta_f and R = p^4 + 4 eta_s p^2 + 4 - 4 eta_f^2). The generated
``cut_line_im`` and ``cut_line_radicand`` declare it, and the runtime integrates the branch-cut part of
Eq. (35) along it in closed geometry (``response/branch_cut.py``), checking R > 0 at its parameters.
"""

from dataclasses import dataclass

import sympy as sp

from . import symbols as s
from .model import coefficients, foundation_image


@dataclass(frozen=True)
class CutLine:
    """Im q = ``im`` on the cut; ``radicand`` = R(p), Re q = alpha p +- sqrt(R)/2."""

    im: sp.Expr
    radicand: sp.Expr


def cut_line(track) -> CutLine | None:
    """The half-line form of the cut of K for ``track``, or None when N(p, q) does not have it."""
    degree, coeffs = coefficients(foundation_image(track).N, s.q)
    if degree != 2:
        return None
    a, b, c = coeffs
    if a.has(s.p) or a == 0:
        return None
    centre = sp.expand(-b / (2 * a) - s.alpha * s.p)
    im = sp.expand(centre / sp.I)
    radicand = sp.expand((b**2 - 4 * a * c) / a**2)
    if centre.has(s.p) or im.has(sp.I) or radicand.has(sp.I) or radicand.has(s.alpha) or radicand.has(s.q):
        return None
    if not radicand.is_polynomial(s.p):
        return None
    return CutLine(im, radicand)
