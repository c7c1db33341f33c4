"""Tests of the finite-beam validation model (paper, Section 3.2, Eqs. (49)-(54)).

Reference values are computed here independently of the package: the steady deflection of constant
moving forces on the infinite beam by direct quadrature of its Fourier integral, and the matrices of
Eq. (49) element by element from the equations of motion.
"""

from __future__ import annotations

import dataclasses
import math
from types import SimpleNamespace

import numpy as np
import pytest
from scipy.integrate import quad

from moving_bogie.errors import MovingBogieError
from moving_bogie.model.cases import table1_case, table2_printed
from moving_bogie.validation.finite_beam import FiniteBeamResult, simulate_finite_beam
from moving_bogie.validation.geometry import choose_geometry, default_time_step, reflection_window
from moving_bogie.validation.modal import ModalBeam, ModalSystem
from moving_bogie.validation.newmark import (
    effective_matrix_dense,
    initial_state,
    newmark_step,
    woodbury_solve,
)
from moving_bogie.validation.track_modes import ModalTrack
from moving_bogie.validation.vehicle import Vehicle


def make_params(**changes: float | str) -> SimpleNamespace:
    """Duck-typed dimensionless parameters (floats), Case 1 of Table 1 by default."""
    values = dict(
        eta_f=0.1, eta_M=20.0, d=1.0, mu_v=34.0, J_b=0.2, kappa_v=0.02, eta_v=0.0, alpha=0.8, eta_s=0.0
    )
    values.update(changes)
    return SimpleNamespace(beam="eb", **values)


def modal_track(beam: str = "eb", **values: float) -> ModalTrack:
    """The generated finite-rail blocks of `beam` on the one-layer track for these group values."""
    return ModalTrack.of(SimpleNamespace(beam=beam, **values))


def eb_symbol(p: np.ndarray, alpha: float, eta_f: float, eta_s: float = 0.0) -> np.ndarray:
    """Moving-load symbol of the one-layer Euler-Bernoulli track, by hand from Eq. (1) with the shear layer.

    ``Omega(p) = 1 + (eta_s - alpha^2) p^2 + p^4 / 4 + 2 i eta_f alpha p``: the steady response of the
    mode ``sin(p x)`` to a load moving at ``alpha`` (forcing ``exp(i p alpha tau)``) is ``1 / Omega(p)``.
    """
    p = np.asarray(p, dtype=float)
    return 1.0 + (eta_s - alpha * alpha) * p * p + 0.25 * p**4 + 2j * eta_f * alpha * p


def moving_force_deflection(alpha: float, eta_f: float, eta_s: float = 0.0, shift: float = 0.0) -> float:
    """Steady deflection at ``xi = shift`` due to a constant force at ``xi = 0`` on the infinite beam.

    In the moving coordinate ``xi = x - alpha tau`` the steady state of
    ``w_xxxx - 4 eta_s w_xx + 4 w_tautau + 8 eta_f w_tau + 4 w = 8 delta(x - alpha tau)`` solves
    ``W'''' + 4 (alpha^2 - eta_s) W'' - 8 eta_f alpha W' + 4 W = 8 delta(xi)``, whose Fourier
    transform (``W' -> i p W``) is ``8 / D(p, 0)`` with
    ``D(p, 0) = p^4 - 4 (alpha^2 - eta_s) p^2 - 8 i eta_f alpha p + 4``: the paper's Eq. (24) at
    ``q = 0`` with the Pasternak term added. So ``w(shift) = (1/2 pi) int 8 e^{i p shift} / D dp``,
    integrated here by QUADPACK (Fourier weights for ``shift != 0``), folded onto ``p >= 0``.
    """

    def f(p: float) -> complex:
        return 8.0 / (p**4 - 4.0 * (alpha**2 - eta_s) * p**2 - 8j * eta_f * alpha * p + 4.0)

    def even(p: float) -> complex:
        return f(p) + f(-p)

    def odd(p: float) -> complex:
        return f(p) - f(-p)

    def integral(g, **kw) -> float:
        return quad(g, 0.0, np.inf, limit=400, **kw)[0]

    if shift == 0.0:
        total = integral(lambda p: even(p).real, epsabs=1e-13, epsrel=1e-12)
        imag = integral(lambda p: even(p).imag, epsabs=1e-13, epsrel=1e-12)
    else:
        s = abs(shift)
        cos_kw = dict(weight="cos", wvar=s, limlst=200)
        sin_kw = dict(weight="sin", wvar=s, limlst=200)
        # int f e^{i p shift} = int_0^inf [even cos(p s) + i sign(shift) odd sin(p s)] dp
        sign = math.copysign(1.0, shift)
        total = integral(lambda p: even(p).real, **cos_kw) - sign * integral(lambda p: odd(p).imag, **sin_kw)
        imag = integral(lambda p: even(p).imag, **cos_kw) + sign * integral(lambda p: odd(p).real, **sin_kw)
    # The deflection is real: the imaginary part is a check of the quadrature.
    assert abs(imag) < 1e-8
    return total / (2.0 * math.pi)


