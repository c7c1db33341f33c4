"""The declared vehicles (derivations/vehicles.py): their generated matrices obey the mechanics they describe.

References: the block determinant of the declared bogie against E_chr of Eq. (38) as derived from the
bogie's own equations of motion (derivations/system.py, proved equal to the printed Eq. (38) in
docs/proofs.md); rigid-body motions of the free vehicle (no rail) that strain no spring-damper.
"""

from __future__ import annotations

import importlib
import sys
from pathlib import Path

import numpy as np
import pytest
from derivation_support import require_sympy

import moving_bogie.generated as generated

REPO = Path(__file__).resolve().parents[1]


def _module(name):
    return importlib.import_module(f"moving_bogie.generated.vehicle_{name}")


def _matrices(name, seed=0):
    module = _module(name)
    rng = np.random.default_rng(7 + seed)
    params = {k: float(10 ** rng.uniform(-1, 1)) for k in module.MATRIX_ARGUMENTS}
    return (
        module,
        params,
        [
            np.array(f(**params), dtype=float)
            for f in (module.mass_matrix, module.damping_matrix, module.stiffness_matrix)
        ],
    )


# The free vehicle's motions that strain no spring-damper, counted by hand from each declaration: one
# vertical translation; a pitch when the wheels are linked to a body that pitches; the two unlinked masses
# move independently; the car also pitches each bogie with its wheels about its centre, where the secondary
# suspension acts (translation, car pitch, two bogie pitches).
#: DOFs less independent spring-dampers; a contact spring adds one DOF and one spring, so each vehicle on its
#: contact springs keeps the rigid vehicle's count.
RIGID_MOTIONS = {"mass": 1, "oscillator": 1, "masses": 2, "bogie": 2, "car": 4}
RIGID_MOTIONS |= {f"hertz_{name}": count for name, count in RIGID_MOTIONS.items()}


@pytest.mark.parametrize("name", tuple(generated.DECLARED_VEHICLES))
def test_rigid_motions_strain_no_spring(name):
    module, _, (M, C, K) = _matrices(name)
    n = len(module.DOFS)
    assert M.shape == C.shape == K.shape == (n, n)
    for A in (M, C, K):
        assert np.array_equal(A, A.T)
    # every DOF has a mass but a massless contact point (hertz_*), which a spring links to one that has
    massless = [i for i in range(n) if M[i, i] == 0]
    assert all(i < module.CONTACTS and K[i, i] > 0 for i in massless)
    massive = [i for i in range(n) if i not in massless]
    assert np.all(np.linalg.eigvalsh(M[np.ix_(massive, massive)]) > 0)
    assert not np.any(M[massless, :])
    translation = np.array([0.0 if module.UNITS[x] == "rad" else 1.0 for x in module.DOFS])
    assert np.allclose(K @ translation, 0, atol=1e-12) and np.allclose(C @ translation, 0, atol=1e-12)
    for A in (K, C):
        singular = np.linalg.svd(A, compute_uv=False)
        nullity = int(np.sum(singular <= 1e-10 * max(singular.max(), 1.0)))
        assert nullity == RIGID_MOTIONS[name], f"{name}: {nullity} rigid motions"
    # Positive semi-definite: springs and dampers store and dissipate energy.
    assert np.linalg.eigvalsh(K).min() > -1e-10 and np.linalg.eigvalsh(C).min() > -1e-10


def test_car_positions_and_loads():
    module, params, _ = _matrices("car")
    d, L = params["d"], params["L_c"]
    assert module.CONTACTS == 4
    assert module.contact_positions(**params) == (0, d, L, L + d)
    assert module.static_loads(**params) == (2, 2, 2, 2)


def test_block_determinant_is_eq38():
    """det of the block system = -1/2 E_chr (bogie: pitch row halved, bounce row negated); masses: E_chr.

    Both the derivation's block system (derivations/vehicles.py) and the runtime's one definition of the
    coupling (kernels/coupling.py, evaluated on SymPy numbers with the generated matrices) against E_chr as
    derived from the vehicle's equations of motion (Eqs. (30)-(34), derivations/system.py). SymPy missing
    fails this test with its install command (skipped only on request, as the derivation tests:
    tests/derivation_support.py).
    """
    sp = require_sympy()
    if str(REPO) not in sys.path:
        sys.path.insert(0, str(REPO))
    from derivations import symbols as s
    from derivations.system import SYSTEMS, in_q
    from derivations.vehicles import VEHICLES, assemble, block_characteristic
    from moving_bogie.kernels.arithmetic import Rows
    from moving_bogie.kernels.coupling import coupled_system, dynamic_stiffness, kernel_matrix

    atoms = {0: s.K0, s.d: s.Kp, -s.d: s.Km}
    ops = Rows(sp.pi, sp.I)
    for name, factor in (("bogie", sp.Rational(-1, 2)), ("masses", 1)):
        system = SYSTEMS[name]()
        closed = sp.expand(factor * in_q(system.E_chr, system))
        assert sp.expand(block_characteristic(assemble(VEHICLES[name]()), lambda x: atoms[x]) - closed) == 0
        module = _module(name)
        values = {k: getattr(s, k) for k in module.MATRIX_ARGUMENTS}
        matrices = [f(**values) for f in (module.mass_matrix, module.damping_matrix, module.stiffness_matrix)]
        D, _ = dynamic_stiffness(s.q, matrices, ops)
        x = module.contact_positions(**values)
        offsets = sorted({sp.expand(a - b) for a in x for b in x}, key=str)
        index = [[offsets.index(sp.expand(a - b)) for b in x] for a in x]
        A = sp.Matrix(coupled_system(D, kernel_matrix([atoms[k] for k in offsets], index, ops), ops).A)
        assert sp.expand(A.applyfunc(sp.expand).det(method="berkowitz") - closed) == 0, name


