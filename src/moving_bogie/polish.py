"""Polishing an induced frequency at high precision and confirming its digits (the precision ladder).

Newton's method on E_chr with the analytic derivative of Eq. (40) (dK/dq by double-pole residues);
for a root of multiplicity m the step is m E/E'. Digits are confirmed by repeating the polish at a
higher precision and comparing: only the digits that agree are reported.
"""

from __future__ import annotations

from dataclasses import dataclass

import mpmath

from .errors import MovingBogieError


class PolishError(MovingBogieError):
    """Newton's method did not converge from the located cell."""


def newton(characteristic, q0, *, multiplicity=1, max_iter=60):
    """Root of E_chr near ``q0`` at the current precision; returns (q, |last step|)."""
    q = mpmath.mpc(q0)
    tol = mpmath.mpf(10) ** (-mpmath.mp.dps + 3)
    step = mpmath.inf
    for _ in range(max_iter):
        E, dE = characteristic.value_and_derivative(q)
        if dE == 0:
            raise PolishError(f"E_chr'(q) = 0 at q = {mpmath.nstr(q, 8)}")
        step = multiplicity * E / dE
        q -= step
        if abs(step) <= tol * max(1, abs(q)):
            return q, abs(step)
    raise PolishError(
        f"Newton did not converge near q = {mpmath.nstr(q0, 8)} (last step {mpmath.nstr(step, 3)})"
    )


@dataclass(frozen=True)
class Confirmed:
    q: mpmath.mpc
    step: mpmath.mpf  # |E/E'| at the root: distance to the exact root at working precision
    error: mpmath.mpf  # |q(dps) - q(dps + extra)|
    decimals: int  # decimal places that agree between the two precisions
    digits: int  # significant digits of q that agree


def polish_and_confirm(characteristic, q0, *, dps, extra_dps, multiplicity=1) -> Confirmed:
    """Polish at ``dps`` digits, re-polish at ``dps + extra_dps`` and compare."""
    with mpmath.workdps(dps):
        q, step = newton(characteristic, q0, multiplicity=multiplicity)
    with mpmath.workdps(dps + extra_dps):
        q_hi, _ = newton(characteristic, q, multiplicity=multiplicity)
        err = abs(q_hi - q)
        if err == 0:
            decimals = dps
        else:
            decimals = int(mpmath.floor(-mpmath.log10(2 * err)))
        mag = abs(q)
        lead = int(mpmath.floor(mpmath.log10(mag))) + 1 if mag > 0 else 0
        decimals = max(0, min(decimals, dps - lead))
        digits = max(0, min(dps, decimals + lead))
    return Confirmed(q, step, err, decimals, digits)
