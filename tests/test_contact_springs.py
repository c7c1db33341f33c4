"""Every vehicle on Hertz contact springs: k_H (c_H) with any vehicle puts each wheel on its own spring.

References, each independent of the transformation under test (``derivations/vehicles.py:
on_contact_springs``):

- a direct assembly by hand, in this file, of the larger system from the rigid-contact vehicle's generated
  M, C, K: n massless contact points, each tied to its wheel by the spring-damper (kappa_H, 2 eta_H) (the
  dimensionless damping of a dashpot whose group is eta is 2 eta, Eq. (17), as ``c_v`` -> ``2 eta_v`` of the
  paper's bogie), compared by the characteristic determinant of the block system (docs of
  ``derivations/vehicles.py``) at random q and random kernel values;
- the rigid-contact vehicle's own roots, searched independently (the argument principle on a continuous
  track, Newton on the Floquet determinant on sleepers): as k_H -> infinity each contact spring locks, and
  first-order perturbation puts the Hertz vehicle's root at distance O(1 / kappa_H) from the rigid one (a
  ratio 10 per decade);
- the parameter files: ``vehicle = "mass"`` with ``k_H`` is the vehicle ``hertz_mass``.
"""

from __future__ import annotations

import importlib

import numpy as np
import pytest

from moving_bogie.generated import CONTACT_SPRINGS
from moving_bogie.kernels.hill import FloquetSystem, VehicleMatrices
from moving_bogie.kernels.sleeper_track import SleeperTrack
from moving_bogie.model.catalogue import default_catalogue
from moving_bogie.model.files import parse_params_toml

#: the catalogue's rails on periodic supports, (beam, track) -> their generated functions
PERIODIC = default_catalogue().periodic

RIGID = ("mass", "oscillator", "masses", "bogie", "car")


def _module(name: str):
    return importlib.import_module(f"moving_bogie.generated.vehicle_{name}")


def _matrices(module, values: dict) -> tuple[np.ndarray, ...]:
    args = {name: values[name] for name in module.MATRIX_ARGUMENTS}
    return tuple(
        np.array(f(**args), dtype=complex)
        for f in (module.mass_matrix, module.damping_matrix, module.stiffness_matrix)
    )


def _by_hand(rigid, values: dict) -> tuple[np.ndarray, ...]:
    """The rigid vehicle's M, C, K with n contact points put in front, each on (kappa_H, 2 eta_H)."""
    n = rigid.CONTACTS
    springs = {"stiffness": values["kappa_H"], "damping": 2 * values["eta_H"]}
    out = []
    for kind, A in zip(("mass", "damping", "stiffness"), _matrices(rigid, values)):
        total = A.shape[0] + n
        B = np.zeros((total, total), dtype=complex)
        B[n:, n:] = A
        if kind in springs:
            k = springs[kind]
            for j in range(n):  # spring between contact j and wheel j (DOF n + j): k (x_c - x_w)^2 / 2
                B[j, j] += k
                B[n + j, n + j] += k
                B[j, n + j] -= k
                B[n + j, j] -= k
        out.append(B)
    return tuple(out)


def _characteristic(matrices, n: int, kmat: np.ndarray, q: complex) -> complex:
    """det [[pi I + 2 Kmat D_cc, 2 Kmat D_ci], [D_ic, D_ii]], D = -q^2 M + i q C + K (Eqs. (21), (28))."""
    M, C, K = matrices
    D = -(q**2) * M + 1j * q * C + K
    A = D.copy()
    A[:n, :] = 2 * kmat @ D[:n, :]
    A[:n, :n] += np.pi * np.eye(n)
    return complex(np.linalg.det(A))