def test_quadrature_reference_static_single_load_is_one():
    # With eta_s = 0 the dimensionless static deflection under one load is 1 by construction of w_st.
    assert moving_force_deflection(0.0, 0.0) == pytest.approx(1.0, abs=1e-10)


# the fast subset checks the bogie's convergence in modes (test_bogie_converges_with_number_of_modes)
@pytest.mark.parametrize("model", ["force", "masses", pytest.param("bogie", marks=pytest.mark.slow)])
def test_moving_loads_converge_to_infinite_beam_steady_state(model):
    # Damped, subcritical: the transient decays like exp(-eta_f tau) (e^-12 at tau = 60). The two
    # masses and the bogie then move without acceleration, so F_j -> 2 and their steady deflection
    # equals that of two moving forces: rear = own load + the front load d ahead, and vice versa.
    alpha, eta_f, d = 0.5, 0.2, 2.0
    params = make_params(alpha=alpha, eta_f=eta_f, d=d, eta_M=1.0, mu_v=1.7, J_b=0.4, kappa_v=0.2, eta_v=0.5)
    rear = moving_force_deflection(alpha, eta_f) + moving_force_deflection(alpha, eta_f, shift=-d)
    front = moving_force_deflection(alpha, eta_f) + moving_force_deflection(alpha, eta_f, shift=d)
    # k_max = 400 pi / 100 = 12.6: modal truncation ~ 8 / (3 pi k^3) = 4e-4 of the deflection.
    vehicle = SimpleNamespace(**vars(params), vehicle="bogie" if model == "force" else model)
    result = simulate_finite_beam(
        vehicle, 60.0, loads_only=model == "force", n_modes=400, length=100.0, entry=45.0
    )
    assert result.w_rear[-1] == pytest.approx(rear, rel=1e-3)
    assert result.w_front[-1] == pytest.approx(front, rel=1e-3)
    if model == "bogie":
        # Static suspension: both springs unstretched, w_j - u + s_j theta d/2 = 0.
        assert result.u[-1] == pytest.approx(0.5 * (rear + front), rel=1e-3)
        assert result.theta[-1] == pytest.approx((front - rear) / d, rel=1e-2)
    else:
        assert set(result.responses) == {"w_rear", "w_front"}  # the wheels only


def test_moving_force_truncation_error_falls_like_k_max_cubed():
    # The deflection spectrum of a point load falls like 8 / p^4: doubling N at fixed L should
    # divide the error of the plain modal model (no static correction) by about 8.
    alpha, eta_f = 0.5, 0.2
    params = make_params(alpha=alpha, eta_f=eta_f, d=2.0)
    exact = moving_force_deflection(alpha, eta_f) + moving_force_deflection(alpha, eta_f, shift=-2.0)

    def error(n: int, correction: bool) -> float:
        run = simulate_finite_beam(
            params, 60.0, loads_only=True, n_modes=n, length=100.0, entry=45.0, static_correction=correction
        )
        return abs(run.w_rear[-1] - exact)

    errors = [error(n, False) for n in (100, 200, 400)]
    assert errors[0] / errors[1] > 6 and errors[1] / errors[2] > 6
    # The static correction adds the missing tail in closed form: 100 corrected modes beat 400 plain
    # ones by far (what is left is the e^-12 transient and the time step).
    assert error(100, True) < errors[2] / 10


