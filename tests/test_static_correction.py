"""Static correction of the truncated modes (``moving_bogie.validation.residual`` and ``.corrected``).

References used here:

* the moving-load deflection of the infinite beam by QUADPACK quadrature of its Fourier integral
  (``moving_force_deflection`` of ``tests/test_finite_beam.py``), for the closed-form Green's function;
* the modal series itself, summed term by term far beyond the retained modes, for the residual
  flexibility;
* a dense solve of the same matrices, for the Woodbury step;
* the closed form (``closed_form_response``: steady part + residues + branch cut, Eqs. (35)-(43)),
  for the convergence of the corrected finite beam against the plain one.
"""

from __future__ import annotations

import numpy as np
import pytest
from test_finite_beam import eb_symbol, make_params, modal_track, moving_force_deflection, small_vehicle

from moving_bogie.errors import MovingBogieError
from moving_bogie.model.cases import table1_case
from moving_bogie.validation.corrected import CorrectedModalSystem
from moving_bogie.validation.finite_beam import simulate_finite_beam
from moving_bogie.validation.modal import ModalBeam, ModalSystem
from moving_bogie.validation.newmark import effective_matrix_dense, initial_state, newmark_step
from moving_bogie.validation.residual import ResidualFlexibility, moving_green_function


@pytest.mark.parametrize("alpha, eta_f, eta_s", [(0.0, 0.0, 0.0), (0.5, 0.2, 0.0), (0.7, 0.05, 0.3)])
def test_green_function_is_the_moving_load_deflection(alpha, eta_f, eta_s):
    # G(s) = (1/2 pi) int e^{ips} / Omega(p) dp with 4 Omega(p) = D(-p, 0); the quadrature reference is
    # the deflection at xi = -s under the load 2, i.e. 2 G(s) (the wheel load is 2 in these units).
    for s in (-2.5, 0.0, 1.5):
        reference = moving_force_deflection(alpha, eta_f, eta_s, shift=-s)
        symbol = modal_track(alpha=alpha, eta_f=eta_f, eta_s=eta_s).symbol_polynomials()
        assert 2.0 * moving_green_function(np.array(s), symbol) == pytest.approx(
            reference, rel=1e-8, abs=1e-12
        )


def test_residual_flexibility_equals_the_tail_of_the_modal_series():
    # Reference: the series of the module docstring summed directly over k = N+1 .. 200 000 (the rest,
    # about 4 / (3 pi lambda^3) = 1.7e-12 at lambda = 6283, i.e. 3e-9 of R), at wheels near a support
    # (x = 7.3, 9.3) so that the image terms matter.
    length, n, alpha, eta_f, eta_s, d = 100.0, 300, 0.7, 0.05, 0.3, 2.0
    kept = np.arange(1, n + 1) * np.pi / length
    x = (7.3, 7.3 + d)
    symbol = modal_track(alpha=alpha, eta_f=eta_f, eta_s=eta_s).symbol_polynomials()
    flex = ResidualFlexibility(kept, length, (0.0, d), symbol)
    r = flex.matrix(np.array(x), np.exp(1j * np.outer(x, kept)))
    tail = np.arange(n + 1, 200_001) * np.pi / length
    weight = 1.0 / (length * eb_symbol(tail, alpha, eta_f, eta_s))  # by hand, not the generated symbol
    for j in range(2):
        for m in range(2):
            phases = np.exp(1j * tail * (x[m] - x[j])) - np.exp(1j * tail * (x[j] + x[m]))
            assert r[j, m] == pytest.approx(np.sum(phases * weight).real, rel=1e-8), (j, m)
    assert r[0, 1] != pytest.approx(r[1, 0], rel=1e-3)  # moving loads: not symmetric


def test_supercritical_undamped_is_refused():
    with pytest.raises(MovingBogieError, match="critical velocity"):
        moving_green_function(np.array(0.0), modal_track(alpha=1.2, eta_f=0.0).symbol_polynomials())


def _static_system(corrected: bool, n: int = 20):
    """Two masses standing still (alpha = 0) on a beam of length 60 in only `n` modes (k_max ~ 1)."""
    beam = ModalBeam(60.0, n, modal_track(eta_f=0.1, eta_s=0.3, alpha=0.0))
    vehicle = small_vehicle("masses", 0.0, 25.0, dict(eta_M=2.0, d=2.0))
    return (CorrectedModalSystem if corrected else ModalSystem)(beam, vehicle)


