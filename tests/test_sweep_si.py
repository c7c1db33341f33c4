"""Sweeps of a ``[physical]`` input in SI units: the store's coordinates are the SI parameters with their
units, the groups are kept beside them, and every point is the point of the SI parameter file.

References: the groups are recomputed here from the scaling of Eqs. (15)-(17) written out in numpy
(alpha = v / v_ref, eta_M = M chi / m with v_ref = (4 k_f EI / m^2)^(1/4), chi = (k_f / (4 EI))^(1/4)); each
verdict is compared with ``induced_frequencies`` of the SI parameter file with that point's v and M, made
dimensionless by :meth:`PhysicalParams.to_dimensionless` (every other SI parameter fixed: the bogie bar's
mass and inertia do not follow the wheel mass, unlike Table 1's cf1, cf2).
"""

from __future__ import annotations

import importlib.util
import json
from fractions import Fraction

import numpy as np
import pytest

from moving_bogie.api import induced_frequencies
from moving_bogie.cli import build_parser, main
from moving_bogie.cli.common import si_input
from moving_bogie.errors import ParameterError
from moving_bogie.model.cases import table1_case
from moving_bogie.model.physical import PhysicalParams
from moving_bogie.sweep import make_spec, open_sweep

# Found, not imported here: every worker collects this module, and only the one that runs it needs Dask.
if importlib.util.find_spec("distributed") is None:
    pytest.skip("distributed is not installed", allow_module_level=True)

# Table 1's Case 1 on a UIC60-like rail (EI, m per rail) on a soft track: unstable points occur in the window
SCALES = {"EI": "6.4e6", "m": "60", "k_f": "2.5e7", "P": "8e4"}


def _physical_file(tmp_path) -> tuple:
    physical = PhysicalParams.from_dimensionless(table1_case(1), digits=8, **SCALES)
    rows = "\n".join(
        f"{k} = {v}" for k, v in physical.to_dict().items() if k not in ("beam", "track", "vehicle")
    )
    path = tmp_path / "case1_si.toml"
    path.write_text(f'[model]\nbeam = "eb"\nvehicle = "bogie"\n\n[physical]\n{rows}\n')
    return path, physical


