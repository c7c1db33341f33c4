"""Ball-arithmetic E_chr for a vehicle without a closed form (the car: the block system over Taylor series).

Reference: the mpmath :class:`~moving_bogie.kernels.characteristic.Characteristic` at 40 digits (the block
determinant by LU at one point, dE/dq by Jacobi's formula, K by double-pole residues): the balls must
contain its values, and be narrow.
"""

from pathlib import Path

import mpmath
import pytest
from flint import acb

from moving_bogie.kernels.bound import bind
from moving_bogie.kernels.characteristic import Characteristic
from moving_bogie.model.files import load_params_file
from moving_bogie.roots.proof.balls import BallCharacteristic, square_ball

CAR = Path(__file__).resolve().parent.parent / "examples" / "car.toml"


@pytest.mark.parametrize("q", [0.7 + 0.3j, 1.3 - 0.2j, 0.05 + 0.4j])
def test_car_balls_contain_the_mpmath_characteristic(q):
    car = load_params_file(CAR)[0]
    E, dE = BallCharacteristic(bind(car)).value_and_derivative(q)
    with mpmath.workdps(40):
        e, de = Characteristic(bind(car)).value_and_derivative(mpmath.mpc(q))
    for ball, value in ((E, e), (dE, de)):
        exact = acb(mpmath.nstr(value.real, 35), mpmath.nstr(value.imag, 35))
        assert ball.overlaps(exact)
        assert ball.rad() < 1e-20 * abs(complex(value))


def test_car_ball_over_a_q_ball_contains_its_points():
    car = load_params_file(CAR)[0]
    E = BallCharacteristic(bind(car)).value(square_ball(0.9 + 0.1j, 1e-6))
    with mpmath.workdps(40):
        for z in (0.9 + 0.1j, 0.9 + 1e-6 + (0.1 - 1e-6) * 1j):
            value = Characteristic(bind(car))(mpmath.mpc(z))
            assert E.overlaps(acb(mpmath.nstr(value.real, 35), mpmath.nstr(value.imag, 35)))
