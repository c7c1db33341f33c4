"""Parameter sweeps (moving_bogie.sweep): stores equal across worker counts and after an interruption,
points equal to the full root search, options checked before any work.

References: every verdict is compared with ``induced_frequencies`` (argument principle over the default
window, roots polished and confirmed in mpmath), which shares with the sweep only E_chr itself.
"""

from __future__ import annotations

import json
import os
import signal
from fractions import Fraction

import numpy as np
import pytest

from moving_bogie.api import induced_frequencies
from moving_bogie.cli import main
from moving_bogie.errors import ParameterError
from moving_bogie.model.cases import table1_case
from moving_bogie.sweep import make_spec, open_sweep
from moving_bogie.sweep.engine import IN_PROCESS_POINTS, run_sweep
from moving_bogie.sweep.store import missing_blocks

# Case 1 over a window holding stable and unstable points with 0 to 3 unstable roots
VARY = {"alpha": "0.5:1.1:12", "eta_M": "5:100:24"}
OPTIONS = dict(block_points=8 * 24, check=1)
VARIABLES = ("stable", "n_unstable", "degree_of_instability", "certain", "settled", "checked", "computed")


def _spec():
    return make_spec(table1_case(1), VARY, **OPTIONS)


def _arrays(path):
    ds = open_sweep(path).compute()
    return {name: ds[name].values for name in VARIABLES}, ds.attrs


def _same(a, b):
    for name in VARIABLES:
        np.testing.assert_array_equal(a[name], b[name], err_msg=name)


@pytest.fixture(scope="module")
def one_worker(tmp_path_factory):
    path = tmp_path_factory.mktemp("sweep") / "one.zarr"
    run = run_sweep(_spec(), path, workers=1, processes=False)
    assert run.blocks_total == 2 and run.points_computed == 12 * 24
    return path


@pytest.mark.slow
def test_one_and_two_workers_give_the_same_store(one_worker, tmp_path):
    # two worker processes (threads would share mpmath's process-wide precision)
    run = run_sweep(_spec(), tmp_path / "two.zarr", workers=2)
    assert run.workers == 2
    a, attrs_a = _arrays(one_worker)
    b, attrs_b = _arrays(tmp_path / "two.zarr")
    _same(a, b)
    assert attrs_a == attrs_b
    assert a["computed"].all() and a["certain"].all()
    assert set(np.unique(a["n_unstable"])) == {0, 1, 2, 3}


# slow: it starts a cluster. In the fast subset, a small sweep of tests/test_sleepers_sweep.py says that it
# ran in-process, and tests/test_margin.py checks an in-process store against the roots at its points.
@pytest.mark.slow
def test_a_small_sweep_runs_in_process_and_equals_the_cluster_store(tmp_path, capsys):
    """Under IN_PROCESS_POINTS points, no cluster asked for, the command computes in this process and
    says so; its store equals the one a LocalCluster worker computes (two blocks, one checked point each)."""
    vary = {"alpha": "0.5:1.1:12", "eta_M": "5,60"}
    cluster = run_sweep(
        make_spec(table1_case(1), vary, block_points=16, check=1), tmp_path / "cluster.zarr", workers=1,
        processes=False,
    )  # fmt: skip
    assert cluster.scheduler == "local cluster" and cluster.blocks_total == 2
    out = tmp_path / "here.zarr"
    varied = [arg for name, spec in vary.items() for arg in ("--vary", f"{name}={spec}")]
    argv = ["sweep", "--case", "1", *varied, "--chunk-points", "16", "--out", str(out), "--json"]
    assert main(argv) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["scheduler"] == "in-process" and summary["points"] == 24 < IN_PROCESS_POINTS
    from moving_bogie.sweep.plan import SWEEP_KEYS

    assert set(SWEEP_KEYS) <= set(summary)  # the keys of every track's sweep (a sleeper file's too)
    (a, attrs_a), (b, attrs_b) = _arrays(tmp_path / "cluster.zarr"), _arrays(out)
    _same(a, b)
    assert attrs_a == attrs_b and a["computed"].all() and len(np.unique(a["n_unstable"])) > 1


