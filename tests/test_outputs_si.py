"""Results of SI parameters show SI: in Jupyter, in xarray and pandas (CF ``units``), and in the terminal.

The independent reference of every conversion is Eq. (16) of the paper evaluated here from the SI values of
``examples/uic60-bogie.toml`` (EI = 6.4e6 N m^2, m = 60 kg/m, k_f = 2.5e7 N/m^2, P = 8e4 N): t_scale =
sqrt(m / k_f), v_ref = (4 k_f EI / m^2)^(1/4), chi = (k_f / (4 EI))^(1/4), w_st = P chi / (2 k_f), and
eta_M = M chi / m (Eq. (17)), not the package's ``Scales``.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from moving_bogie import closed_form_response, induced_frequencies, load_parameters, stability_map
from moving_bogie.cli import main
from moving_bogie.presentation import field_lines, json_clean, number_text, quantity, value_text

FILE = Path(__file__).resolve().parent.parent / "examples" / "uic60-bogie.toml"
EI, M_RAIL, K_F, P = 6.4e6, 60.0, 2.5e7, 8e4  # the file's [physical] values
T_SCALE = np.sqrt(M_RAIL / K_F)
V_REF = (4 * K_F * EI / M_RAIL**2) ** 0.25
CHI = (K_F / (4 * EI)) ** 0.25
W_ST = P * CHI / (2 * K_F)


@pytest.fixture(scope="module")
def physical():
    return load_parameters(FILE)[1]


@pytest.fixture(scope="module")
def frequencies(physical):
    return induced_frequencies(physical, dps=20)


def test_numbers_print_as_numbers_never_as_reprs_or_negative_zero():
    assert number_text(-0.0) == "0" and number_text(-1e-30, 3) == "-1e-30" and number_text(None) == "n/a"
    assert value_text(quantity(1.2177527123692207, "1/s")) == "1.21775 1/s"
    assert value_text(quantity(-0.0, "1/s")) == "0 1/s"
    assert value_text([0.0, 0.6160140576482046, 20]) == "0, 0.616014, 20"
    assert value_text({"v": 3}) == "v 3" and value_text(quantity(2.0, "1")) == "2"
    assert json_clean({"a": [-0.0, {"b": -0.0}]}) == {"a": [0.0, {"b": 0.0}]}
    assert str(json_clean(-0.0)) == "0.0"
    assert field_lines({"x": quantity(1.5, "m"), "skip": 1}, skip=["skip"], width=4) == ["x    1.5 m"]


def test_frequency_result_of_si_parameters_shows_si(frequencies):
    html = frequencies._repr_html_()
    assert "rad/s" in html and "Hz" in html and "1/s" in html
    for root in frequencies.roots:  # no dimensionless q: neither its digits nor its name
        assert root.re_text[:8] not in html and root.im_text[:8] not in html
    assert "Re q" not in html and "Im q" not in html
    ds = frequencies.to_xarray()
    q = np.array([complex(r.q) for r in frequencies.roots])
    np.testing.assert_allclose(ds["omega_re"].values, q.real / T_SCALE, rtol=1e-12)
    np.testing.assert_allclose(ds["omega_im"].values, q.imag / T_SCALE, rtol=1e-12)
    np.testing.assert_allclose(ds["frequency"].values, q.real / T_SCALE / (2 * np.pi), rtol=1e-12)
    units = {name: ds[name].attrs["units"] for name in ("omega_re", "omega_im", "frequency")}
    assert units == {"omega_re": "rad/s", "omega_im": "1/s", "frequency": "Hz"}
    assert "q_re" not in ds
    frame = frequencies.to_dataframe()
    assert list(frame.index) == list(range(1, len(q) + 1)) and frame.attrs["units"]["frequency"] == "Hz"
    np.testing.assert_allclose(frame["omega_re"], q.real / T_SCALE, rtol=1e-12)


def test_frequency_result_of_dimensionless_parameters_keeps_q(frequencies):
    params = load_parameters(FILE)[0]
    result = induced_frequencies(params, dps=20)
    ds = result.to_xarray()
    assert ds["q_re"].attrs["units"] == "1" and "omega_re" not in ds
    np.testing.assert_allclose(ds["q_re"].values, [float(r.q.real) for r in result.roots], rtol=1e-15)
    assert all(r.re_text in result._repr_html_() for r in result.roots)


def test_time_series_exports_with_cf_units(physical, frequencies):
    t = np.linspace(0.0, 0.2, 5)
    series = closed_form_response(physical, t, frequencies=frequencies)
    ds = series.to_xarray()
    assert ds["t"].attrs["units"] == "s" and list(ds["t"].values) == list(t)
    assert {n: ds[n].attrs["units"] for n in series.names} == {
        "w_rear": "m",
        "w_front": "m",
        "u": "m",
        "theta": "rad",
    }
    np.testing.assert_array_equal(ds["w_rear"].values, series["w_rear"])
    frame = series.to_dataframe()
    assert frame.index.name == "t" and frame.attrs["units"]["theta"] == "rad"
    np.testing.assert_array_equal(frame["u"].to_numpy(), series["u"])
    html = series._repr_html_()
    assert " s to 0.2 s" in html and " m<" in html and " rad<" in html


def test_time_series_in_groups_exports_their_scale(physical, frequencies):
    """Dimensionless: the rail deflection is in multiples of w_st, so its ``units`` is 1 and its scale w_st.
    The same series in SI is w_st times it (Eq. (16))."""
    params = load_parameters(FILE)[0]
    tau = np.linspace(0.0, 0.2 / T_SCALE, 3)
    ds = closed_form_response(params, tau, frequencies=frequencies).to_xarray()
    assert ds["tau"].attrs["units"] == "1"
    assert ds["w_rear"].attrs == {"units": "1", "long_name": ds["w_rear"].attrs["long_name"], "scale": "w_st"}
    si = closed_form_response(physical, tau * T_SCALE, frequencies=frequencies).to_xarray()
    np.testing.assert_allclose(si["w_rear"].values, ds["w_rear"].values * W_ST, rtol=1e-9, atol=1e-15)


def test_stability_map_of_si_parameters_shows_si(physical):
    alphas, thetas = np.array([0.1, 0.5]), np.array([10.0, 40.0])
    smap = stability_map(physical, alphas=alphas, thetas=thetas, workers=1)
    ds = smap.to_xarray()
    np.testing.assert_allclose(ds["v"].values, alphas * V_REF, rtol=1e-9)
    np.testing.assert_allclose(ds["M"].values, thetas * M_RAIL / CHI, rtol=1e-9)  # eta_M = M chi / m
    units = (ds["v"].attrs["units"], ds["M"].attrs["units"], ds["margin"].attrs["units"])
    assert units == ("m/s", "kg", "1/s")
    np.testing.assert_allclose(ds["margin"].values, smap.margin / T_SCALE, rtol=1e-12)
    assert ds["unstable_count"].dims == ("M", "v") and "count" not in ds  # not xarray's Dataset.count
    html = smap._repr_html_()
    assert "m/s" in html and " kg" in html and "1/s" in html and "eta_M" not in html and "Im q" not in html
    assert smap.to_dataframe().attrs["units"]["margin"] == "1/s"


def test_stability_map_terminal_prints_numbers_with_units(capsys):
    """The summary of a map in SI: each number as a number with its unit, no dict, no ``-0``."""
    argv = ["stability-map", "--file", str(FILE), "--n", "3", "--range", "v=0:400", "--range", "M=0:3000"]
    assert main(argv + ["--workers", "1"]) == 0
    out = capsys.readouterr().out
    assert "{" not in out and "'" not in out and not re.search(r"(?<![\w.])-0(?![.\d])", out), out
    assert re.search(r"^min_decay_rate +\d[\d.e+-]* 1/s$", out, re.M), out
    assert "max_degree" not in out and "eta_M_range" not in out  # dimensionless, not asked for


def test_critical_velocity_of_si_parameters_is_in_si(capsys):
    """Eq. (65) without a shear layer: alpha_cr = 1 at p_cr = sqrt(2), so v_cr = v_ref and the critical
    wavelength is 2 pi / (sqrt(2) chi) (Eq. (16)); no group is printed."""
    assert main(["critical-velocity", "--file", str(FILE)]) == 0
    out = capsys.readouterr().out
    first = out.splitlines()[0].split()
    assert (
        first[:3] == ["v_cr", f"{V_REF:.6f}", "m/s"] and first[4] == f"{2 * np.pi / (np.sqrt(2) * CHI):.5g}"
    )
    assert "alpha" not in out and "p_cr" not in out, out
