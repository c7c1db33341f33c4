"""A vehicle on a track on the soil: the file, the bound model, the induced frequencies and the verdict.

References: the continuous Winkler track of the same bound parameters (``roots/frequencies.py``: residues,
the cut traced, its own far field) for a ballasted track on a rigid soil; (slow) the winding number of the
same characteristic function on every cell of a coarse grid over the window (a brute-force count that
places each root in its cell, with no use of the search's bisection or moments).
"""

from __future__ import annotations

import copy
import json
from pathlib import Path

import mpmath
import numpy as np
import pytest

from moving_bogie.api import bind, induced_frequencies, load_soil_vehicle, soil_vehicle
from moving_bogie.cli import main
from moving_bogie.errors import ParameterError
from moving_bogie.kernels.bound import BoundModel
from moving_bogie.roots.count.contour import Rectangle, winding_number
from moving_bogie.roots.quadrature_window import QuadratureCharacteristic
from moving_bogie.roots.verdict import UNSTABLE
from moving_bogie.soil.file import soil_input

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
RIGID = {
    "model": {"track": "ballasted-soil", "vehicle": "mass"},
    "physical": {
        "EI": 1.29e7, "m": 120.0, "k_pad": 5e8, "c_pad": 0.0, "m_s": 0.0, "E_b": 130e6, "rho_b": 1e-3,
        "h_b": 0.35, "A_b": 1.25, "b": 1.25, "P": 1e5, "M": 3000.0, "v": 60.0,
    },
    "soil": [{"rho": 2000.0, "c_s": 1e5, "nu": 0.33, "eta": 1e-6}],
}  # fmt: skip


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


@pytest.mark.slow
def test_rigid_soil_roots_are_those_of_the_winkler_track():
    """A heavy mass faster than the Winkler track's critical velocity (v_ref = 963 m/s here) is unstable on
    it; on the rigid soil (the Winkler track of k_ref to 1e-4, test_soil_receptance.py) the same roots with
    Im q < 0, to the receptance's 1e-3 and the roots' own confirmed digits."""
    vehicle = soil_vehicle(soil_input(_with(v=1100.0, M=20000.0)))
    soil = induced_frequencies(vehicle)
    winkler = induced_frequencies(BoundModel(bind(vehicle).params))
    growing = [r for r in winkler.roots if mpmath.im(r.q) < 0]
    assert winkler.verdict.state == UNSTABLE and soil.verdict.state == UNSTABLE
    assert soil.count == len(growing) == len(soil.roots)
    for root in soil.roots:
        nearest = min(abs(complex(root.q) - complex(r.q)) for r in growing)
        assert nearest < 1e-3 * abs(complex(root.q))


@pytest.mark.slow
def test_example_count_and_roots_against_winding_on_a_grid(capsys):
    """The window of examples/soil-mass.toml cut into 3 x 3 cells, each counted by its own winding number
    (the same characteristic function, sampled afresh): the cells' counts add up to the search's count and
    each root found lies in a cell that holds one; the command prints the same roots in its JSON."""
    vehicle = load_soil_vehicle(EXAMPLES / "soil-mass.toml")
    result = induced_frequencies(vehicle)
    bound = bind(vehicle)
    E = QuadratureCharacteristic(bound)
    w = result.window
    xs, ys = np.linspace(w.x0, w.x1, 4), np.linspace(w.y0, w.y1, 4)
    cells = [Rectangle(xs[i], xs[i + 1], ys[j], ys[j + 1]) for i in range(3) for j in range(3)]
    counts = [winding_number(E, c, spacing=min(c.width, c.height) / 8, max_points=4000) for c in cells]
    assert sum(counts) == result.count == len(result.roots)
    for root in result.roots:
        q = complex(root.q)
        assert any(n >= 1 and c.contains(q) for c, n in zip(cells, counts, strict=True))
    assert main(["frequencies", "--file", str(EXAMPLES / "soil-mass.toml"), "--json"]) in (0, 1)
    out = json.loads(capsys.readouterr().out)
    assert out["verdict"]["state"] == result.verdict.state
    assert len(out["roots"]) == len(result.roots)
