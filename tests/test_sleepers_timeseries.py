"""The time series on a sleeper track: ``moving-bogie timeseries --file`` and response/sleeper_series.py.

References: the static wheel load P of the file (the mean contact force over a bay: (S17) at n = 0 has no
inertia or damping term, and the vehicle's springs carry no mean force, so F_0 = s); the continuous track's
steady deflection computed by the continuous model's public closed form (``api.closed_form_response``, the
steady part of the paper's Eq. (39)) for the track with the same smeared supports (docs/sleepers.md (S2):
``k_f = k_sup / l``, ``c_f = c_sup / l + c_f``), which the deflection under the wheel must approach as l -> 0
with the supports per metre held fixed, the error falling like l^4 (S - G of (S12) is of order K^-4).
"""

from __future__ import annotations

import csv
import json
from pathlib import Path

import numpy as np
import pytest

from moving_bogie import load_parameters, sleeper_series
from moving_bogie.cli import main

#: examples/sleepers.toml's UIC60 rail and wheel (its SI values, per rail)
RAIL = {"EI": 6.42e6, "m": 60.21, "c_f": 2.0e3, "M": 600.0, "P": 6.4e4, "v": 40.0}
K_PER_M, C_PER_M = 1.0e8, 5.0e4  # N/m^2, N s/m^2: k_sup / l and c_sup / l


def _file(tmp_path, vehicle: str = "mass", name: str = "track.toml", **physical: float):
    values = RAIL | {"l": 0.6, "k_sup": K_PER_M * 0.6, "c_sup": C_PER_M * 0.6} | physical
    text = f'[model]\nbeam = "eb"\ntrack = "sleepers"\nvehicle = "{vehicle}"\n\n[physical]\n'
    text += "".join(f"{key} = {value!r}\n" for key, value in values.items())
    path = tmp_path / name
    path.write_text(text)
    return path


BOGIE = {"M": 1000.0, "M_b": 2600.0, "J_b": 2200.0, "k_v": 1.2e6, "c_v": 1.0e4, "d": 2.5, "P": 8.0e4}


@pytest.mark.parametrize(
    ("vehicle", "extra"),
    [("mass", {}), ("hertz_mass", {"k_H": 1.4e9}), ("bogie", BOGIE)],
    ids=["mass", "hertz_mass", "bogie"],
)
def test_the_mean_contact_force_is_the_static_load(tmp_path, vehicle, extra):
    """Over a bay each wheel presses on the rail with its static load on average, at any bay, speed and
    number of harmonics: the harmonic n = 0 of (S17) sees D_v(0) = K only, whose springs carry no mean
    force. Checked both on F_0 and on the mean of the series sampled over one bay (the periodic trapezoid
    rule, exact for the harmonics kept when the points exceed 2N)."""
    _, physical = load_parameters(_file(tmp_path, vehicle, **extra))
    series = sleeper_series(physical, points=129, free=False).bay
    assert series is not None and series.converged
    P = float(physical.P)
    assert series.wheels == (2 if vehicle == "bogie" else 1)
    np.testing.assert_allclose(series.force_mean, P, rtol=1e-12)
    np.testing.assert_allclose(np.mean(series.contact_force[:, :-1], axis=1), P, rtol=1e-12)
    # the force does vary over the bay (the test is not about a constant)
    assert np.all(series.force_peak_to_peak > 1e-3 * P)


def _continuous_steady(bay_free_values: dict) -> float:
    """The continuous one-layer track with the smeared supports: its steady deflection under the wheel [m],
    the steady part of the closed form (the paper's Eq. (39)) of the continuous model's public API (whose
    JSON has the keys every track's series has)."""
    from moving_bogie.api import closed_form_response
    from moving_bogie.model.physical import PhysicalParams
    from moving_bogie.response.closed_form import SERIES_KEYS

    values = bay_free_values | {"k_f": K_PER_M, "c_f": C_PER_M + RAIL["c_f"]}
    params = PhysicalParams(beam="eb", track="one-layer", vehicle="mass", **values)
    series = closed_form_response(params, [0.0], branch_cut=False, dps=15)
    assert set(SERIES_KEYS) <= set(series.to_dict())
    return float(series.steady[series.names[0]])


