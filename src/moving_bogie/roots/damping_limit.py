"""What a little foundation damping does to the real induced frequencies of an undamped foundation.

With eta_f = 0 and an undamped vehicle, E_chr is real on the gap |Re q| < q_c, and the induced
frequencies there are real: neutral, constant amplitude (Table 1's Cases 2-4, 10). The verdict at
eta_f = 0 counts them as stable. Under a small foundation damping eta_f > 0 a simple real root q0 moves to

    q(eta_f) = q0 - eta_f E_eta(q0) / E_q(q0) + O(eta_f^2),        E_eta = dE_chr/deta_f at eta_f = 0,

so it becomes unstable, with a growth rate proportional to eta_f, when Im(E_eta / E_q) > 0 (the
mechanism :mod:`moving_bogie.stability.maps.undamped` follows over whole parameter planes). Here E_eta(q0) is
read from E_chr(q0) at eta_f = :data:`PROBE` (E_chr(q0) = 0 at eta_f = 0, so E_chr(q0; PROBE) =
PROBE E_eta(q0) to first order), E_q from Eq. (40) at eta_f = 0.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import TYPE_CHECKING

import mpmath

from moving_bogie.kernels.characteristic import Characteristic

if TYPE_CHECKING:
    from moving_bogie.roots.frequencies import FrequencyResult

#: eta_f at which E_eta is read (first order: the relative error is of order PROBE).
PROBE = Fraction(1, 10**10)


@dataclass(frozen=True)
class DampingLimit:
    """Per real root (same order as ``roots``): d Im q / d eta_f at eta_f = 0+ (``slopes``)."""

    roots: tuple  # the real InducedFrequency objects of the eta_f = 0 result
    slopes: tuple  # d Im q / d eta_f at eta_f -> 0+, floats

    @property
    def destabilised(self) -> int:
        return sum(s < 0 for s in self.slopes)

    def statement(self) -> str:
        n = len(self.roots)
        if not self.destabilised:
            return (
                f"eta_f -> 0+: the {n} real root(s) move into Im q > 0 (d Im q / d eta_f from "
                f"{min(self.slopes):.3g} to {max(self.slopes):.3g}): stable for small eta_f > 0 as well"
            )
        return (
            f"eta_f -> 0+: {self.destabilised} of the {n} real root(s) move into Im q < 0 (growth rate "
            f"proportional to eta_f): UNSTABLE for small eta_f > 0"
        )

    def to_dict(self) -> dict:
        return {
            "roots": [r.re_text for r in self.roots],
            "d_im_q_d_eta_f": [float(s) for s in self.slopes],
            "destabilised": self.destabilised,
            "statement": self.statement(),
        }


def damping_limit(result: FrequencyResult) -> DampingLimit | None:
    """The eta_f -> 0+ fate of the real roots of an eta_f = 0 result (None when eta_f != 0 or none)."""
    bound = result.bound
    if bound.params.eta_f != 0:
        return None
    real = tuple(r for r in result.roots if r.marginal)
    if not real:
        return None
    undamped = Characteristic(bound)
    probe = Characteristic(bound.replace(eta_f=PROBE))
    slopes = []
    with mpmath.workdps(max(30, result.dps)):
        for r in real:
            q0 = mpmath.mpf(mpmath.re(r.q))
            _, E_q = undamped.value_and_derivative(q0)
            E_eta = probe(q0) / mpmath.mpf(PROBE.numerator) * PROBE.denominator
            slopes.append(float(mpmath.im(-E_eta / E_q)))
    return DampingLimit(real, tuple(slopes))
