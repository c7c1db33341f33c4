"""E_chr(q) and dE_chr/dq of Eqs. (38) and (40) in ball arithmetic, on a point or a whole complex ball of q.

Every quantity is an arb/acb ball (python-flint, Arb) guaranteed to contain the exact value, for every q in
the input ball; the parameters enter as balls around their exact rational values (Table 1 prints decimals).

K(xi, q) of Eq. (29) is the residue sum of :mod:`moving_bogie.kernels.track`:

    K(xi, q) = +2 pi i sum_{Im p_k > 0} exp(i p_k xi) Q(p_k) / N'(p_k)     (xi >= 0; the minus sign and
                                                                            Im p_k < 0 for xi < 0),

Here the p-roots of N(p, q) are isolated balls, and the side of the real p-axis on which each lies is
*decided*: a root ball that meets the real axis (q too close to the cut of K for the given ball) raises
:class:`Undecided`, so a caller can only subdivide, never guess.

The p-root balls over a q-ball come from one of two proven methods: for tracks whose N has degree 4 in p
(the one-layer beams) the Smith discs at the centre widened by a Krawczyk test on N evaluated over the
ball (:mod:`~moving_bogie.roots.proof.p_balls`), cheapest there; for the layered tracks (degree 6 and more,
roots |p| ~ 60 whose balls that test overestimates) discs from N's exact Taylor expansion at the centre
(:mod:`~moving_bogie.roots.proof.p_discs`). ``p_roots="direct"`` or ``"discs"`` forces one.

Derivatives in q (dK/dq, dE_chr/dq of Eq. (40), and higher) come from truncated Taylor series arithmetic
(``acb_series``) through the same residue sum, not from the double-pole formula of
:mod:`moving_bogie.kernels.track`, which the tests use as an independent check.

The generated kernels (``moving_bogie.generated``) are plain arithmetic, so they are called unchanged with
acb arguments (their ``1j`` literals combine with acb exactly).
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from fractions import Fraction
from typing import TYPE_CHECKING

from flint import acb, acb_series, arb, ctx, fmpq

from moving_bogie.kernels.bound import BoundModel
from moving_bogie.kernels.track import foundation_arguments
from moving_bogie.roots.proof.ball_block import BlockBalls
from moving_bogie.roots.proof.p_balls import (
    Undecided,
    derivative_coefficients,
    direct_root_balls,
    horner,
    isolate_roots,
)
from moving_bogie.roots.proof.p_discs import PRootDiscs, RootDisc
from moving_bogie.typing import Acb, AcbSeries, Arb

if TYPE_CHECKING:
    from moving_bogie.model.params import DimensionlessParams

#: A series in t = q - c, or its value alone (a ball) when no derivative is asked for.
Series = Acb | AcbSeries

__all__ = [
    "BallCharacteristic",
    "Undecided",
    "derivative_coefficients",
    "exact_ball",
    "horner",
    "isolate_roots",
    "square_ball",
]

#: Highest degree of N in p for which the direct p-root balls are used by default (the one-layer beams).
DIRECT_DEGREE = 4


def exact_ball(x: Fraction | int | None) -> Acb | None:
    """An acb ball containing the rational ``x`` (a Fraction, int or None) at the current precision
    (None for None)."""
    if x is None:
        return None
    return acb(arb(fmpq(x.numerator, x.denominator)))


def square_ball(center: complex | Acb, radius: float | Arb) -> Acb:
    """The acb ball (a square) of centre ``center`` (complex or acb) and half-side ``radius``."""
    c = acb(center)
    r = arb(radius)
    return acb(arb(c.real.mid(), r), arb(c.imag.mid(), r))


def _exact(x: Fraction | int | None) -> Fraction | None:
    """A parameter's exact value as a Fraction (it is a Fraction or an int), or None."""
    return None if x is None else Fraction(x)


class _ExactBalls:
    """Attribute access to the parameters of a DimensionlessParams as balls around their exact values."""

    def __init__(self, params: DimensionlessParams) -> None:
        self._params = params

    def __getattr__(self, name: str) -> Acb:
        if name.startswith("_"):
            raise AttributeError(name)
        return exact_ball(getattr(self._params, name))


def _constant(value: Acb | AcbSeries) -> Acb:
    """A number, or the constant term of a series (of one term), as an acb."""
    if isinstance(value, acb_series):
        coeffs = value.coeffs()
        return acb(coeffs[0]) if coeffs else acb(0)
    return acb(value)


def _series(values: Iterable[Acb | AcbSeries], length: int) -> list[AcbSeries]:
    """Each value as an acb_series of ``length`` terms (constants become constant series)."""
    return [v if isinstance(v, acb_series) else acb_series([acb(v)], prec=length) for v in values]


