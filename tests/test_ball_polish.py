"""The polish and the residues in Arb's balls against the mpmath path they replace where asked.

References: :class:`moving_bogie.kernels.characteristic.Characteristic` (E_chr and dE_chr/dq at the mpmath
precision, dK/dq by double-pole residues) for :class:`~moving_bogie.roots.ball_polish.BallPrecise`,
and :func:`moving_bogie.response.residues.residue_expansion` on its mpmath path (Cramer's rule and Jacobi's
formula on the condensed system) for :func:`~moving_bogie.response.ball_residues.ball_amplitudes`.
"""

from __future__ import annotations

import mpmath
import numpy as np
import pytest

from moving_bogie.kernels.bound import bind
from moving_bogie.kernels.characteristic import Characteristic
from moving_bogie.model.cases import table1_case
from moving_bogie.response.residues import residue_expansion
from moving_bogie.roots.ball_polish import BallPrecise, acb_from_mpc, mpc_from_acb
from moving_bogie.roots.count.contour import Rectangle
from moving_bogie.roots.frequencies import induced_frequencies
from moving_bogie.roots.refine.polish import polish_and_confirm


def test_mpmath_numbers_pass_to_balls_and_back_exactly():
    with mpmath.workdps(60):
        z = mpmath.mpc(1, -2) / 3
        ball = acb_from_mpc(z)
        assert ball.rad() == 0
        assert mpc_from_acb(ball) == z


# the fast subset polishes a damped unstable case and an undamped one, the full suite two more
@pytest.mark.parametrize(
    "case", [1, 2, pytest.param(5, marks=pytest.mark.slow), pytest.param(7, marks=pytest.mark.slow)]
)
def test_ball_polish_finds_the_mpmath_roots(case, table1_search):
    """The same windows, counts and roots (to the confirmed decimals of both) with the polish in balls; the
    undamped case 2 has real roots, where the balls cannot decide the side of p-roots on the real axis and
    the mpmath path answers."""
    bound = bind(table1_case(case))
    plain = table1_search(case)  # induced_frequencies(bound, dps=30)
    balls = induced_frequencies(bound, dps=30, balls=True)
    assert balls.count == plain.count and balls.count_ok == plain.count_ok
    assert len(balls.roots) == len(plain.roots)
    for a, b in zip(plain.roots, balls.roots):
        decimals = min(a.decimals, b.decimals)
        assert decimals >= 28
        assert abs(a.q - b.q) <= mpmath.mpf(10) ** (-decimals)
        assert a.side == b.side and a.multiplicity == b.multiplicity


def test_ball_polish_agrees_with_mpmath_step_by_step():
    """E / E' from the balls equals the mpmath step to the working precision, at a root and off it (E itself
    may differ by a constant factor: the balls take the bogie's closed form of Eq. (38), the mpmath path
    the determinant of its block system, -1/2 times it)."""
    bound = bind(table1_case(5))
    precise = Characteristic(bound)
    balls = BallPrecise(bound, precise)
    factors = []
    with mpmath.workdps(30):
        root = polish_and_confirm(precise, 0.1747 + 0.0075j, dps=30, extra_dps=15).q
        for q in (root, root + mpmath.mpc("1e-6", "-3e-7"), mpmath.mpc("0.3", "0.05")):
            E, dE = precise.value_and_derivative(q)
            Eb, dEb = balls.value_and_derivative(q)
            assert abs(E / dE - Eb / dEb) <= mpmath.mpf(10) ** -29 * max(1, abs(q))
            factors.append(dEb / dE)
        assert all(abs(f - factors[0]) <= mpmath.mpf(10) ** -25 for f in factors)
    assert balls.fallbacks == 0 and balls.ball_evaluations == 3


@pytest.mark.parametrize("case", [1, 7])
def test_ball_residues_equal_the_mpmath_residues(case):
    bound = bind(table1_case(case))
    result = induced_frequencies(bound, dps=30, check_window=False)
    plain = residue_expansion(bound, result, shapes=False)
    balls = residue_expansion(bound, result, shapes=False, balls=True)
    np.testing.assert_array_equal(plain.q, balls.q)
    for name in plain.names:
        a, b = plain.amplitudes[name], balls.amplitudes[name]
        assert np.all(np.abs(a - b) <= 1e-20 + 1e-14 * np.abs(a)), name
        assert plain.steady[name] == balls.steady[name]


def test_ball_residues_of_the_timoshenko_rayleigh_sequence():
    """Roots along the real axis (Re q in [24, 48], 15 digits as the sequence has them): the amplitudes
    proven to 15 digits in balls; the mpmath path at 15 digits loses some to the near-singular system, so
    the two agree to 1e-9 relative, far below what the residue sum needs (amplitudes ~1e-8)."""
    bound = bind(table1_case(7).replace(beam="tr", S=10, r="0.09"))
    strip = Rectangle(24.0, 48.0, -1.0, 1.0)
    result = induced_frequencies(bound, dps=15, window=strip, check_window=False, balls=True)
    assert result.count_ok and result.roots
    plain = residue_expansion(bound, result, shapes=False)
    balls = residue_expansion(bound, result, shapes=False, balls=True)
    for name in plain.names:
        a, b = plain.amplitudes[name], balls.amplitudes[name]
        assert np.all(np.abs(a - b) <= 1e-9 * np.abs(a)), name
