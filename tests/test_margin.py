"""The stability margin of maps and sweeps: the smallest Im q of the induced frequencies, earned.

References: every margin is compared with the smallest Im q of the roots that
:func:`~moving_bogie.roots.frequencies.induced_frequencies` (the full count over the far-field window,
roots confirmed in mpmath) locates at the same exact point.
"""

from __future__ import annotations

import json
import warnings

import numpy as np
import pytest

from moving_bogie import induced_frequencies, load_parameters, stability_map
from moving_bogie.kernels.bound import bind
from moving_bogie.kernels.sweep_characteristic import SweepCharacteristic
from moving_bogie.stability.maps.column import at_theta, column_window, exact
from moving_bogie.stability.maps.column_margin import column_margin

EXAMPLES = __import__("pathlib").Path(__file__).resolve().parents[1] / "examples"


def smallest_im(params) -> float:
    """The reference: the smallest Im q of the roots the full count locates."""
    res = induced_frequencies(params, dps=15)
    assert res.count_ok and res.verdict.determined
    return min(float(r.q.imag) for r in res.roots)


@pytest.fixture(scope="module")
def uic60():
    return load_parameters(EXAMPLES / "uic60-bogie.toml")


def test_map_margin_is_the_smallest_decay_rate(uic60):
    params, _ = uic60
    alphas, thetas = np.array([0.1, 0.5]), np.array([5.0, 30.0])
    smap = stability_map(params, alphas=alphas, thetas=thetas, workers=1)
    assert not smap.uncertain.any() and not (smap.count > 0).any()
    assert not smap.margin_bound.any()
    for j, i in [(0, 0), (1, 1)]:
        ref = smallest_im(params.replace(alpha=exact(alphas[i]), eta_M=exact(thetas[j])))
        assert smap.margin[j, i] == pytest.approx(ref, rel=1e-9)


def test_cells_measured_together_are_each_cell_measured_alone(uic60):
    """The stable cells of a column are polished and their circles counted in shared evaluations: four
    wheel masses in one column against a column of each mass alone (the same roots, to the polish)."""
    params, _ = uic60
    thetas = np.array([5.0, 15.0, 30.0, 60.0])
    together = stability_map(params, alphas=[0.3], thetas=thetas, workers=1)
    assert not together.uncertain.any() and not together.margin_bound.any()
    for j, theta in enumerate(thetas):
        alone = stability_map(params, alphas=[0.3], thetas=[theta], workers=1)
        assert not alone.margin_bound[0, 0]
        assert together.margin[j, 0] == pytest.approx(alone.margin[0, 0], rel=1e-10)


def test_unstable_cells_keep_their_degree_as_margin():
    from moving_bogie import table1_case

    smap = stability_map(table1_case(1), alphas=[0.9], thetas=[50.0], workers=1)
    assert smap.count[0, 0] > 0
    assert smap.margin[0, 0] == smap.degree[0, 0] < 0


def test_a_top_below_every_root_gives_a_lower_bound(uic60):
    """No root below h: the margin is h, flagged as a bound; the true smallest Im q lies above it."""
    params, _ = uic60
    sweep = SweepCharacteristic(bind(params), "eta_M")
    alpha, thetas = float(params.alpha), np.array([float(params.eta_M)])
    scale = float(thetas.max())

    def coeffs(z):
        K, dK, _ = sweep.kernel(z, alpha, derivative=True)
        return sweep.coefficients(z, K, scale=scale, dK=dK)

    X, Y, _ = column_window(bind(params), "eta_M", thetas)
    h = 1e-3
    found = column_margin(sweep, alpha, thetas, coeffs, (X, Y), h, np.array([0]))
    assert found.bound[0] and found.margin[0] <= h
    assert smallest_im(params) > h
    unknown = column_margin(sweep, alpha, thetas, coeffs, (X, Y), None, np.array([0]))
    assert np.isnan(unknown.margin[0]) and not unknown.bound[0]


@pytest.fixture(scope="module")
def si_store(tmp_path_factory, uic60):
    from moving_bogie.sweep.api import sweep

    params, physical = uic60
    out = tmp_path_factory.mktemp("store") / "s.zarr"
    ds = sweep(params, {"v": "60,120", "M": "600,1400"}, out=out, physical=physical, check=0, margin=True)
    return out, ds, params, physical


