"""The bound model (kernels/bound.py): one object per parameter set, its own catalogue, same numbers.

References: the generated modules the parameters' model names (``Model.foundation``, ``vehicle_kernels``), the
vehicle's matrices built directly from the generated module, and the old override semantics (a vehicle of
the same catalogue evaluated at the same parameters) for ``params.replace(vehicle=...)``.
"""

from __future__ import annotations

import pickle
from fractions import Fraction
from pathlib import Path

import mpmath
import numpy as np
import pytest

from moving_bogie import table1_case
from moving_bogie.errors import ParameterError
from moving_bogie.kernels.bound import BoundModel, bind
from moving_bogie.kernels.characteristic import Characteristic, CharacteristicArray
from moving_bogie.kernels.foundation import Foundation
from moving_bogie.kernels.vehicle import VehicleSystem
from moving_bogie.model.catalogue import Model, load_catalogue
from moving_bogie.model.params import DimensionlessParams
from moving_bogie.model.physical import PhysicalParams
from moving_bogie.roots.count.window import far_field_window

GENERATED = Path(__file__).resolve().parents[1] / "src" / "moving_bogie" / "generated"


def test_bind_is_idempotent_and_holds_the_parameters_own_modules():
    p = table1_case(7)
    bound = bind(p)
    assert bind(bound) is bound and bound.params is p and bound == bind(p) and hash(bound) == hash(bind(p))
    assert bound.foundation is p.model.foundation and bound.vehicle is p.model.vehicle_kernels
    assert bound.names == tuple(p.model.vehicle_kernels.DOFS)
    assert bound.span == float(p.d) and list(bound.positions) == [0.0, float(p.d)]
    assert bound.kernel_decay == 1.5 and bound.polynomial_degrees["eta_M"] == 4
    with pytest.raises(ParameterError, match="params"):
        bind("bogie")


def test_the_systems_are_those_of_the_generated_module_and_kept_per_precision():
    p = table1_case(1)
    bound = bind(p)
    ns = p.as_float()
    direct = VehicleSystem(
        p.model.vehicle_kernels, {n: getattr(ns, n) for n in bound.vehicle.MATRIX_ARGUMENTS}
    )
    assert np.array_equal(np.array(direct.mass, float), np.array(bound.float_system.mass, float))
    assert bound.float_system is bound.float_system
    with mpmath.workdps(30):
        thirty = bound.vehicle_system()
        assert bound.vehicle_system() is thirty
    with mpmath.workdps(50):
        fifty = bound.vehicle_system()
        assert fifty is not thirty and mpmath.mp.dps == 50
        assert abs(fifty.mass[2][2] - p.mu_v) == 0  # exact at this precision


def test_a_foundation_given_beside_the_parameters_is_another_bound_model():
    """BoundModel(params, foundation=...) is the one way to change the track: its own module given gives the
    default's numbers; a value given for a group of the track gives the numbers of parameters that carry
    that value (the reference: eta_f = 1/5 set in the parameters, bound the ordinary way)."""
    p = table1_case(3)
    q = mpmath.mpc("0.41", "-0.07")
    qs = np.array([0.3 - 0.1j, 1.2 + 0.4j])
    default = bind(p)
    same = BoundModel(p, foundation=p.model.foundation)
    assert same == default
    other = default.with_foundation(Foundation(p.model.foundation, {"eta_f": "0.2"}))
    reference = bind(p.replace(eta_f=Fraction(1, 5)))
    assert (
        other != default
        and other.params == p
        and other.replace(d=3).foundation_model.values == {"eta_f": "0.2"}
    )
    layered = {"track": "two-layer", "mu_2": 1, "kappa_2": 1, "eta_2": 0}  # another track: its own module
    assert other.replace(**layered).foundation is default.replace(**layered).foundation
    with mpmath.workdps(40):
        assert Characteristic(same)(q) == Characteristic(default)(q)
        assert Characteristic(other)(q) == Characteristic(reference)(q) != Characteristic(default)(q)
    assert np.array_equal(CharacteristicArray(same)(qs), CharacteristicArray(default)(qs))
    assert np.array_equal(CharacteristicArray(other)(qs), CharacteristicArray(reference)(qs))


