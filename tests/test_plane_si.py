"""Stability planes of a ``[physical]`` input shown in SI: axes, legends, operating point, JSON units.

References: the SI scales are written out here from Eqs. (15)-(16) in numpy (v_ref = (4 k_f EI / m^2)^(1/4),
chi = (k_f / (4 EI))^(1/4), t_scale = sqrt(m / k_f)): alpha = v / v_ref, eta_M = M chi / m, d = d_SI chi,
omega = q / t_scale. The figures are checked by the data of their artists, not only by their files.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from moving_bogie.api import instability_lines, stability_map
from moving_bogie.cli import main
from moving_bogie.cli.lines_cmd import instability_figure
from moving_bogie.model.cases import table1_case
from moving_bogie.model.files import load_params_file
from moving_bogie.model.physical import PhysicalParams
from moving_bogie.stability.figures.plot_units import PlaneUnits
from moving_bogie.stability.figures.plots import plot_stability_map

SCALES = {"EI": "6.4e6", "m": "60", "k_f": "2.5e7", "P": "8e4"}


def _scales(physical):
    EI, m, k_f = (float(getattr(physical, k)) for k in ("EI", "m", "k_f"))
    return (4 * k_f * EI / m**2) ** 0.25, (k_f / (4 * EI)) ** 0.25, (m / k_f) ** 0.5, m


@pytest.fixture(scope="module")
def case1_si(tmp_path_factory):
    """Table 1's Case 1 as an SI file (a UIC60-like rail, per rail), and its parameters."""
    physical = PhysicalParams.from_dimensionless(table1_case(1), digits=8, **SCALES)
    skip = ("beam", "track", "vehicle")
    rows = "\n".join(f"{k} = {v}" for k, v in physical.to_dict().items() if k not in skip)
    path = tmp_path_factory.mktemp("plane") / "case1_si.toml"
    path.write_text(f'[model]\nbeam = "eb"\nvehicle = "bogie"\n\n[physical]\n{rows}\n')
    params, physical = load_params_file(path)
    return path, params, physical


def test_plane_units_match_the_scaling(case1_si):
    _, params, physical = case1_si
    v_ref, chi, t_scale, m = _scales(physical)
    units = PlaneUnits.of(params, physical, operating=True)
    assert units.label("alpha") == "v [m/s]" and units.label("eta_M") == "M [kg]"
    assert units.value("alpha", 0.5) == pytest.approx(0.5 * v_ref, rel=1e-12)
    assert units.value("eta_M", 20.0) == pytest.approx(20.0 * m / chi, rel=1e-12)
    assert units.legend("d", float(params.d)) == f"d = {float(physical.d):.6g} m"
    assert units.frequency(1.5) == pytest.approx(1.5 / t_scale, rel=1e-12)
    assert PlaneUnits.of(params).legend("d", 2.95544) == "d = 2.95544"  # dimensionless input unchanged


# slow: the lines of a whole panel; the fast subset checks the SI axes of the stability map and of the
# frequency lines, and the scaling of the plane's units
@pytest.mark.slow
def test_instability_lines_in_si(case1_si):
    _, params, physical = case1_si
    v_ref, chi, _, m = _scales(physical)
    res = instability_lines(params, spacings=[float(params.d)], alpha_range=(0.6, 1.2), theta_max=200.0)
    units = PlaneUnits.of(params, physical, operating=True)
    data = units.with_si(res.to_dict())
    branch = data["branches"][0]
    assert branch["si"]["d"] == {"value": pytest.approx(branch["d"] / chi, rel=1e-12), "unit": "m"}
    for point in branch["points"]:
        assert point["si"]["v"]["value"] == pytest.approx(point["alpha"] * v_ref, rel=1e-12)
        assert point["si"]["M"]["value"] == pytest.approx(point["eta_M"] * m / chi, rel=1e-12)
        assert point["si"]["v"]["unit"] == "m/s" and point["si"]["M"]["unit"] == "kg"
    fig = instability_figure(res, units, (0.6, 1.2), 200.0)
    ax = fig.axes[0]
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("v [m/s]", "M [kg]")
    drawn = [line for line in ax.get_lines() if line.get_label().startswith("d = ")]
    assert drawn and drawn[0].get_label() == f"d = {float(physical.d):.6g} m"
    b = res.branches[0]
    np.testing.assert_allclose(drawn[0].get_xdata(), b.alpha * v_ref, rtol=1e-12)
    np.testing.assert_allclose(drawn[0].get_ydata(), b.theta * m / chi, rtol=1e-12)
    (star,) = [line for line in ax.get_lines() if line.get_label() == "operating point"]
    assert star.get_xdata()[0] == pytest.approx(float(physical.v), rel=1e-7)
    assert star.get_ydata()[0] == pytest.approx(float(physical.M), rel=1e-7)
    (critical,) = [line for line in ax.get_lines() if line.get_label().startswith("v_cr = ")]
    assert critical.get_xdata()[0] == pytest.approx(v_ref, rel=1e-12)  # alpha_cr = 1 (Eq. (65), eta_s = 0)
    assert critical.get_label() == f"v_cr = {v_ref:.6g} m/s (critical velocity)"


