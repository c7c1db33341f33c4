"""Closed-form vibrations (Eqs. (35)-(47)): initial conditions, amplitudes, decay/growth, shapes, units.

References used here, each independent of the code under test:
* the homogeneous initial conditions of the paper (Section 2: "The initial conditions are assumed to be
  homogeneous"): w(0,0) = w(d,0) = u(0) = theta(0) = 0;
* K(xi, q) of Eq. (29) evaluated by :class:`TrackKernel` at q -+ i eps, off the cut, for the side values;
* the induced frequencies themselves (rates of decay/growth e^{-Im q tau}, Eq. (35), Section 3.7);
* Eq. (28) at xi = 0 and xi = d, which defines w(0, tau) and w(d, tau) from the shape;
* the scales of Eq. (16) for the SI conversion.
"""

from __future__ import annotations

import dataclasses

import mpmath
import numpy as np
import pytest

from moving_bogie.api import closed_form_response, deflection_shape, induced_frequencies
from moving_bogie.errors import MovingBogieError, ParameterError
from moving_bogie.kernels.bound import bind
from moving_bogie.kernels.track import TrackKernel
from moving_bogie.model.cases import table1_case
from moving_bogie.model.physical import PhysicalParams
from moving_bogie.response.branch_cut import BranchCut, BranchCutUnavailable
from moving_bogie.response.residues import IncompleteFrequencies, residue_expansion

NAMES = ("w_rear", "w_front", "u", "theta")


@pytest.fixture(scope="module")
def freqs(table1_search):
    """``freqs(case, model)``: the induced frequencies of a case of Table 1 at dps = 30 (searched once)."""

    def get(case, model="bogie"):
        return table1_search(case, None if model == "bogie" else model)

    return get


@pytest.mark.parametrize("case", [7, 2, 1, 13])
def test_homogeneous_initial_conditions_hold_with_the_branch_cut(freqs, case):
    # Reference: the paper's homogeneous initial conditions, x(0) = 0 for every response.
    ts = closed_form_response(table1_case(case), [0.0], frequencies=freqs(case), branch_cut=True)
    for name in NAMES:
        assert abs(ts[name][0]) < 1e-9, name
    # Without I_bc the residues alone miss them by the size of the branch-cut part (docs/vibrations.md).
    off = closed_form_response(table1_case(case), [0.0], frequencies=freqs(case), branch_cut=False)
    assert abs(off["w_rear"][0]) > 1e-4
    assert off.branch_cut is False and ts.branch_cut is True


def test_initial_conditions_two_masses(freqs):
    # Reference: homogeneous initial conditions; the masses model has no bar: its responses are its two
    # DOFs (generated/vehicle_masses.py), and asking for the bar's names fails with them.
    ts = closed_form_response(
        table1_case(7).replace(vehicle="masses"), [0.0, 5.0], frequencies=freqs(7, "masses")
    )
    assert abs(ts["w_rear"][0]) < 1e-9 and abs(ts["w_front"][0]) < 1e-9
    assert ts.names == ("w_rear", "w_front") and set(ts.steady) == set(ts.response_units) == set(ts.names)
    with pytest.raises(KeyError, match="known: w_rear, w_front"):
        ts["u"]
    # Steady state (q = 0): Eqs. (25)-(26) leave no force in the suspension, so the beam carries the two
    # wheel loads alone, as under two moving masses: the steady parts of both models coincide.
    bogie = closed_form_response(table1_case(7), [0.0], frequencies=freqs(7), branch_cut=False)
    assert ts.steady["w_rear"] == pytest.approx(bogie.steady["w_rear"], rel=1e-12)
    assert ts.steady["w_front"] == pytest.approx(bogie.steady["w_front"], rel=1e-12)


def test_a_purely_imaginary_root_is_its_own_mirror():
    # Reference: Eq. (35) sums the residue of every pole once; a root on Re q = 0 (the two of
    # IMAGINARY_ROOTS in tests/test_search_random.py, Re q ~ 1e-47 at 30 digits) equals its mirror
    # -conj(q), so it is listed once, and a complex root with its mirror (exact negation of Re q).
    from types import SimpleNamespace

    from moving_bogie.response.residues import both_members

    with mpmath.workdps(30):
        on_axis = mpmath.mpc("1.41297340001946e-48", "0.204018663754486")
        off_axis = mpmath.mpc("0.129145285682305", "0.0238007704203665")
    roots = [SimpleNamespace(q=q, multiplicity=1, decimals=28) for q in (on_axis, off_axis)]
    result = SimpleNamespace(count_ok=True, roots=roots, dps=30, warnings=[])
    members = both_members(result)
    assert len(members) == 3
    with mpmath.workdps(30):
        assert members[0] == on_axis and members[1] == off_axis
        assert members[2] == -mpmath.conj(off_axis)


