"""The closed form (steady + residues + branch cut) against an independent inversion of Eq. (35).

Reference: :mod:`moving_bogie.response.bromwich` integrates the Bromwich line Im q = -a directly
(QUADPACK QAWF on
X~(q) e^{i q tau} built from K of Eq. (29)); it uses no induced frequencies, no residues and no branch
cut, so it checks all three parts of the closed form at once. Cases: 7 (damped, stable), 2 (undamped,
eta_f = 0: the cut lies on the real axis), 1 (unstable: a must exceed 0.000130, Table 2), 13 (alpha = 0.95,
near critical: q_c = 0.06 and an induced frequency 0.0015 below the cut, a sharp peak of the jump).
"""

from __future__ import annotations

import numpy as np
import pytest

from moving_bogie.api import closed_form_response, deflection_shape, induced_frequencies
from moving_bogie.kernels.bound import bind
from moving_bogie.model.cases import table1_case
from moving_bogie.response.bromwich import bromwich_response, bromwich_shape

NAMES = ("w_rear", "w_front", "u", "theta")


@pytest.mark.slow
@pytest.mark.parametrize(
    ("case", "taus"), [(7, (20.0, 100.0)), (2, (20.0, 100.0)), (1, (20.0, 100.0)), (13, (5.0, 20.0))]
)
def test_closed_form_matches_the_bromwich_integral(case, taus):
    params = table1_case(case)
    result = induced_frequencies(params, dps=30)
    a = 0.02
    assert a > -min(0.0, float(result.degree_of_instability))
    ref = bromwich_response(bind(params), taus, a=a)
    ts = closed_form_response(params, taus, frequencies=result, branch_cut=True)
    for name in NAMES:
        np.testing.assert_allclose(ts[name], ref[name], rtol=1e-6, atol=1e-12, err_msg=name)
        assert np.all(ref.errors[name] < 1e-7 * np.abs(ref[name]) + 1e-10)  # QUADPACK estimate


@pytest.mark.slow
def test_without_the_branch_cut_the_early_response_is_off():
    # Case 7 at tau = 20: I_bc is about 2e-5 (docs/vibrations.md), above the 1e-6 agreement.
    params = table1_case(7)
    result = induced_frequencies(params, dps=30)
    ref = bromwich_response(bind(params), [20.0], names=["w_rear"])
    off = closed_form_response(params, [20.0], frequencies=result, branch_cut=False)
    assert abs(off["w_rear"][0] - ref["w_rear"][0]) > 1e-5 * abs(ref["w_rear"][0])


@pytest.mark.slow
def test_deflection_shape_matches_the_bromwich_integral():
    # Away from the wheels the early shape is the radiated transient: it lives in the branch-cut part.
    params = table1_case(7)
    result = induced_frequencies(params, dps=30)
    xi = np.array([-15.0, 0.5])
    ref = bromwich_shape(bind(params), xi, 30.0)
    w = deflection_shape(params, xi, 30.0, frequencies=result, branch_cut=True)
    np.testing.assert_allclose(w, ref, rtol=1e-6, atol=1e-10)