def test_stability_map_in_si(case1_si):
    _, params, physical = case1_si
    v_ref, chi, _, m = _scales(physical)
    alphas, thetas = np.linspace(0.6, 1.1, 6), np.linspace(5, 60, 6)
    smap = stability_map(params, alphas=alphas, thetas=thetas, workers=1)
    units = PlaneUnits.of(params, physical, operating=True)
    fig = plot_stability_map(smap, units=units)
    ax = fig.axes[0]
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("v [m/s]", "M [kg]")
    decay, growth = ax.collections[:2]  # the stable cells by their decay rate, the unstable by growth
    for mesh in (decay, growth):
        x, y = mesh.get_coordinates()[0, :, 0], mesh.get_coordinates()[:, 0, 1]
        np.testing.assert_allclose(0.5 * (x[1:] + x[:-1]), alphas * v_ref, rtol=1e-12)  # cell centres
        np.testing.assert_allclose(0.5 * (y[1:] + y[:-1]), thetas * m / chi, rtol=1e-12)
    assert np.isfinite(decay.get_array()).sum() == int((smap.count == 0).sum())
    assert np.isfinite(growth.get_array()).sum() == int((smap.count > 0).sum())
    (star,) = [line for line in ax.get_lines() if line.get_label() == "operating point"]
    assert star.get_xdata()[0] == pytest.approx(float(physical.v), rel=1e-7)


def test_stability_map_cli_takes_si_ranges(case1_si, capsys, tmp_path):
    from moving_bogie.sweep import open_sweep

    path, _, physical = case1_si
    v_ref, chi, _, m = _scales(physical)
    args = ["stability-map", "--file", str(path), "--n", "4", "--workers", "1", "--json"]
    store = tmp_path / "map.zarr"
    assert main([*args, "--range", "v=300:700", "--range", "M=0:2400", "--out", str(store)]) == 0
    ds = open_sweep(store).compute()
    assert ds.n_unstable.dims == ("v", "M") and ds.v.attrs["units"] == "m/s" and ds.M.attrs["units"] == "kg"
    np.testing.assert_allclose(ds.v.values, np.linspace(300, 700, 4), rtol=1e-12)
    np.testing.assert_allclose(ds.M.values, np.linspace(600, 2400, 4), rtol=1e-12)
    np.testing.assert_allclose(ds.alpha.values, ds.v.values / v_ref, rtol=1e-12)
    assert "follow it (Eq. (63))" in ds.attrs["vertical_axis"]
    data = json.loads(capsys.readouterr().out)
    assert data["axes"]["x"]["name"] == "v" and data["axes"]["x"]["unit"] == "m/s"
    assert data["axes"]["x"]["range"] == pytest.approx([300, 700], rel=1e-12)
    assert data["axes"]["y"]["range"][1] == pytest.approx(2400, rel=1e-12)
    assert data["alpha_range"][:2] == pytest.approx([300 / v_ref, 700 / v_ref], rel=1e-12)
    assert data["eta_M_range"][1] == pytest.approx(2400 * chi / m, rel=1e-12)
    assert data["units"]["units"] == "si"
    t_scale = _scales(physical)[2]
    assert data["max_growth_rate"] == {
        "value": pytest.approx(data["max_degree"] / t_scale, rel=1e-12),
        "unit": "1/s",
    }
    assert ds.degree_of_instability.attrs["t_scale_s"] == pytest.approx(t_scale, rel=1e-12)
    assert main([*args, "--range", "alpha=0:1"]) == 2
    error = json.loads(capsys.readouterr().out)
    assert error == {"error": "--range alpha: not an axis (known: v, M)", "option": "--range"}
    assert main(["stability-map", "--case", "1", "--units", "si", "--n", "4"]) == 2
    assert "--units si needs a [physical]" in capsys.readouterr().err


def test_frequency_lines_in_si(case1_si, capsys):
    path, _, physical = case1_si
    v_ref, _, t_scale, _ = _scales(physical)
    args = ["frequency-lines", "--file", str(path), "--range", "v=500:600", "--checkpoints", "3", "--json"]
    assert main(args) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["alpha_range"] == pytest.approx([500 / v_ref, 600 / v_ref], rel=1e-12)
    assert data["lines"] and data["units"]["frequency_unit"] == "rad/s"
    for line in data["lines"]:
        alpha = np.array([p["alpha"] for p in line["points"]])
        q = np.array([complex(p["re"], p["im"]) for p in line["points"]])
        assert line["si"]["v"]["unit"] == "m/s" and line["si"]["omega"]["unit"] == "rad/s"
        np.testing.assert_allclose(line["si"]["v"]["values"], alpha * v_ref, rtol=1e-12)
        np.testing.assert_allclose(line["si"]["omega"]["re"], q.real / t_scale, rtol=1e-12)
        np.testing.assert_allclose(line["si"]["omega"]["im"], q.imag / t_scale, rtol=1e-12, atol=1e-300)


@pytest.mark.slow
def test_compare_tracks_in_si(capsys):
    """The two-layer example (per rail, SI): both critical velocities in m/s, spacings in metres."""
    from pathlib import Path

    path = Path(__file__).resolve().parents[1] / "examples" / "two-layer.toml"
    _, physical = load_params_file(path)
    EI, m, k_1 = (float(physical.values()[k]) for k in ("EI", "m", "k_1"))  # k_1: the reference stiffness
    v_ref = (4 * k_1 * EI / m**2) ** 0.25  # Eq. (16)
    args = ["compare-tracks", "--file", str(path), "--quick", "--range", "v=0:400", "--json"]
    assert main(args) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["units"]["units"] == "si"
    for track in data["tracks"]:
        assert track["v_cr"] == {"value": pytest.approx(track["alpha_cr"] * v_ref, rel=1e-12), "unit": "m/s"}
    assert data["alpha_range"] == pytest.approx([0, 400 / v_ref], rel=1e-12)
    main(args[:-1])
    out = capsys.readouterr().out
    assert f"d = {float(physical.d):.6g} m" in out and "v_cr = " in out
