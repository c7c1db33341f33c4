"""DimensionlessParams: validation, exactness, Eq. (63) coefficients, conversions."""

from __future__ import annotations

import json
import math
from fractions import Fraction

import mpmath
import pytest
from hypothesis import given
from hypothesis import strategies as st

from moving_bogie import DimensionlessParams, ParameterError, table1_case

BASE = dict(eta_f="0.05", eta_M=30, d=2, mu_v=51, J_b="1.2", kappa_v="0.2", eta_v="0.05", alpha="0.4")


def make(**changes):
    return DimensionlessParams(**(BASE | changes))


@pytest.mark.parametrize(
    ("name", "value"),
    [
        ("eta_M", -3),
        ("eta_M", 0),
        ("d", 0),
        ("d", "-0.5"),
        ("mu_v", -1),
        ("J_b", 0),
        ("kappa_v", 0),
        ("eta_f", "-0.01"),
        ("eta_f", 1),
        ("eta_v", -1),
        ("alpha", "-0.1"),
        ("eta_s", -1),
        ("alpha", math.nan),
        ("eta_M", math.inf),
        ("kappa_v", True),
        ("d", "two"),
        ("d", [2]),
    ],
)
def test_invalid_value_names_its_parameter(name, value):
    with pytest.raises(ParameterError) as info:
        make(**{name: value})
    assert info.value.parameter == name
    assert str(info.value).startswith(name + " ")


def test_message_shows_the_rule_and_the_value():
    with pytest.raises(ParameterError, match=r"^eta_M must be a positive finite number \(got -3\)$"):
        make(eta_M=-3)
    with pytest.raises(ParameterError, match=r"eta_f must satisfy 0 <= eta_f < 1 \(got 1\.5\)"):
        make(eta_f="1.5")


def test_parameter_error_is_a_value_error():
    with pytest.raises(ValueError):
        make(d=0)


@pytest.mark.parametrize(
    ("changes", "name"),
    [
        (dict(beam="timoshenko"), "beam"),
        (dict(beam="tr", r="0.03"), "S"),
        (dict(beam="tr", S=100), "r"),
        (dict(beam="tr", S=0, r="0.03"), "S"),
        (dict(beam="tr", S=100, r=-1), "r"),
        (dict(S=100), "S"),
        (dict(r="0.03"), "r"),
    ],
)
def test_beam_theory_parameters(changes, name):
    with pytest.raises(ParameterError) as info:
        make(**changes)
    assert info.value.parameter == name


def test_timoshenko_rayleigh_parameters_are_kept():
    p = make(beam="tr", S=100, r="0.03")
    assert (p.beam, p.S, p.r) == ("tr", 100, Fraction(3, 100))
    assert p.replace(beam="eb").S is None


def test_decimal_text_is_stored_exactly():
    p = make(eta_f="0.1", alpha="0.85")
    assert p.eta_f == Fraction(1, 10)
    assert p.alpha == Fraction(17, 20)
    assert all(isinstance(getattr(p, name), Fraction) for name in ("eta_M", "d", "mu_v", "eta_s"))


def test_floats_are_read_by_their_shortest_decimal_text():
    # As on the command line: replace(alpha=0.1) means 1/10, not the binary 0.1000000000000000055...
    assert make(eta_f=0.1).eta_f == Fraction(1, 10) != Fraction(0.1)
    assert make(alpha=1 / 3).alpha == Fraction("0.3333333333333333")


def test_instances_are_immutable_and_hashable():
    p = make()
    with pytest.raises(AttributeError):
        p.alpha = 1  # type: ignore[misc]
    assert p == make() and hash(p) == hash(make())


def test_repr_is_exact_and_evaluable():
    p = make(eta_M=Fraction(100, 3))
    assert eval(repr(p), {"DimensionlessParams": DimensionlessParams}) == p  # noqa: S307


def test_coefficients_of_eq_63():
    p = DimensionlessParams.from_coefficients(
        eta_f="0.05", eta_M=30, d=2, cf1="1.7", cf2="0.01", kappa_v="0.2", eta_v="0.05", alpha="0.4"
    )
    assert p.mu_v == 51 and p.J_b == Fraction(6, 5)
    assert (p.cf1, p.cf2) == (Fraction(17, 10), Fraction(1, 100))
    assert p == make()