def test_short_bays_give_the_continuous_tracks_steady_deflection(tmp_path):
    """l -> 0 with k_sup / l and c_sup / l fixed: the largest distance of the deflection under the wheel
    from the continuous track's steady deflection falls like l^4 (log2 of the ratio per halving within
    0.7 of 4) once the bay is short against the rail's wavelength (l chi = 0.21 at l = 0.15 m; from the
    example's 0.6 m to 0.3 m it falls faster, by 2^6.7), and the series' own dashed-line value is that of the
    continuous model."""
    reference = _continuous_steady({k: RAIL[k] for k in ("EI", "m", "M", "P", "v")})
    errors = []
    for bay in (0.15, 0.075, 0.0375):
        path = _file(tmp_path, l=bay, k_sup=K_PER_M * bay, c_sup=C_PER_M * bay)
        series = sleeper_series(load_parameters(path)[1], points=65, free=False).bay
        assert series is not None and series.converged
        assert series.continuous_deflection is not None
        assert abs(series.continuous_deflection[0] - reference) < 1e-10 * reference
        errors.append(np.max(np.abs(series.deflection[0] - reference)))
    rates = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all(np.abs(rates - 4) < 0.7), (errors, rates)
    assert errors[-1] < 1e-6 * reference


def test_json_csv_and_figure_are_complete(tmp_path, capsys):
    """One run writes JSON (stdout), CSV and PNG: every series has the points asked for over the bays, the
    CSV's columns are the JSON's series, the free vibrations carry their count and verdict."""
    path = _file(tmp_path)
    out_csv, out_png = tmp_path / "bay.csv", tmp_path / "bay.png"
    argv = ["timeseries", "--file", str(path), "--bays", "2", "--points", "17", "--json"]
    assert main([*argv, "--csv", str(out_csv), "--plot", str(out_png)]) == 0
    data = json.loads(capsys.readouterr().out)
    steady, free = data["steady_bay"], data["free"]
    from moving_bogie.response.closed_form import SERIES_KEYS

    assert set(SERIES_KEYS) <= set(data)  # the continuous tracks' keys, same meaning
    assert data["tau"] == steady["time_s"] and data["responses"]["w"] == steady["deflection_m"][0]
    assert data["steady"] == {"w": steady["wheels"][0]["deflection_mean_m"]} and data["units"]["w"] == "m"
    assert data["model"] == "eb/sleepers/mass" and data["l_m"] == 0.6 and data["v_m_s"] == 40.0
    assert data["Omega0_rad_s"] == pytest.approx(2 * np.pi * 40.0 / 0.6, rel=1e-14)
    assert steady["converged"] is True and steady["change"] < steady["tol"]
    assert len(steady["time_s"]) == 17 and steady["position_m"][-1] == pytest.approx(1.2, rel=1e-14)
    assert np.shape(steady["contact_force_N"]) == (1, 17) == np.shape(steady["deflection_m"])
    (wheel,) = steady["wheels"]
    assert set(wheel) >= {
        "force_mean_N",
        "force_peak_to_peak_N",
        "deflection_mean_m",
        "continuous_deflection_m",
    }
    assert {"count", "roots", "verdict", "notes", "strip_rad_s", "window_im_rad_s"} <= set(free)
    assert free["verdict"] in ("stable", "unstable", "undetermined")
    assert free["count"] == len(free["roots"])
    lines = out_csv.read_text().splitlines()
    assert lines[0] == "t,x,F_0,w_0" and lines[1] == "# units: s,m,N,m"
    rows = list(csv.reader(lines[2:]))
    assert len(rows) == 17
    table = np.array(rows, dtype=float)
    np.testing.assert_array_equal(table[:, 0], steady["time_s"])
    np.testing.assert_array_equal(table[:, 2], steady["contact_force_N"][0])
    np.testing.assert_array_equal(table[:, 3], steady["deflection_m"][0])
    assert out_png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize(
    ("argv", "option"),
    [
        (["--case", "1"], "--case"),
        (["--beam", "tr"], "--beam"),
        (["--S", "100"], "--S"),
        (["--r", "0.03"], "--r"),
        (["--alpha", "0.3"], "--alpha"),
        (["--tmax", "5"], "--tmax"),
        (["--tau", "1,2"], "--tau"),
        (["--no-branch-cut"], "--branch-cut"),
        (["--plot-long", "x.png"], "--plot-long"),
        (["--dps", "20"], "--dps"),
        (["--bays", "0"], "--bays"),
        (["--points", "1"], "--points"),
        (["--set", "k_sup"], "--set"),
    ],
)
def test_an_option_that_does_not_apply_is_named(tmp_path, capsys, argv, option):
    """Each refused option is named in one line, exit status 2, before any computation."""
    assert main(["timeseries", "--file", str(_file(tmp_path)), *argv]) == 2
    err = capsys.readouterr().err
    assert err.startswith("moving-bogie: error: ") and err.count("\n") == 1, err
    assert option in err, err