def test_static_single_wheel_equals_quadrature():
    # alpha = 0: the masses stand still; after the damped transient the deflection is static. The
    # wheels are 30 apart, so each acts alone (exp(-1.14 * 30) ~ 1e-15), and the mass (eta_M = 2)
    # must not matter. The Pasternak layer is on to test its modal stiffness.
    eta_s = 0.3
    params = make_params(alpha=0.0, eta_f=0.3, eta_s=eta_s, d=30.0, eta_M=2.0)
    exact = moving_force_deflection(0.0, 0.0, eta_s)
    masses = SimpleNamespace(**vars(params), vehicle="masses")
    result = simulate_finite_beam(masses, 60.0, n_modes=500, length=100.0, entry=35.0)
    assert result.w_rear[-1] == pytest.approx(exact, rel=1e-3)
    assert result.w_front[-1] == pytest.approx(exact, rel=1e-3)


def test_bogie_converges_with_number_of_modes():
    # Case 1 on a fixed beam: successive differences between N = 100, 200, 400 must shrink.
    params = make_params()
    tau = np.linspace(0.0, 30.0, 301)
    runs = [
        simulate_finite_beam(
            params, 30.0, n_modes=n, length=80.0, entry=25.0, dt=0.025, tau_out=tau, static_correction=False
        )
        for n in (100, 200, 400)
    ]
    for field in ("w_rear", "w_front", "u", "theta"):
        d1 = np.max(np.abs(getattr(runs[0], field) - getattr(runs[1], field)))
        d2 = np.max(np.abs(getattr(runs[1], field) - getattr(runs[2], field)))
        assert d2 < d1 / 3, field


def test_time_step_convergence_is_second_order():
    params = make_params()
    runs = [
        simulate_finite_beam(params, 20.0, n_modes=100, length=60.0, entry=20.0, dt=dt)
        for dt in (0.1, 0.05, 0.025)
    ]
    # Compare at common times (every 4th, 2nd, 1st step).
    w = [runs[0].w_rear, runs[1].w_rear[::2], runs[2].w_rear[::4]]
    ratio = np.max(np.abs(w[0] - w[1])) / np.max(np.abs(w[1] - w[2]))
    assert 3.0 < ratio < 5.0


# --- Eq. (49) assembled element by element ------------------------------------------------------


#: A small vehicle with every parameter non-zero (the assembly checks).
SMALL = dict(eta_M=3.0, d=1.5, mu_v=5.1, J_b=0.8, kappa_v=0.3, eta_v=0.11)


def dense_reference(system: ModalSystem, model: str, tau: float, eta_f: float = 0.07, eta_s: float = 0.2):
    """``(M, C, K, f)`` of Eq. (49), modal rows divided by L/2, written term by term.

    By hand from Eq. (1) with the shear layer (one-layer Euler-Bernoulli track, damping `eta_f`, Pasternak
    `eta_s`; the defaults are those of :func:`small_system`) and the bogie of Eqs. (2)-(4), (19)-(20) with
    the parameters :data:`SMALL` ("masses": wheel masses only; "force": constant loads), its pitch row
    Eq. (20) divided by 2 (the symmetric form).
    """
    beam, veh = system.beam, system.vehicle
    n, L, al = beam.n_modes, beam.length, veh.alpha
    lam = np.arange(1, n + 1) * np.pi / L
    x = (veh.entry + al * tau, veh.entry + al * tau + SMALL["d"])
    phi = [np.sin(lam * xj) for xj in x]
    dphi = [lam * np.cos(lam * xj) for xj in x]
    ddphi = [-(lam**2) * np.sin(lam * xj) for xj in x]
    size = n + (2 if model == "bogie" else 0)
    M, C, K, f = np.zeros((size, size)), np.zeros((size, size)), np.zeros((size, size)), np.zeros(size)
    em = 0.0 if model == "force" else SMALL["eta_M"]
    kv, ev, d = SMALL["kappa_v"], SMALL["eta_v"], SMALL["d"]
    bogie = model == "bogie"
    for k in range(n):
        M[k, k], C[k, k] = 1.0, 2.0 * eta_f
        K[k, k] = 1.0 + eta_s * lam[k] ** 2 + lam[k] ** 4 / 4.0
        for j, s in ((0, 1.0), (1, -1.0)):
            g = 2.0 / L * phi[j][k]  # projection of the wheel force 4 F_j delta / (2 L)
            f[k] += 2.0 * g
            for m in range(n):
                M[k, m] += g * em * phi[j][m]
                C[k, m] += g * em * 2.0 * al * dphi[j][m]
                K[k, m] += g * em * al**2 * ddphi[j][m]
                if bogie:
                    C[k, m] += g * 2.0 * ev * phi[j][m]
                    K[k, m] += g * (kv * phi[j][m] + 2.0 * ev * al * dphi[j][m])
            if bogie:
                K[k, n] -= g * kv
                C[k, n] -= g * 2.0 * ev
                K[k, n + 1] += g * kv * s * d / 2.0
                C[k, n + 1] += g * 2.0 * ev * s * d / 2.0
    if bogie:
        u, th = n, n + 1
        M[u, u], C[u, u], K[u, u] = SMALL["mu_v"], 4.0 * ev, 2.0 * kv
        M[th, th], C[th, th], K[th, th] = SMALL["J_b"], ev * d**2, kv * d**2 / 2.0
        for m in range(n):
            C[u, m] = -2.0 * ev * (phi[0][m] + phi[1][m])
            K[u, m] = -kv * (phi[0][m] + phi[1][m]) - 2.0 * ev * al * (dphi[0][m] + dphi[1][m])
            C[th, m] = ev * d * (phi[0][m] - phi[1][m])
            K[th, m] = kv * d / 2.0 * (phi[0][m] - phi[1][m]) + ev * d * al * (dphi[0][m] - dphi[1][m])
    return M, C, K, f


