"""Table 1 and Table 2 of the paper, as packaged data."""

from __future__ import annotations

from fractions import Fraction

import pytest

from moving_bogie import TABLE1_CASES, ParameterError, table1_case, table2_printed

# Table 1 of the paper, typed in again from the paper's text (not read from the packaged CSV).
PAPER_TABLE1 = {
    1: ("0.1", "20", "1", "1.7", "0.01", "0.02", "0", "0.8"),
    7: ("0.05", "30", "2", "1.7", "0.01", "0.2", "0.05", "0.4"),
    12: ("0.15", "50", "1.5", "1.7", "0.1", "0.2", "0", "0.85"),
    13: ("0.15", "15", "1", "1.7", "0.1", "0.2", "0", "0.95"),
}
KEYS = ("eta_f", "eta_M", "d", "cf1", "cf2", "kappa_v", "eta_v", "alpha")


def test_case_numbers():
    assert TABLE1_CASES == tuple(range(1, 14))


@pytest.mark.parametrize("case", sorted(PAPER_TABLE1))
def test_cases_match_the_paper_exactly(case):
    p = table1_case(case)
    expected = dict(zip(KEYS, (Fraction(text) for text in PAPER_TABLE1[case]), strict=True))
    got = {key: getattr(p, key) for key in KEYS}
    assert got == expected
    assert p.beam == "eb" and p.eta_s == 0


@pytest.mark.parametrize("case", TABLE1_CASES)
def test_every_case_is_valid(case):
    assert table1_case(case).mu_v == table1_case(case).cf1 * table1_case(case).eta_M


@pytest.mark.parametrize("case", [0, 14, -1, "7", 7.0, True, None])
def test_unknown_case_names_case_and_lists_valid_ones(case):
    with pytest.raises(ParameterError, match=r"valid cases of Table 1: 1, 2, .*, 13") as info:
        table1_case(case)
    assert info.value.parameter == "case"


def test_table2_printed_rows():
    assert table2_printed(1) == [
        ("0.307227", "0.021025"),
        ("0.222538", "-0.000130"),
        ("0.184817", "0.028535"),
        ("0.033910", "0.000014"),
    ]
    assert all(len(table2_printed(case)) == 4 for case in range(1, 7))
    assert all(table2_printed(case) == [] for case in range(7, 14))
    with pytest.raises(ParameterError):
        table2_printed(99)
