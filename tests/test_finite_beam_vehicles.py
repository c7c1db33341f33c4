"""The finite beam under any generated vehicle: n moving contacts, every degree of freedom reported.

References, independent of the vehicle coupling they check:

* the steady deflection of constant moving forces on the infinite beam by QUADPACK quadrature
  (``moving_force_deflection`` of ``tests/test_finite_beam.py``): after the damped transient a vehicle
  moves without acceleration, so its wheels deflect like its static loads moving as forces;
* the paper's bogie on the same finite beam: a car whose secondary suspension vanishes is two bogies that
  interact only through the rail, and with the bogies far apart on a damped track each of them moves as the
  bogie alone;
* one wheel under a sprung mass with a rigid spring (``kappa_v`` large) against one moving mass of the
  total mass: the classical moving mass;
* the car's closed form (residues and branch cut from the block system of its generated matrices), which
  shares no code with the modal expansion, for ``validate``.
"""

from __future__ import annotations

from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
from test_finite_beam import moving_force_deflection

from moving_bogie.validation.finite_beam import simulate_finite_beam

#: A car per rail (dimensionless; the bogie groups as in Table 1's scale, the body about five times a bogie).
CAR = dict(
    eta_M=1.0,
    d=2.0,
    mu_v=1.7,
    J_b=0.4,
    kappa_v=0.2,
    eta_v=0.5,
    L_c=9.0,
    mu_c=8.0,
    J_c=60.0,
    kappa_sec=0.5,
    eta_sec=1.0,
)


def car(**changes) -> SimpleNamespace:
    return SimpleNamespace(beam="eb", vehicle="car", eta_s=0.0, **(CAR | changes))


@pytest.mark.slow
def test_car_converges_to_the_infinite_beam_steady_state():
    alpha, eta_f = 0.5, 0.2
    params = car(alpha=alpha, eta_f=eta_f)
    # the body's bounce on its secondary suspension is the slowest transient: below 1e-6 of the deflection
    # by tau = 120 (measured)
    result = simulate_finite_beam(params, 120.0, n_modes=400, length=170.0, entry=45.0)
    assert set(result.responses) == {
        "w_1",
        "w_2",
        "w_3",
        "w_4",
        "u_b1",
        "theta_b1",
        "u_b2",
        "theta_b2",
        "u_c",
        "theta_c",
    }
    xi = np.array([0.0, CAR["d"], CAR["L_c"], CAR["L_c"] + CAR["d"]])
    for j, name in enumerate(("w_1", "w_2", "w_3", "w_4")):
        steady = sum(moving_force_deflection(alpha, eta_f, shift=xi[j] - x) for x in xi)
        assert result.responses[name][-1] == pytest.approx(steady, rel=1e-3), name
    # Unloaded suspensions in the steady state: each bogie at the mean of its wheels, the body at theirs.
    u_b1 = 0.5 * (result.w_1[-1] + result.w_2[-1])
    u_b2 = 0.5 * (result.w_3[-1] + result.w_4[-1])
    assert result.u_b1[-1] == pytest.approx(u_b1, rel=1e-3)
    assert result.u_b2[-1] == pytest.approx(u_b2, rel=1e-3)
    assert result.u_c[-1] == pytest.approx(0.5 * (u_b1 + u_b2), rel=1e-3)


def test_car_without_secondary_suspension_is_two_bogies_far_apart():
    alpha, eta_f, L_c = 0.6, 0.3, 40.0
    params = car(alpha=alpha, eta_f=eta_f, kappa_sec=1e-12, eta_sec=0.0, L_c=L_c)
    grid = dict(n_modes=300, length=140.0, dt=0.02, tau_out=np.linspace(0.0, 30.0, 301))
    both = simulate_finite_beam(params, 30.0, entry=30.0, **grid)
    bogie = SimpleNamespace(
        beam="eb",
        vehicle="bogie",
        eta_s=0.0,
        alpha=alpha,
        eta_f=eta_f,
        **{k: CAR[k] for k in ("eta_M", "d", "mu_v", "J_b", "kappa_v", "eta_v")},
    )
    rear = simulate_finite_beam(bogie, 30.0, entry=30.0, **grid)
    front = simulate_finite_beam(bogie, 30.0, entry=30.0 + L_c, **grid)
    for car_names, alone in (
        (("w_1", "w_2", "u_b1", "theta_b1"), rear),
        (("w_3", "w_4", "u_b2", "theta_b2"), front),
    ):
        for name, own in zip(car_names, ("w_rear", "w_front", "u", "theta")):
            scale = np.max(np.abs(alone.responses[own]))
            difference = np.max(np.abs(both.responses[name] - alone.responses[own]))
            assert difference < 1e-3 * scale, (name, difference / scale)


def test_oscillator_with_a_rigid_spring_is_the_moving_mass():
    alpha, eta_f = 0.5, 0.1
    base = dict(beam="eb", eta_s=0.0, alpha=alpha, eta_f=eta_f)
    grid = dict(n_modes=200, length=80.0, entry=30.0, dt=0.02, tau_out=np.linspace(0.0, 20.0, 201))
    stiff = SimpleNamespace(vehicle="oscillator", eta_M=1.0, mu_v=2.0, kappa_v=1e4, eta_v=0.0, **base)
    mass = SimpleNamespace(vehicle="mass", eta_M=3.0, **base)
    sprung = simulate_finite_beam(stiff, 20.0, **grid)
    alone = simulate_finite_beam(mass, 20.0, **grid)
    scale = np.max(np.abs(alone.w))
    assert np.max(np.abs(sprung.w - alone.w)) < 1e-2 * scale
    assert np.max(np.abs(sprung.u - alone.w)) < 1e-2 * scale


@pytest.mark.slow
def test_validate_car_agrees_with_the_closed_form():
    # Reference: the closed form of the car (residues at its induced frequencies and the branch-cut part,
    # from the block system of its generated matrices), examples/car.toml (SI, per rail), tau <= 40.
    from moving_bogie.api import validate
    from moving_bogie.model.files import load_params_file

    params = load_params_file(Path(__file__).resolve().parents[1] / "examples" / "car.toml")[0]
    result = validate(params, tau_max=40.0, estimate=False)
    assert set(result.quantities) == {
        "w_1",
        "w_2",
        "w_3",
        "w_4",
        "u_b1",
        "theta_b1",
        "u_b2",
        "theta_b2",
        "u_c",
        "theta_c",
    }
    assert result.agrees and max(result.relative_diff.values()) < 2e-3, result.relative_diff
