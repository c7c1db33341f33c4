"""PhysicalParams and the scaling of Eqs. (15)-(17), (59)."""

from __future__ import annotations

import math

import pytest

from moving_bogie import DimensionlessParams, ParameterError, PhysicalParams, table1_case

# A made-up but plausible SI set (UIC60-like rail on a soft foundation).
SI = dict(
    EI="6.42e6",
    m=60,
    k_f="2.5e7",
    c_f="3000",
    M=800,
    M_b=2500,
    J_b=2200,
    k_v="1.2e6",
    c_v="2.0e4",
    d="2.5",
    v=120,
    P="9.81e4",
    k_s="1.5e5",
)


def test_eq_17_by_hand_with_plain_floats():
    EI, m, k_f, c_f = 6.42e6, 60.0, 2.5e7, 3000.0
    M, M_b, J_b, k_v, c_v, d, v, k_s = 800.0, 2500.0, 2200.0, 1.2e6, 2.0e4, 2.5, 120.0, 1.5e5
    chi = (k_f / (4 * EI)) ** 0.25
    v_ref = (4 * k_f * EI / m**2) ** 0.25
    expected = dict(
        eta_M=M * chi / m,
        mu_v=M_b * chi / m,
        J_b=chi**3 * J_b / m,
        kappa_v=k_v * chi / k_f,
        eta_v=c_v * chi / (2 * math.sqrt(m * k_f)),
        eta_f=c_f / (2 * math.sqrt(m * k_f)),
        eta_s=k_s / (2 * math.sqrt(k_f * EI)),
        alpha=v / v_ref,
        d=d * chi,
    )
    got = PhysicalParams(**SI).to_dimensionless().as_float()
    for name, value in expected.items():
        assert getattr(got, name) == pytest.approx(value, rel=1e-13), name
    assert got.beam == "eb"


def test_scales_of_eqs_15_16():
    s = PhysicalParams(**SI).scales()
    chi = (2.5e7 / (4 * 6.42e6)) ** 0.25
    assert s.chi == pytest.approx(chi, rel=1e-15)
    assert s.v_ref == pytest.approx(math.sqrt(2.5e7 / 60) / chi, rel=1e-15)
    assert s.w_st == pytest.approx(9.81e4 * chi / (2 * 2.5e7), rel=1e-15)
    assert s.t_scale == pytest.approx(math.sqrt(60 / 2.5e7), rel=1e-15)
    assert s.rotation(1.0) == pytest.approx(s.w_st * s.chi)
    assert s.position(s.chi) == pytest.approx(1.0)
    assert s.time(1 / s.t_scale) == pytest.approx(1.0)
    assert s.deflection(2.0) == s.displacement(2.0) == pytest.approx(2 * s.w_st)
    assert s.velocity(1.0) == pytest.approx(s.v_ref)
    assert s.angular_frequency(s.t_scale) == pytest.approx(1.0)


def _close(a, b, rel=1e-17):
    return abs(a - b) <= rel * max(abs(a), abs(b))


def test_physical_dimensionless_round_trip():
    physical = PhysicalParams(**SI, GA="1.1e9", r_g="0.07")
    params = physical.to_dimensionless()
    assert params.beam == "tr"
    back = PhysicalParams.from_dimensionless(
        params, EI=physical.EI, m=physical.m, k_f=physical.k_f, P=physical.P
    )
    for name in SI:
        assert _close(getattr(back, name), getattr(physical, name)), name
    assert _close(back.GA, physical.GA) and _close(back.r_g, physical.r_g)


@pytest.mark.parametrize("case", [1, 7, 13])
def test_dimensionless_physical_round_trip(case):
    params = table1_case(case).replace(eta_s="0.3", beam="tr", S=100, r="0.03")
    again = PhysicalParams.from_dimensionless(params, EI="5e6", m=55, k_f="1e8", P="8e4").to_dimensionless()
    assert again.beam == "tr"
    for name in ("eta_f", "eta_M", "d", "mu_v", "J_b", "kappa_v", "eta_v", "alpha", "eta_s", "S", "r"):
        assert _close(getattr(again, name), getattr(params, name)), name


def test_with_dimensionless_keeps_unchanged_fields_exactly():
    physical = PhysicalParams(**SI)
    faster = physical.with_dimensionless(physical.to_dimensionless().replace(alpha="0.5"))
    assert faster.M == physical.M and faster.J_b == physical.J_b and faster.k_v == physical.k_v
    assert faster.v != physical.v and _close(faster.to_dimensionless().alpha, 0.5)


@pytest.mark.parametrize(
    ("name", "value"),
    [
        ("M", -800),
        ("EI", 0),
        ("m", "nan"),
        ("k_f", 0),
        ("P", 0),
        ("d", 0),
        ("J_b", -1),
        ("k_v", 0),
        ("c_f", -1),
        ("c_v", -1),
        ("v", -1),
        ("k_s", -1),
        ("M_b", True),
    ],
)
def test_invalid_physical_value_names_its_parameter(name, value):
    with pytest.raises(ParameterError) as info:
        PhysicalParams(**(SI | {name: value}))
    assert info.value.parameter == name
    assert name in str(info.value)


@pytest.mark.parametrize(("given", "name"), [(dict(GA="1e9"), "r_g"), (dict(r_g="0.07"), "GA")])
def test_timoshenko_needs_both_ga_and_radius_of_gyration(given, name):
    with pytest.raises(ParameterError) as info:
        PhysicalParams(**SI, **given)
    assert info.value.parameter == name


def test_overcritical_foundation_damping_names_c_f():
    critical = 2 * math.sqrt(60 * 2.5e7)
    with pytest.raises(ParameterError) as info:
        PhysicalParams(**(SI | {"c_f": critical * 1.01})).to_dimensionless()
    assert info.value.parameter == "c_f"


def test_from_dimensionless_validates_the_track():
    with pytest.raises(ParameterError) as info:
        PhysicalParams.from_dimensionless(table1_case(1), EI=0, m=60, k_f="1e8", P="1e5")
    assert info.value.parameter == "EI"


def test_to_dict():
    d = PhysicalParams(**SI).to_dict()
    # only the model's own SI parameters (an Euler-Bernoulli beam has no GA)
    assert d["EI"] == "6420000" and d["c_f"] == "3000" and "GA" not in d and d["beam"] == "eb"
    assert isinstance(PhysicalParams(**SI).to_dimensionless(), DimensionlessParams)


def test_per_rail_and_whole_vehicle_give_the_same_groups():
    """The convention of ``moving-bogie models``: a whole vehicle on a combined beam is the per-rail input
    with every SI parameter doubled except lengths and the speed (units m, m/s); the groups are the same."""
    from pathlib import Path

    from moving_bogie.cli import main
    from moving_bogie.model.files import load_params_file
    from moving_bogie.model.physical import PER_RAIL_CONVENTION

    examples = Path(__file__).resolve().parents[1] / "examples"
    for name in ("physical_eb.toml", "physical_tr.toml", "two-layer.toml"):
        per_rail, physical = load_params_file(examples / name)
        units = physical.units()
        whole = {k: (v if units[k] in ("m", "m/s") else 2 * v) for k, v in physical.values().items()}
        combined = PhysicalParams(model=physical.model, **whole)
        assert combined.to_dimensionless() == per_rail, name
        assert combined.scales().w_st == pytest.approx(physical.scales().w_st, rel=1e-15)
    assert "per rail" in PER_RAIL_CONVENTION and "halving" in PER_RAIL_CONVENTION
    import contextlib
    import io

    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert main(["models", "--verbose"]) == 0
    assert "Convention: SI inputs are per rail" in out.getvalue()