def test_an_unknown_set_key_and_bays_on_a_continuous_file_are_named(tmp_path, capsys):
    assert main(["timeseries", "--file", str(_file(tmp_path)), "--set", "k_spr=1e8"]) == 2
    assert "'k_spr'" in capsys.readouterr().err
    continuous = Path(__file__).resolve().parent.parent / "examples" / "uic60-bogie.toml"
    assert main(["timeseries", "--file", str(continuous), "--bays", "2"]) == 2
    assert "--bays" in capsys.readouterr().err


def test_growth_rate_and_doubling_time_of_a_root():
    """e^{i Omega t} with Im Omega = -2 1/s has modulus e^{2 t}: it doubles in ln 2 / 2 s; Im Omega = +3
    halves in ln 2 / 3 s."""
    from moving_bogie.response.bay_response import FreeVibration

    growing, decaying = FreeVibration(100 - 2j), FreeVibration(50 + 3j)
    t = growing.doubling_time
    assert t is not None and abs(np.exp(1j * growing.Omega * t)) == pytest.approx(2, rel=1e-14)
    t = decaying.halving_time
    assert t is not None and abs(np.exp(1j * decaying.Omega * t)) == pytest.approx(0.5, rel=1e-14)
    assert (growing.state, decaying.state) == ("growing", "decaying")
    assert growing.halving_time is None and decaying.doubling_time is None
    assert growing.frequency_hz == pytest.approx(100 / (2 * np.pi), rel=1e-15)


def test_the_series_takes_the_bound_model_and_its_scales(tmp_path):
    """The library's series takes the bound model and its SI scales, as the closed form does: the same
    series as the public entry; without scales (dimensionless parameters) it is refused by name, since its
    outputs are in s, m and N."""
    from moving_bogie import bind
    from moving_bogie.errors import ParameterError
    from moving_bogie.response.sleeper_series import sleeper_series as run

    params, physical = load_parameters(_file(tmp_path))
    public = sleeper_series(physical, points=33, free=False).bay
    own = run(bind(physical), physical.scales(), points=33, free=False).bay
    assert public is not None and own is not None
    assert np.array_equal(public.contact_force, own.contact_force) and own.continuous_deflection is None
    np.testing.assert_allclose(own.force_mean, RAIL["P"], rtol=1e-12)  # the static load P of the file
    with pytest.raises(ParameterError) as err:
        sleeper_series(params, points=33, free=False)
    assert err.value.parameter == "params"


def test_one_series_type_and_one_json_schema_on_every_track(tmp_path):
    """``mb.time_series`` gives a TimeSeries on sleepers and on the continuous track of the same smeared
    supports (``mb.smeared_track``): one type, whose JSON on sleepers holds every key of the continuous
    one (then its bay's), with the same steady deflection under the wheel within 1 % (the mean over a bay
    differs from the continuous track's by the bay's error only, which falls like l^4, the test above: 0.24 %
    at the file's l = 0.6 m). Times are refused by name on sleepers, and the bays on a continuous track."""
    from moving_bogie import smeared_track, time_series
    from moving_bogie.errors import ParameterError
    from moving_bogie.response.closed_form import TimeSeries

    _, physical = load_parameters(_file(tmp_path))
    on_sleepers = time_series(physical, points=9, free=False)
    continuous = time_series(smeared_track(physical), [0.0, 0.01], branch_cut=False, dps=15)
    assert type(on_sleepers) is type(continuous) is TimeSeries
    assert on_sleepers.bay is not None and continuous.bay is None
    assert set(continuous.to_dict()) <= set(on_sleepers.to_dict())
    assert on_sleepers.names == continuous.names[:1] and on_sleepers.response_units["w"] == "m"
    name = continuous.names[0]
    assert on_sleepers.steady[name] == pytest.approx(continuous.steady[name], rel=1e-2)
    with pytest.raises(ParameterError) as err:
        time_series(physical, [0.0, 0.01])
    assert err.value.parameter == "tau"


def test_the_closed_form_on_sleepers_is_refused_by_name(tmp_path):
    """No closed form exists on periodic supports: the public closed form and deflection shape name
    ``params`` and point to time_series, before any computation (not an error from deep inside)."""
    import moving_bogie as mb
    from moving_bogie.errors import ParameterError

    _, physical = load_parameters(_file(tmp_path))
    for call in (
        lambda: mb.closed_form_response(physical, [0.0, 0.01]),
        lambda: mb.deflection_shape(physical, [0.0, 1.0], 0.01),
    ):
        with pytest.raises(ParameterError, match="time_series") as err:
            call()
        assert err.value.parameter == "params"
