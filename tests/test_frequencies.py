"""Induced frequencies (roots of E_chr, Eq. (48)) found with no starting guesses.

References: the paper's Table 2 (printed, six decimals; shipped in moving_bogie/data)
for Cases 1-6; for every case the argument-principle count; the pair symmetry E(-conj q) = conj E(q);
a precision ladder (the same roots recomputed at 45 digits); seeded random parameter sets.
"""

import json
import subprocess
import sys

import mpmath
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from moving_bogie.api import induced_frequencies
from moving_bogie.errors import ParameterError
from moving_bogie.kernels.bound import bind
from moving_bogie.kernels.characteristic import Characteristic
from moving_bogie.model.cases import TABLE1_CASES, table1_case, table2_printed
from moving_bogie.model.params import DimensionlessParams
from moving_bogie.roots.table2 import PRINT_TOLERANCE, compare_with_print


@pytest.fixture(scope="module")
def table(table1_search):
    """Every case of Table 1 searched with the default options (dps = 30)."""
    return {case: table1_search(case) for case in TABLE1_CASES}


@pytest.mark.parametrize("case", [1, 2, 3, 4, 5, 6])
def test_cases_1_to_6_equal_the_printed_table2(table, case):
    result = table[case]
    printed = table2_printed(case)
    assert len(printed) == 4 and len(result.roots) == 4
    for diff in compare_with_print(result, printed):
        assert abs(diff[0]) <= PRINT_TOLERANCE and abs(diff[1]) <= PRINT_TOLERANCE


@pytest.mark.parametrize("case", TABLE1_CASES)
def test_every_case_has_four_pairs_and_an_agreeing_count(table, case):
    result = table[case]
    assert result.count == 4 and result.found == 4 and result.count_ok
    assert not result.warnings
    for r in result.roots:
        assert r.digits >= 25 and r.multiplicity == 1
        assert mpmath.re(r.q) > 0


def test_paper_unstable_cases(table):
    """Sections 3.5-3.7, Appendix A: Cases 1, 5, 12, 13 are unstable (one root with Im q < 0)."""
    unstable = {case for case, res in table.items() if not res.stable}
    assert unstable == {1, 5, 12, 13}
    for case in unstable:
        assert len(table[case].unstable_roots) == 1


def test_undamped_cases_have_real_roots_in_the_gap(table):
    """eta_f = eta_v = 0 (Cases 2-4, 10): real induced frequencies, constant amplitudes; limits from below."""
    for case in (2, 3, 4, 10):
        for r in table[case].roots:
            assert r.marginal and r.side == "below"


def test_pairs_are_symmetric(table):
    """If q is a root so is -conj(q): E_chr(-conj q) = conj E_chr(q) (Section 2, after Eq. (39))."""
    mpmath.mp.dps = 30
    for case in (1, 6, 13):
        ch = Characteristic(bind(table1_case(case)))
        for r in table[case].roots:
            E = ch(r.q)
            E_m = ch(-mpmath.conj(r.q))
            assert abs(E_m - mpmath.conj(E)) < 1e-25 * (1 + abs(ch.value_and_derivative(r.q)[1]))


def test_precision_ladder_30_vs_45_digits(table):
    """The same roots at 45 digits agree with the 30-digit roots to the 30-digit result's confirmed digits."""
    for case in (1, 5, 9):
        low = table[case]
        high = induced_frequencies(table1_case(case), dps=45, check_window=False)
        assert len(high.roots) == len(low.roots)
        for a, b in zip(low.roots, high.roots):
            assert abs(a.q - b.q) <= mpmath.mpf(10) ** (-a.decimals)
            assert b.digits >= 40


def test_masses_model_and_timoshenko_rayleigh(table, table1_search):
    res = table1_search(7, "masses")  # induced_frequencies(table1_case(7).replace(vehicle="masses"))
    assert res.count_ok and res.count >= 1
    tr = induced_frequencies(table1_case(7).replace(beam="tr", S=100, r="0.03"))
    assert tr.count_ok and len(tr.roots) == 4
    eb = table[7]  # induced_frequencies(table1_case(7)), the module's search
    # S=100, r=0.03 is nearly Euler-Bernoulli (Section 3.6): roots close but not equal
    for a, b in zip(eb.roots, tr.roots):
        assert 0 < abs(a.q - b.q) < 0.02