def test_the_help_names_the_in_process_limit(capsys):
    with pytest.raises(SystemExit):
        main(["sweep", "--help"])
    assert f"under {IN_PROCESS_POINTS} points" in " ".join(capsys.readouterr().out.split())


@pytest.mark.slow
def test_random_points_agree_with_induced_frequencies(one_worker):
    ds = open_sweep(one_worker).compute()
    exact = {name: [Fraction(v) for v in ds[name].attrs["exact"]] for name in ("alpha", "eta_M")}
    rng = np.random.default_rng(15)
    for i, j in rng.integers((0, 0), (12, 24), size=(4, 2)):
        point = ds.isel(alpha=i, eta_M=j)
        ref = induced_frequencies(
            table1_case(1).replace(alpha=exact["alpha"][i], eta_M=exact["eta_M"][j]), dps=20
        )
        assert ref.count_ok and ref.verdict.determined
        assert int(point.n_unstable) == len(ref.unstable_roots)
        assert bool(point.stable) == (ref.verdict.state == "stable")
        assert float(point.degree_of_instability) == pytest.approx(float(ref.degree_of_instability), abs=1e-9)


@pytest.mark.slow
def test_sigint_then_resume_equals_an_uninterrupted_sweep(one_worker, tmp_path, ctrl_c_raises):
    path = tmp_path / "interrupted.zarr"

    def interrupt(index):
        os.kill(os.getpid(), signal.SIGINT)  # what Ctrl-C sends

    with pytest.raises(KeyboardInterrupt):
        run_sweep(_spec(), path, workers=1, processes=False, on_block=interrupt)
    left = missing_blocks(path, _spec())
    assert len(left) == 1  # the finished block is kept, the other is not
    with pytest.raises(ParameterError, match="--out"):
        run_sweep(_spec(), path, workers=1, processes=False)  # neither --resume nor --overwrite
    run = run_sweep(_spec(), path, resume=True, workers=1, processes=False)
    assert run.blocks_computed == len(left)
    _same(_arrays(one_worker)[0], _arrays(path)[0])


@pytest.mark.slow
def test_resume_of_a_different_sweep_is_refused(one_worker):
    other = make_spec(table1_case(1), {"alpha": "0.5:1.1:12", "eta_M": "5:100:23"}, **OPTIONS)
    with pytest.raises(ParameterError, match="--resume"):
        run_sweep(other, one_worker, resume=True, workers=1, processes=False)


@pytest.mark.slow
def test_sweep_plot_draws_a_slice(one_worker, tmp_path, capsys, monkeypatch):
    """The slice by content: the colour mesh read back from the figure is log10 |degree| of the store's
    unstable points (whose verdicts the tests above check against induced_frequencies), blank elsewhere."""
    from matplotlib.collections import QuadMesh

    import moving_bogie.sweep.plots as plots

    drawn = []
    original = plots.plot_sweep_slice
    monkeypatch.setattr(
        plots, "plot_sweep_slice", lambda *a, **k: drawn.append(original(*a, **k)) or drawn[-1]
    )
    out = tmp_path / "slice.png"
    assert main(["sweep-plot", str(one_worker), "--x", "alpha", "--y", "eta_M", "--out", str(out)]) == 0
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    (ax,) = [ax for ax in drawn[0].axes if ax.get_xlabel() == "alpha"]
    meshes = [c for c in ax.collections if isinstance(c, QuadMesh) and c.colorbar is not None]
    (mesh,) = [c for c in meshes if "growth" in c.colorbar.ax.get_ylabel()]  # the unstable points
    ds = open_sweep(one_worker).compute().transpose("eta_M", "alpha")
    unstable = ds.n_unstable.values > 0
    shown = np.ma.getdata(mesh.get_array()).reshape(unstable.shape)
    blank = np.ma.getmaskarray(mesh.get_array()).reshape(unstable.shape) | np.isnan(shown)
    np.testing.assert_array_equal(blank, ~unstable)
    expected = -ds.degree_of_instability.values[unstable]  # the growth rate: the margin of an unstable point
    np.testing.assert_allclose(shown[unstable], expected, rtol=1e-12)
    assert main(["sweep-plot", str(one_worker), "--x", "alpha", "--y", "eta_f", "--out", str(out)]) == 2
    assert "--y eta_f" in capsys.readouterr().err


