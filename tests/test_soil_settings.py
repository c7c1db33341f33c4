"""``--set KEY=VALUE`` on a soil-track file (soil/settings.py): the run equals the run of the file edited.

Reference: a copy of the example file edited as text in the test (the value replaced, or for a layer that
gives E and nu, E replaced by c_s), read by the file's own reader; refusals name the key.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from moving_bogie.api import load_soil_vehicle
from moving_bogie.cli import main
from moving_bogie.errors import ParameterError
from moving_bogie.soil.file import load_soil_file

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def _edited(tmp_path: Path, name: str, old: str, new: str) -> Path:
    """A copy of the example ``name`` with the first line that starts with ``old`` replaced by ``new``."""
    lines = (EXAMPLES / name).read_text(encoding="utf-8").splitlines()
    index = next(i for i, line in enumerate(lines) if line.startswith(old))
    lines[index] = new
    path = tmp_path / name
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def test_set_equals_the_edited_file_track_and_layer_keys(tmp_path):
    """EI (a track key) and c_s1 on a layer given by E and nu: c_s replaces E, nu is held."""
    text = (EXAMPLES / "soil-ballasted.toml").read_text(encoding="utf-8")
    edited = tmp_path / "soil-ballasted.toml"
    edited.write_text(text.replace("EI = 1.29e7", "EI = 2.1e7").replace("E = 2.67e7", "c_s = 90", 1), "utf-8")
    changed = load_soil_file(EXAMPLES / "soil-ballasted.toml", {"EI": 2.1e7, "c_s1": 90.0})
    assert changed == load_soil_file(edited)
    assert changed != load_soil_file(EXAMPLES / "soil-ballasted.toml")
    assert changed.soil.layers[0].c_s == pytest.approx(90.0, rel=1e-12)


def test_set_dispersion_command_equals_the_edited_file(tmp_path, capsys):
    """The whole JSON of ``dispersion --set`` is that of the edited file (a soil key and a rail key)."""
    edited = _edited(tmp_path, "soil-homogeneous.toml", "c_s = 60", "c_s = 70")
    text = edited.read_text(encoding="utf-8").replace("EI = 6.42e6", "EI = 7e6")
    edited.write_text(text, encoding="utf-8")
    base = ["dispersion", "--omega", "10,40", "--json", "--file"]
    assert main([*base, str(edited)]) == 0
    expected = json.loads(capsys.readouterr().out)
    file = str(EXAMPLES / "soil-homogeneous.toml")
    assert main([*base, file, "--set", "c_s1=70", "--set", "EI=7e6"]) == 0
    assert json.loads(capsys.readouterr().out) == expected
    assert main([*base, file]) == 0
    assert json.loads(capsys.readouterr().out) != expected


def test_set_vehicle_key_equals_the_edited_file(tmp_path):
    """M and v of a file with a vehicle: its SI parameters are those of the edited file."""
    text = (EXAMPLES / "soil-mass.toml").read_text(encoding="utf-8")
    edited = tmp_path / "soil-mass.toml"
    edited.write_text(text.replace("M = 2000", "M = 2500").replace("v = 50", "v = 65"), encoding="utf-8")
    changed = load_soil_vehicle(EXAMPLES / "soil-mass.toml", {"M": 2500.0, "v": 65.0})
    assert changed.physical == load_soil_vehicle(edited).physical
    assert float(changed.physical.M) == 2500.0


@pytest.mark.parametrize(
    ("setting", "words"),
    [
        ("cs1=90", ["cs1", "c_s1", "k_pad", "eta4"]),  # unknown: the close key and every allowed one
        ("h4=3", ["h4", "half-space"]),  # the last layer has no depth
        ("c_p1=300", ["c_p1", "E1", "nu1"]),  # fits no stiffness form of layer 1 (E and nu)
        ("c_s1=-90", ["c_s", "soil[1]", "positive"]),  # the file's own check
        ("nu2=0.5", ["nu", "soil[2]"]),
        ("k_pad=0", ["k_pad", "positive"]),
        ("EI=abc", ["EI=abc", "NAME=NUMBER"]),
    ],
)
def test_set_refusals_name_the_key(setting, words, capsys):
    file = str(EXAMPLES / "soil-ballasted.toml")
    assert main(["dispersion", "--file", file, "--omega", "10", "--set", setting]) == 2
    err = capsys.readouterr().err
    assert "--set" in err and "Traceback" not in err
    for word in words:
        assert word in err


def test_set_vehicle_refusal_names_the_key():
    with pytest.raises(ParameterError, match="--set: M must be a positive"):
        load_soil_vehicle(EXAMPLES / "soil-mass.toml", {"M": -3.0})


@pytest.mark.slow
def test_set_critical_velocity_equals_the_edited_file(tmp_path, capsys):
    """``critical-velocity --file --set`` on the ballasted example against the edited file (h1, k_pad)."""
    text = (EXAMPLES / "soil-ballasted.toml").read_text(encoding="utf-8")
    edited = tmp_path / "soil-ballasted.toml"
    edited.write_text(text.replace("h = 5.0", "h = 3.0").replace("k_pad = 5e8", "k_pad = 3e8"), "utf-8")
    assert main(["critical-velocity", "--file", str(edited), "--json"]) == 0
    expected = json.loads(capsys.readouterr().out)
    argv = ["critical-velocity", "--file", str(EXAMPLES / "soil-ballasted.toml"), "--json"]
    assert main([*argv, "--set", "h1=3", "--set", "k_pad=3e8"]) == 0
    assert json.loads(capsys.readouterr().out) == expected


def test_json_params_state_the_track_they_stand_for():
    """``params`` of a vehicle on the soil keeps every key of every track's and says what it is."""
    from types import SimpleNamespace

    from moving_bogie.cli.soil_frequencies_cmd import equivalent_params
    from moving_bogie.model.cases import table1_case

    params = table1_case(1)
    soil = {"track": "ballasted-soil", "per": "track", "k_ref": 3.5e7, "layers": [{}, {}]}
    run = SimpleNamespace(result=SimpleNamespace(params=params), soil=soil)
    out = equivalent_params(run)  # type: ignore[arg-type]
    assert {k: v for k, v in out.items() if k != "equivalent_of"} == params.to_dict()
    assert (
        "ballasted-soil track on 2-layer soil" in out["equivalent_of"] and "3.5e+07" in out["equivalent_of"]
    )