def small_vehicle(model: str, alpha: float, entry: float, values: dict = SMALL) -> Vehicle:
    """The generated bogie or two masses with `values`; "force": the bogie's loads only."""
    params = SimpleNamespace(vehicle="masses" if model == "masses" else "bogie", alpha=alpha, **values)
    vehicle = Vehicle.of(params, entry)
    return vehicle.loads_only() if model == "force" else vehicle


def small_system(model: str = "bogie", alpha: float = 0.7) -> ModalSystem:
    beam = ModalBeam(length=12.0, n_modes=9, track=modal_track(eta_f=0.07, eta_s=0.2, alpha=alpha))
    return ModalSystem(beam, small_vehicle(model, alpha, 3.3))


@pytest.mark.parametrize("model", ["bogie", "masses", "force"])
def test_assembly_matches_term_by_term_matrices(model):
    system = small_system(model)
    for tau in (0.0, 1.7):
        ref = dense_reference(system, model, tau)
        got = system.assemble(tau)
        for a, b in zip((*got.dense(), got.force), ref, strict=True):
            np.testing.assert_allclose(a, b, rtol=1e-13, atol=1e-13)


def test_matrices_are_symmetric_at_rest():
    # At alpha = 0 the system derives from kinetic, potential and dissipation functions: after
    # scaling the modal rows by L/2, M, C and K are symmetric (the vehicle's generated rows are). This
    # pins the signs and factors of the wheel-bar couplings (the pitch equation's d, Eq. (20)).
    system = small_system("bogie", alpha=0.0)
    n, L = system.beam.n_modes, system.beam.length
    scale = np.concatenate([np.full(n, L / 2.0), [1.0, 1.0]])
    for matrix in system.assemble(0.9).dense():
        scaled = scale[:, None] * matrix
        np.testing.assert_allclose(scaled, scaled.T, rtol=1e-13, atol=1e-13)


@pytest.mark.parametrize("model", ["bogie", "masses", "force"])
def test_woodbury_step_equals_dense_solve(model):
    system = small_system(model)
    h = 0.05
    rng = np.random.default_rng(7)
    z, v = rng.standard_normal(system.n_dof), rng.standard_normal(system.n_dof)
    state = initial_state(0.0, z, v, system.assemble(0.0))
    M0, C0, K0, f0 = dense_reference(system, model, 0.0)
    np.testing.assert_allclose(state.a, np.linalg.solve(M0, f0 - C0 @ v - K0 @ z), rtol=1e-10, atol=1e-10)

    new = newmark_step(state, h, system.assemble(h))
    M, C, K, f = dense_reference(system, model, h)
    z_pred = z + h * v + h * h / 4.0 * state.a
    v_pred = v + h / 2.0 * state.a
    a_new = np.linalg.solve(M + h / 2.0 * C + h * h / 4.0 * K, f - C @ v_pred - K @ z_pred)
    np.testing.assert_allclose(new.a, a_new, rtol=1e-10, atol=1e-10)
    np.testing.assert_allclose(new.z, z_pred + h * h / 4.0 * a_new, rtol=1e-10, atol=1e-10)
    np.testing.assert_allclose(new.v, v_pred + h / 2.0 * a_new, rtol=1e-10, atol=1e-10)
    np.testing.assert_allclose(
        effective_matrix_dense(system.assemble(h), h), M + h / 2.0 * C + h * h / 4.0 * K, atol=1e-13
    )