@given(
    eta_M=st.fractions(min_value=Fraction(1, 100), max_value=200),
    d=st.fractions(min_value=Fraction(1, 10), max_value=10),
    cf1=st.fractions(min_value=Fraction(1, 100), max_value=5),
    cf2=st.fractions(min_value=Fraction(1, 1000), max_value=1),
)
def test_coefficients_round_trip_exactly(eta_M, d, cf1, cf2):
    p = DimensionlessParams.from_coefficients(
        eta_f=0, eta_M=eta_M, d=d, cf1=cf1, cf2=cf2, kappa_v="0.2", eta_v=0, alpha="0.5"
    )
    assert (p.cf1, p.cf2) == (cf1, cf2)
    q = p.replace(eta_M=eta_M * 2, d=d + 1)  # Table 1 semantics: cf1, cf2 stay fixed
    assert (q.cf1, q.cf2) == (cf1, cf2)
    assert q.mu_v == cf1 * eta_M * 2 and q.J_b == cf2 * eta_M * 2 * (d + 1) ** 2


def test_from_coefficients_names_the_coefficient():
    args = dict(eta_f=0, eta_M=20, d=1, cf1="1.7", cf2="0.01", kappa_v="0.02", eta_v=0, alpha="0.8")
    for name in ("cf1", "cf2"):
        with pytest.raises(ParameterError) as info:
            DimensionlessParams.from_coefficients(**(args | {name: -1}))
        assert info.value.parameter == name


def test_replace_semantics():
    p = table1_case(7)
    assert p.replace(alpha="0.5").alpha == Fraction(1, 2)
    assert p.replace(alpha="0.5").mu_v == p.mu_v
    assert p.replace(mu_v=60).cf1 == 2
    assert p.replace(cf1=2) == p.replace(mu_v=60)
    assert p.replace(eta_M=40, mu_v=51).mu_v == 51  # an explicit field wins over the kept coefficient
    assert p.replace(eta_M=40, mu_v=51).cf2 == p.cf2
    assert p.replace(d=3, cf2="0.1").J_b == Fraction(1, 10) * 30 * 9
    assert p.replace() == p


@pytest.mark.parametrize(
    ("changes", "name"),
    [
        (dict(cf1=2, mu_v=60), "cf1"),
        (dict(cf2="0.1", J_b=1), "cf2"),
        (dict(speed=1), "speed"),
        (dict(eta_M=-1), "eta_M"),
        (dict(cf1=0), "cf1"),
    ],
)
def test_replace_errors_name_the_parameter(changes, name):
    with pytest.raises(ParameterError) as info:
        table1_case(7).replace(**changes)
    assert info.value.parameter == name


@pytest.mark.parametrize(("missing", "name"), [("alpha", "alpha"), ("mu_v", "cf1"), ("J_b", "cf2")])
def test_from_mapping_names_the_missing_parameter(missing, name):
    values = {k: v for k, v in BASE.items() if k != missing}
    with pytest.raises(ParameterError, match="missing") as info:
        DimensionlessParams.from_mapping(values)
    assert info.value.parameter == name


def test_as_mp_uses_the_current_precision():
    p = make(eta_f="0.1")
    with mpmath.workdps(60):
        ns = p.as_mp()
        assert isinstance(ns.eta_f, mpmath.mpf)
        assert abs(ns.eta_f - mpmath.mpf(1) / 10) < mpmath.mpf(10) ** -59
        assert ns.beam == "eb" and ns.S is None
    assert p.as_float().eta_f == 0.1


def test_to_dict_is_json_ready_with_coefficients():
    d = make(eta_M=Fraction(100, 3)).to_dict()
    assert json.loads(json.dumps(d)) == d
    assert d["eta_f"] == "0.05" and d["eta_M"] == repr(100 / 3) and d["beam"] == "eb" and "S" not in d
    assert d["cf1"] == repr(float(Fraction(51) / Fraction(100, 3)))
    exact = make().to_dict()
    assert DimensionlessParams(**{k: v for k, v in exact.items() if k not in ("cf1", "cf2")}) == make()
    assert {"track", "vehicle"} <= set(exact)
