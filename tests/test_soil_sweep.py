"""``sweep --file`` on a soil-track file (sweep/soil.py): the critical velocity per point.

References: each stored point against the single-point command ``critical-velocity --file F --set KEY=X``
(the same file edited by --set, tests/test_soil_settings.py); the store's placement of the points against
the inputs themselves (a stand-in critical velocity that returns the point's own values); refusals name the
option before any computation.
"""

from __future__ import annotations

import json
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from moving_bogie.cli import main
from moving_bogie.sweep.store import open_sweep

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
BALLASTED = str(EXAMPLES / "soil-ballasted.toml")
HOMOGENEOUS = str(EXAMPLES / "soil-homogeneous.toml")


def _echo(track, soil, omega=None):
    """A stand-in for critical_velocity: v_cr = the top layer's c_s + EI/1e6, omega_cr = the layer's h, a note
    where h = 4."""
    c_s, h = soil.layers[0].c_s, soil.layers[0].h
    notes = ("a note",) if h == 4 else ()
    return SimpleNamespace(
        v_cr=c_s + track.EI / 1e6, omega_cr=h, v_cr_uncoupled=c_s, omega_uncoupled=np.nan, notes=notes
    )


def test_points_are_stored_at_their_values(tmp_path, capsys, monkeypatch):
    """A 3 x 2 grid over c_s1 and h1 (with --set EI): each stored value is that of its own point."""
    monkeypatch.setattr("moving_bogie.soil.critical.critical_velocity", _echo)
    out = tmp_path / "s.zarr"
    argv = ["sweep", "--file", BALLASTED, "--vary", "c_s1=60:100:3", "--vary", "h1=2,4"]
    assert main([*argv, "--set", "EI=2e7", "--out", str(out), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["points_computed"] == 6 and summary["unstable_fraction"] is None
    assert summary["uncertain_points"] == 3  # the points of h1 = 4, noted
    assert summary["units"]["c_s1"] == "m/s" and summary["units"]["h1"] == "m"
    assert summary["v_cr_min"] == {"v_cr": pytest.approx(60 + 20), "c_s1": 60.0, "h1": 2.0}
    ds = open_sweep(out).compute()
    assert ds.attrs["kind"] == "soil" and ds.c_s1.attrs["units"] == "m/s"
    c_s, h = np.meshgrid(ds.c_s1.values, ds.h1.values, indexing="ij")
    np.testing.assert_allclose(ds.v_cr.values, c_s + 20.0, rtol=1e-12)
    np.testing.assert_allclose(ds.omega_cr.values, h, rtol=0)
    assert ds.found.values.all() and ds.computed.values.all()
    assert ds.noted.values.tolist() == [[False, True]] * 3
    assert json.loads(ds.attrs["operating_point"])["h1"] == 5.0  # the file's own top layer
    figure = tmp_path / "v.png"
    assert main(["sweep-plot", str(out), "--x", "c_s1", "--y", "h1", "--out", str(figure)]) == 0
    assert figure.stat().st_size > 10_000


@pytest.mark.parametrize(
    ("options", "words"),
    [
        (["--vary", "P=1e5:2e5:3"], ["P", "does not enter"]),
        (["--vary", "cs1=40:120:3"], ["--vary", "c_s1"]),
        (["--vary", "c_s1=-40:120:3"], ["--vary c_s1", "positive"]),
        (["--vary", "c_p1=300:400:3"], ["c_p1", "E1"]),
        (["--vary", "c_s1=40:120:3", "--roots"], ["--roots", "soil-track"]),
        (["--vary", "c_s1=40:120:3", "--alpha", "0.5"], ["--alpha", "soil-track"]),
        (["--vary", "c_s1=40:120:3", "--set", "h4=2"], ["h4", "half-space"]),
    ],
)
def test_bad_options_are_named_before_any_computation(tmp_path, capsys, monkeypatch, options, words):
    def never(*args, **kwargs):
        raise AssertionError("computed")

    monkeypatch.setattr("moving_bogie.soil.critical.critical_velocity", never)
    out = tmp_path / "s.zarr"
    assert main(["sweep", "--file", BALLASTED, *options, "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert all(word in err for word in words) and "Traceback" not in err
    assert not out.exists()


@pytest.mark.slow
def test_sweep_equals_the_single_point_command_and_resumes(tmp_path, capsys):
    """An interrupted 2-point sweep over c_s1, resumed; each point against ``critical-velocity --set``."""
    import tomllib

    from moving_bogie.sweep.engine import run_sweep
    from moving_bogie.sweep.soil import make_soil_spec

    data = tomllib.loads(Path(HOMOGENEOUS).read_text(encoding="utf-8"))
    spec = make_soil_spec(data, HOMOGENEOUS, {"c_s1": "55,70"})
    out = tmp_path / "s.zarr"

    def interrupt(index: int) -> None:
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        run_sweep(spec, out, on_block=interrupt)
    argv = ["sweep", "--file", HOMOGENEOUS, "--vary", "c_s1=55,70", "--out", str(out), "--resume", "--json"]
    assert main(argv) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["points_computed"] == 1 and summary["blocks"] == [1, 2]
    ds = open_sweep(out).compute()
    for k, c_s in enumerate(["55", "70"]):
        assert main(["critical-velocity", "--file", HOMOGENEOUS, "--set", f"c_s1={c_s}", "--json"]) == 0
        ref = json.loads(capsys.readouterr().out)
        point = ds.isel(c_s1=k)
        assert float(point.v_cr) == ref["v_cr"] and float(point.omega_cr) == ref["omega_cr"]
        assert float(point.v_cr_uncoupled) == ref["v_cr_uncoupled"]