def test_a_sweep_measures_the_margin_only_when_asked(si_store, tmp_path):
    """Without ``margin`` the store has no margin variables, and every other variable is the one the sweep
    with the margin stores (the margin changes nothing else)."""
    from moving_bogie.sweep.api import sweep

    out, with_margin, params, physical = si_store
    ds = sweep(params, {"v": "60,120", "M": "600,1400"}, out=tmp_path / "s.zarr", physical=physical, check=0)
    assert "margin" not in ds and "margin_bound" not in ds
    assert set(with_margin.data_vars) - set(ds.data_vars) == {"margin", "margin_bound"}
    for name in ds.data_vars:
        np.testing.assert_array_equal(ds[name].values, with_margin[name].values, err_msg=name)


def test_store_keeps_the_margin_in_si_units(si_store):
    _, ds, params, physical = si_store
    t_scale = physical.scales().t_scale
    assert ds.margin.attrs["units"] == "1/s"
    for i, j in [(0, 0), (1, 1)]:  # the bar (mu_v, J_b) follows M: the default rule of model/bar.py
        point = at_theta(
            bind(params.replace(alpha=exact(ds.alpha.values[i]))), "eta_M", exact(ds.eta_M.values[j])
        )
        assert float(ds.margin[i, j]) == pytest.approx(smallest_im(point) / t_scale, rel=1e-9)


def test_store_opens_consolidated_with_units_and_names(si_store):
    import xarray as xr

    from moving_bogie.sweep import open_sweep

    out, *_ = si_store
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ds = open_sweep(out)
        xr.open_zarr(out, consolidated=True)
    for name in list(ds.data_vars) + list(ds.coords):
        assert ds[name].attrs.get("units") and ds[name].attrs.get("long_name"), name


def test_a_store_without_margin_or_consolidated_metadata_still_opens(si_store, tmp_path):
    """A store as an earlier version wrote it: no consolidated metadata, no margin."""
    import shutil

    from moving_bogie.sweep import open_sweep
    from moving_bogie.sweep.plots import plot_sweep_slice

    out, *_ = si_store
    old = tmp_path / "old.zarr"
    shutil.copytree(out, old)
    meta = json.loads((old / "zarr.json").read_text())
    meta.pop("consolidated_metadata")
    (old / "zarr.json").write_text(json.dumps(meta))
    shutil.rmtree(old / "margin")
    shutil.rmtree(old / "margin_bound")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ds = open_sweep(old)
    assert "margin" not in ds
    fig = plot_sweep_slice(ds, "v", "M")
    assert "not in this store" in fig.axes[0].get_title()


def test_figure_shows_the_margin_and_lists_only_what_is_drawn(uic60):
    from moving_bogie.stability.figures.plot_units import PlaneUnits
    from moving_bogie.stability.figures.plots import plot_stability_map

    params, physical = uic60
    smap = stability_map(params, alphas=np.array([0.1, 0.3]), thetas=np.array([10.0, 30.0]), workers=1)
    units = PlaneUnits.of(params, physical, operating=True)
    fig = plot_stability_map(smap, units=units)
    ax, *bars = fig.axes
    assert [bar.get_ylabel() for bar in bars] == [r"decay rate $\min\,\mathrm{Im}\,\omega$ [1/s] (stable)"]
    mesh = ax.collections[0]
    np.testing.assert_allclose(
        np.sort(mesh.get_array().compressed()), np.sort(smap.margin.ravel() / units.t_scale)
    )
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    # v_cr = 649 m/s lies beyond the 0.3 alpha axis: not drawn, listed as beyond it; the stable cell closest
    # to instability is marked with its rate, the smallest margin of the map
    closest = float(np.nanmin(smap.margin) / units.t_scale)
    v_cr = "v_cr = 649.336 m/s (critical velocity): beyond this axis"  # v_ref (alpha_cr = 1, Eq. (65))
    assert labels == [v_cr, "operating point", f"smallest decay rate {closest:.3g} 1/s"]
    assert not ax.texts  # no note in the plane, where it could hide a cell or a marker
    fig.canvas.draw()
    legend = ax.get_legend().get_window_extent()
    for line in ax.get_lines():  # neither the closest cell nor the operating point lies under the legend
        if len(line.get_xdata()):
            x, y = ax.transData.transform((line.get_xdata()[0], line.get_ydata()[0]))
            assert not legend.contains(x, y), line.get_label()
    title = ax.get_title()
    assert "bogie, eb beam, one-layer track" in title and "c_f = 1.2e+04 N s/m^2" in title


