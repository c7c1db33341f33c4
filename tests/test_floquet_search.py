"""Floquet roots in the strip: the principal parametric zone, convergence in the harmonics, the command.

References: the symmetry q -> Omega_0 - conj(q) of docs/sleepers.md (S14) puts the principal zone's root on
Re q = Omega_0 / 2 exactly; the argument principle (roots/count/contour.py) counts it with no guess; the
sleeper-passing frequency 2 pi v / l is computed here from the file's v and l.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from moving_bogie.cli import main
from moving_bogie.generated import vehicle_mass
from moving_bogie.kernels.hill import FloquetSystem, VehicleMatrices
from moving_bogie.kernels.sleeper_track import SleeperTrack
from moving_bogie.model.catalogue import default_catalogue
from moving_bogie.roots.count.contour import Rectangle, winding_number

#: the catalogue's rails on periodic supports, (beam, track) -> their generated functions
PERIODIC = default_catalogue().periodic

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "sleepers.toml"


def _newton(f, q, h=1e-7):
    for _ in range(30):
        step = f(q) / ((f(q + h) - f(q - h)) / (2 * h))
        q -= step
        if abs(step) < 1e-11:
            break
    return q


@pytest.mark.slow
def test_principal_parametric_zone_root_sits_on_half_the_passing_frequency():
    """A heavy, lightly damped wheel on long bays at 2 x its frequency = Omega_0: one root with Im q < 0
    counted in a box around Re q = Omega_0 / 2, on that line; one more harmonic moves it by 2e-6 (N = 1 to
    2), a tenth of that from N = 2 to 3: it converges in the harmonics."""
    track = SleeperTrack(
        PERIODIC["eb", "sleepers"],
        {"lam": 1.5, "alpha": 0.25, "kappa_f": 0.0, "eta_f": 0.0, "eta_sup": 0.005},
    )
    vehicle = VehicleMatrices.from_module(vehicle_mass, {"eta_M": 5.0})
    omega0 = track.Omega0
    system = FloquetSystem(track, vehicle, N=1, tol=1e-6)
    box = Rectangle(0.3 * omega0, 0.7 * omega0, -0.2 * omega0, -1e-3 * omega0)
    assert winding_number(system, box, spacing=box.width / 10) == 1
    system.tol = 1e-12
    q1 = _newton(system, box.center)
    assert box.contains(q1) and q1.imag < 0
    assert abs(q1.real - omega0 / 2) < 1e-9
    system.N = 2
    q2 = _newton(system, q1)
    system.N = 3
    q3 = _newton(system, q2)
    assert abs(q2.real - omega0 / 2) < 1e-9 and abs(q3.real - omega0 / 2) < 1e-9
    assert abs(q3 - q2) < 0.1 * abs(q2 - q1) < 1e-5


@pytest.mark.parametrize(
    "text, fragment",
    [
        ("k_sup = 6.0e7\nksup = 1", "ksup"),
        ("k_sup = -6.0e7", "k_sup must be a positive"),
        ("", "missing SI parameter 'k_sup'"),
    ],
)
def test_bad_sleeper_files_name_the_key(tmp_path, capsys, text, fragment):
    """One line naming the key, exit 2, before any computation."""
    path = tmp_path / "bad.toml"
    head = '[model]\nbeam = "eb"\ntrack = "sleepers"\nvehicle = "mass"\n[physical]\n'
    path.write_text(head + "EI = 6.4e6\nm = 60\nl = 0.6\nM = 600\nv = 40\n" + text + "\n")
    assert main(["frequencies", "--file", str(path)]) == 2
    assert fragment in capsys.readouterr().err


@pytest.mark.parametrize("setting, fragment", [("Mx=1200", "'Mx'"), ("k_sup=-1", "k_sup must be a positive")])
def test_set_on_a_sleeper_file_is_checked_as_the_file(capsys, setting, fragment):
    """--set NAME=VALUE reaches the sleeper file's [physical] values and is checked as they are."""
    assert main(["frequencies", "--file", str(EXAMPLE), "--set", setting]) == 2
    assert fragment in capsys.readouterr().err


@pytest.mark.parametrize(
    "extra, option",
    [(["--case", "1"], "--case"), (["--alpha", "0"], "--alpha"), (["--window", "0:1:-1:1"], "--window")],
)
def test_options_a_sleeper_file_does_not_take_are_named(capsys, extra, option):
    """A parameter option (the file sets every value; a zero counts as given), a case or a window: one
    line naming it, exit status 2, before the search (a case with a file as on every track)."""
    assert main(["frequencies", "--file", str(EXAMPLE), *extra]) == 2
    err = capsys.readouterr().err
    assert option in err and err.count("\n") == 1, err
    assert "sleeper" in err or "give either --case or --file, not both" in err, err


@pytest.mark.slow
def test_example_file_gives_the_strip_the_harmonics_and_a_verdict(capsys):
    """examples/sleepers.toml with --set v=45: Omega_0 = 2 pi v / l, the harmonics -N-1..N, converged, a
    verdict."""
    assert main(["frequencies", "--file", str(EXAMPLE), "--set", "v=45", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["region"]["Omega_0_rad_s"] == pytest.approx(2 * np.pi * 45 / 0.6, rel=1e-12)
    # converged in the harmonics: a strip search that is not has a "strip" reason and is undetermined
    assert out["verdict"]["state"] in ("stable", "unstable") and not out["verdict"]["reasons"]
    n = out["region"]["harmonics"]
    assert n == list(range(-n[-1] - 1, n[-1] + 1))
    assert out["count"] == len(out["roots"])
