"""The sweep characteristic for any vehicle (the batched block system of ``kernels/sweep_vehicle.py``).

References: the mpmath :class:`~moving_bogie.kernels.characteristic.Characteristic` (the block
system one point at a time, at 30 digits, with its own kernel K of ``kernels/track.py``); the closed form
of Eq. (38) for the paper's bogie (an independent derivation: ``derivations/system.py``), equal to -2
times the block determinant.
"""

import dataclasses
from pathlib import Path

import mpmath
import numpy as np
import pytest

from moving_bogie.kernels.bound import bind
from moving_bogie.kernels.characteristic import Characteristic
from moving_bogie.kernels.sweep_characteristic import SweepCharacteristic
from moving_bogie.model.cases import table1_case
from moving_bogie.model.files import load_params_file
from moving_bogie.stability.maps.column import settle_cells, stability_column

CAR = Path(__file__).resolve().parent.parent / "examples" / "car.toml"


@pytest.fixture(scope="module")
def car():
    return load_params_file(CAR)[0]


def _points(seed, n=5):
    rng = np.random.default_rng(seed)
    return rng.uniform(0.1, 2.0, n) + 1j * rng.uniform(-0.3, 0.3, n)


def test_car_block_sweep_equals_mpmath_characteristic(car):
    sweep = SweepCharacteristic(bind(car))
    assert sweep.blocks is not None
    q = _points(1)
    alpha = np.full(q.shape, float(car.as_float().alpha))
    E, E_q = sweep.e_and_dq(q, alpha)
    reference = Characteristic(bind(car))
    with mpmath.workdps(30):
        for k in range(len(q)):
            e, de = reference.value_and_derivative(mpmath.mpc(q[k]))
            assert abs(E[k] - complex(e)) <= 1e-9 * abs(complex(e))
            assert abs(E_q[k] - complex(de)) <= 1e-8 * abs(complex(de))


def test_car_polynomial_in_eta_M_is_exact(car):
    """The degree-8 interpolation in eta_M (generated degree) reproduces E_chr at other eta_M values."""
    sweep = SweepCharacteristic(bind(car), parameter="eta_M")
    assert sweep.degree == 8
    q = _points(2)
    alpha = np.full(q.shape, float(car.as_float().alpha))
    K, _, _ = sweep.kernel(q, alpha)
    scale = 40.0
    c = sweep.coefficients(q, K, scale=scale)
    nodal = np.max(np.abs([sweep.e_chr(q, K, t) for t in sweep.nodes(scale)]), axis=0)
    for theta in (3.7, 14.9, 31.0):
        direct = sweep.e_chr(q, K, theta)
        # rounding: eps times the condition of the degree-8 monomial Vandermonde on [0, 1] (~1e5) times the
        # largest value interpolated; a wrong degree would leave an O(1) relative error
        assert np.all(np.abs(np.polyval(c.T, theta / scale) - direct) <= 1e-10 * nodal)
    # the leading coefficient is that of a degree-8 polynomial, not rounding noise
    assert np.all(np.abs(c[:, 0]) > 1e-6 * np.max(np.abs(c), axis=-1))


@pytest.mark.parametrize("parameter", ["eta_M", "kappa_v", "eta_v"])
def test_block_path_matches_closed_form_for_the_bogie(parameter):
    params = table1_case(1)
    closed = SweepCharacteristic(bind(params), parameter)
    block = SweepCharacteristic(bind(params), parameter, block=True)
    assert closed.blocks is None and block.blocks is not None
    q = _points(3)
    alpha = np.full(q.shape, float(params.as_float().alpha))
    theta = np.full(q.shape, 0.7 * float(getattr(params.as_float(), parameter)))
    ours = block.derivatives(q, alpha, theta)
    theirs = closed.derivatives(q, alpha, theta)
    for a, b in zip(ours, theirs):  # E, E_q, E_alpha, E_theta: the block determinant is -E_chr(38) / 2
        assert np.allclose(-2 * a, b, rtol=1e-8, atol=0)


@pytest.mark.slow
def test_car_stability_column_agrees_with_induced_frequencies(car):
    """Map cells of the car (a stable one and one with two unstable frequencies, found by a coarse scan of
    the default map) against the full argument-principle count of induced_frequencies at those points."""
    thetas = np.array([10.0, 40.0])
    col = stability_column(SweepCharacteristic(bind(car), parameter="eta_M"), 1.137, thetas)
    assert not col.uncertain.any()
    forced = dataclasses.replace(col, uncertain=np.array([True, True]))
    settled = settle_cells(bind(car.replace(vehicle="car")), "eta_M", forced)
    assert settled.settled.all() and not settled.uncertain.any()
    np.testing.assert_array_equal(settled.count, col.count)
    assert col.count.tolist() == [0, 2]  # a cell of each kind, so that the comparison can fail