@pytest.mark.slow
def test_frequencies_set_on_the_soil_json(tmp_path, capsys):
    """``frequencies --file soil-mass.toml --set M=2500 --json``: ``params`` are the groups of the vehicle
    read with the setting (its SI values scaled with k_ref, api.soil_vehicle), the equivalent track named."""
    argv = ["frequencies", "--file", str(EXAMPLES / "soil-mass.toml"), "--set", "M=2500", "--json"]
    main(argv)
    out = json.loads(capsys.readouterr().out)
    assert out["params"]["track"] == "one-layer" and "ballasted-soil" in out["params"]["equivalent_of"]
    vehicle = load_soil_vehicle(EXAMPLES / "soil-mass.toml", {"M": 2500.0})
    assert out["params"] == vehicle.physical.to_dimensionless().to_dict() | {
        "equivalent_of": out["params"]["equivalent_of"]
    }
    assert out["soil"]["k_ref"] == vehicle.rail.k_ref


@pytest.mark.parametrize("command", ["instability-lines", "stability-map"])
def test_set_reaches_the_threshold_and_the_map(command, capsys):
    """``--set`` on the D-decomposition commands goes through the same reader as ``frequencies`` (whose
    result equals the edited file's, above): a wrong value is named before any work, exit 2."""
    file = str(EXAMPLES / "soil-mass.toml")
    assert main([command, "--file", file, "--set", "M=-3"]) == 2
    err = capsys.readouterr().err
    assert "--set: M must be a positive" in err and "Traceback" not in err
    assert main([command, "--file", file, "--set", "M=-3", "--json"]) == 2
    assert json.loads(capsys.readouterr().out)["option"] == "--set"
