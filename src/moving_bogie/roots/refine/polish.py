"""Polishing an induced frequency at high precision and confirming its digits (the precision ladder).

Newton's method on E_chr with the analytic derivative of Eq. (40) (dK/dq by double-pole residues);
for a root of multiplicity m the step is m E/E'. Digits are confirmed by repeating the polish at a
higher precision and comparing: only the digits that agree are reported.
"""

from __future__ import annotations

import decimal
import math
from dataclasses import dataclass
from typing import Any, Protocol

import mpmath

from moving_bogie.errors import MovingBogieError
from moving_bogie.roots.count.contour import Region
from moving_bogie.typing import Mpc, Mpf


class PreciseCharacteristic(Protocol):
    """E_chr and dE_chr/dq (Eqs. (38), (40)) at the current mpmath precision
    (:class:`~moving_bogie.kernels.characteristic.Characteristic`,
    :class:`~moving_bogie.roots.ball_polish.BallPrecise`)."""

    params: Any  # the dimensionless parameters

    @property
    def evaluations(self) -> int: ...

    def value_and_derivative(self, q: Mpc) -> tuple[Mpc, Mpc]: ...


class PolishError(MovingBogieError):
    """Newton's method did not converge from the located cell."""


def newton(
    characteristic: PreciseCharacteristic, q0: Mpc | complex, *, multiplicity: int = 1, max_iter: int = 60
) -> tuple[Mpc, Mpf]:
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


def fixed_text(x: Mpf | float | str, decimals: int) -> str:
    """``x`` rounded to ``decimals`` places in fixed-point notation (no exponent, no negative zero)."""
    ctx = decimal.Context(prec=decimals + 40, rounding=decimal.ROUND_HALF_EVEN)
    with mpmath.workdps(max(mpmath.mp.dps, decimals + 20)):
        text = mpmath.nstr(mpmath.mpf(x), decimals + 30, min_fixed=-math.inf, max_fixed=math.inf)
    value = ctx.create_decimal(text).quantize(decimal.Decimal(1).scaleb(-decimals), context=ctx)
    if value == 0:
        value = abs(value)
    return f"{value:.{decimals}f}"


@dataclass(frozen=True)
class Confirmed:
    q: Mpc  # the value polished at the higher precision
    step: Mpf  # |E/E'| at the root: distance to the exact root at working precision
    error: Mpf  # |q(dps) - q(dps + extra)|
    decimals: int  # decimal places on which both precisions round identically (Re and Im)
    digits: int  # significant digits of q so confirmed


def polish_and_confirm(
    characteristic: PreciseCharacteristic,
    q0: Mpc | complex,
    *,
    dps: int,
    extra_dps: int,
    multiplicity: int = 1,
    confirming: PreciseCharacteristic | None = None,
) -> Confirmed:
    """Polish at ``dps`` digits, re-polish at ``dps + extra_dps`` and keep the digits both agree on.

    The reported value is the higher-precision one; ``decimals`` is the largest number of decimal places at
    which the two values, rounded, print the same real and imaginary parts (so every printed digit has been
    recomputed at higher precision and confirmed).

    When Newton stalls at ``dps`` digits (roots closer together than that precision resolves: two identical
    bogies that interact only through the rail give pairs 1e-13 apart), the polish is repeated at twice
    and four times ``dps``; the digits are still confirmed one ``extra_dps`` step higher.

    ``confirming``: the evaluation of E_chr and dE_chr/dq for the higher precision (default
    ``characteristic``), e.g. :class:`~moving_bogie.roots.ball_polish.BallPrecise`, whose error is
    bounded: the recomputation then also comes from another arithmetic.
    """
    work = dps
    while True:
        try:
            with mpmath.workdps(work):
                q, step = newton(characteristic, q0, multiplicity=multiplicity)
            break
        except PolishError:
            if work >= 4 * dps:
                raise
            work *= 2
    with mpmath.workdps(work + extra_dps):
        q_hi = confirming_step(confirming or characteristic, q, work, multiplicity)
        err = abs(q_hi - q)
        mag = abs(q_hi)
        lead = int(mpmath.floor(mpmath.log10(mag))) + 1 if mag > 0 else 0
        decimals = dps - max(lead, 0)
        if err > 0:
            decimals = min(decimals, int(mpmath.floor(-mpmath.log10(err))))
        decimals = max(0, decimals)
        while decimals > 0 and not _same_rounding(q, q_hi, decimals):
            decimals -= 1
        digits = max(0, min(dps, decimals + lead))
    return Confirmed(q_hi, step, err, decimals, digits)


def confirming_step(characteristic: PreciseCharacteristic, q: Mpc, work: int, multiplicity: int = 1) -> Mpc:
    """The root near ``q`` (converged at ``work`` digits) recomputed at the current, higher precision.

    Newton's method converges quadratically at a simple root: when the first step at the higher precision
    is below 10^-(work - 3) |q| (``q`` is a root to the lower precision), the error after it is of the order
    of that step squared times |E''/E'| (about the inverse distance to the nearest other root: 1e13 for the
    closest pairs seen), many digits below the last one of ``work`` that the comparison confirms, so one
    evaluation recomputes the root. Otherwise (or for a multiple root, where the convergence is linear)
    Newton runs to convergence at the higher precision.
    """
    q = mpmath.mpc(q)
    if multiplicity == 1:
        E, dE = characteristic.value_and_derivative(q)
        if dE != 0:
            step = E / dE
            if abs(step) <= mpmath.mpf(10) ** (3 - work) * max(1, abs(q)):
                return q - step
            q -= step
    return newton(characteristic, q, multiplicity=multiplicity)[0]


def _same_rounding(a: Mpc, b: Mpc, decimals: int) -> bool:
    return fixed_text(mpmath.re(a), decimals) == fixed_text(mpmath.re(b), decimals) and fixed_text(
        mpmath.im(a), decimals
    ) == fixed_text(mpmath.im(b), decimals)


def split_cluster(
    characteristic: PreciseCharacteristic,
    q0: Mpc | complex,
    multiplicity: int,
    rect: Region,
    *,
    dps: int,
    extra_dps: int,
    confirming: PreciseCharacteristic | None = None,
) -> list[tuple[Confirmed, int]]:
    """The simple roots of a cluster that the cells could not separate (size below 1e-10), or [].

    Two identical bogies that interact only through the rail give pairs closer than that. Plain Newton at
    twice ``dps`` from points around the cluster's centre reaches its members; when exactly
    ``multiplicity`` distinct roots inside ``rect`` are reached, each is polished and confirmed as a simple
    root (:func:`polish_and_confirm`, ``confirming`` as there); otherwise nothing is returned and the
    cluster stays unresolved.
    """
    found: list[Mpc] = []
    with mpmath.workdps(2 * dps):
        q0 = mpmath.mpc(q0)
        size = max(rect.width, rect.height)
        for k in range(4 * multiplicity):
            start = q0 + size * mpmath.expjpi(mpmath.mpf(k) / (2 * multiplicity))
            try:
                q, _ = newton(characteristic, start)
            except PolishError:
                continue
            close = mpmath.mpf(10) ** (-dps) * max(1, abs(q))
            if rect.contains(complex(q)) and all(abs(q - other) > close for other in found):
                found.append(q)
    if len(found) != multiplicity:
        return []
    out = []
    for q in found:
        try:
            confirmed = polish_and_confirm(
                characteristic, q, dps=dps, extra_dps=extra_dps, confirming=confirming
            )
            out.append((confirmed, 1))
        except PolishError:
            return []
    return out
