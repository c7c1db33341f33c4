"""The check against a window twice as large: decaying roots beyond the window versus missing roots.

Timoshenko-Rayleigh (Case 7 with S = 10, r = 0.09) has a sequence of decaying roots near the real axis
beyond Re q ~ sqrt(S)/r = 35.1: Re q = 39.07, 44.27, 95.01, ... (found by the search in a window reaching
Re q = 100 in tests/test_response_tr.py, whose time series they make agree with the Bromwich integral).
A window reaching Re q = 30 therefore has exactly two of them (39.07 and 44.27) in its twice-as-large
window, and its far-field radius R = 3 lies well inside it: those two roots must be reported as decaying
(Im q >= 0, by the far-field check) and leave the count and the verdict alone; a residue sum takes them
in from the strips along the real axis (response/axis_sequence.py), or refuses when nothing accounts for them.
"""

from __future__ import annotations

import pytest

from moving_bogie.api import closed_form_response, induced_frequencies
from moving_bogie.errors import MovingBogieError
from moving_bogie.model.cases import table1_case
from moving_bogie.roots.count.contour import Rectangle

PARAMS = table1_case(7).replace(beam="tr", S=10, r="0.09", eta_v="0.05")


@pytest.fixture(scope="module")
def within_30():
    return induced_frequencies(PARAMS, dps=15, window=Rectangle(-0.03, 30.0, -30.0, 30.05))


def test_decaying_roots_beyond_the_window_keep_the_count_and_the_verdict(within_30):
    result = within_30
    assert result.far_field.radius is not None and result.far_field.radius <= 30.0
    assert result.decaying_outside == 2  # Re q = 39.07 and 44.27 (see the module docstring)
    assert result.count_ok and result.count == result.found
    assert result.verdict.determined and result.stable
    assert any(w.startswith("beyond the window: 2 root(s)") for w in result.warnings)
    assert result.to_dict()["decaying_outside"] == 2


def test_roots_beyond_a_window_without_the_far_disc_fail_the_count():
    # Im q >= -2 does not hold the lower half-disc of R = 3: the roots outside could be unstable ones.
    result = induced_frequencies(PARAMS, dps=15, window=Rectangle(-0.03, 30.0, -2.0, 30.05))
    assert result.decaying_outside == 0
    assert not result.count_ok
    assert any(w.startswith("window: 2 more root(s)") for w in result.warnings)


def test_a_residue_sum_refuses_decaying_roots_left_outside_for_a_beam_without_the_sequence(
    within_30, monkeypatch
):
    # Roots beyond the window that the real-axis strips (response/axis_sequence.py) do not account for
    # would be missing from the residue sum: a beam without rotary inertia gets no strips and refuses.
    import moving_bogie.response.axis_sequence as axis_sequence

    monkeypatch.setattr(axis_sequence, "sequence_start", lambda params: None)
    with pytest.raises(MovingBogieError, match="2 decaying induced frequencies lie outside"):
        closed_form_response(PARAMS, (2.0,), frequencies=within_30)


@pytest.mark.slow
def test_the_first_strip_accounts_for_the_decaying_roots_the_check_window_found(within_30):
    # The two roots in the window twice as large (39.07, 44.27) lie in the first strip along the real
    # axis, Re q in [30, 60]: the residue sum takes them in and says so.
    ts = closed_form_response(PARAMS, (2.0,), frequencies=within_30, branch_cut=False)
    (note,) = [n for n in ts.notes if n.startswith("decaying induced frequencies along the real axis")]
    assert "a sequence from Re q ~ 35.14" in note


@pytest.mark.slow
def test_a_tr_time_series_says_how_far_it_summed_the_decaying_roots():
    # Case 7's vehicle on the Timoshenko-Rayleigh beam: sqrt(S)/r = sqrt(10)/0.09 = 35.14, beyond a window
    # reaching Re q = 3; the Euler-Bernoulli beam has no such sequence and gets no note.
    ts = closed_form_response(PARAMS, (2.0,), branch_cut=False)
    (note,) = [n for n in ts.notes if n.startswith("decaying induced frequencies along the real axis")]
    assert "up to Re q = 384 " in note and "estimated at" in note
    eb = closed_form_response(table1_case(7), (2.0,), branch_cut=False)
    assert not any(n.startswith("decaying induced frequencies") for n in eb.notes)