def test_static_deflection_is_exact_with_few_modes():
    # Reference: quadrature of the infinite beam's static deflection under the two wheel loads (the
    # supports are 25 and 33 away: exp(-25) negligible). The static correction completes the modal
    # series in closed form, so 20 modes (k_max = 1.05) give it to rounding; the plain model does not.
    exact = moving_force_deflection(0.0, 0.0, 0.3) + moving_force_deflection(0.0, 0.0, 0.3, shift=2.0)
    for corrected, tol in ((True, 1e-9), (False, None)):
        system = _static_system(corrected)
        _, _, k = system.assemble(0.0).dense()
        z = np.linalg.solve(k, system.assemble(0.0).force)
        w = tuple(system.response(0.0, z, np.zeros_like(z)).w[:2])
        if tol:
            assert w == pytest.approx((exact, exact), rel=tol)
        else:
            assert abs(w[0] / exact - 1.0) > 0.05


@pytest.mark.parametrize("model", ["masses", "bogie"])
def test_corrected_woodbury_step_equals_dense_solve(model):
    track = modal_track(eta_f=0.12, eta_s=0.2, alpha=SMALL_MOTION["alpha"])
    system = CorrectedModalSystem(
        ModalBeam(9.0, 9, track), small_vehicle(model, **SMALL_MOTION, values=SMALL_VEHICLE)
    )
    assert_step_equals_dense_solve(system)


#: A small vehicle with every parameter non-zero (for the step-by-step checks).
SMALL_VEHICLE = dict(eta_M=1.3, d=1.7, mu_v=2.1, J_b=0.6, kappa_v=0.4, eta_v=0.15)
SMALL_MOTION = dict(alpha=0.6, entry=3.1)


def assert_step_equals_dense_solve(system, h: float = 0.05) -> None:
    """Initial state and one Newmark step of `system` against dense solves of the same matrices."""
    first = system.assemble(0.0)
    m, _, _ = first.dense()
    state = initial_state(0.0, np.zeros(system.n_dof), np.zeros(system.n_dof), first)
    assert np.allclose(m @ state.a, first.force)
    stepped = newmark_step(state, h, system.assemble(h))
    second = system.assemble(h)
    _, c, k = second.dense()
    z_pred = state.z + h * state.v + 0.25 * h * h * state.a
    v_pred = state.v + 0.5 * h * state.a
    rhs = second.force - c @ v_pred - k @ z_pred
    a_dense = np.linalg.solve(effective_matrix_dense(second, h), rhs)
    assert np.allclose(stepped.a, a_dense, rtol=1e-10, atol=1e-12)


@pytest.mark.slow
def test_corrected_run_converges_faster_than_plain():
    # Reference: the closed form of Case 7 (bogie, eta_f = 0.05), tau <= 40, on a fixed beam
    # (L = 120, x0 = 40: the supports stay beyond the near field). Error against modes: the plain model
    # converges like k_max^-3 (about 8 per doubling of N); the corrected one much faster, and with
    # N = 150 (k_max = 3.9) it is well below the plain model with twice the modes.
    from moving_bogie.api import closed_form_response

    params = table1_case(7)
    tau = np.linspace(0.0, 40.0, 401)
    closed = closed_form_response(params, tau)
    names = ("w_rear", "w_front", "u", "theta")
    errors = {}
    for corrected, n in ((False, 150), (False, 300), (True, 75), (True, 150)):
        run = simulate_finite_beam(
            params, 40.0, n_modes=n, length=120.0, entry=40.0, tau_out=tau, static_correction=corrected
        )
        errors[corrected, n] = max(
            np.max(np.abs(getattr(run, k) - closed[k])) / np.max(np.abs(closed[k])) for k in names
        )
    assert errors[False, 150] / errors[False, 300] > 6, errors
    assert errors[True, 75] / errors[True, 150] > 3 * errors[False, 150] / errors[False, 300], errors
    assert errors[True, 150] < errors[False, 300] / 10 and errors[True, 150] < 1e-3, errors


def test_plain_model_is_still_available():
    params = make_params()
    plain = simulate_finite_beam(params, 1.0, n_modes=40, length=40.0, entry=15.0, static_correction=False)
    corrected = simulate_finite_beam(params, 1.0, n_modes=40, length=40.0, entry=15.0)
    assert not plain.static_correction and corrected.static_correction
    assert plain.w_rear[-1] != pytest.approx(corrected.w_rear[-1], rel=1e-6)