@pytest.mark.parametrize("name", tuple(generated.DECLARED_VEHICLES))
def test_numerators_from_one_solve_are_cramers_determinants(name):
    """responses_array takes every residue numerator from one solve (n = E A^-1 b); reference: Cramer's
    rule written out, det(A with column X replaced by b), with made-up kernel values."""
    from moving_bogie.kernels.vehicle import VehicleSystem

    module, params, _ = _matrices(name, seed=3)
    system = VehicleSystem(module, params)
    rng = np.random.default_rng(11)
    q = rng.uniform(0.05, 1.5, 6) + 1j * rng.uniform(-0.2, 0.3, 6)
    K = [rng.normal(size=6) + 1j * rng.normal(size=6) for _ in system.offsets]
    E, nums, G = system.responses_array(q, K)
    A, _ = system.block_array(q, K)
    b = system.rhs_array(q, K)
    for x in range(system.size):
        Ax = A.copy()
        Ax[..., :, x] = b
        reference = np.linalg.det(Ax)
        scale = np.max(np.abs(reference)) + np.max(np.abs(E))
        assert np.max(np.abs(nums[..., x] - reference)) < 1e-10 * scale, (name, x)
    # the quadratures' variant without the determinant: X = n / E and G / E
    X, GE = system.solutions_array(q, K)
    assert np.allclose(X * E[:, None], nums, rtol=1e-10, atol=1e-12 * np.max(np.abs(nums)))
    assert np.allclose(GE * E[:, None], G, rtol=1e-10, atol=1e-12 * np.max(np.abs(G)))


def test_validation_labels_come_from_the_generated_dofs():
    """Every response of every vehicle is compared under its DOFS name, labelled by its kind and unit."""
    from moving_bogie.validation.verdict import quantity_labels

    for name in generated.DECLARED_VEHICLES:
        module = _module(name)
        labels = quantity_labels(module.DOFS, module.UNITS, module.CONTACTS)
        assert tuple(labels) == tuple(module.DOFS)
        for k, dof in enumerate(module.DOFS):
            assert labels[dof].startswith(dof)
            if k < module.CONTACTS:
                assert f"wheel {k + 1} of {module.CONTACTS}" in labels[dof]
            else:
                kind = "pitch" if module.UNITS[dof] == "rad" else "bounce"
                assert labels[dof].endswith(kind), labels[dof]
    car = _module("car")
    assert quantity_labels(car.DOFS, car.UNITS, car.CONTACTS)["theta_c"] == "theta_c / (w_st chi), pitch"


@pytest.mark.parametrize(
    ("name", "wheel_mass", "primary_stiffness"),
    [
        ("mass", "eta_M", None),
        ("oscillator", "eta_M", "kappa_v"),
        ("masses", "eta_M", None),
        ("bogie", "eta_M", "kappa_v"),
        ("car", "eta_M", "kappa_v"),
    ],
)
def test_the_default_axes_come_from_the_declared_vehicle(name, wheel_mass, primary_stiffness):
    """Reference: the declarations of derivations/vehicles.py: every wheel has the mass M (group eta_M,
    Eq. (17)); the primary suspension k_v (kappa_v) acts on the wheels of the oscillator, the bogie and the
    car; one mass and two masses have none. The stability tools sweep these by default."""
    from moving_bogie.api import critical_stiffness
    from moving_bogie.errors import ParameterError
    from moving_bogie.kernels.bound import bind
    from moving_bogie.kernels.sweep_characteristic import SweepCharacteristic
    from moving_bogie.model.cases import table1_case
    from moving_bogie.model.catalogue import get_model

    model = get_model(vehicle=name)
    assert (model.wheel_mass, model.primary_stiffness) == (wheel_mass, primary_stiffness)
    if name in ("bogie", "masses"):
        params = table1_case(7).replace(vehicle=name)
        assert SweepCharacteristic(bind(params)).parameter == wheel_mass
        if primary_stiffness is None:
            with pytest.raises(ParameterError, match="no primary suspension") as error:
                critical_stiffness(params, [0.5])
            assert error.value.parameter == "vehicle"
