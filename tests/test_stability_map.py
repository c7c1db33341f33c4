"""Stability maps: no uncertain cells where the column count used to alias, full-count settling, hatching.

Reference: ``induced_frequencies`` (argument principle over the default window, roots confirmed in mpmath).
"""

from __future__ import annotations

import dataclasses
from fractions import Fraction

import numpy as np
import pytest

from moving_bogie.api import induced_frequencies
from moving_bogie.kernels.bound import bind
from moving_bogie.kernels.sweep_characteristic import SweepCharacteristic
from moving_bogie.model.cases import table1_case
from moving_bogie.stability.figures.plots import plot_stability_map
from moving_bogie.stability.maps.column import exact, settle_cells, stability_column
from moving_bogie.stability.maps.map import StabilityMap


def test_two_roots_next_to_the_axis_are_not_counted_unstable():
    """Case 7, alpha = 0.1, eta_M = 170.5: two stable roots 6e-4 apart, 6e-4 above the real axis, turn the
    phase of E by about 2 pi between two samples of the axis; a phase test alone counted one unstable
    pair there (4044 uncertain cells in the 400 x 400 map). The log|E| bend test refines it."""
    p = table1_case(7)
    thetas = np.array([150.5, 170.5, 190.5])
    col = stability_column(SweepCharacteristic(bind(p), "eta_M"), 0.1, thetas)
    assert not col.uncertain.any()
    for j, theta in enumerate(thetas):
        ref = induced_frequencies(p.replace(alpha=exact(0.1), eta_M=exact(theta)), dps=20)
        assert ref.count_ok and col.count[j] == len(ref.unstable_roots) == 0


def test_a_pair_aliased_inside_a_halved_segment_is_resolved():
    """Case 1 with eta_f = 0.02 at alpha = 0.3 + 0.8 * 47/99: two stable roots 1.4e-3 apart at 1.4e-4 and
    3.3e-4 above the axis sat in one half of a refined segment whose midpoint bend cancelled; the half's
    phase step aliased to -0.92 rad and one spurious unstable pair was counted. The change of log|E| across
    the half (1.9) now refines it."""
    p = table1_case(1).replace(eta_f=Fraction("0.02"))
    alpha = Fraction(3, 10) + Fraction(8, 10) * 47 / 99
    thetas = [1 + Fraction(199) * k / 999 for k in (691, 726, 803)]
    col = stability_column(
        SweepCharacteristic(bind(p), "eta_M"), float(alpha), np.array([float(t) for t in thetas])
    )
    assert not col.uncertain.any()
    for j, theta in enumerate(thetas):
        ref = induced_frequencies(p.replace(alpha=alpha, eta_M=theta), dps=20)
        assert ref.count_ok and col.count[j] == len(ref.unstable_roots) == 0


def test_settling_by_a_full_count_agrees_with_the_column_count():
    p = table1_case(1)
    thetas = np.array([10.0, 40.0, 90.0, 160.0])
    col = stability_column(SweepCharacteristic(bind(p), "eta_M"), 0.95, thetas)
    assert not col.uncertain.any() and col.count.max() > 0
    forced = dataclasses.replace(col, uncertain=np.array([True, False, True, True]))
    settled = settle_cells(bind(p), "eta_M", forced)
    assert settled.settled.tolist() == [True, False, True, True] and not settled.uncertain.any()
    np.testing.assert_array_equal(settled.count, col.count)
    np.testing.assert_allclose(settled.degree, col.degree, atol=1e-9)


def test_uncertain_cells_are_listed_and_hatched():
    alphas, thetas = np.array([0.5, 0.6, 0.7]), np.array([10.0, 20.0])
    uncertain = np.array([[False, True, False], [False, False, False]])
    smap = StabilityMap(
        table1_case(1), "bogie", "eta_M", alphas, thetas, np.zeros((2, 3)), np.zeros((2, 3), int), uncertain
    )
    summary = smap.summary()
    assert summary["uncertain_cells"] == 1 and summary["uncertain"] == [{"alpha": 0.6, "eta_M": 10.0}]
    fig = plot_stability_map(smap)
    ax = fig.axes[0]
    assert "1 uncertain" in ax.get_title()
    assert [c.get_hatch() for c in ax.collections if c.get_hatch()] == ["////"]


@pytest.mark.slow
@pytest.mark.parametrize("n", [6])
def test_stability_map_store_matches_the_arrays(n, tmp_path, capsys):
    from moving_bogie.cli import main
    from moving_bogie.sweep import open_sweep

    out, npz = tmp_path / "m.zarr", tmp_path / "m.npz"
    args = ["stability-map", "--case", "1", "--n", str(n), "--workers", "1", "--alpha-min", "0.7"]
    assert main([*args, "--out", str(out), "--npz", str(npz)]) == 0
    assert main([*args, "--out", str(out)]) == 2  # exists: refused before computing
    assert "--out" in capsys.readouterr().err
    ds = open_sweep(out).compute()
    arrays = np.load(npz)
    np.testing.assert_array_equal(ds.n_unstable.values.T, arrays["count"])
    np.testing.assert_array_equal(ds.degree_of_instability.values.T, arrays["degree"])
