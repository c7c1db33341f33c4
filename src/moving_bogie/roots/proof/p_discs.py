"""Isolating discs for the roots p of N(p, q) (Eq. (24)), each valid for every q of a whole q-ball.

N is a polynomial in p and in q (degrees ``DEGREE_N`` and ``DEGREE_N_IN_Q`` of the generated track). Around
a point (p_m, m) its Taylor expansion

    N(p_m + s, m + t) = sum_{k, j} c_kj s^k t^j

is finite, and its coefficients are balls computed at that point (narrow), not on the wide q-ball: bounds
of N and N_p over |s| <= r, |t| <= r_t follow as sums of |c_kj| r^k r_t^j, without the overestimation of
evaluating N on wide balls (which, for the two-layer track's large roots |p| ~ 60, failed almost every
test on segments longer than 1e-3).

**The test** (a Krawczyk test in disc form). With Y ~ 1 / N_p(p_m, m) and g(p) = p - Y N(p, q), for every
|t| <= r_t and every p = p_m + s, |s| <= r:

    |g(p) - p_m| <= |Y N(p_m, m + t)| + sup |1 - Y N_p| r <= A + B(r) r.

If A + B(r) r < r (so B(r) < 1), g maps the closed disc |s| <= r into itself and is a contraction there,
for every q of the ball: the disc holds exactly one root of N(., q) (Banach's fixed-point theorem; Y != 0).
When all ``DEGREE_N`` discs are pairwise disjoint and the leading coefficient does not vanish over the ball,
they hold every root. The disc is returned as the square acb ball around it.

The approximations p_m are the previous call's discs polished by Newton's method at the point m (adjacent
boundary segments are close), or, when those do not give disjoint discs, Arb's ``acb_poly.roots``.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from types import ModuleType
from typing import Any

from flint import acb, acb_poly, acb_series, arb, arb_poly

from moving_bogie.roots.proof.p_balls import Undecided
from moving_bogie.typing import Acb, AcbSeries


def coefficients_in_q(foundation: ModuleType, args: dict[str, Any]) -> list[acb_poly]:
    """N's coefficient of each power of p (highest first) as an acb_poly in q, exactly.

    N is a polynomial of degree ``DEGREE_N_IN_Q`` in q, so the series at q = 0 of that many terms (plus
    one) is its whole expansion; the extra term is checked to vanish.
    """
    length = int(foundation.DEGREE_N_IN_Q) + 2
    series = [
        c if isinstance(c, acb_series) else acb_series([acb(c)], prec=length)
        for c in foundation.n_coeffs(acb_series([0, 1], prec=length), **args)
    ]
    rows = [(s.coeffs() + [acb(0)] * length)[:length] for s in series]
    if not all(row[-1].is_zero() for row in rows):
        raise ArithmeticError("N(p, q) is not a polynomial of degree DEGREE_N_IN_Q in q")
    return [acb_poly(row[:-1]) for row in rows]


def taylor_in_q(in_q: Sequence[acb_poly], m: Acb) -> list[acb_poly]:
    """N(p, m + t) as ``[N_0, N_1, ...]``: acb_poly in p (lowest power first), the coefficient of t^j each,
    from :func:`coefficients_in_q` ``in_q``."""
    shift = acb_poly([m, 1])
    rows = [row(shift).coeffs() for row in in_q]
    length = max(len(row) for row in rows)
    return [acb_poly([row[j] if j < len(row) else acb(0) for row in reversed(rows)]) for j in range(length)]


class PRootDiscs:
    """Root discs of N(p, q) over q-balls; remembers the last approximations to start from."""

    def __init__(self, foundation: ModuleType, args: dict[str, Any], prec: int) -> None:
        self.foundation = foundation
        self.args = args
        self.prec = prec
        self.tol = 2.0 ** (8 - prec)
        self.approx: list[Acb] | None = None
        self.in_q = coefficients_in_q(foundation, args)

    def discs(self, q: Acb) -> list[Acb]:
        """Squares, one per root of N(p, xi), each holding exactly one root for every xi in the ball q.

        Raises
        ------
        Undecided
            If the discs cannot be proven (the ball too wide for the roots' motion, or roots too close).
        """
        return [d.ball for d in self.roots(q)]

    def roots(self, q: Acb) -> list[RootDisc]:
        """:class:`RootDisc` per root of N(p, xi) over the ball q (see :meth:`discs`)."""
        m = q.mid()
        if q.rad() == 0:  # a point: N's coefficients there are all the expansion needed
            polys = [acb_poly([acb(c) for c in reversed(self.foundation.n_coeffs(m, **self.args))])]
        else:
            polys = taylor_in_q(self.in_q, m)
        rt = (q - m).abs_upper()
        centre = polys[0]
        n = centre.degree()
        lead = centre.coeffs()[-1]
        spread = sum(
            (_coefficient(poly, n).abs_upper() * rt**j for j, poly in enumerate(polys[1:], 1)), arb(0)
        )
        if lead.contains(0) or not lead.abs_lower() > spread:
            raise Undecided("leading coefficient of N(p, q) not bounded away from 0 over the q ball")
        polished = _newton(centre, self.approx, self.tol) if self.approx and len(self.approx) == n else None
        if polished is not None:
            found = self._try(polys, q - m, polished)
            if found is not None:
                return found
        try:
            mid = acb_poly([c.mid() for c in centre.coeffs()])
            approx = [z.mid() for z in mid.roots(tol=self.tol)]
        except ValueError as exc:
            raise Undecided(f"root isolation of N(p, q) failed: {exc}") from None
        found = self._try(polys, q - m, approx)
        if found is None:
            raise Undecided("no disjoint isolating discs for the roots of N(p, q) over the q ball")
        return found

    def _try(self, polys: Sequence[acb_poly], t: Acb, approx: Sequence[Acb]) -> list[RootDisc] | None:
        found = []
        for pm in approx:
            disc = _disc(polys, t, pm)
            if disc is None:
                return None
            found.append(disc)
        for k in range(len(found)):
            for j in range(k + 1, len(found)):
                if found[k].ball.overlaps(found[j].ball):
                    return None
        self.approx = [d.centre for d in found]
        return found


@dataclass(frozen=True)
class RootDisc:
    """A proven root disc: the square ``ball`` around ``centre`` (p_m) and the expansion of N there,
    ``shifted[j][k]`` = c_kj (coefficient of s^k t^j, module docstring)."""

    ball: Acb
    centre: Acb
    shifted: list[list[Acb]]

    def series(self, u: Acb, length: int) -> list[AcbSeries]:
        """N(p_m + s, m + u + tau) as a polynomial in s (highest power first) with coefficients series in
        tau of ``length`` terms: u is the ball q - m, so the coefficients hold for every q of it."""
        ts = acb_series([u, 1], prec=length)
        degree = max(len(c) for c in self.shifted)
        out = []
        for k in reversed(range(degree)):
            in_t = [c[k] if k < len(c) else acb(0) for c in self.shifted]
            total = acb_series([in_t[-1]], prec=length)
            for c in reversed(in_t[:-1]):
                total = total * ts + c
            out.append(total)
        return out


def _coefficient(poly: acb_poly, k: int) -> Acb:
    coeffs = poly.coeffs()
    return coeffs[k] if k < len(coeffs) else acb(0)


def _newton(poly: acb_poly, approx: Sequence[Acb], tol: float, steps: int = 4) -> list[Acb] | None:
    """Midpoint Newton steps from ``approx`` on ``poly``; None unless every step converged to a relative
    ``tol`` (a far start is not polished: its disc would be proven, but wide)."""
    dpoly = poly.derivative()
    out = []
    for z in approx:
        for _ in range(steps):
            d: Acb = dpoly(z)  # at a point z: a ball (python-flint's stubs say a polynomial)
            if d.contains(0):
                return None
            value: Acb = poly(z)
            step = (value / d).mid()
            z = (z - step).mid()
            if step.abs_upper() < tol * z.abs_lower():
                break
        else:
            return None
        out.append(z)
    return out


def _disc(polys: Sequence[acb_poly], t: Acb, pm: Acb) -> RootDisc | None:
    """The disc around ``pm`` passing the test of the module docstring (smallest radius tried), or None.

    ``t`` is the ball q - m, r_t = |t|. With the majorant M(s) = sum_{k, j} |Y c_kj| r_t^j s^k (its
    coefficients upper bounds, all >= 0): A = M(0), and over |s| <= r
    sup |1 - Y N_p| <= |1 - Y c_10| + (M'(r) - |Y c_10|), since N_p = sum (k + 1) c_{k+1, j} s^k t^j.
    """
    shift = acb_poly([pm, 1])
    shifted = [poly(shift) for poly in polys]
    c0: list[Acb] = shifted[0].coeffs()
    if len(c0) < 2 or c0[1].contains(0):
        return None
    Y = (1 / c0[1]).mid()
    rt = t.abs_upper()
    M, power = arb_poly([0]), arb(1)
    for poly in shifted:
        M += arb_poly([c.abs_upper() for c in (poly * Y).coeffs()]) * power
        power *= rt
    dM = M.derivative()
    A = M(arb(0))
    slope = Y * c0[1]
    b0 = (1 - slope).abs_upper() - slope.abs_upper()  # B(r) = b0 + M'(r)
    if not b0 + dM(arb(0)) < 1:
        return None
    r = 2 * A.upper() / (1 - (b0 + dM(arb(0))).upper()) + arb(2) ** -1074
    for _ in range(6):
        if A + (b0 + dM(r)) * r < r:
            return RootDisc(acb(arb(pm.real, r), arb(pm.imag, r)), pm, [poly.coeffs() for poly in shifted])
        r = 2 * r
    return None
