"""Timoshenko-Rayleigh time series with the branch-cut part of any model (response/cut_integral.py).

Reference: :func:`moving_bogie.response.bromwich.bromwich_line`, a direct quadrature of the Bromwich
integral of Eq. (35) on a horizontal line below every singularity; it uses no induced frequencies, no
residues and no branch cut. Its own convergence is shown by two lines (a = 0.02 and 0.05) agreeing far
below the tolerance. The closed form needs every induced frequency whose residue matters: for this beam
E_chr has a sequence of roots near the cut curve that runs along the real axis beyond Re q ~ sqrt(S)/r
(Re q = 39.07, 44.27, 95.01, ...), far outside the default search window; the window here reaches
Re q = 100 (the roots beyond carry amplitudes below 1e-10).
"""

from __future__ import annotations

import functools

import numpy as np
import pytest

from moving_bogie.api import closed_form_response, induced_frequencies
from moving_bogie.kernels.bound import bind
from moving_bogie.model.cases import table1_case
from moving_bogie.response import closed_form
from moving_bogie.response.bromwich import bromwich_line
from moving_bogie.response.cut_integral import CurveBranchCut, branch_cut_for
from moving_bogie.roots.count.contour import Rectangle

TAUS = (2.0, 20.0)


@pytest.fixture
def axis_roots_once(monkeypatch):
    """The decaying roots along the real axis beyond the window (``closed_form.axis_roots``, a search of
    strip after strip) found once per set of induced frequencies: the series with and without I_bc of one
    test sum the same residues, the sequence included, and differ only in I_bc."""
    compute, kept = closed_form.axis_roots, {}

    def once(bound, result, expansion):
        if id(result) not in kept:
            kept[id(result)] = (result, compute(bound, result, expansion))
        return kept[id(result)][1]

    monkeypatch.setattr(closed_form, "axis_roots", once)
    return kept


#: The times of the default series below; TAUS are among them.
DEFAULT_TAUS = (0.5, *TAUS)


@functools.cache
def _reference(eta_v: str, a: float) -> dict:
    """The Bromwich line of Case 7 on the Timoshenko-Rayleigh beam at DEFAULT_TAUS, once per (eta_v, a) for
    the tests below (their panels follow the largest time, the same for TAUS and DEFAULT_TAUS)."""
    params = table1_case(7).replace(beam="tr", S=10, r="0.09", eta_v=eta_v)
    return bromwich_line(bind(params), DEFAULT_TAUS, a=a)


def _at(values: dict, taus: tuple) -> dict:
    """The reference at the times ``taus`` (a subset of DEFAULT_TAUS)."""
    index = [DEFAULT_TAUS.index(t) for t in taus]
    return {name: v[index] for name, v in values.items()}


@pytest.mark.slow
@pytest.mark.parametrize("eta_v", ["0.05", "0"])  # with and without damping in the suspension
def test_tr_time_series_match_the_bromwich_integral(eta_v, axis_roots_once):
    params = table1_case(7).replace(beam="tr", S=10, r="0.09", eta_v=eta_v)
    ref, other = (_at(_reference(eta_v, a), TAUS) for a in (0.02, 0.05))
    result = induced_frequencies(
        params, dps=20, window=Rectangle(-0.01, 100.0, -1.0, 1.0), check_window=False
    )
    assert result.count_ok and result.count >= 6
    ts = closed_form_response(params, TAUS, frequencies=result, branch_cut=True)
    off = closed_form_response(params, TAUS, frequencies=result, branch_cut=False)
    scale = max(abs(ts.steady["w_rear"]), abs(ts.steady["w_front"]))
    for name in ref:
        assert np.abs(ref[name] - other[name]).max() < 1e-11 * scale, name  # the reference converged
        assert np.abs(ts[name] - ref[name]).max() < 1e-9 * scale, name
    # the branch-cut part is what makes the difference (I_bc ~ 1e-4 at tau = 2 for this beam)
    assert np.abs(off["w_rear"] - ref["w_rear"]).max() > 1e-6 * scale
    assert len(axis_roots_once) == 1  # both series summed the one sequence


@pytest.mark.slow
def test_the_default_tr_time_series_is_within_1e9_of_the_bromwich_integral():
    # No window given: the decaying roots along the real axis beyond the default window (Re q <= 3) come
    # from the strips of response/axis_sequence.py (39.07, 44.27, 95.01, ... up to Re q = 384 here).
    params = table1_case(7).replace(beam="tr", S=10, r="0.09", eta_v="0.05")
    ref = _reference("0.05", 0.02)
    ts = closed_form_response(params, DEFAULT_TAUS, branch_cut=True)
    scale = max(abs(ts.steady["w_rear"]), abs(ts.steady["w_front"]))
    for name in ref:
        assert np.abs(ts[name] - ref[name]).max() < 1e-9 * scale, name
    assert any(n.startswith("decaying induced frequencies along the real axis") for n in ts.notes)


def test_the_curve_integral_reproduces_the_half_line_integral():
    # Reference: the Euler-Bernoulli branch cut integrated on its half-line (response/branch_cut.py,
    # itself checked against the Bromwich integral in test_response_bromwich.py); the traced-cut integral
    # counts the doubly covered half-line once (two real roots p at every point of it).
    params = table1_case(7)
    taus = np.array([1.0, 5.0, 20.0])
    line = branch_cut_for(bind(params)).responses(taus)
    curve = CurveBranchCut(bind(params)).responses(taus)
    for name in line:
        np.testing.assert_allclose(curve[name], line[name], rtol=0, atol=1e-10)


@pytest.mark.slow
def test_the_wide_starting_panels_give_the_integral_of_panels_of_half_a_unit():
    # Reference: the same adapted quadrature started from panels of at most 0.5 in p along the whole cut
    # (the half-line's start; no rule subdivides them for e^{i p xi}). Wide starting panels (3 pi of
    # e^{i p xi} at the wheel spacing) where the jump is smooth meet the same halving test, and the rules
    # keep pieces of up to 3 pi of it; the two agree far below the truncation tolerance 1e-10.
    params = table1_case(7).replace(beam="tr", S=10, r="0.09")
    taus = np.array([0.3, 2.0, 20.0])
    wide = CurveBranchCut(bind(params))
    narrow = CurveBranchCut(bind(params), widest=0.5)
    assert wide.widest > 4 * narrow.widest
    got, ref = wide.responses(taus), narrow.responses(taus)
    for name in ref:
        np.testing.assert_allclose(got[name], ref[name], rtol=0, atol=1e-11)