@pytest.mark.parametrize("case", [7, 1])
def test_side_values_of_K_on_the_cut_match_the_kernel_just_off_it(case):
    # Reference: K of Eq. (29) by TrackKernel at q - i eps (below) and q + i eps (above).
    params = table1_case(case)
    bc = BranchCut(bind(params))
    xis = [0.0, 0.7, -1.3, 3.0]
    for p0 in (bc.p_c + 0.3, 0.4, 2.5):
        s = float(bc.s(p0))
        for side, sign in (("below", -1), ("above", 1)):
            with mpmath.workdps(40):
                q = mpmath.mpc(s, params.as_mp().eta_f + sign * mpmath.mpf("1e-25"))
                ref = TrackKernel(bind(params))(q, xis).K
            ours = bc.kernels(np.array([p0]), xis, side)[0]
            np.testing.assert_allclose(ours, [complex(k) for k in ref], rtol=1e-11, atol=1e-13)


def test_branch_cut_geometry():
    # Reference: kernels/cut.py's formula q = alpha p + i eta_f + sqrt(p^4 + 4 eta_s p^2 + 4 - 4
    # eta_f^2)/2 is a root
    # of N(p, q) for real p; q_c is its minimum.
    params = table1_case(7)
    bc = BranchCut(bind(params))
    from moving_bogie.kernels.cut import cut_locus

    assert bc.q_c == pytest.approx(cut_locus(bind(params), 0.0, 3.0).x_start, abs=1e-8)
    ps = np.array([-0.5, 0.3, 4.0])
    N = [np.polyval(bc.foundation.n_coeffs(complex(bc.q(p)), **bc.fargs), p) for p in ps]
    assert np.max(np.abs(N)) < 1e-10
    assert np.allclose(bc.s(bc.p_of_s(np.array([1.0, 10.0, 300.0]))), [1.0, 10.0, 300.0], rtol=1e-14)


@pytest.mark.parametrize("tau_lo", [0.0, 3.0])
def test_truncation_point_is_the_first_that_passes_one_at_a_time(tau_lo):
    """choose_S estimates several truncation points in one evaluation of the jump; reference: the same
    sequence floor + 2^k tried one point at a time, the tail term |j''(S)| / tau^3 from the three-point
    differences of ``_tail_terms`` (those the integral's tails use) or, for the first band, |j(S)| S /
    (kappa - 1) from j at S and 2 S, each evaluated on its own."""
    from moving_bogie.response.branch_cut import _S_STEPS

    bc = BranchCut(bind(table1_case(1)))
    channel, tol = bc.response_jumps, 1e-10
    for S in bc.q_c + np.array(_S_STEPS):
        if tau_lo > 0:
            est = np.abs(bc._tail_terms(channel, float(S))[2]).max() / tau_lo**3
        else:
            _, g = channel(bc.p_of_s(np.array([S, 2 * S])))
            a, b = np.abs(g[0]).max(), np.abs(g[1]).max()
            est = a * S / max(np.log2(a / b) - 1.0, 0.5)
        if est <= tol:
            break
    chosen = bc.choose_S(channel, tau_lo, tol)
    assert chosen == S and S < bc.q_c + _S_STEPS[-1]  # a point before the last one passed
    batch = bc._truncation_estimates(channel, bc.q_c + np.array(_S_STEPS[:6]), tau_lo)
    alone = [bc._truncation_estimates(channel, np.array([bc.q_c + s]), tau_lo)[0] for s in _S_STEPS[:6]]
    np.testing.assert_allclose(batch, alone, rtol=1e-9)


@pytest.mark.parametrize("case", [2, 3, 4])
def test_undamped_cases_keep_constant_amplitudes(freqs, case):
    # Reference: Section 3.7, Cases 2-4 are undamped, the induced frequencies are real (Table 2) and "all
    # amplitudes remain unchanged". Fit the unsteady part with the four real frequencies on an early and
    # a late window: the fitted amplitudes agree.
    result = freqs(case)
    assert all(abs(mpmath.im(r.q)) < 1e-20 for r in result.roots)
    params = table1_case(case)
    qs = np.array([float(mpmath.re(r.q)) for r in result.roots])

    def amplitudes(t0):
        tau = np.linspace(t0, t0 + 600, 3001)
        ts = closed_form_response(params, tau, frequencies=result, branch_cut=False)
        basis = np.hstack([np.cos(np.outer(tau, qs)), np.sin(np.outer(tau, qs))])
        coef, *_ = np.linalg.lstsq(basis, ts["w_rear"] - ts.steady["w_rear"], rcond=None)
        return np.hypot(coef[: qs.size], coef[qs.size :])

    np.testing.assert_allclose(amplitudes(10000.0), amplitudes(0.0), rtol=1e-8)


