"""Closed-form vibrations with a cut that crosses Re q = 0 above q = 0 (response/cut_integral.py): the
layered tracks (the mass layer's curves) and the damped beam above the critical velocity.

References (independent of residues, induced frequencies and the cut):
* the homogeneous initial conditions: the response at tau = 0 is exactly zero at every xi, also on the
  suite's set of two purely imaginary roots (``IMAGINARY_ROOTS`` of tests/test_search_random.py), where
  each such root is its own mirror and enters the residue sum once;
* :func:`moving_bogie.response.bromwich.bromwich_line` and :func:`~moving_bogie.response.bromwich.
  bromwich_line_shape`, direct quadratures of the Bromwich integral of Eq. (35) on a line Im q = -a below
  every singularity; their own convergence is shown by a second line (a = 0.05) or a longer range.
The parameters are the dimensionless groups of examples/two-layer.toml (UIC60 rail on pads over sleepers on
ballast, alpha = 0.0497).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from test_search_random import IMAGINARY_ROOTS

from moving_bogie.api import closed_form_response, deflection_shape, induced_frequencies
from moving_bogie.kernels.bound import bind
from moving_bogie.model.cases import table1_case
from moving_bogie.model.files import load_params_file
from moving_bogie.response.branch_cut import BranchCutUnavailable
from moving_bogie.response.bromwich import bromwich_line, bromwich_line_shape
from moving_bogie.response.cut_integral import CurveBranchCut, branch_cut_for

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "two-layer.toml"
RESPONSES = ("w_rear", "w_front", "u", "theta")


@pytest.fixture(scope="module")
def two_layer():
    params, _ = load_params_file(EXAMPLE)
    result = induced_frequencies(params, dps=20)
    assert result.count_ok
    return params, result


def _scale(ts):
    return max(abs(ts.steady["w_rear"]), abs(ts.steady["w_front"]))


def test_the_mass_layer_cut_crosses_re_q_0_above_q_0(two_layer):
    params, _ = two_layer
    bc = CurveBranchCut(bind(params))
    ends = [piece.q_at([piece.p_lo])[0] for piece in bc.pieces if not piece.far[0]]
    assert len(ends) == 2  # the two mass-layer curves, mirror images of each other
    for q in ends:
        assert abs(q.real) < 1e-12 and q.imag > 0.1  # an interior point of the cut, above the pole q = 0
    assert bc.q_c == pytest.approx(0.0, abs=1e-12) and bc.eta_f > 0


@pytest.mark.slow
def test_the_response_starts_from_rest(two_layer):
    # exact reference: the loads are switched on at tau = 0 on a track at rest, so w(xi, 0) = 0 and
    # u(0) = theta(0) = 0; the residues alone miss this by 4 % of w_st, I_bc makes it hold
    params, result = two_layer
    ts = closed_form_response(params, [0.0], frequencies=result, branch_cut=True)
    off = closed_form_response(params, [0.0], frequencies=result, branch_cut=False)
    scale = _scale(ts)
    for name in RESPONSES:
        assert abs(ts[name][0]) < 1e-10 * scale, name
    assert abs(off["w_rear"][0]) > 1e-2 * scale
    xi = np.linspace(-6.0, 10.0, 9)
    w = deflection_shape(params, xi, 0.0, frequencies=result, branch_cut=True)
    assert np.abs(w).max() < 1e-10 * scale


@pytest.mark.slow
def test_purely_imaginary_roots_count_once_in_the_response():
    # exact reference: homogeneous initial conditions, w(0, 0) = w(d, 0) = 0 (Section 2), on two masses
    # over a two-layer track with two induced frequencies on Re q = 0. A purely imaginary root q equals its
    # mirror -conj(q); counted twice, its residue shifts w_rear(0) by 5 % of the steady deflection.
    # (The fast companion is tests/test_response.py::test_a_purely_imaginary_root_is_its_own_mirror.)
    result = induced_frequencies(IMAGINARY_ROOTS)
    assert result.count_ok, result.warnings
    on_axis = [r for r in result.roots if abs(complex(r.q).real) < 1e-12]
    assert len(on_axis) == 2  # the set keeps what its name says
    ts = closed_form_response(IMAGINARY_ROOTS, [0.0], frequencies=result, branch_cut=True)
    off = closed_form_response(IMAGINARY_ROOTS, [0.0], frequencies=result, branch_cut=False)
    scale = max(abs(v) for v in ts.steady.values())
    for name, values in ts.responses.items():
        assert abs(values[0]) < 1e-10 * scale, name
    assert abs(off.responses["w_rear"][0]) > 1e-3 * scale  # I_bc matters here: the check is not idle


@pytest.mark.slow
def test_two_layer_time_series_match_the_bromwich_integral(two_layer):
    params, result = two_layer
    taus = (0.5, 2.0, 20.0)
    ref = bromwich_line(bind(params), taus, a=0.02)
    other = bromwich_line(bind(params), taus, a=0.05)
    ts = closed_form_response(params, taus, frequencies=result, branch_cut=True)
    off = closed_form_response(params, taus, frequencies=result, branch_cut=False)
    scale = _scale(ts)
    for name in RESPONSES:
        assert np.abs(ref[name] - other[name]).max() < 1e-11 * scale, name  # the reference converged
        assert np.abs(ts[name] - ref[name]).max() < 1e-9 * scale, name
    # without the branch-cut part the wheels are 1e-3 to 4e-2 of w_st off at these times
    assert np.abs(off["w_rear"] - ref["w_rear"]).min() > 1e-4 * scale


@pytest.mark.slow
def test_two_layer_deflection_shape_matches_the_bromwich_integral(two_layer):
    params, result = two_layer
    xi = np.linspace(-10.0, 12.0, 12)
    ref = bromwich_line_shape(bind(params), xi, 2.0, a=0.02, s_max=1600.0)
    other = bromwich_line_shape(bind(params), xi, 2.0, a=0.05, s_max=800.0)
    w = deflection_shape(params, xi, 2.0, frequencies=result, branch_cut=True)
    ts = closed_form_response(params, [2.0], frequencies=result, branch_cut=False)
    scale = _scale(ts)
    assert np.abs(ref - other).max() < 1e-10 * scale
    assert np.abs(w - ref).max() < 1e-9 * scale
    # the far field without I_bc: the residues alone leave 0.13 w_st there
    off = deflection_shape(params, xi, 2.0, frequencies=result, branch_cut=False)
    assert np.abs(off - ref).max() > 1e-2 * scale


@pytest.mark.parametrize(
    ("change", "reason"),
    [({"eta_f": 0, "eta_2": 0}, "q = 0"), ({"alpha": 0}, "bounded")],
)
def test_degenerate_cuts_are_refused_with_the_reason(two_layer, change, reason):
    params, _ = two_layer
    with pytest.raises(BranchCutUnavailable, match=reason):
        CurveBranchCut(bind(params.replace(**change)))


@pytest.mark.slow
def test_damped_beam_above_the_critical_velocity_matches_the_bromwich_integral():
    # Table 1, Case 7 (eta_f = 0.05) at alpha = 1.2 > alpha_cr: the half-lines of the cut overlap across
    # Re q = 0 at Im q = eta_f, so the traced-cut integral takes over from the half-line one; one induced
    # frequency is unstable (Im q = -0.165), and the Bromwich line lies below it.
    params = table1_case(7).replace(alpha="1.2")
    assert isinstance(branch_cut_for(bind(params)), CurveBranchCut)
    result = induced_frequencies(params, dps=20)
    assert result.count_ok
    a = 0.02 - min(0.0, min(float(r.im_text) for r in result.roots))
    taus = (0.5, 2.0, 20.0)
    ref = bromwich_line(bind(params), taus, a=a)
    other = bromwich_line(bind(params), taus, a=a + 0.03)
    ts = closed_form_response(params, taus, frequencies=result, branch_cut=True)
    scale = _scale(ts)
    for name in RESPONSES:
        assert np.abs(ref[name] - other[name]).max() < 1e-11 * scale, name  # the reference converged
        assert np.abs(ts[name] - ref[name]).max() < 1e-9 * scale, name
