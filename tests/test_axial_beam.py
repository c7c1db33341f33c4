"""The Euler-Bernoulli beam under an axial compressive force (``eb_axial``): declared in derivations/ only.

A compressive force N (the thermal force E A alpha_T dT of a continuous welded rail; Metrikine & Dieterman,
J. Sound Vib. 201(5), 1997) adds N w_xx to Eq. (1). With eta_N = N / (2 sqrt(k_f EI)) the dimensionless beam
row reads, by hand from Eqs. (15)-(18),

    w_xxxx - 4 (eta_s - eta_N) w_xx + 4 w_tautau + 8 eta_f w_tau + 4 w = (loads),

so in moving coordinates (xi = x - alpha tau, d/dxi -> i p, d/dtau -> i q)

    N(p, q) = p^4 + 4 (eta_s - eta_N) p^2 - 4 (q - alpha p)^2 + 8 i eta_f (q - alpha p) + 4.

References, each independent of the generated kernel it checks:

* K(xi, q) = int exp(i p xi) / N dp by adaptive quadrature (mpmath.quad; quadosc for xi != 0) of the N
  written above;
* the critical velocity in closed form: the phase speed of free waves,
  alpha^2 = (eta_s - eta_N) + p^2/4 + 1/p^2, is smallest at p^2 = 2, so alpha_cr = sqrt(1 + eta_s - eta_N)
  (compression lowers Eq. (65)'s sqrt(1 + eta_s));
* the per-mode blocks of the finite rail by hand: 1, 2 eta_f, 1 + (eta_s - eta_N) lambda^2 + lambda^4 / 4;
* the induced frequencies of the paper's beam with the shear layer eta_s - eta_N (the same N, another module);
* the finite beam (modal expansion) against the closed form (residues and branch cut), within 0.2 %.
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest

from moving_bogie.api import induced_frequencies, validate
from moving_bogie.kernels.bound import bind
from moving_bogie.kernels.track import TrackKernel
from moving_bogie.model.cases import table1_case
from moving_bogie.model.catalogue import get_model
from moving_bogie.stability.velocity.critical_velocity import critical_velocity
from moving_bogie.validation.track_modes import ModalTrack


def n_by_hand(p, q, alpha, eta_f, eta_s, eta_N):
    """N(p, q) of the compressed Euler-Bernoulli beam on the one-layer track (module docstring)."""
    s = q - alpha * p
    return p**4 + 4 * (eta_s - eta_N) * p**2 - 4 * s**2 + 8j * eta_f * s + 4


@pytest.mark.parametrize("eta_s, eta_N", [(0.0, 0.3), (0.4, 0.9)])
def test_critical_velocity_drops_with_compression(eta_s, eta_N):
    got = critical_velocity(get_model(beam="eb_axial"), eta_s=eta_s, groups={"eta_N": eta_N})
    assert float(got.alpha_cr) == pytest.approx(math.sqrt(1 + eta_s - eta_N), rel=1e-12)
    assert float(got.alpha_cr) < float(critical_velocity(get_model(beam="eb"), eta_s=eta_s).alpha_cr)


@pytest.mark.slow
def test_kernel_against_quadrature():
    params = table1_case(7).replace(beam="eb_axial", eta_N="0.3")
    f = params.as_float()
    q = mpmath.mpc("0.3", "-0.2")
    with mpmath.workdps(30):
        got = TrackKernel(bind(params))(q, [0, "1.5"]).K
        breaks = [-mpmath.inf, *mpmath.linspace(-20, 20, 81), mpmath.inf]

        def integrand(p, xi=0):
            return mpmath.exp(1j * p * xi) / n_by_hand(p, q, f.alpha, f.eta_f, f.eta_s, f.eta_N)

        at_zero = mpmath.quad(integrand, breaks)
        xi = mpmath.mpf("1.5")
        shifted = sum(
            mpmath.quadosc(lambda p: integrand(p, xi), interval, omega=xi)
            for interval in ([-mpmath.inf, 0], [0, mpmath.inf])
        )
        for k, quadrature in zip(got, (at_zero, shifted)):
            assert abs(k - quadrature) < 1e-12 * abs(quadrature)


def test_modal_blocks_of_the_finite_rail():
    params = table1_case(7).replace(beam="eb_axial", eta_s="0.2", eta_N="0.5")
    m, c, k = ModalTrack.of(params).blocks(np.linspace(0.1, 6.0, 13))
    lam = np.linspace(0.1, 6.0, 13)
    np.testing.assert_allclose(m[:, 0, 0], 1.0, rtol=1e-15)
    np.testing.assert_allclose(c[:, 0, 0], 2 * 0.05, rtol=1e-14)  # eta_f = 0.05 in Case 7
    np.testing.assert_allclose(k[:, 0, 0], 1 + (0.2 - 0.5) * lam**2 + lam**4 / 4, rtol=1e-14)


@pytest.mark.slow
def test_frequencies_equal_those_of_the_paper_beam_with_less_shear():
    case = table1_case(1)
    compressed = induced_frequencies(case.replace(beam="eb_axial", eta_s="0.5", eta_N="0.3"), dps=20)
    sheared = induced_frequencies(table1_case(1).replace(eta_s="0.2"), dps=20)
    assert compressed.count_ok and sheared.count_ok and compressed.found == sheared.found > 0
    for a, b in zip(compressed.roots, sheared.roots):
        assert abs(complex(a.q) - complex(b.q)) < 1e-15


@pytest.mark.slow
def test_finite_beam_agrees_with_the_closed_form():
    params = table1_case(7).replace(beam="eb_axial", eta_N="0.3")
    result = validate(params, tau_max=40.0, estimate=False)
    assert result.agrees and max(result.relative_diff.values()) < 2e-3, result.relative_diff
