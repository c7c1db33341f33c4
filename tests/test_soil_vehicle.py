"""A vehicle on a track on the soil: the file, the bound model, the induced frequencies and the verdict.

References: the file's values as given (per track) against the same values given per rail; the messages
name the key. The search itself is tested through a continuous track's receptance
(tests/test_quadrature_window.py) and the soil's receptance against independent quadratures
(tests/test_soil_receptance.py).
"""

from __future__ import annotations

import copy
from pathlib import Path

import pytest
from soil_cases import RIGID

from moving_bogie.api import soil_vehicle
from moving_bogie.cli import main
from moving_bogie.errors import ParameterError
from moving_bogie.soil.file import soil_input

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def _with(**changes: object) -> dict:
    data = copy.deepcopy(RIGID)
    data["physical"].update(changes)
    return data


def test_file_per_rail_doubles_the_vehicle_like_the_track():
    """Per rail, the masses and loads (kg, N) double with EI and m; the speed does not."""
    per_track = soil_vehicle(soil_input(RIGID)).physical
    data = _with(EI=1.29e7 / 2, m=60.0, k_pad=2.5e8, A_b=0.625, P=5e4, M=1500.0)
    data["model"]["per"] = "rail"
    per_rail = soil_vehicle(soil_input(data)).physical
    for key in ("EI", "m", "P", "M", "v", "k_f"):
        assert getattr(per_rail, key) == getattr(per_track, key), key


@pytest.mark.parametrize(
    ("change", "parameter"),
    [({"k_f": 1e8}, "k_f"), ({"M": -1.0}, "M"), ({"Q": 1.0}, "Q")],
)
def test_file_errors_name_the_key(change: dict, parameter: str):
    with pytest.raises(ParameterError) as info:
        soil_vehicle(soil_input(_with(**change)))
    assert info.value.parameter == parameter


def test_frequencies_command_on_a_bad_soil_file_exits_2(tmp_path, capsys):
    path = tmp_path / "bad.toml"
    text = (EXAMPLES / "soil-mass.toml").read_text().replace('vehicle = "mass"', 'vehicle = "mas"')
    path.write_text(text)
    assert main(["frequencies", "--file", str(path), "--json"]) == 2
    assert "vehicle" in capsys.readouterr().out  # --json: the error as JSON on stdout


def test_the_soil_has_a_public_api():
    """Notebook 10-soil runs on ``moving_bogie``'s public names alone; each is the function of its module."""
    import moving_bogie as mb
    from moving_bogie.soil.critical import critical_velocity

    names = ("load_soil_file", "load_soil_vehicle", "soil_modes", "moving_load", "threshold_mass")
    names += ("dispersion_figure", "moving_load_figure", "soil_critical_velocity")
    assert all(callable(getattr(mb, name)) for name in names)
    assert mb.soil_critical_velocity is critical_velocity
    notebook = (Path(__file__).resolve().parent.parent / "notebooks" / "10-soil.py").read_text("utf-8")
    assert "from moving_bogie." not in notebook and "import moving_bogie as mb" in notebook


def test_threshold_mass_refuses_a_mass_axis_without_masses():
    import moving_bogie as mb

    vehicle = mb.load_soil_vehicle(EXAMPLES / "soil-unstable.toml")
    with pytest.raises(ParameterError, match="M_max must be a positive mass"):
        mb.threshold_mass(vehicle, M_max=0.0)


@pytest.mark.parametrize("command", ["timeseries", "validate", "frequency-lines", "compare-tracks", "params"])
def test_a_command_that_takes_no_soil_file_names_those_that_do(command, capsys):
    """A soil example given to a command of the other tracks: one message naming the commands that take it
    (not a complaint about its [[soil]] tables), exit status 2."""
    from moving_bogie.model.files import SOIL_COMMANDS

    assert main([command, "--file", str(EXAMPLES / "soil-mass.toml")]) == 2
    err = capsys.readouterr().err
    assert "a track on soil" in err and all(name in err for name in SOIL_COMMANDS), err
    assert "Traceback" not in err