@pytest.mark.parametrize("name", RIGID)
def test_contact_spring_vehicle_is_the_direct_assembly(name):
    """det of the generated Hertz vehicle's block system == that of the hand-assembled one, at random q
    and random kernel matrices, to rounding (both are the same polynomial in the same numbers)."""
    rigid, hertz = _module(name), _module(CONTACT_SPRINGS[name])
    rng = np.random.default_rng(7)
    values = {g: float(rng.uniform(0.5, 3.0)) for g in (*hertz.MATRIX_ARGUMENTS, *rigid.MATRIX_ARGUMENTS)}
    n = rigid.CONTACTS
    assert hertz.CONTACTS == n and len(hertz.DOFS) == len(rigid.DOFS) + n
    assert np.allclose(
        hertz.contact_positions(**{g: values[g] for g in hertz.MATRIX_ARGUMENTS}),
        rigid.contact_positions(**{g: values[g] for g in rigid.MATRIX_ARGUMENTS}),
    )
    generated, hand = _matrices(hertz, values), _by_hand(rigid, values)
    for _ in range(3):
        q = complex(rng.normal(), rng.normal())
        kmat = rng.normal(size=(n, n)) + 1j * rng.normal(size=(n, n))
        a, b = _characteristic(generated, n, kmat, q), _characteristic(hand, n, kmat, q)
        assert abs(a - b) <= 1e-10 * max(abs(a), abs(b)), (a, b)


def test_mass_with_k_H_is_hertz_mass():
    """``vehicle = "mass"`` with k_H in [physical] is ``hertz_mass``; every other vehicle its own variant,
    on a continuous track and (kappa_H) in a [dimensionless] table."""
    text = (
        '[model]\nvehicle = "{v}"\n[physical]\nEI = 6.42e6\nm = 60.21\nk_f = 1.0e8\nc_f = 5.2e4\nM = 600\n'
        "k_H = 1.4e9\nP = 6.4e4\nv = 40\n"
    )
    params, _ = parse_params_toml(text.format(v="mass"))
    reference, _ = parse_params_toml(text.format(v="hertz_mass"))
    assert params.model.vehicle == "hertz_mass" and params == reference
    dimensionless, _ = parse_params_toml(
        '[model]\nvehicle = "masses"\n[dimensionless]\nalpha = 0.3\neta_f = 0.2\neta_M = 2\nd = 1\n'
        "kappa_H = 100\n"
    )
    assert dimensionless.model.vehicle == "hertz_masses"


def _newton(f, q: complex, h: float = 1e-7) -> complex:
    for _ in range(40):
        step = f(q) / ((f(q + h) - f(q - h)) / (2 * h))
        q -= step
        if abs(step) < 1e-12:
            break
    return q


SLEEPER_VEHICLES = {
    "masses": {"eta_M": 2.0, "d": 2.5},
    "bogie": {"eta_M": 2.0, "d": 2.5, "mu_v": 4.0, "J_b": 6.0, "kappa_v": 1.0, "eta_v": 0.1},
    "car": {
        "eta_M": 2.0,
        "d": 2.5,
        "mu_v": 4.0,
        "J_b": 6.0,
        "kappa_v": 1.0,
        "eta_v": 0.1,
        "L_c": 17.0,
        "mu_c": 30.0,
        "J_c": 700.0,
        "kappa_sec": 0.3,
        "eta_sec": 0.1,
    },
}


@pytest.mark.slow  # about 6 s each; test_hertz.py keeps the one-wheel case quick
@pytest.mark.parametrize("name", ["masses", "bogie", "car"])
def test_contact_spring_vehicle_on_sleepers_tends_to_the_rigid_contact(name):
    """The Floquet root of the Hertz vehicle on sleepers approaches the rigid vehicle's (found by Newton
    from the same start, same track and harmonics) as 1 / kappa_H: the distance falls by 10 per decade."""
    track = SleeperTrack(
        PERIODIC["eb", "sleepers"], {"lam": 1.0, "alpha": 0.3, "kappa_f": 0.0, "eta_f": 0.0, "eta_sup": 0.2}
    )
    values = SLEEPER_VEHICLES[name]
    rigid = FloquetSystem(track, VehicleMatrices.from_module(_module(name), values), N=1, tol=1e-12)
    q0 = _newton(rigid, 0.69 + 0.11j)
    assert abs(rigid(q0)) < 1e-9 * abs(rigid(q0 + 0.1))
    errors = []
    for kappa in (1e3, 1e4):
        hertz = _module(CONTACT_SPRINGS[name])
        vehicle = VehicleMatrices.from_module(hertz, values | {"kappa_H": kappa, "eta_H": 0.0})
        errors.append(abs(_newton(FloquetSystem(track, vehicle, N=1, tol=1e-12), q0) - q0))
    assert 9 < errors[0] / errors[1] < 11, errors