def _log_envelope_slope(params, result, t0, t1):
    centers = np.linspace(t0, t1, 9)
    logs = []
    for c in centers:
        tau = np.linspace(c - 100, c + 100, 2001)
        ts = closed_form_response(params, tau, frequencies=result, branch_cut=False)
        logs.append(np.log(np.max(np.abs(ts["w_rear"] - ts.steady["w_rear"]))))
    return np.polyfit(centers, logs, 1)[0]


def test_stable_damped_case_decays_at_the_slowest_rate(freqs):
    # Reference: Case 7 is stable; at long times the envelope decays like e^{-min Im q tau}.
    result = freqs(7)
    assert result.stable
    rate = min(float(mpmath.im(r.q)) for r in result.roots)
    slope = _log_envelope_slope(table1_case(7), result, 3000.0, 6000.0)
    assert slope == pytest.approx(-rate, rel=0.03)


def test_unstable_case_grows_at_rate_minus_im_q(freqs):
    # Reference: Case 5 is unstable (Table 2: -0.000472); the envelope grows like e^{-Im q tau} (Figure 13).
    result = freqs(5)
    assert not result.stable
    rate = -float(result.degree_of_instability)
    assert rate == pytest.approx(0.000472, abs=1e-6)
    slope = _log_envelope_slope(table1_case(5), result, 15000.0, 20000.0)
    assert slope == pytest.approx(rate, rel=0.02)


@pytest.mark.parametrize(("case", "tau", "branch_cut"), [(7, 20.0, True), (1, 100.0, False), (2, 3.0, True)])
def test_shape_at_the_wheels_equals_the_contact_series(freqs, case, tau, branch_cut):
    # Reference: Eq. (28) at xi = 0 and xi = d defines w(0, tau) and w(d, tau).
    params = table1_case(case)
    d = float(params.d)
    w = deflection_shape(params, [0.0, d], tau, frequencies=freqs(case), branch_cut=branch_cut)
    ts = closed_form_response(params, [tau], frequencies=freqs(case), branch_cut=branch_cut)
    assert w[0] == pytest.approx(ts["w_rear"][0], rel=1e-10, abs=1e-12)
    assert w[1] == pytest.approx(ts["w_front"][0], rel=1e-10, abs=1e-12)


@pytest.mark.slow
def test_whole_beam_starts_at_rest_and_the_transient_disperses(freqs):
    # Reference: homogeneous initial conditions for the whole beam, w(xi, 0) = 0 for every xi (Section 2).
    # The residues alone do not vanish at tau = 0; with I_bc the shape does, far from the wheels too.
    params = table1_case(7)
    xi = np.array([-60.0, -15.0, -1.0, 0.5, 15.0, 62.0])
    off = deflection_shape(params, xi, 0.0, frequencies=freqs(7), branch_cut=False)
    on = deflection_shape(params, xi, 0.0, frequencies=freqs(7), branch_cut=True)
    assert np.max(np.abs(off)) > 1e-3
    assert np.max(np.abs(on)) < 1e-10
    # Boundary conditions w -> 0 far away: by tau = 200 the radiated transient has dispersed and decayed.
    late = deflection_shape(params, np.array([-100.0, 100.0]), 200.0, frequencies=freqs(7))
    assert np.max(np.abs(late)) < 1e-6


def test_auto_rule_drops_only_a_negligible_branch_cut(freqs):
    # Reference: the branch-cut integral itself beyond the chosen end (documented auto rule).
    params = table1_case(7)
    ts = closed_form_response(params, np.linspace(0, 400, 9), frequencies=freqs(7))
    assert 0 < ts.branch_cut_until < 400
    bc = BranchCut(bind(params))
    late = bc.responses(np.linspace(ts.branch_cut_until, ts.branch_cut_until + 60, 25))
    assert max(np.abs(v).max() for v in late.values()) < 1e-6 * ts.steady["w_rear"]