@pytest.mark.parametrize(
    "args, option",
    [
        (["--vary", "alpah=0.3:1:5"], "--vary 'alpah"),
        (["--vary", "alpha=0.3:1"], "--vary 'alpha=0.3:1'"),
        (["--vary", "alpha=0.3:x:5"], "--vary"),
        (["--vary", "eta_M=-1:5:3"], "--vary eta_M"),
        (["--vary", "alpha=0.3:1:5", "--sample", "halton:8"], "--sample"),
        (["--vary", "alpha=0.3:1:5", "--workers", "0"], "--workers"),
        ([], "--vary"),
    ],
)
def test_bad_options_fail_before_any_work(args, option, tmp_path, capsys):
    out = tmp_path / "s.zarr"
    assert main(["sweep", "--case", "1", "--out", str(out), *args]) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert option in lines[0]  # one line naming the option (an argparse refusal adds "see: ... --help")
    assert lines[1:] in ([], ["see: moving-bogie sweep --help"])
    assert not out.exists()


def test_existing_out_needs_resume_or_overwrite(tmp_path, capsys):
    out = tmp_path / "s.zarr"
    out.mkdir()
    assert main(["sweep", "--case", "1", "--vary", "alpha=0.3:1:5", "--out", str(out)]) == 2
    assert "--out" in capsys.readouterr().err


@pytest.mark.slow
def test_sobol_design_and_cli_json(tmp_path, capsys):
    out = tmp_path / "sobol.zarr"
    code = main(
        [
            "sweep",
            "--case",
            "1",
            "--vary",
            "alpha=0.6:1.1",
            "--vary",
            "eta_f=0.05:0.2",
            "--sample",
            "sobol:4",
            "--workers",
            "1",
            "--check",
            "0",
            "--roots",
            "--margin",
            "--out",
            str(out),
            "--json",
        ]
    )
    assert code == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["dims"] == {"point": 4, "root": 8} and summary["uncertain_points"] == 0
    assert summary["scheduler"] == "local cluster"  # --workers asks for the cluster at any size
    ds = open_sweep(out).compute()
    assert ((ds.alpha >= 0.6) & (ds.alpha <= 1.1)).all()
    # the roots stored are the unstable ones: their number is n_unstable, the deepest is the degree
    n = (~np.isnan(ds.roots_im.values)).sum(axis=1)
    np.testing.assert_array_equal(n, ds.n_unstable.values)
    k = 0
    ref = induced_frequencies(
        table1_case(1).replace(
            alpha=Fraction(repr(float(ds.alpha[k]))), eta_f=Fraction(repr(float(ds.eta_f[k])))
        )
    )
    assert int(ds.n_unstable[k]) == len(ref.unstable_roots)
    # --margin: the smallest Im q of the full count's roots
    assert float(ds.margin[k]) == pytest.approx(min(float(r.q.imag) for r in ref.roots), rel=1e-9)


@pytest.mark.slow
@pytest.mark.parametrize(
    "vary",
    [
        {"eta_M": "10,60", "d": "1,1.5"},  # eta_M a column; d changes J_b = cf2 eta_M d^2 too
        {"eta_M": "10,60", "mu_v": "20"},  # mu_v fixed while eta_M varies: no column
    ],
)
def test_every_point_is_the_point_of_replace(vary, tmp_path):
    """The point (i, j) is ``params.replace(name_i=..., name_j=...)``: Eq. (63) scaling as replace does."""
    base = table1_case(1).replace(alpha=Fraction("0.95"))
    spec = make_spec(base, vary, check=0)
    run_sweep(spec, tmp_path / "s.zarr", workers=1, processes=False)
    ds = open_sweep(tmp_path / "s.zarr").compute()
    for index in np.ndindex(ds.n_unstable.shape):
        point = {name: Fraction(ds[name].attrs["exact"][i]) for name, i in zip(ds.n_unstable.dims, index)}
        ref = induced_frequencies(base.replace(**point), dps=20)
        assert ref.count_ok and int(ds.n_unstable[index]) == len(ref.unstable_roots)