@pytest.fixture(scope="module")
def si_store(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("si")
    path, physical = _physical_file(tmp)
    v_ref = float(physical.scales().v_ref)
    v = f"{0.6 * v_ref:.0f}:{1.05 * v_ref:.0f}:4"
    out = tmp / "si.zarr"
    args = ["sweep", "--file", str(path), "--vary", f"v={v}", "--vary", "M=200:1800:3", "--check", "0"]
    args += ["--bar", "fixed"]  # the bar (M_b, J_b) at the file's values: the reference below holds it
    assert main([*args, "--workers", "1", "--out", str(out), "--json"]) == 0
    return out, physical


@pytest.mark.slow
def test_store_is_in_si_units_with_the_groups_beside(si_store):
    out, physical = si_store
    ds = open_sweep(out).compute()
    assert ds.n_unstable.dims == ("v", "M")
    assert ds.v.attrs["units"] == "m/s" and ds.M.attrs["units"] == "kg"
    assert ds.alpha.dims == ("v",) and ds.eta_M.dims == ("M",)
    assert ds.alpha.attrs["units"] == "1" and ds.eta_M.attrs["units"] == "1"
    EI, m, k_f = (float(getattr(physical, k)) for k in ("EI", "m", "k_f"))
    v_ref = (4 * k_f * EI / m**2) ** 0.25  # Eq. (16)
    chi = (k_f / (4 * EI)) ** 0.25  # Eq. (15)
    np.testing.assert_allclose(ds.alpha.values, ds.v.values / v_ref, rtol=1e-14)
    np.testing.assert_allclose(ds.eta_M.values, ds.M.values * chi / m, rtol=1e-14)
    assert [float(Fraction(t)) for t in ds.M.attrs["exact"]] == [200.0, 1000.0, 1800.0]
    point = json.loads(ds.attrs["operating_point"])
    assert point == {"v": float(physical.v), "M": float(physical.M)}
    assert ds.attrs["units"] == "si"
    # the speed regime: v > v_ref is supercritical on this track (alpha_cr = 1, Eq. (65) with eta_s = 0)
    np.testing.assert_array_equal(
        ds.supercritical.values, np.broadcast_to((ds.v > v_ref).values[:, None], (4, 3))
    )
    assert ds.supercritical.any() and json.loads(ds.attrs["v_cr"])["values"] == [
        pytest.approx(v_ref, rel=1e-12)
    ]


@pytest.mark.slow
def test_every_point_is_the_si_file_at_that_v_and_m(si_store):
    out, physical = si_store
    ds = open_sweep(out).compute()
    counts = set()
    for i, j in np.ndindex(ds.n_unstable.shape):
        v, M = (Fraction(ds[k].attrs["exact"][n]) for k, n in (("v", i), ("M", j)))
        point = PhysicalParams(model=physical.model, **(physical.values() | {"v": v, "M": M}))
        ref = induced_frequencies(point.to_dimensionless(), dps=20)
        assert ref.count_ok and ref.verdict.determined
        assert int(ds.n_unstable[i, j]) == len(ref.unstable_roots), (v, M)
        counts.add(len(ref.unstable_roots))
    assert len(counts) > 1  # the window holds stable and unstable points


@pytest.mark.slow
def test_sweep_plot_in_si_marks_the_operating_point(si_store, tmp_path):
    from moving_bogie.sweep.plots import plot_sweep_slice

    out, physical = si_store
    ds = open_sweep(out)
    fig = plot_sweep_slice(ds, "v", "M")
    ax = fig.axes[0]
    assert ax.get_xlabel() == "v [m/s]" and ax.get_ylabel() == "M [kg]"
    marks = [line for line in ax.get_lines() if line.get_label() == "operating point"]
    assert len(marks) == 1
    assert marks[0].get_xdata()[0] == float(physical.v) and marks[0].get_ydata()[0] == float(physical.M)
    mesh = ax.collections[0].get_array()
    assert np.isfinite(mesh).sum() == int((ds.n_unstable > 0).sum())  # coloured where unstable only
    png = tmp_path / "si.png"
    assert main(["sweep-plot", str(out), "--x", "v", "--y", "M", "--out", str(png)]) == 0


@pytest.mark.parametrize(
    "vary, message",
    [
        ("alpha=0.5:1:3", "vary v [m/s] instead"),
        ("EI=1e6:2e6:3", "unknown parameter 'EI'"),
        ("c_f=1e7:2e7:3", "--vary c_f"),  # beyond critical damping: eta_f >= 1
    ],
)
def test_si_sweep_refuses_groups_and_bad_values(vary, message, tmp_path, capsys):
    path, _ = _physical_file(tmp_path)
    assert main(["sweep", "--file", str(path), "--vary", vary, "--out", str(tmp_path / "s.zarr")]) == 2
    err = capsys.readouterr().err
    assert message in err and err.strip().count("\n") == 0
    assert not (tmp_path / "s.zarr").exists()


def test_units_option(tmp_path, capsys):
    out = str(tmp_path / "s.zarr")
    assert main(["sweep", "--case", "1", "--units", "si", "--vary", "alpha=0.5:1:3", "--out", out]) == 2
    assert "--units si needs a [physical]" in capsys.readouterr().err
    assert main(["sweep", "--case", "1", "--vary", "v=100:300:3", "--out", out]) == 2
    assert "needs a [physical] parameter file" in capsys.readouterr().err
    path, physical = _physical_file(tmp_path)
    argv = ["sweep", "--file", str(path), "--units", "dimensionless", "--out", out]
    args = build_parser().parse_args(argv)
    assert si_input(args, physical) is None  # a [physical] file swept by its groups
    args.units = None
    assert si_input(args, physical) is physical


def test_make_spec_holds_the_bar_fixed_in_si():
    physical = PhysicalParams.from_dimensionless(table1_case(1), digits=8, **SCALES)
    default = make_spec(physical.to_dimensionless(), {"M": "500,1500"}, physical=physical)
    assert default.fixed == {} and default.held == ()  # the bar follows M by default, Eq. (63), as in maps
    spec = make_spec(physical.to_dimensionless(), {"M": "500,1500"}, physical=physical, bar="fixed")
    assert spec.dims == ("M",)
    # a column of eta_M with the bar's mu_v, J_b held (not scaled with it: FIXED_POLYNOMIAL_DEGREES)
    assert spec.column_parameter == "eta_M" and spec.held == ("J_b", "mu_v")
    params = spec.params.replace(**(spec.fixed | {"eta_M": spec.axes[0].values[1]}))
    back = PhysicalParams.from_dimensionless(params, digits=8, **SCALES)
    assert float(back.M_b) == pytest.approx(float(physical.M_b), rel=1e-7)
    assert float(back.M) == pytest.approx(1500, rel=1e-7)
    with pytest.raises(ParameterError, match="vary M"):
        make_spec(physical.to_dimensionless(), {"eta_M": "5,10"}, physical=physical)


def test_sobol_design_in_si(tmp_path):
    """A quasi-random SI design: every SI parameter and its group are coordinates along ``point``."""
    from moving_bogie.sweep.store import prepare_store

    physical = PhysicalParams.from_dimensionless(table1_case(1), digits=8, **SCALES)
    spec = make_spec(
        physical.to_dimensionless(), {"v": "300:700", "c_f": "2000:9000"}, sample=8, physical=physical
    )
    prepare_store(tmp_path / "s.zarr", spec)  # the coordinates are written before any computation
    ds = open_sweep(tmp_path / "s.zarr")
    assert {"v", "c_f", "alpha", "eta_f"} <= set(ds.coords) and ds.v.dims == ("point",)
    assert ds.v.attrs["units"] == "m/s" and ds.c_f.attrs["units"] == "N s/m^2"
    assert ((ds.v >= 300) & (ds.v <= 700)).all() and ((ds.c_f >= 2000) & (ds.c_f <= 9000)).all()
    EI, m, k_f = (float(getattr(physical, k)) for k in ("EI", "m", "k_f"))
    np.testing.assert_allclose(ds.alpha.values, ds.v.values / (4 * k_f * EI / m**2) ** 0.25, rtol=1e-14)
    np.testing.assert_allclose(
        ds.eta_f.values, ds.c_f.values / (2 * np.sqrt(k_f * m)), rtol=1e-14
    )  # Eq. (17)