class BallCharacteristic:
    """Taylor coefficients of E_chr (Eq. (38)) on acb balls of q, at ``prec`` bits.

    Every quantity is a truncated power series in t = q - c whose coefficients are balls: evaluated at a
    ball c, coefficient j encloses E_chr^(j)(xi)/j! for every xi in the ball (coefficient 1 is dE_chr/dq of
    Eq. (40), here by differentiating the residue sum rather than by double-pole residues).
    The p-roots are series too: from the isolated ball p0 of a root, Newton steps on series,
    p <- p - N(p, q) / N_p(p, q), each doubling the number of exact coefficients; since every step is
    inclusion-monotone, the coefficients enclose those of the true root p(xi + t) for every xi in the ball.

    Parameters
    ----------
    bound : BoundModel
        The parameters (exact) bound to their model.
    prec : int
        Working precision in bits; every call runs at it (the p-roots are approximated to it too).
    below : bool
        On the real q-axis, K as the limit from below (eta_f = 0, the cut on the axis). For a q-ball that
        meets the axis, a p-root ball P that meets the real p-axis is proven real at the
        ball's real points x (N(p, x) has real coefficients and the mirror of P meets no other root ball,
        so the root is its own conjugate) and counted upper iff Re(N_q / N_p) > 0 on the ball: with
        dp/dq = -N_q / N_p, Im p(x - iy) = integral from 0 to y of Re(N_q / N_p)(x - it) dt. K so
        defined is K on Im q < 0 continued analytically across the axis (for the part of the ball above
        it too: the continuation, not the values from above), away from the branch points.
    """

    def __init__(
        self, bound: BoundModel, *, prec: int = 128, below: bool = False, p_roots: str = "auto"
    ) -> None:
        params = bound.params
        self.below = below
        self.params = params
        self.prec = prec
        self.tol = 2.0 ** (8 - prec)
        self.foundation = bound.foundation
        self.vehicle = bound.vehicle
        self.blocks: BlockBalls | None = None
        self.last_point: tuple[Acb, list[Acb]] | None = None  # a point q and its roots' midpoints
        self.evaluations = 0
        self._series_args: dict[int, dict[str, AcbSeries]] = {}
        with ctx.workprec(prec):
            numbers = _ExactBalls(params)
            self.foundation_args = foundation_arguments(bound, numbers)
            if p_roots not in ("auto", "direct", "discs"):
                raise ValueError(f"p_roots must be 'auto', 'direct' or 'discs' (got {p_roots!r})")
            if p_roots == "auto":
                p_roots = "direct" if int(self.foundation.DEGREE_N) <= DIRECT_DEGREE else "discs"
            self.direct = p_roots == "direct"
            self.p_discs = None if self.direct else PRootDiscs(self.foundation, self.foundation_args, prec)
            if hasattr(self.vehicle, "e_chr"):  # the closed form of Eq. (38)
                self.vehicle_args = {name: getattr(numbers, name) for name in self.vehicle.PARAMETERS}
                self.vehicle_args["pi"] = acb(arb.pi())
            else:  # any vehicle: the block system (roots/proof/ball_block.py)
                values = {name: getattr(numbers, name) for name in self.vehicle.MATRIX_ARGUMENTS}
                exact = {name: _exact(getattr(params, name)) for name in self.vehicle.MATRIX_ARGUMENTS}
                self.blocks = BlockBalls(self.vehicle, values, exact)
            self.d = numbers.d
            self.two_pi_i = acb(0, 2) * acb(arb.pi())

    def p_roots(self, q: Acb | complex) -> tuple[list[Acb], list[Acb]]:
        """(upper, lower): balls holding each one root of N(p, xi) for every xi in the ball ``q``, split by
        the sign of Im p (proven; Undecided if a ball meets the real axis)."""
        with ctx.workprec(self.prec):
            return self._sides(acb(q), self._root_balls(acb(q)))

    def _root_balls(self, q: Acb) -> list[Acb]:
        """Root balls of N(p, xi), xi in the ball q, each holding exactly one root for every xi (direct:
        :mod:`p_balls`; else :mod:`p_discs`, a Krawczyk test in disc form on N's exact Taylor expansion).

        Direct: the roots at the last point evaluated start the tests over a ball that contains the point
        (a boundary segment's ball holds its end evaluated before it), and the Newton steps to the Smith
        discs at a point (a boundary segment's end next to the one before), as approximations only."""
        if self.p_discs is not None:  # not self.direct
            return self.p_discs.discs(q)
        last = self.last_point
        approx = last[1] if last is not None and (q.rad() == 0 or q.contains(last[0])) else None
        balls = direct_root_balls(self.foundation, self.foundation_args, q, self.tol, self.prec, approx)
        if q.rad() == 0:
            self.last_point = (q, [b.mid() for b in balls])
        return balls

    def _sides(self, q: Acb, roots: Sequence[Acb]) -> tuple[list[Acb], list[Acb]]:
        """(upper, lower) p-root balls at the q-ball ``q``; on the real axis with ``below``, real roots
        go to the side they move to when q -> q - i0 (class docstring)."""
        on_axis = self.below and q.imag.contains(0)
        if not on_axis:
            return _sides(roots)
        upper: list[Acb] = []
        lower: list[Acb] = []
        f, args = self.foundation, self.foundation_args
        if not all(acb(c).imag.is_zero() for c in f.n_coeffs(acb(q.real), **args)):
            return _sides(roots)  # a damped track: no limit from below needed (or possible) here
        n1 = derivative_coefficients([acb(c) for c in f.n_coeffs(q, **args)])
        nq = [acb(c) for c in f.n_coeffs_dq(q, **args)]
        for k, p in enumerate(roots):
            if p.imag > 0 or p.imag < 0:
                (upper if p.imag > 0 else lower).append(p)
                continue
            mirror = p.conjugate()
            if any(mirror.overlaps(other) for j, other in enumerate(roots) if j != k):
                raise Undecided("a root of N(p, q) near the real p-axis not proven real")
            ratio = (horner(nq, p) / horner(n1, p)).real
            if ratio > 0:
                upper.append(p)
            elif ratio < 0:
                lower.append(p)
            else:
                raise Undecided("side of a real root of N(p, q) from below not decided (N_q / N_p near 0)")
        return upper, lower

    def kernel_series(self, q: Acb, order: int) -> list[Series]:
        """K (Eq. (29)) at the contact offsets ([K(0), K(d), K(-d)] for the closed form) as series in
        t = q - c to ``order``, for every c in the ball q (as balls, the values, for ``order`` 0)."""
        length = order + 1
        f = self.foundation
        args = self.foundation_args
        found: list[RootDisc] | None
        if self.p_discs is None:  # self.direct
            found, balls = None, self._root_balls(q)
        else:
            found = self.p_discs.roots(q)
            balls = [d.ball for d in found]
        upper, lower = self._sides(q, balls)
        point = order == 0  # values only: plain balls, not series of one term (the same sums, faster)

        def lift(values: Iterable[Acb | AcbSeries]) -> list[Series]:
            return [_constant(v) for v in values] if point else _series(values, length)

        qs = q if point else acb_series([q, 1], prec=length)
        qc = lift(f.q_coeffs(qs, **args))
        i_unit = acb(0, 1)
        if q.rad() == 0 or found is None:  # N's coefficients as series in t = q - c directly
            n = lift(f.n_coeffs(qs, **args))
            n1 = derivative_coefficients(n)

            def expanded(p0: Acb) -> tuple[Acb, list[Series], list[Series], Acb]:
                return acb(0), n, n1, p0
        else:  # a ball: N around each root disc's centre (narrow coefficients, p_discs.py)
            discs = {id(d.ball): d for d in found}
            u = q - q.mid()

            def expanded(p0: Acb) -> tuple[Acb, list[Series], list[Series], Acb]:
                d = discs[id(p0)]
                n = lift(d.series(u, length))
                return d.centre, n, derivative_coefficients(n), p0 - d.centre

        def solved(roots: Sequence[Acb]) -> list[tuple[Series, Series, Series]]:
            """(p, Q(p), N_p(p)) per root: the series of the root and what its residue divides, which every
            offset shares (only exp(i xi p) depends on xi). The root is c + s, s a series found by Newton
            steps on N(c + s) (c = 0 at a point, the disc's centre over a ball)."""
            out = []
            for p0 in roots:
                centre, n, n1, s0 = expanded(p0)
                s: Series = s0 if point else acb_series([s0], prec=length)
                for _ in range(order.bit_length()):
                    step = horner(n1, s)
                    if acb(step.coeffs()[0] if step.coeffs() else 0).contains(0):
                        raise Undecided("N_p(p, q) not bounded away from 0 over the q ball")
                    s = s - horner(n, s) / step
                    s = acb_series([s0] + s.coeffs()[1:], prec=length)
                p = s + centre
                out.append((p, horner(qc, p), horner(n1, s)))
            return out

        def residues(roots: Sequence[tuple[Series, Series, Series]], xi: Acb) -> Series:
            total: Series = acb(0) if point else acb_series([acb(0)], prec=length)
            for p, Qp, N1p in roots:
                total += (i_unit * xi * p).exp() * Qp / N1p
            return total

        above, below = solved(upper), solved(lower)
        if self.blocks is None:
            return [
                self.two_pi_i * residues(above, acb(0)),
                self.two_pi_i * residues(above, self.d),
                -self.two_pi_i * residues(below, -self.d),
            ]
        out = []
        for xi, side in zip(self.blocks.offsets, self.blocks.sides()):
            if side is None:
                raise Undecided("the sign of a contact offset xi_i - xi_j is not decided")
            out.append(side * self.two_pi_i * residues(above if side > 0 else below, xi))
        return out

    def taylor(self, q: Acb | complex, order: int = 1) -> list[Acb]:
        """[E, E', E''/2, ...] to ``order``: balls enclosing E_chr^(j)(xi)/j! for every xi in the ball q."""
        with ctx.workprec(self.prec):
            q = acb(q)
            self.evaluations += 1
            K = self.kernel_series(q, order)
            qs = acb_series([q, 1], prec=order + 1) if order else acb_series([q], prec=1)
            if self.blocks is None:
                E = self.vehicle.e_chr(qs if order else q, *K, **self._vehicle_args(order + 1))
            else:
                E = self.blocks.det(qs, _series(K, order + 1), order + 1)
                if E is None:
                    raise Undecided("a pivot of the block system contains 0 over the q ball")
            coeffs = E.coeffs() if isinstance(E, acb_series) else [acb(E)]
            return (coeffs + [acb(0)] * (order + 1))[: order + 1]

    def _vehicle_args(self, length: int) -> dict[str, Acb | AcbSeries]:
        """The vehicle's parameters for :meth:`taylor`: balls for values (``length`` 1), else constant
        series of ``length`` terms (the same products as with balls, without converting a ball at each)."""
        if length == 1:
            return self.vehicle_args
        if length not in self._series_args:
            constants = _series(self.vehicle_args.values(), length)
            self._series_args[length] = dict(zip(self.vehicle_args, constants))
        return self._series_args[length]

    def value(self, q: Acb | complex) -> Acb:
        """E_chr(q): a ball containing E_chr at every point of the ball ``q``."""
        return self.taylor(q, 0)[0]

    def value_and_derivative(self, q: Acb | complex) -> tuple[Acb, Acb]:
        """(E_chr, dE_chr/dq) as balls over the ball ``q``."""
        E, dE = self.taylor(q, 1)
        return E, dE

    def derivative(self, q: Acb | complex) -> Acb:
        """dE_chr/dq as a ball over the ball ``q``.

        For the block system over a ball B of positive radius, E' = E T with T = tr(A^-1 dA/dq) (Jacobi)
        over B, and E over B is narrowed by the mean-value form E(m) + E'(B) (B - m) (m the midpoint), in
        turn: the determinant of a matrix of balls loses much to the dependency of its entries on the one
        q, while T and the point value E(m) do not. Each step is an enclosure of the same quantity (the ball
        being convex), so their intersection is one too; it contracts by about |T| rad(B) per step. Where
        A is not proven regular over B, E' over B directly.
        """
        q = acb(q)
        if self.blocks is None or q.rad() == 0:
            return self.taylor(q, 1)[1]
        with ctx.workprec(self.prec):
            qs = acb_series([q, 1], prec=2)
            pair = self.blocks.log_derivative(qs, _series(self.kernel_series(q, 1), 2))
            if pair is None:
                return self.taylor(q, 1)[1]
            self.evaluations += 1
            E, T = pair
            m = q.mid()
            Em, t = self.value(m), q - m
            dE = E * T
            for _ in range(12):
                E = _intersection(E, Em + dE * t)
                narrower = E * T
                if not narrower.rad() < 0.9 * dE.rad():
                    break
                dE = narrower
            return dE


def _intersection(a: Acb, b: Acb) -> Acb:
    """The intersection of two enclosures of one complex number (both rectangles hold it)."""
    return acb(a.real.intersection(b.real), a.imag.intersection(b.imag))


def _sides(roots: Iterable[Acb]) -> tuple[list[Acb], list[Acb]]:
    """Split isolated p-root balls by the sign of Im p; a ball meeting the real axis raises Undecided."""
    upper: list[Acb] = []
    lower: list[Acb] = []
    for p in roots:
        if p.imag > 0:
            upper.append(p)
        elif p.imag < 0:
            lower.append(p)
        else:
            raise Undecided("a root of N(p, q) meets the real p-axis: q ball too close to the cut of K")
    return upper, lower
