"""Exact conversion of parameter values (moving_bogie.model.exact)."""

from __future__ import annotations

import math
from decimal import Decimal
from fractions import Fraction

import mpmath
import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from moving_bogie import ParameterError
from moving_bogie.model.exact import fraction_to_exact_text, fraction_to_mpf, fraction_to_text, to_fraction


@pytest.mark.parametrize(
    ("value", "expected"),
    [
        ("0.1", Fraction(1, 10)),
        (" 1e-3 ", Fraction(1, 1000)),
        ("3/4", Fraction(3, 4)),
        (Decimal("0.05"), Fraction(1, 20)),
        (7, Fraction(7)),
        (np.int64(7), Fraction(7)),
        (0.1, Fraction(1, 10)),  # a float is read by its shortest decimal text, as the CLI reads it
        (2.5e-20, Fraction(25, 10**21)),
        (np.float64(0.5), Fraction(1, 2)),
        (mpmath.mpf(0.25), Fraction(1, 4)),
    ],
)
def test_to_fraction_is_exact(value, expected):
    assert to_fraction("x", value) == expected


@pytest.mark.parametrize(
    "value",
    [math.nan, math.inf, -math.inf, "nan", "inf", "", "abc", True, False, 1j, [1], None, Decimal("NaN")],
)
def test_to_fraction_rejects_non_numbers_naming_the_parameter(value):
    with pytest.raises(ParameterError, match=r"^eta_v ") as info:
        to_fraction("eta_v", value)
    assert info.value.parameter == "eta_v"


@given(st.integers(-(10**30), 10**30), st.integers(0, 40))
def test_finite_decimals_print_exactly(numerator, places):
    value = Fraction(numerator, 10**places)
    text = fraction_to_text(value)
    assert Fraction(text) == value
    assert "e" not in text


def test_non_terminating_fraction_prints_float_repr_and_exact_text():
    assert fraction_to_text(Fraction(1, 3)) == repr(1 / 3)
    assert fraction_to_exact_text(Fraction(1, 3)) == "1/3"
    assert fraction_to_exact_text(Fraction(-5, 4)) == "-1.25"


def test_fraction_to_mpf_rounds_at_current_precision():
    with mpmath.workdps(50):
        x = fraction_to_mpf(Fraction(1, 10))
        assert mpmath.almosteq(x, mpmath.mpf(1) / 10, rel_eps=mpmath.mpf(10) ** -49)
    assert fraction_to_mpf(Fraction(1, 10)) == mpmath.mpf("0.1")


@pytest.mark.parametrize("value", ["1e400", "-1e31", 1e200, "1e-31", 2.5e-100, Decimal("1e-400")])
def test_to_fraction_refuses_values_beyond_double_precision(value):
    """Beyond 1e30 (or nearer 0 than 1e-30) the groups' powers and products leave double precision:
    refused by name, never an OverflowError later (issue: --set v=1e400)."""
    with pytest.raises(ParameterError, match="out of range") as info:
        to_fraction("v", value)
    assert info.value.parameter == "v"
    assert to_fraction("v", "1e30") == 10**30 and to_fraction("v", 0) == 0
