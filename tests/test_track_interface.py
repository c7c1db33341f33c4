"""The track interface of the bound model (kernels/track_model.py): each track answers the same questions.

References: the continuous track's receptance against the defining integral K(xi, q) = int exp(i p xi)
Q(p, q) / N(p, q) dp (Eq. (29)) by mpmath's quadrature on the real p-axis (no residues); the periodic
track's receptance, coupled to a vehicle by the one coupling of kernels/coupling.py, against the Hill
determinant of kernels/hill.py, which assembles the same system in its own arithmetic (pi = 1).
"""

from __future__ import annotations

import importlib
import pickle
from pathlib import Path

import mpmath
import numpy as np
import pytest

from moving_bogie import bind, table1_case
from moving_bogie.kernels.arithmetic import Batched
from moving_bogie.kernels.continuous_track import ContinuousTrack
from moving_bogie.kernels.coupling import coupled_system, dynamic_stiffness, harmonic_blocks
from moving_bogie.kernels.hill import FloquetSystem, VehicleMatrices, harmonic_set
from moving_bogie.kernels.periodic_track import PeriodicTrack
from moving_bogie.kernels.sleeper_track import SleeperTrack
from moving_bogie.kernels.track_model import STRIP, WINDOW, Track
from moving_bogie.model.sleeper_input import load_sleeper_file

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def _kernel_by_quadrature(bound, q: complex, xi: float) -> complex:
    """K(xi, q) of Eq. (29) as the integral over real p itself."""
    module, args = bound.foundation, bound.foundation_mp()
    n = [mpmath.mpc(c) for c in module.n_coeffs(q, **args)]
    Q = [mpmath.mpc(c) for c in module.q_coeffs(q, **args)]

    def f(p: mpmath.mpf) -> mpmath.mpc:
        return mpmath.exp(1j * p * xi) * mpmath.polyval(Q, p) / mpmath.polyval(n, p)

    # panels of width 1/2 over |p| <= 40, then the tails (oscillating ones by mpmath's quadosc)
    middle = mpmath.quad(f, mpmath.linspace(-40, 40, 161))
    if xi == 0:
        tails = mpmath.quad(f, [-mpmath.inf, -40]) + mpmath.quad(f, [40, mpmath.inf])
    else:
        omega = abs(xi)
        tails = mpmath.quadosc(f, [-mpmath.inf, -40], omega=omega)
        tails += mpmath.quadosc(f, [40, mpmath.inf], omega=omega)
    return complex(middle + tails)


def _check_entry(i: int, j: int) -> None:
    bound = bind(table1_case(1))
    track = bound.track
    assert isinstance(track, ContinuousTrack) and isinstance(track, Track)
    assert track.search_region().kind == WINDOW and track.kernel_decay == bound.kernel_decay
    q = 0.3 + 0.4j
    G = track.receptance(q).matrix
    reference = _kernel_by_quadrature(bound, q, float(bound.positions[i] - bound.positions[j]))
    assert abs(G[i, j] - reference) < 1e-9 * abs(reference)
    with pytest.raises(ValueError, match="harmonics"):
        track.receptance(q, harmonics=(-1, 0))


def test_continuous_track_receptance_is_the_kernel_of_eq_29_at_a_wheel() -> None:
    _check_entry(1, 1)


def test_continuous_track_receptance_is_the_kernel_of_eq_29_between_wheels() -> None:
    _check_entry(0, 1)


def test_the_kind_of_track_survives_replace_and_pickling() -> None:
    bound = bind(table1_case(1))
    other = type(bound)(bound.params, track=ContinuousTrack)
    assert other == bound  # the default kind, given explicitly
    assert pickle.loads(pickle.dumps(bound)) == bound
    assert bound.replace(alpha="0.3").track_factory is ContinuousTrack


def test_periodic_track_receptance_couples_as_the_hill_determinant() -> None:
    data = load_sleeper_file(EXAMPLES / "sleepers.toml")
    sleepers = SleeperTrack(data.foundation, data.groups)
    module = importlib.import_module("moving_bogie.generated.vehicle_mass")
    vehicle = VehicleMatrices.from_module(module, data.vehicle_groups)
    track = PeriodicTrack.on(sleepers, vehicle.positions)
    region = track.search_region(N=1)
    assert region.kind == STRIP and region.period == pytest.approx(sleepers.Omega0, rel=1e-15)
    assert region.harmonics == tuple(harmonic_set(1)) and track.kernel_decay is None
    q = 0.2 * sleepers.Omega0 - 0.05j
    h = np.array(region.harmonics)
    G = track.receptance(q, region.harmonics).matrix
    D, _ = dynamic_stiffness(q + h * sleepers.Omega0, vehicle.dynamic, Batched)
    A = coupled_system(harmonic_blocks(list(D), vehicle.contacts, Batched), G, Batched).A
    pairs = len(h) * vehicle.contacts
    hill = FloquetSystem(sleepers, vehicle, 1, tol=1e-12)(q)
    assert np.linalg.det(A) / np.pi**pairs == pytest.approx(hill, rel=1e-10)