def test_bind_makes_si_parameters_dimensionless():
    physical = PhysicalParams.from_dimensionless(table1_case(1), EI="6.4e6", m=60, k_f="1e8", P="1e5")
    assert bind(physical) == bind(physical.to_dimensionless())


def test_replace_gives_the_values_the_vehicle_override_used():
    """The old override evaluated vehicle_masses at the bogie's parameters; replace(vehicle=...) drops the
    groups the masses do not use and keeps every other value."""
    p = table1_case(7)
    masses = bind(p).replace(vehicle="masses")
    assert isinstance(masses, BoundModel) and masses.params.vehicle == "masses"
    module = p.model.catalogue.module("vehicle_masses")
    assert masses.vehicle is module
    old = VehicleSystem(module, {n: getattr(p.as_float(), n) for n in module.MATRIX_ARGUMENTS})
    assert np.array_equal(np.array(old.mass, float), np.array(masses.float_system.mass, float))
    assert np.array_equal(np.array(old.stiffness, float), np.array(masses.float_system.stiffness, float))
    assert all(masses.params.values()[k] == v for k, v in p.values().items() if k in masses.params.values())


def test_a_bound_model_pickles_to_its_parameters():
    bound = bind(table1_case(2))
    again = pickle.loads(pickle.dumps(bound))
    assert isinstance(again, BoundModel) and again == bound


def test_a_loaded_catalogue_reaches_its_own_kernels_and_asymptotics():
    """The packaged catalogue loaded from its folder under private names (no regeneration): the bound model
    holds that copy's modules, and the far-field check finds its radius from that copy's KERNEL_DECAY."""
    catalogue = load_catalogue(GENERATED)
    p = table1_case(1)
    own = DimensionlessParams(model=Model(p.beam, p.track, p.vehicle, catalogue), **p.values())
    bound = bind(own)
    assert bound.foundation is catalogue.module("foundation_eb")
    assert bound.foundation is not p.model.foundation and bound.vehicle is catalogue.module("vehicle_bogie")
    assert bound.kernel_decay == bind(p).kernel_decay
    window, far = far_field_window(bound)
    reference_window, reference = far_field_window(bind(p))
    assert far.radius is not None and far.radius == reference.radius and window == reference_window


def test_the_half_line_cut_is_read_from_the_generated_track():
    """The closed-geometry branch cut is chosen by what the derivation generated (cut_line_radicand), not by a
    model name: the paper's beam and the compressed rail have it, the Timoshenko-Rayleigh beam has not.
    Reference: the roots of N(p, q) in q for real p (n_coeffs_in_q) lie on Im q = cut_line_im, Re q =
    alpha p +- sqrt(R(p))/2."""
    from moving_bogie.response.cut_integral import CurveBranchCut, branch_cut_for

    axial = table1_case(7).replace(beam="eb_axial", eta_s="0.2", eta_N="0.5")
    for params in (table1_case(1), axial):
        bound = bind(params)
        args = {k: float(v) for k, v in params.as_float().__dict__.items() if k in bound.foundation.ARGUMENTS}
        c = bound.foundation.cut_line_im(**args)
        R = np.polyval([float(x) for x in bound.foundation.cut_line_radicand(**args)], 0.7)
        roots = np.roots([complex(x) for x in bound.foundation.n_coeffs_in_q(0.7, **args)])
        expected = args["alpha"] * 0.7 + 1j * c + np.array([1, -1]) * np.sqrt(R) / 2
        assert np.allclose(np.sort_complex(roots), np.sort_complex(expected), rtol=1e-13)
        assert type(branch_cut_for(bind(params))).__name__ == "BranchCut"
    tr = table1_case(7).replace(beam="tr", S=10, r="0.09")
    assert not hasattr(bind(tr).foundation, "cut_line_radicand")
    assert isinstance(branch_cut_for(bind(tr)), CurveBranchCut)
