"""A sweep in SI units over speed and wheel mass on the two-layer track: whole columns of wheel masses.

In SI units the bogie frame's M_b and J_b stay fixed while the wheel mass M varies, so mu_v and J_b do not
follow eta_M (Eq. (63) does not apply). E_chr is still a polynomial in eta_M at fixed (q, alpha), of the
degree of the generated ``FIXED_POLYNOMIAL_DEGREES`` (2 for the bogie: its two wheel masses), so the sweep
counts a whole column of wheel masses at once from one evaluation of the track kernel per contour point.

References: E_chr of the exact point (the block determinant of ``CharacteristicArray`` with the point's
own parameters, -2 times the closed form of Eq. (38) for the bogie); the per-point path of the sweep
before the columns (each point a column of one value, mu_v and J_b following eta_M at that point's own
cf1, cf2, so that they equal the file's); and ``induced_frequencies`` of the point (the full search over
its far-field window) at random points of the grid.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from moving_bogie.api import induced_frequencies
from moving_bogie.errors import ParameterError
from moving_bogie.kernels.bound import bind
from moving_bogie.kernels.characteristic import CharacteristicArray
from moving_bogie.kernels.sweep_characteristic import SweepCharacteristic, polynomial_degree
from moving_bogie.model.files import load_params_file
from moving_bogie.stability.maps.column import at_theta
from moving_bogie.sweep import make_spec
from moving_bogie.sweep.engine import block_task
from moving_bogie.sweep.evaluate import evaluate_block

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "two-layer.toml"
HELD = ("J_b", "mu_v")
# speeds and wheel masses where the bogie on the example track is stable at some points, unstable at others
# (found by the sweep, confirmed below by the full counts)
GRID = {"v": "400:900:6", "M": "3000:30000:5"}
Q = np.array([0.3 - 0.2j, 1.1 - 0.05j, 2.4 - 0.6j, 0.05 - 1.3j, 0.7 + 0.0j])


@pytest.fixture(scope="module")
def spec():
    params, physical = load_params_file(EXAMPLE)
    return make_spec(params, GRID, physical=physical, check=0, bar="fixed")


def _grid(spec, task_changes) -> dict:
    out = {k: np.zeros(spec.shape) for k in ("n_unstable", "degree_of_instability", "certain", "settled")}
    for b in spec.blocks():
        res = evaluate_block(replace(block_task(spec, b), **task_changes))
        for k in out:
            out[k][b.slices] = res[k]
    return out


@pytest.fixture(scope="module")
def columns(spec):
    return _grid(spec, {})


def test_the_wheel_mass_is_a_column_with_the_frame_held(spec):
    assert spec.column_parameter == "eta_M" and spec.held == HELD
    assert spec.chunks == (6, 5)  # one block: the whole column of M, the run of v
    params = spec.params
    assert polynomial_degree(bind(params), "eta_M", HELD) == 2  # the two wheel masses
    assert polynomial_degree(bind(params), "eta_M") == 4  # mu_v, J_b following eta_M (Table 1)
    with pytest.raises(ParameterError, match="eta_M"):  # one held, the other following: no polynomial
        polynomial_degree(bind(params), "eta_M", ("mu_v",))


def test_held_interpolation_is_e_chr_of_the_point(spec):
    """Degree-2 interpolation in eta_M (mu_v, J_b fixed) against the block determinant at each point."""
    params = spec.params.replace(**spec.fixed)
    alpha = float(spec.axes[0].values[3])
    sweep = SweepCharacteristic(bind(params), "eta_M", held=HELD)
    assert sweep.degree == 2 and not sweep.followers
    K, _, _ = sweep.kernel(Q, alpha)
    thetas = spec.axes[1].values
    scale = float(max(thetas))
    c = sweep.coefficients(Q, K, scale=scale)
    for theta in thetas:
        point = at_theta(bind(params.replace(alpha=spec.axes[0].values[3])), "eta_M", theta, HELD)
        assert point.params.mu_v == params.mu_v and point.params.J_b == params.J_b
        ref = -2 * CharacteristicArray(point)(Q)
        interp = np.array([np.polyval(c[k], float(theta) / scale) for k in range(len(Q))])
        assert np.all(np.abs(interp - ref) <= 1e-9 * np.abs(ref))


# slow: every point of the grid twice; the fast subset checks the column's polynomial in eta_M against
# E_chr of each point (test_held_interpolation_is_e_chr_of_the_point)
@pytest.mark.slow
def test_columns_equal_the_per_point_path(spec, columns):
    """Every point of the grid: the column of wheel masses gives the verdict of the per-point path."""
    points = _grid(spec, {"column": None, "held": ()})
    assert columns["certain"].all() and points["certain"].all()
    np.testing.assert_array_equal(columns["n_unstable"], points["n_unstable"])
    np.testing.assert_allclose(columns["degree_of_instability"], points["degree_of_instability"], atol=1e-8)
    assert 0 < (columns["n_unstable"] > 0).sum() < columns["n_unstable"].size  # both kinds of point


@pytest.mark.slow
def test_random_points_agree_with_the_full_search(spec, columns):
    """Two unstable and two stable points drawn at random: the count of ``induced_frequencies`` (the full
    search over the far-field window) and its lowest Im q."""
    rng = np.random.default_rng(24)
    n = columns["n_unstable"]
    drawn = []
    for kind in (n > 0, n == 0):
        cells = np.argwhere(kind)
        drawn += [tuple(cells[k]) for k in rng.choice(len(cells), size=2, replace=False)]
    for i, j in drawn:
        point = spec.params.replace(
            **(spec.fixed | {"alpha": spec.axes[0].values[i], "eta_M": spec.axes[1].values[j]})
        )
        ref = induced_frequencies(point, dps=15)
        assert ref.count_ok and ref.verdict.determined
        unstable = [complex(r.q) for r in ref.unstable_roots]
        assert n[i, j] == len(unstable), (i, j)
        lowest = min([0.0, *(q.imag for q in unstable)])
        assert columns["degree_of_instability"][i, j] == pytest.approx(lowest, abs=1e-8)