@pytest.fixture(scope="module")
def car():
    params, _ = load_parameters(EXAMPLES / "car.toml")
    res = induced_frequencies(params, dps=15)
    assert res.count_ok and res.verdict.determined
    return params, sorted((complex(r.q) for r in res.roots), key=lambda q: q.imag)


def test_car_margin_is_earned_where_its_rectangle_holds_more_roots_than_the_power_sums_locate(car):
    """The car of examples/car.toml: 20 roots below 0.4 eta_f (more than MAX_STRIP_ROOTS), among them pairs
    about 2e-10 apart; the rectangle's top is lowered until it holds few enough, and the margin is the
    smallest Im q of the full count's roots (the reference)."""
    from moving_bogie.stability.maps.column_margin import MAX_STRIP_ROOTS

    params, roots = car
    assert 2 * sum(q.imag < 0.4 * float(params.eta_f) for q in roots) > MAX_STRIP_ROOTS
    smap = stability_map(params, alphas=[float(params.alpha)], thetas=[float(params.eta_M)], workers=1)
    assert not smap.uncertain.any() and not smap.margin_bound.any()
    assert smap.margin[0, 0] == pytest.approx(roots[0].imag, rel=1e-9)


def test_a_pair_closer_than_newton_separates_counts_twice_on_its_circle(car):
    """cluster_counts against the full count's roots: one circle around a root of the car's pair 2e-10
    apart holds both (and the mirror circle both mirrors: 4), two roots 1e-7 apart get a circle each, and a
    point that is no root is refused."""
    from moving_bogie.stability.maps.column_margin import cluster_counts

    params, roots = car
    gaps = [(abs(a - b), a, b) for i, a in enumerate(roots) for b in roots[i + 1 :]]
    tight = min(gaps, key=lambda g: g[0])
    near = min((g for g in gaps if g[0] > 1e-8), key=lambda g: g[0])
    assert tight[0] < 1e-9 and near[0] < 1e-6
    sweep = SweepCharacteristic(bind(params), "eta_M")
    alpha, theta = float(params.alpha), float(params.eta_M)
    box = (3.0, 3.0, 0.5)
    assert cluster_counts(sweep, alpha, theta, np.array([tight[1]]), box) == 4
    assert cluster_counts(sweep, alpha, theta, np.array([near[1], near[2]]), box) == 4
    assert cluster_counts(sweep, alpha, theta, np.array([near[1] + 1e-3]), box) == -1


# slow: a second column of the car; the fast subset checks the car's margin where its rectangle is lowered
# (test_car_margin_is_earned_where_its_rectangle_holds_more_roots_than_the_power_sums_locate)
@pytest.mark.slow
def test_car_margin_in_a_column_of_two_wheel_masses(car):
    """The column's E as a polynomial in the wheel mass (two values): 14 roots below h / 4 at the heavier
    wheel, more than its power sums locate in a rectangle 6 wide, so its top is lowered once more; both
    margins against the full count's roots at the exact points."""
    params, roots = car
    heavy = params.eta_M * 14 / 9  # a wheel of 1400 kg in place of 900 kg
    smap = stability_map(
        params, alphas=[float(params.alpha)], thetas=[float(params.eta_M), float(heavy)], workers=1
    )
    assert not smap.uncertain.any() and not smap.margin_bound.any()
    assert smap.margin[0, 0] == pytest.approx(roots[0].imag, rel=1e-9)
    assert smap.margin[1, 0] == pytest.approx(smallest_im(params.replace(eta_M=heavy)), rel=1e-9)
