"""An interrupted sweep's store: ``sweep-plot`` says how much is missing and leaves those points blank (not
hatched as uncertain), each legend entry once; stores written with older variable names still open."""

from __future__ import annotations

import numpy as np
import pytest

from moving_bogie import table1_case
from moving_bogie.cli import main
from moving_bogie.sweep.api import make_spec
from moving_bogie.sweep.engine import run_sweep
from moving_bogie.sweep.plots import plot_sweep_slice
from moving_bogie.sweep.store import missing_points, open_sweep


@pytest.fixture(scope="module")
def partial(tmp_path_factory):
    """A 16 x 3 sweep of two chunks, interrupted once the first is in the store."""
    out = tmp_path_factory.mktemp("partial") / "s.zarr"
    spec = make_spec(table1_case(1), {"alpha": "0.3:1.1:16", "eta_M": "5:150:3"}, check=0, block_points=8)

    def ctrl_c(_block: int) -> None:
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        run_sweep(spec, out, on_block=ctrl_c)
    return out


def test_a_partial_store_counts_its_missing_points(partial):
    assert missing_points(partial) == (24, 48)


def test_the_slice_leaves_missing_points_blank_and_says_so(partial):
    ds = open_sweep(partial)
    fig = plot_sweep_slice(ds, "alpha", "eta_M")
    ax = fig.axes[0]
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert len(labels) == len(set(labels)) and "not computed (interrupted)" in labels
    assert not any("certified" in label for label in labels)  # every computed point here is certain
    assert "24 of 48 points not computed" in ax.get_title()
    computed = ds.computed.values
    assert not any(c.get_hatch() for c in ax.collections)  # nothing hatched: the missing are not uncertain
    mesh = ax.collections[0]  # the colours: only the computed points have one
    assert mesh.get_array().count() <= int(computed.sum())


@pytest.mark.slow
def test_sweep_plot_says_how_much_is_missing(partial, tmp_path, capsys):
    out = tmp_path / "slice.png"
    assert main(["sweep-plot", str(partial), "--x", "alpha", "--y", "eta_M", "--out", str(out)]) == 0
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "24 of 48 points not computed" in err[0] and "--resume" in err[0]


def test_an_older_store_opens_with_the_new_names(tmp_path):
    import xarray as xr

    path = tmp_path / "old.zarr"
    xr.Dataset({"count": ("v", np.array([0, 2], dtype=np.int16))}, attrs={"kind": "sleepers"}).to_zarr(path)
    ds = open_sweep(path)
    assert "count" not in ds.variables and ds.n_roots.values.tolist() == [0, 2]
    assert callable(ds.count)  # the xarray method again


def test_a_partial_sleeper_sweep_leaves_its_missing_points_out():
    import xarray as xr

    from moving_bogie.sweep.sleeper_plots import plot_sleeper_sweep

    v, M = np.array([40.0, 60.0, 80.0]), np.array([400.0, 800.0])
    computed = np.array([[True, True], [True, True], [False, False]])  # (v, M): the last velocity missing
    stable = computed.copy()
    data = {
        "stable": (("v", "M"), stable),
        "unstable": (("v", "M"), np.zeros((3, 2), dtype=bool)),
        "certain": (("v", "M"), computed),  # a missing point is not certain: it must not look uncertain
        "computed": (("v", "M"), computed),
        "Omega_im": (("v", "M"), np.full((3, 2), np.nan)),
    }
    ds = xr.Dataset(data, coords={"v": v, "M": M}, attrs={"kind": "sleepers", "model": "eb/sleepers/mass"})
    ax = plot_sleeper_sweep(ds, "v", "M").axes[0]
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert labels == ["stable", "not computed (interrupted)"]  # neither undetermined nor hatched
    assert "2 of 6 points not computed" in ax.get_title()
    ax = plot_sleeper_sweep(ds, "v", None, {"M": 400.0}).axes[0]
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert len(labels) == 1 and labels[0].startswith("stable")  # the missing point: no mark at all
    assert ax.get_xlim()[1] > 80.0  # the axis spans the missing point