def test_woodbury_solve_random():
    rng = np.random.default_rng(3)
    n, r = 30, 4
    diag = 1.0 + rng.random(n)
    ut, vt = rng.standard_normal((r, n)) * 0.3, rng.standard_normal((r, n)) * 0.3
    rhs = rng.standard_normal(n)
    x = woodbury_solve(diag, ut, vt, rhs)
    np.testing.assert_allclose((np.diag(diag) + ut.T @ vt) @ x, rhs, atol=1e-12)
    np.testing.assert_allclose(woodbury_solve(diag, ut[:0], vt[:0], rhs), rhs / diag)


# --- geometry ------------------------------------------------------------------------------------


def test_near_field_decay_rate_and_group_velocity():
    # Static, no shear: the roots of p^4 + 4 are 1 +- i, -1 +- i.
    assert modal_track(alpha=0.0, eta_f=0.0).near_field_decay_rate() == pytest.approx(1.0)
    critical = modal_track(alpha=1.0, eta_f=0.0).near_field_decay_rate()  # Eq. (65)
    assert critical == pytest.approx(0.0, abs=1e-7)
    eta_s = 0.4

    def omega(x):  # by hand: the undamped dispersion of Eq. (1) with the shear layer
        return np.sqrt(1.0 + eta_s * x * x + x**4 / 4.0)

    track = modal_track(alpha=0.5, eta_f=0.1, eta_s=eta_s)
    p = np.linspace(0.0, 6.0, 601)
    np.testing.assert_allclose(track.dispersion(p)[:, 0], omega(p), rtol=1e-12)
    # EB group velocity (p^3 + 2 eta_s p) / (2 omega) grows with p: the envelope is the velocity itself
    exact = (p**3 + 2.0 * eta_s * p) / (2.0 * omega(p))
    np.testing.assert_allclose(track.group_velocity_envelope(p)[1:-1], exact[1:-1], rtol=1e-3, atol=1e-4)
    # every free wave decays at eta_f (modal damping 2 eta_f, underdamped)
    assert track.free_wave_decay_rate(6.0) == pytest.approx(0.1, rel=1e-9)


def test_choose_geometry_meets_its_criteria():
    # Short run, many modes: the reflection criterion can be met with k_max >= 4.
    g = choose_geometry(track=modal_track(alpha=0.5, eta_f=0.0), d=2.0, tau_max=40.0, n_modes=500)
    assert g.k_max >= 4.0
    assert g.tau_valid >= 40.0 * (1 - 1e-9)
    assert g.entry >= g.margin and g.length - g.entry - 2.0 - 0.5 * 40.0 >= g.margin * (1 - 1e-9)
    assert g.tau_valid == pytest.approx(reflection_window(g.length, g.entry, 2.0, 0.5, g.c_max, g.margin))
    # Long run, few modes: resolution wins, the window is reported shorter than the run.
    g = choose_geometry(track=modal_track(alpha=0.8, eta_f=0.1), d=1.0, tau_max=400.0, n_modes=500)
    assert g.k_max == pytest.approx(4.0)
    assert 0 < g.tau_valid < 400.0
    assert g.length >= g.entry + 1.0 + 0.8 * 400.0 + g.margin * (1 - 1e-9)


def test_default_time_step_resolves_relevant_band():
    track = modal_track(alpha=0.8, eta_f=0.1)
    h = default_time_step(k_max=12.0, track=track)
    assert h == pytest.approx(2 * math.pi / (32 * math.sqrt(1 + 4.0**4 / 4)))
    assert default_time_step(k_max=2.0, track=track) > h


# --- API -----------------------------------------------------------------------------------------


def test_result_fields_and_output_resampling():
    params = make_params()
    fractions: list[float] = []
    full = simulate_finite_beam(params, 10.0, n_modes=60, length=50.0, entry=15.0, dt=0.01)
    tau = np.array([0.0, 2.5, 7.3, 10.0])
    part = simulate_finite_beam(
        params, 10.0, n_modes=60, length=50.0, entry=15.0, dt=0.01, tau_out=tau, progress=fractions.append
    )
    assert isinstance(part, FiniteBeamResult)
    with pytest.raises(dataclasses.FrozenInstanceError):
        part.dt = 1.0  # type: ignore[misc]
    np.testing.assert_array_equal(part.tau, tau)
    assert full.tau.size == 1001 and full.dt == pytest.approx(0.01)
    # Cubic Hermite interpolation with exact rates: close to the step values.
    for name in ("w_rear", "w_front", "u", "theta"):
        np.testing.assert_allclose(
            getattr(part, name), np.interp(tau, full.tau, getattr(full, name)), rtol=1e-4, atol=1e-6
        )
    assert fractions[0] == 0.0 and fractions[-1] == 1.0 and fractions == sorted(fractions)
    assert part.w_rear[0] == 0.0 and part.u[0] == 0.0  # starts at rest, undeflected
    assert part.length == 50.0 and part.entry == 15.0 and part.n_modes == 60
    assert part.elapsed_s > 0 and part.k_max == pytest.approx(60 * math.pi / 50)


