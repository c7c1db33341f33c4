"""Lines that end say why: folds (tips), the searched q range raised automatically, ends in the JSON."""

from fractions import Fraction

import numpy as np
import pytest

from moving_bogie.api import induced_frequencies, instability_lines
from moving_bogie.paper.stability_figures import _base


@pytest.fixture(scope="module")
def figure3e_d2():
    """Figure 3(e) (two masses, eta_f = 0.25), the d = 2 line."""
    return instability_lines(
        _base("0.25").replace(vehicle="masses"), spacings=[2.0], alpha_step=0.02, q_step=0.008
    )


def _unstable(alpha, eta_M):
    p = _base("0.25").replace(alpha=Fraction(str(round(alpha, 6))), eta_M=Fraction(str(round(eta_M, 4))), d=2)
    res = induced_frequencies(p.replace(vehicle="masses"), dps=20)
    assert res.verdict.determined, res.verdict.reasons
    return len(res.unstable_roots)


def test_figure3e_tip_is_marked_and_is_where_the_line_really_ends(figure3e_d2):
    (branch,) = figure3e_d2.branches
    assert [e.reason for e in branch.ends] == ["theta_max", "alpha_max"]  # both ends on the plot's edge
    (tip,) = branch.folds
    assert tip.inside and abs(tip.alpha - 1.07) < 0.01 and abs(tip.theta - 110) < 3
    # Independent check by the argument principle (roots/frequencies): just below the tip, inside the spike,
    # one more root is unstable than just above it, where no line passes (the same count on both sides).
    below = _unstable(tip.alpha, tip.theta - 2)
    above = _unstable(tip.alpha, tip.theta + 2)
    assert abs(below - above) == 1
    assert _unstable(tip.alpha - 0.01, tip.theta + 2) == above == _unstable(tip.alpha + 0.01, tip.theta + 2)


@pytest.mark.slow
def test_q_range_is_raised_automatically():
    grid = dict(alpha_step=0.02, q_step=0.008)
    low = instability_lines(_base("0.25").replace(vehicle="masses"), spacings=[2.0], q_max=0.12, **grid)
    ref = instability_lines(_base("0.25").replace(vehicle="masses"), spacings=[2.0], **grid)
    assert low.q_max > 0.12 and not low.warnings
    assert not any(e.reason == "q_max" for b in low.branches for e in b.ends)
    # The same line as with the default range (reference: q_max = 1.5, which the line never reaches).
    (a,), (b,) = low.branches, ref.branches
    assert np.allclose([a.alpha[-1], a.theta[-1]], [b.alpha[-1], b.theta[-1]], atol=1e-8)


def test_capped_q_range_is_a_warning_and_an_end_inside():
    res = instability_lines(
        _base("0.25").replace(vehicle="masses"),
        spacings=[2.0],
        q_max=0.12,
        q_max_cap=0.12,
        alpha_step=0.02,
        q_step=0.008,
    )
    assert any("q_max" in w for w in res.warnings)
    ends = [e for b in res.branches for e in b.stops_inside if e.reason == "q_max"]
    assert ends and all(abs(e.q - 0.12) < 1e-9 for e in ends)


def test_ends_and_folds_are_in_the_json(figure3e_d2):
    (branch,) = figure3e_d2.to_dict()["branches"]
    assert [e["reason"] for e in branch["ends"]] == ["theta_max", "alpha_max"]
    assert branch["folds"][0]["reason"] == "fold" and branch["folds"][0]["inside"]
    assert "touches the real axis" in branch["folds"][0]["explanation"]
