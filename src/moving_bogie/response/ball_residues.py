"""Residue amplitudes n_X(q_j) / (q_j E_chr'(q_j)) of Eqs. (36), (40)-(43) in Arb's ball arithmetic.

With A the block system of :mod:`moving_bogie.kernels.coupling` and b its right-hand side, n_X = E_chr x_X
(Cramer's rule, x = A^-1 b) and E_chr' = E_chr tr(A^-1 dA/dq) (Jacobi's formula, Eq. (40)), so

    n_X / (q E_chr') = x_X / (q tr(A^-1 dA/dq)),

the determinant cancelling. A, dA/dq and b come from the vehicle's generated matrices and the kernel values
K(xi_i - xi_j) (with dK/dq) as balls (:mod:`moving_bogie.roots.proof.balls`,
:mod:`moving_bogie.roots.proof.ball_block`), the solves from Arb's ``acb_mat`` (C code). Each amplitude is
a ball that encloses the exact value at the given q; it is returned (as its midpoint) only when its radius
is below the requested relative accuracy, else None, and the caller takes the mpmath path
(:func:`moving_bogie.response.residues.residue_expansion`) for that root.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from fractions import Fraction

import mpmath
from flint import acb, acb_series, arb, ctx

from moving_bogie.kernels.bound import BoundModel
from moving_bogie.kernels.coupling import coupled_system, dynamic_stiffness, kernel_matrix
from moving_bogie.roots.ball_polish import acb_from_mpc, balls_apply, mpc_from_acb
from moving_bogie.roots.proof.ball_block import BlockBalls, coefficient
from moving_bogie.roots.proof.balls import BallCharacteristic, Undecided, exact_ball
from moving_bogie.typing import Acb, Mpc

__all__ = ["ball_amplitudes"]

#: Bits carried beyond the precision of the roots.
GUARD_BITS = 32


def _block_characteristic(bound: BoundModel, prec: int) -> tuple[BallCharacteristic, list[Acb]]:
    """The ball characteristic on the vehicle's block system (its kernel values at the offsets of the block
    system, whatever closed form the vehicle also has) and the static loads s_j as balls."""
    chi = BallCharacteristic(bound, prec=prec)
    module = bound.vehicle
    with ctx.workprec(prec):
        params = bound.params
        values = {name: exact_ball(getattr(params, name)) for name in module.MATRIX_ARGUMENTS}
        exact = {name: _fraction(getattr(params, name)) for name in module.MATRIX_ARGUMENTS}
        if chi.blocks is None:
            chi.blocks = BlockBalls(module, values, exact)
        loads = [acb(s) for s in module.static_loads(**values)]
    return chi, loads


def _fraction(x: Fraction | int | None) -> Fraction | None:
    return None if x is None else Fraction(x)


def ball_amplitudes(
    bound: BoundModel, qs: Sequence[Mpc], names: Sequence[str], dps: int
) -> list[dict[str, Mpc] | None]:
    """Per root q (mpmath), the amplitudes n_X(q) / (q E_chr'(q)) by response name, each to ``dps`` digits
    relative (the ball's radius below 10^-dps of its size, rounded at ``dps`` digits), or None for a root
    where the balls do not reach that (the caller's mpmath path then; for every root of a model the balls do
    not evaluate, :func:`~moving_bogie.roots.ball_polish.balls_apply`).

    At a root A is singular to about the root's accuracy (10^-dps relative), so x and tr(A^-1 dA/dq) lose
    about dps digits to cancellation that their ratio recovers: the balls are evaluated at twice the bits
    of ``dps`` digits plus :data:`GUARD_BITS`, and at twice that again for a root still too wide.
    """
    tolerance = arb(10) ** -dps
    first = 2 * int(dps * math.log2(10)) + GUARD_BITS
    out: list[dict[str, Mpc] | None] = [None] * len(qs)
    for bits in (first, 2 * first) if balls_apply(bound) else ():
        wanted = [k for k, found in enumerate(out) if found is None]
        if not wanted:
            break
        chi, loads = _block_characteristic(bound, bits)
        blocks = chi.blocks
        assert blocks is not None  # set by _block_characteristic
        with ctx.workprec(bits):
            for k in wanted:
                try:
                    amps = _amplitudes_at(chi, blocks, loads, acb_from_mpc(qs[k]))
                except (Undecided, ZeroDivisionError):
                    continue
                if all(a.rad() <= tolerance * abs(a).lower() for a in amps):
                    with mpmath.workdps(dps):
                        out[k] = {name: mpc_from_acb(a) for name, a in zip(names, amps)}
    return out


def _amplitudes_at(chi: BallCharacteristic, blocks: BlockBalls, loads: list[Acb], q: Acb) -> list[Acb]:
    """x_X / (q tr(A^-1 dA/dq)) for every DOF X at the point q (module docstring), as balls."""
    K = chi.kernel_series(q, 1)
    qs = acb_series([q, 1], prec=2)
    A0, A1 = blocks.coefficient_matrices(qs, K, 2)
    trace = A0.solve(A1).trace()
    ops = blocks.arb
    D0, _ = dynamic_stiffness(q, blocks.mats, ops)
    K0 = kernel_matrix([coefficient(k, 0) for k in K], blocks.index, ops)
    b = coupled_system(D0, K0, ops, loads=loads).b
    assert b is not None  # loads given
    x = A0.solve(b)
    scale = q * trace
    return [x[k, 0] / scale for k in range(x.nrows())]