params_strategy = st.builds(
    lambda eta_f, eta_M, d, cf1, cf2, kappa_v, eta_v, alpha: DimensionlessParams.from_coefficients(
        eta_f=eta_f, eta_M=eta_M, d=d, cf1=cf1, cf2=cf2, kappa_v=kappa_v, eta_v=eta_v, alpha=alpha
    ),
    eta_f=st.sampled_from(["0", "0.02", "0.05", "0.1", "0.2"]),
    eta_M=st.floats(2, 60).map(lambda x: round(x, 2)),
    d=st.floats(0.6, 4).map(lambda x: round(x, 2)),
    cf1=st.floats(0.8, 3).map(lambda x: round(x, 2)),
    cf2=st.floats(0.005, 0.2).map(lambda x: round(x, 3)),
    kappa_v=st.floats(0.01, 0.6).map(lambda x: round(x, 3)),
    eta_v=st.sampled_from(["0", "0.01", "0.05", "0.1"]),
    alpha=st.floats(0.1, 0.95).map(lambda x: round(x, 3)),
)


def test_newton_of_many_cells_at_once_equals_each_cell_alone(table):
    """The Newton starts of several cells in one batch (``newton_inside_many``, what locating does per
    level) reach what each cell reaches alone (``newton_inside``), and that is the root the search
    polished at 30 digits (reference: the polished roots of Case 1; a cell without a root gets None)."""
    from moving_bogie.kernels.characteristic import CharacteristicArray
    from moving_bogie.roots.count.contour import Rectangle
    from moving_bogie.roots.refine.locate import newton_inside, newton_inside_many

    roots = [complex(r.q) for r in table[1].roots]
    cells = [Rectangle(z.real - 0.01, z.real + 0.02, z.imag - 0.012, z.imag + 0.008) for z in roots]
    long = roots[0]  # a long cell: its starts along the longer side
    cells.append(Rectangle(long.real - 0.01, long.real + 0.07, long.imag - 0.006, long.imag + 0.009))
    assert all(sum(cell.contains(z) for z in roots) == 1 for cell in cells)  # one root each
    empty = Rectangle(0.70, 0.72, -2.02, -2.0)  # no root of Case 1 there (Table 2)
    assert all(not empty.contains(z) for z in roots)
    cells.append(empty)
    fast = CharacteristicArray(bind(table1_case(1)))
    together = newton_inside_many(fast, cells)
    alone = [newton_inside(fast, cell) for cell in cells]
    assert together[-1] is None and alone[-1] is None
    for z, a, b in zip(roots + [long], together[:-1], alone[:-1]):
        assert a is not None and b is not None
        assert abs(complex(a) - z) < 1e-12 and abs(complex(b) - z) < 1e-12


@pytest.mark.slow
@settings(max_examples=8, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow])
@given(params_strategy)
def test_random_parameter_sets_never_report_a_count_mismatch(params):
    res = induced_frequencies(params, dps=20, extra_dps=10)
    assert res.count_ok, (params, res.warnings)
    for r in res.roots:
        assert r.digits >= 15


def test_bad_input_fails_cleanly(capsys):
    """In this process (an exception escaping ``main`` would fail the test): one message naming the
    parameter and exit status 2; the test below runs the command as a subprocess."""
    from moving_bogie.cli import main

    with pytest.raises(ParameterError, match="vehicle must be one of"):
        table1_case(1).replace(vehicle="trolley")
    assert main(["frequencies", "--case", "99"]) == 2
    err = capsys.readouterr().err
    assert "case 99" in err and "Traceback" not in err
    assert main(["frequencies", "--case", "1", "--eta-M", "-3"]) == 2
    err = capsys.readouterr().err
    assert "eta_M" in err and "Traceback" not in err


@pytest.mark.slow
def test_cli_frequencies_json_reports_q_M2_unstable_for_case_1():
    out = subprocess.run(
        [sys.executable, "-m", "moving_bogie", "frequencies", "--case", "1", "--json"],
        capture_output=True,
        text=True,
        check=True,
    )
    data = json.loads(out.stdout)
    assert data["count"] == 4 and data["stable"] is False
    assert set(data["roots"][0]) >= {"re", "im", "side", "multiplicity", "digits"}
    unstable = [r for r in data["roots"] if r["im"].startswith("-")]
    assert len(unstable) == 1 and unstable[0]["re"].startswith("0.222537")
    assert np.isclose(float(unstable[0]["im"]), -0.000130, atol=5e-7)
    assert len(unstable[0]["re"]) > 25  # every confirmed digit