def _roots(params) -> tuple[str, list[complex]]:
    from moving_bogie.api import induced_frequencies

    result = induced_frequencies(params, dps=15)
    assert result.verdict.state in ("stable", "unstable"), result.verdict  # decided: every root counted
    return result.verdict.state, [complex(r.q) for r in result.roots]


def _continuous(name: str):
    """Parameters of each rigid vehicle on the continuous Euler-Bernoulli track: Table 1 case 1 for the
    bogie and the two masses, ``examples/car.toml`` for the car."""
    from pathlib import Path

    from moving_bogie.model.cases import table1_case
    from moving_bogie.model.files import load_parameters

    if name == "car":
        return load_parameters(Path(__file__).resolve().parents[1] / "examples" / "car.toml")[0]
    return table1_case(1).replace(vehicle=name)


@pytest.mark.slow  # 1-10 s each; test_hertz.py keeps the one-wheel case quick
@pytest.mark.parametrize("name", ["masses", "bogie", "car"])
def test_contact_spring_vehicle_on_a_continuous_track_tends_to_the_rigid_contact(name):
    """``frequencies`` of the Hertz vehicle: next to every root of the rigid vehicle (searched on its own
    by the argument principle) lies one of the Hertz vehicle's, at a distance that falls like 1 / kappa_H, and
    the verdicts agree (Table 1 case 1 is unstable on the bogie).

    kappa_H = 1e3 and 1e4, as on sleepers above: already in the 1 / kappa_H regime (every ratio within 0.5 %
    of 10 for the three vehicles), while the search at 1e5 costs two to five times as much (the stiff contact
    puts roots where the kernel varies fast)."""
    rigid_params = _continuous(name)
    verdict, rigid = _roots(rigid_params)
    assert rigid
    distances = []
    for kappa in (1e3, 1e4):
        hertz_verdict, hertz = _roots(rigid_params.replace(vehicle=CONTACT_SPRINGS[name], kappa_H=kappa))
        assert hertz_verdict == verdict
        distances.append(np.array([min(abs(h - r) for h in hertz) for r in rigid]))
    ratio = distances[0] / distances[1]
    assert np.all((9 < ratio) & (ratio < 11)), (distances, ratio)


def test_sleeper_file_chooses_the_contact_spring_vehicle():
    """On sleepers too: k_H in [physical] (or in the overrides of --set) runs the vehicle's variant, and the
    wheel spacing d of two wheels is read with or without it (the reader takes every group of the model)."""
    from moving_bogie.model.sleeper_input import sleeper_input

    physical = {"EI": 6.42e6, "m": 60.21, "l": 1.0, "k_sup": 1e8, "c_sup": 3e3, "M": 1400, "d": 2.0}
    data = {"model": {"track": "sleepers", "vehicle": "masses"}, "physical": physical | {"P": 6.4e4, "v": 90}}
    rigid = sleeper_input(data, "rigid.toml")
    assert rigid.vehicle == "masses" and rigid.vehicle_groups["d"] > 0
    hertz = sleeper_input(data, "hertz.toml", {"k_H": 1.4e9})
    assert hertz.vehicle == "hertz_masses" and hertz.vehicle_groups["d"] == rigid.vehicle_groups["d"]
    assert hertz.vehicle_groups["kappa_H"] > 0