def test_rejects_bad_input():
    with pytest.raises(MovingBogieError, match="positive mass.*r=0"):
        simulate_finite_beam(
            SimpleNamespace(**{**vars(make_params()), "beam": "tr", "S": 10.0, "r": 0.0}), 10.0
        )
    with pytest.raises(MovingBogieError, match="beam must be"):
        simulate_finite_beam(SimpleNamespace(**{**vars(make_params()), "beam": "layered"}), 10.0)
    with pytest.raises(MovingBogieError, match="leave the beam"):
        simulate_finite_beam(make_params(), 100.0, n_modes=50, length=50.0, entry=10.0)
    with pytest.raises(MovingBogieError, match="vehicle must be one of .*bogie"):
        simulate_finite_beam(SimpleNamespace(**vars(make_params()), vehicle="tram"), 10.0)
    with pytest.raises(MovingBogieError, match="tau_out"):
        simulate_finite_beam(make_params(), 1.0, n_modes=20, length=40.0, entry=15.0, tau_out=[2.0])


def test_accepts_dimensionless_params():
    # Exact Fractions from DimensionlessParams; J_b = cf2 eta_M d^2 = 0.2 and mu_v = 34 as in make_params.
    exact = simulate_finite_beam(table1_case(1), 5.0, n_modes=50, length=40.0, entry=15.0)
    floats = simulate_finite_beam(make_params(), 5.0, n_modes=50, length=40.0, entry=15.0)
    np.testing.assert_allclose(exact.theta, floats.theta, rtol=1e-12, atol=1e-14)
    np.testing.assert_allclose(exact.w_rear, floats.w_rear, rtol=1e-12, atol=1e-14)


# --- validation against the paper ---------------------------------------------------------------


def matrix_pencil(y: np.ndarray, dt: float, order: int) -> np.ndarray:
    """Complex frequencies ``q`` of ``y(tau) ~ sum c e^{i q tau}`` by the matrix pencil method.

    Hua & Sarkar, IEEE Trans. Acoust. Speech Signal Process. 38(5), 814-824 (1990): the signal
    subspace of the Hankel matrix of `y`, shifted by one sample, gives ``z = e^{i q dt}``.
    """
    n = y.size
    rows = n // 3
    hankel = np.array([y[i : i + rows + 1] for i in range(n - rows)])
    basis = np.linalg.svd(hankel, full_matrices=False)[2][:order].conj().T
    z = np.linalg.eigvals(np.linalg.pinv(basis[:-1]) @ basis[1:])
    return -1j * np.log(z) / dt


@pytest.mark.slow
def test_case1_reproduces_induced_frequencies_of_table2():
    # The wheel-followed deflection of Case 1 (500 modes, default beam) is a sum of the residues at
    # the induced frequencies, Eq. (40): fitting 9 exponentials (4 pairs + the steady part) to
    # tau >= 60 recovers Table 2, including the slightly unstable root 0.222538 - 0.000130i.
    tau = np.arange(0.0, 300.0 + 1e-9, 1.0)
    result = simulate_finite_beam(table1_case(1), 300.0, n_modes=500, tau_out=tau)
    expected = np.array([float(re) + 1j * float(im) for re, im in table2_printed(1)])
    for series in (result.w_rear, result.theta):
        q = matrix_pencil(series[tau >= 60.0], 1.0, 9)
        q = np.sort_complex(q[q.real > 1e-3])[::-1]
        assert q.size == expected.size == 4
        np.testing.assert_allclose(q.real, expected.real, atol=2.5e-3)
        np.testing.assert_allclose(q.imag, expected.imag, atol=1e-3)
        assert q[1].imag == pytest.approx(-0.00013, abs=3e-5)
