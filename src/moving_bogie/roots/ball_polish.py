"""E_chr and dE_chr/dq (Eqs. (38), (40)) for Newton's method at the current mpmath precision, evaluated in
Arb's ball arithmetic (:class:`~moving_bogie.roots.proof.balls.BallCharacteristic`, C code: about eight
times faster than the mpmath path of :class:`~moving_bogie.kernels.characteristic.Characteristic`).

The point q (an mpmath number) enters as an exact ball; the values returned are the midpoints of the balls,
rounded to the working precision. Every ball encloses the exact value, so the evaluation knows its own
error: the values are accepted only when the error of E over |E'| (what the Newton step E / E' and so the
root inherit; that of E' only scales a step) is below the last working digit of q by
:data:`GUARD_DIGITS`; otherwise the evaluation is repeated at twice the bits, and where the balls cannot
decide (a p-root of N on the real p-axis, :class:`Undecided`) or stay too wide, and for a model they do
not evaluate (:func:`balls_apply`), the mpmath path answers.
The roots so polished are those of the mpmath path to the working precision (a test compares the two).
"""

from __future__ import annotations

import mpmath
from flint import acb, arb, ctx

from moving_bogie.kernels.bound import BoundModel
from moving_bogie.kernels.characteristic import Characteristic
from moving_bogie.kernels.track import foundation_arguments
from moving_bogie.roots.proof.balls import BallCharacteristic, Undecided
from moving_bogie.typing import Acb, Arb, Mpc, Mpf

__all__ = ["BallPrecise", "acb_from_mpc", "balls_apply", "mpc_from_acb"]

#: Bits carried beyond the working precision in the ball evaluation.
GUARD_BITS = 32
#: Values are accepted when rad(E) / |E'| is below 10^-(dps + GUARD_DIGITS) max(1, |q|).
GUARD_DIGITS = 3
#: Doublings of the ball precision tried before the mpmath path answers.
RETRIES = 2


def arb_from_mpf(x: Mpf) -> Arb:
    """The exact arb of an mpmath real (its binary mantissa and exponent)."""
    sign, man, exp, _ = x._mpf_
    return arb((-int(man) if sign else int(man), int(exp)))


def acb_from_mpc(z: Mpc) -> Acb:
    """The exact acb (radius 0) of an mpmath complex (formed at a precision that holds both parts)."""
    bits = max(int(z.real._mpf_[3]), int(z.imag._mpf_[3]), ctx.prec)
    with ctx.workprec(bits):
        return acb(arb_from_mpf(z.real), arb_from_mpf(z.imag))


def _mpf_from_arb(x: Arb) -> Mpf:
    """The midpoint of an arb as an mpmath real rounded to the working precision."""
    man, exp = x.mid().man_exp()
    return mpmath.mpf((int(man), int(exp)))


def mpc_from_acb(z: Acb) -> Mpc:
    """The midpoint of an acb as an mpmath complex rounded to the working precision."""
    return mpmath.mpc(_mpf_from_arb(z.real), _mpf_from_arb(z.imag))


class BallPrecise:
    """(E_chr, dE_chr/dq) at one q for :func:`~moving_bogie.roots.refine.polish.newton`, by Arb (module
    docstring); the mpmath path ``precise`` where the balls do not settle the step.

    Parameters
    ----------
    bound : BoundModel
        The parameters bound to their model.
    precise : Characteristic, optional
        The mpmath path (the fallback); a new one for ``bound`` by default.
    """

    def __init__(self, bound: BoundModel, precise: Characteristic | None = None) -> None:
        self.bound = bound
        self.params = bound.params
        self.precise = Characteristic(bound) if precise is None else precise
        self.applies = balls_apply(bound)
        self._balls: dict[int, BallCharacteristic] = {}
        self.ball_evaluations = 0
        self.fallbacks = 0

    @property
    def evaluations(self) -> int:
        """Evaluations in balls and by the mpmath path."""
        return self.ball_evaluations + self.precise.evaluations

    def _at(self, prec: int) -> BallCharacteristic:
        """The ball characteristic at ``prec`` bits (built once per precision)."""
        if prec not in self._balls:
            self._balls[prec] = BallCharacteristic(self.bound, prec=prec)
        return self._balls[prec]

    def value_and_derivative(self, q: Mpc) -> tuple[Mpc, Mpc]:
        """(E_chr(q), dE_chr/dq) at the current mpmath precision (Eq. (40)), each with the error of its
        Newton step E / E' below the last working digit (module docstring)."""
        q = mpmath.mpc(q)
        point = acb_from_mpc(q)
        bound = mpmath.mpf(10) ** (-mpmath.mp.dps - GUARD_DIGITS) * max(1, abs(q))
        prec = mpmath.mp.prec + GUARD_BITS
        for _ in range(RETRIES + 1 if self.applies else 0):
            try:
                E, dE = self._at(prec).value_and_derivative(point)
            except Undecided:
                break
            if not dE.contains(0) and _upper(E.rad() / abs(dE).lower()) <= bound:
                self.ball_evaluations += 1
                return mpc_from_acb(E), mpc_from_acb(dE)
            prec *= 2
        self.fallbacks += 1
        return self.precise.value_and_derivative(q)


def balls_apply(bound: BoundModel) -> bool:
    """Whether :class:`~moving_bogie.roots.proof.balls.BallCharacteristic` evaluates this bound model: it
    takes the track's arguments from the parameters, so not a track whose own values (a
    :class:`~moving_bogie.kernels.foundation.Foundation` given its layer) fill arguments they lack."""
    from_params = foundation_arguments(bound, bound.params)
    return all(
        from_params.get(name) is not None or value is None for name, value in bound.foundation_mp().items()
    )


def _upper(x: Arb) -> Mpf:
    """An upper bound of a non-negative arb as an mpmath real."""
    return _mpf_from_arb(arb(x.upper())) if x.is_finite() else mpmath.inf
