"""TOML parameter files (moving_bogie.model.files)."""

from __future__ import annotations

from fractions import Fraction

import pytest

from moving_bogie import ParameterError, table1_case
from moving_bogie.model.files import load_params_file, parse_params_toml

DIMENSIONLESS = """
[dimensionless]
eta_f = 0.05
eta_M = 30
d = 2
cf1 = 1.7
cf2 = 0.01
kappa_v = 0.2
eta_v = 0.05
alpha = 0.4
"""

PHYSICAL = """
[physical]
EI = 6.4e6
m = 60
k_f = 5e7
c_f = 5477.2
M = 1522.6
M_b = 2588.4
J_b = 43.58
k_v = 8.46e6
c_v = 0
d = 1.69
v = 300
P = 1e5
"""


def test_dimensionless_file_equals_table1_case_7(tmp_path):
    path = tmp_path / "case7.toml"
    path.write_text(DIMENSIONLESS)
    params, physical = load_params_file(path)
    assert params == table1_case(7)
    assert physical is None


def test_decimals_are_read_exactly():
    params, _ = parse_params_toml(DIMENSIONLESS.replace("alpha = 0.4", "alpha = 0.1"))
    assert params.alpha == Fraction(1, 10)


def test_case_with_overrides_keeps_cf1_cf2():
    params, _ = parse_params_toml("case = 7\n[dimensionless]\neta_M = 40\nbeam = 'tr'\nS = 100\nr = 0.03\n")
    assert params == table1_case(7).replace(eta_M=40, beam="tr", S=100, r="0.03")
    assert params.cf1 == Fraction(17, 10)


def test_case_alone():
    assert parse_params_toml("case = 3")[0] == table1_case(3)


def test_mu_v_may_replace_cf1():
    text = DIMENSIONLESS.replace("cf1 = 1.7", "mu_v = 51")
    assert parse_params_toml(text)[0] == table1_case(7)


def test_physical_file():
    params, physical = parse_params_toml(PHYSICAL)
    assert physical is not None and physical.M == Fraction("1522.6") and physical.k_f == 50_000_000
    assert params == physical.to_dimensionless()
    assert abs(float(params.eta_M) - 30) < 1e-3


@pytest.mark.parametrize(
    ("text", "name"),
    [
        (DIMENSIONLESS.replace("eta_M = 30", "eta_m = 30"), "eta_m"),  # unknown key (case matters)
        (DIMENSIONLESS.replace("alpha = 0.4\n", ""), "alpha"),  # missing key
        (DIMENSIONLESS.replace("cf1 = 1.7\n", ""), "cf1"),
        (DIMENSIONLESS.replace("alpha = 0.4", 'alpha = "0.4"'), "alpha"),  # wrong type
        (DIMENSIONLESS.replace("alpha = 0.4", "alpha = true"), "alpha"),
        (DIMENSIONLESS.replace("alpha = 0.4", "alpha = [0.4]"), "alpha"),
        (DIMENSIONLESS.replace("alpha = 0.4", "alpha = inf"), "alpha"),
        (DIMENSIONLESS.replace("alpha = 0.4", "alpha = nan"), "alpha"),
        (DIMENSIONLESS.replace("eta_f = 0.05", "eta_f = -0.05"), "eta_f"),
        (DIMENSIONLESS + "beam = 1\n", "beam"),
        (DIMENSIONLESS + "[vehicle]\nx = 1\n", "vehicle"),
        ("speed = 3\n" + DIMENSIONLESS, "speed"),
        ("case = 14\n", "case"),
        ("case = '7'\n", "case"),
        ("case = 7\n" + PHYSICAL, "case"),
        (DIMENSIONLESS + PHYSICAL, "physical"),
        ("dimensionless = 3\n", "dimensionless"),
        (PHYSICAL.replace("M = 1522.6", "M = -1522.6"), "M"),
        (PHYSICAL.replace("EI = 6.4e6", "EI = 0"), "EI"),
        (PHYSICAL.replace("P = 1e5\n", ""), "P"),
        (PHYSICAL + "GA = 1e9\n", "r_g"),
        (PHYSICAL.replace("c_f = 5477.2", "c_f = 2e5"), "c_f"),
        ("case = 7\n[dimensionless]\ncf1 = 2\nmu_v = 3\n", "cf1"),
        ("[dimensionless\n", "file"),  # not TOML
    ],
)
def test_errors_name_the_key_and_the_file(tmp_path, text, name):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    with pytest.raises(ParameterError) as info:
        load_params_file(path)
    assert info.value.parameter == name
    assert str(path) in str(info.value)
    assert name in str(info.value)


def test_missing_file_raises_file_not_found(tmp_path):
    with pytest.raises(FileNotFoundError):
        load_params_file(tmp_path / "nope.toml")
