"""A vehicle on a track on the soil: the file, the bound model, the induced frequencies and the verdict.

References: the continuous Winkler track of the same bound parameters (``roots/frequencies.py``: residues,
the cut traced, its own far field; its kernel by residues and Brent's method for the threshold masses) for
a ballasted track on a rigid soil.
"""

from __future__ import annotations

import copy
from pathlib import Path

import mpmath
import numpy as np
import pytest
from scipy import optimize

from moving_bogie.api import bind, induced_frequencies, soil_vehicle
from moving_bogie.cli import main
from moving_bogie.errors import ParameterError
from moving_bogie.kernels.bound import BoundModel
from moving_bogie.kernels.continuous_track import ContinuousTrack
from moving_bogie.roots.verdict import UNSTABLE
from moving_bogie.soil.file import soil_input
from moving_bogie.soil.threshold import threshold_mass

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
def test_threshold_mass_on_rigid_soil_is_the_winkler_tracks():
    """D-decomposition along real Omega: on the rigid soil (the Winkler track of k_ref, above) at 1100 m/s the
    crossings of M = 1 / (Omega^2 G) are those of the continuous track's kernel by residues,
    G = 2 chi K / (pi k_ref) at Omega = q sqrt(k_ref / m), whose sign changes of Im 1/K brentq closes in on
    (no code of soil/ in the reference); to the receptance's 1e-4 of the rigid-soil approximation."""
    data = soil_input(_with(v=1100.0))
    vehicle = soil_vehicle(data)
    bound = bind(vehicle)
    k_ref, track = vehicle.rail.k_ref, data.track
    chi, omega_0 = (k_ref / (4 * track.EI)) ** 0.25, np.sqrt(k_ref / track.m)
    winkler = ContinuousTrack(BoundModel(bound.params))

    def inverse(q: float) -> complex:
        # just below the real axis: the undamped Winkler track's K there is the limit from below, which
        # the soil's (damped, analytic for Im q < 0) receptance takes on the axis
        G = 2 * chi * complex(winkler.receptance(q - 1e-10j).matrix[0, 0]) / (np.pi * k_ref)
        return 1 / G

    grid = np.geomspace(0.02, 4.0, 40)
    values = [inverse(q).imag for q in grid]
    ref = []
    for a, b, fa, fb in zip(grid[:-1], grid[1:], values[:-1], values[1:], strict=True):
        if fa * fb < 0:
            q = optimize.brentq(lambda x: inverse(x).imag, a, b, xtol=1e-14)
            M = inverse(q).real / (q * omega_0) ** 2
            if M > 0:
                ref.append(M)
    got = threshold_mass(track, data.soil, 1100.0, grid * omega_0)
    assert ref and len(got.crossings) == len(ref)
    for c, M in zip(sorted(got.crossings, key=lambda c: c.omega), ref, strict=True):
        assert abs(c.M / M - 1) < 1e-4