def test_physical_parameters_give_si_units(freqs):
    # Reference: the scales of Eq. (16): w = w~ w_st, theta = theta~ w_st chi, t = tau t_scale.
    params = table1_case(7)
    physical = PhysicalParams.from_dimensionless(params, EI="6.4e6", m=60, k_f="2.5e7", P="8e4")
    scales = physical.scales()
    dimless = physical.to_dimensionless()
    result = induced_frequencies(dimless, dps=30)
    t = np.array([0.0, 20.0, 100.0]) * scales.t_scale
    si = closed_form_response(physical, t, frequencies=result)
    ref = closed_form_response(dimless, t / scales.t_scale, frequencies=result)
    assert si.units["w"] == "m" and si.units["theta"] == "rad" and si.units["tau"] == "s"
    np.testing.assert_allclose(si.tau, t)
    np.testing.assert_allclose(si["w_rear"], ref["w_rear"] * scales.w_st, rtol=1e-12, atol=1e-20)
    np.testing.assert_allclose(si["theta"], ref["theta"] * scales.w_st * scales.chi, rtol=1e-12, atol=1e-20)
    assert si.steady["w_rear"] == pytest.approx(ref.steady["w_rear"] * scales.w_st, rel=1e-12)
    assert si.response_units == {"w_rear": "m", "w_front": "m", "u": "m", "theta": "rad"}


@pytest.mark.slow
def test_timoshenko_rayleigh_series_start_at_rest(freqs):
    # The half-line integral needs a cut that is a half-line (generated cut_line_radicand: Euler-Bernoulli);
    # any other beam goes through the traced cut
    # (response/cut_integral.py), on by default. Reference: the homogeneous initial conditions of Eq. (35),
    # w(., 0) = 0, which the residues alone miss by 6e-4 here (S = 100, r = 0.03, Section 3.6).
    params = table1_case(7).replace(beam="tr", S=100, r="0.03")
    with pytest.raises(BranchCutUnavailable, match="is not a half-line"):
        BranchCut(bind(params))
    result = induced_frequencies(params, dps=30)
    off = closed_form_response(params, [0.0], frequencies=result, branch_cut=False)
    assert abs(off["w_rear"][0]) == pytest.approx(6.0e-4, rel=0.05)
    ts = closed_form_response(params, [0.0], frequencies=result)  # branch_cut="auto"
    assert abs(ts["w_rear"][0]) < 1e-9 and abs(ts["w_front"][0]) < 1e-9


def test_incomplete_or_foreign_frequencies_are_refused(freqs):
    from moving_bogie.roots.count.outcomes import count_mismatch

    result = freqs(7)
    broken = type(result)(
        result.params,
        result.model,
        result.dps,
        result.window,
        result.roots[:-1],
        result.count,
        result.unsearched,
        result.evaluations,
        (count_mismatch(result.count, result.found - result.roots[-1].multiplicity),),
    )
    with pytest.raises(IncompleteFrequencies):
        residue_expansion(bind(table1_case(7)), broken)
    with pytest.raises(ParameterError):
        closed_form_response(table1_case(1), [1.0], frequencies=result)
    with pytest.raises(ParameterError):
        closed_form_response(table1_case(7), [1.0], frequencies=result, branch_cut="maybe")


def test_a_missing_pair_member_is_detected(freqs):
    # Reference: x(tau) is real; the members q and -conj(q) of a pair have conjugate amplitudes.
    e = residue_expansion(bind(table1_case(7)), freqs(7), shapes=False)
    half = dataclasses.replace(
        e, q=e.q[1:], amplitudes={k: v[1:] for k, v in e.amplitudes.items()}, q_mp=e.q_mp[1:]
    )
    with pytest.raises(MovingBogieError, match="does not cancel"):
        half.harmonic("w_rear", [10.0])
    amps = e.amplitudes["w_rear"]
    assert np.allclose(amps[1::2], np.conj(amps[0::2]), rtol=1e-14)


def test_to_dict_is_json_ready(freqs):
    import json

    ts = closed_form_response(
        table1_case(7).replace(vehicle="masses"), [0.0, 1.0], frequencies=freqs(7, "masses")
    )
    data = json.loads(json.dumps(ts.to_dict()))
    # every response under its DOF name, and nothing under a DOF the vehicle does not have
    assert set(data) >= {"tau", "w_rear", "w_front", "responses", "steady", "branch_cut", "units"}
    assert "u" not in data and "theta" not in data and set(data["steady"]) == {"w_rear", "w_front"}
    assert data["w_rear"] == data["responses"]["w_rear"] and data["branch_cut"] is True
