"""A wheel on a linearised Hertz spring (vehicle hertz_mass) tends to the rigid contact as k_H -> infinity.

References: the rigid-contact wheel ``mass`` (the paper's moving mass, its roots searched independently by the
same argument principle on the same track), and first-order perturbation of the block determinant: with
kd = kappa_H + 2 i eta_H q the Hertz wheel's determinant is kd E_mass(q) - pi eta_M q^2 (E_mass = pi + 2 K
(-eta_M q^2), kernels/coupling.py), so its root lies at q_mass + pi eta_M q^2 / (kappa_H E_mass'(q)) +
O(kappa_H^-2): the distance to the rigid root falls like 1 / kappa_H (ratio 10 per decade).
"""

from __future__ import annotations

import pytest

from moving_bogie.api import induced_frequencies
from moving_bogie.generated import vehicle_hertz_mass, vehicle_mass
from moving_bogie.kernels.hill import FloquetSystem, VehicleMatrices
from moving_bogie.kernels.sleeper_track import SleeperTrack
from moving_bogie.model.catalogue import default_catalogue
from moving_bogie.model.params import DimensionlessParams

#: the catalogue's rails on periodic supports, (beam, track) -> their generated functions
PERIODIC = default_catalogue().periodic

CONTINUOUS = {"beam": "eb", "eta_f": "0.2", "alpha": "0.3", "eta_M": "2"}


def _root(vehicle: str, **groups: str) -> complex:
    params = DimensionlessParams.from_mapping({**CONTINUOUS, "vehicle": vehicle, **groups})
    result = induced_frequencies(params, dps=15)
    assert result.verdict.state == "stable", result.verdict  # the far field of a massless contact too
    (root,) = [complex(r.q) for r in result.roots]
    return root


def test_hertz_wheel_on_the_one_layer_track_tends_to_the_rigid_contact():
    """frequencies of hertz_mass on the continuous track: the one root (Re q >= 0) approaches the mass's
    as 1 / kappa_H (the distance falls by 10 per decade, between 9 and 11)."""
    rigid = _root("mass")
    errors = [abs(_root("hertz_mass", kappa_H=str(k)) - rigid) for k in (1e3, 1e4)]
    assert 9 < errors[0] / errors[1] < 11, errors
    assert errors[1] < 1e-4 * abs(rigid)


def _newton(f, q, h=1e-7):
    for _ in range(30):
        step = f(q) / ((f(q + h) - f(q - h)) / (2 * h))
        q -= step
        if abs(step) < 1e-12:
            break
    return q


def test_hertz_wheel_on_sleepers_tends_to_the_rigid_contact():
    """The Floquet root of hertz_mass on sleepers approaches that of mass as 1 / kappa_H (same track,
    same harmonics): the distance falls by 10 per decade."""
    track = SleeperTrack(
        PERIODIC["eb", "sleepers"], {"lam": 1.0, "alpha": 0.3, "kappa_f": 0.0, "eta_f": 0.0, "eta_sup": 0.2}
    )
    rigid = FloquetSystem(track, VehicleMatrices.from_module(vehicle_mass, {"eta_M": 2.0}), N=1, tol=1e-12)
    q0 = _newton(rigid, 0.69 + 0.11j)
    assert abs(rigid(q0)) < 1e-9 * abs(rigid(q0 + 0.1))
    errors = []
    for kappa in (1e3, 1e4):
        vehicle = VehicleMatrices.from_module(
            vehicle_hertz_mass, {"eta_M": 2.0, "kappa_H": kappa, "eta_H": 0.0}
        )
        errors.append(abs(_newton(FloquetSystem(track, vehicle, N=1, tol=1e-12), q0) - q0))
    assert 9 < errors[0] / errors[1] < 11, errors


@pytest.mark.parametrize("vehicle", ["mass", "hertz_mass"])
def test_hertz_and_mass_are_both_listed(vehicle, capsys):
    """``moving-bogie models`` lists the Hertz wheel beside the rigid one, and ``models NAME`` gives each on a
    continuous track."""
    from moving_bogie.cli import main

    assert main(["models"]) == 0
    vehicles = next(line for line in capsys.readouterr().out.splitlines() if line.startswith("  vehicles"))
    assert vehicle in vehicles.split(None, 1)[1].split(", ")
    assert main(["models", f"eb/one-layer/{vehicle}"]) == 0
    assert capsys.readouterr().out.startswith(f"eb/one-layer/{vehicle} ")
