"""K(xi, q) and dK/dq by residues (kernels/track.py) against direct numerical quadrature over real p.

Reference: Eq. (29), K = integral of exp(i p xi) Q/N dp over the real line, evaluated with scipy's QUADPACK
(QAWF Fourier integrals for xi != 0, QAGI for xi = 0) on the generated N, Q coefficients; dK/dq against
quadrature of exp(i p xi) (Q_q N - Q N_q) / N^2. Independent of the residue sums being tested.
"""

import mpmath
import numpy as np
import pytest
from scipy import integrate

from moving_bogie.kernels.bound import bind
from moving_bogie.kernels.track import TrackKernel, TrackKernelArray, foundation_arguments
from moving_bogie.model.cases import table1_case


def _params(beam):
    p = table1_case(1)
    if beam == "tr":
        p = p.replace(beam="tr", S=10, r="0.09")
    return p


def _horner(coeffs, p):
    """The polynomial with ``coeffs`` (highest power first) at the scalar ``p``: QUADPACK calls the
    integrand one point at a time, where Python's complex arithmetic is much cheaper than numpy's."""
    acc = 0j
    for c in coeffs:
        acc = acc * p + c
    return acc


def _integrand_parts(mod, args, q, derivative):
    n, qc, nq, qq = (
        [complex(c) for c in getattr(mod, f)(q, **args)]
        for f in ("n_coeffs", "q_coeffs", "n_coeffs_dq", "q_coeffs_dq")
    )

    def f(p):
        N, Q = _horner(n, p), _horner(qc, p)
        if not derivative:
            return Q / N
        return (_horner(qq, p) * N - Q * _horner(nq, p)) / N**2

    return f


def quadrature_K(params, q, xi, derivative=False):
    mod = bind(params).foundation
    return quadrature_module_K(mod, foundation_arguments(bind(params), params.as_float()), q, xi, derivative)


def quadrature_module_K(mod, args, q, xi, derivative=False):
    """Eq. (29) by QUADPACK for any generated foundation module ``mod`` with keyword arguments ``args``."""
    f = _integrand_parts(mod, args, q, derivative)
    opts = {"limit": 400}
    if xi == 0:
        re = integrate.quad(lambda p: f(p).real, -np.inf, np.inf, epsabs=1e-13, **opts)[0]
        im = integrate.quad(lambda p: f(p).imag, -np.inf, np.inf, epsabs=1e-13, **opts)[0]
        return re + 1j * im
    # int_0^inf [(f(p)+f(-p)) cos(p xi) + i (f(p)-f(-p)) sin(p xi)] dp, finite part [0, A] + Fourier tail
    even = lambda p: f(p) + f(-p)  # noqa: E731
    odd = lambda p: f(p) - f(-p)  # noqa: E731
    A = 30.0
    total = 0j
    for part, weight in ((even, "cos"), (odd, "sin")):
        factor = 1 if weight == "cos" else 1j
        for comp, unit in ((lambda p, f=part: f(p).real, 1), (lambda p, f=part: f(p).imag, 1j)):
            head = integrate.quad(comp, 0, A, weight=weight, wvar=abs(xi), limit=400, epsabs=1e-14)[0]
            tail = integrate.quad(comp, A, np.inf, weight=weight, wvar=abs(xi), limlst=200, epsabs=1e-14)[0]
            sign = 1 if (weight == "cos" or xi > 0) else -1
            total += factor * unit * sign * (head + tail)
    return total


@pytest.mark.parametrize("beam", ["eb", "tr"])
@pytest.mark.parametrize("q", [0.3 + 0.02j, 0.31 + 0.2j, 0.9 - 0.3j, 0.05 - 0.6j, 1.4 + 0.04j, 1.4 + 0.17j])
def test_K_and_dK_against_quadrature(beam, q):
    """Both sides of the cut line Im q = eta_f = 0.1 (the last two points straddle it past q_c)."""
    params = _params(beam)
    mpmath.mp.dps = 30
    d = float(params.d)
    kv = TrackKernel(bind(params))(mpmath.mpc(q), [0, d, -d], derivative=True)
    for k, xi in enumerate((0.0, d, -d)):
        ref = quadrature_K(params, q, xi)
        assert abs(complex(kv.K[k]) - ref) < 1e-9 * max(1, abs(ref)), (xi, kv.K[k], ref)
        dref = quadrature_K(params, q, xi, derivative=True)
        assert abs(complex(kv.dK[k]) - dref) < 1e-8 * max(1, abs(dref)), (xi, kv.dK[k], dref)


def test_K_jumps_across_the_cut_but_not_across_the_gap():
    """Eq. (29): K jumps across Im q = eta_f right of the branch point q_c, is continuous left of it."""
    params = _params("eb")
    kernel = TrackKernelArray(bind(params))
    eta_f = float(params.eta_f)
    h = 1e-7
    gap = kernel(np.array([0.1 + 1j * (eta_f - h), 0.1 + 1j * (eta_f + h)]), [0.0]).K[0]
    cut = kernel(np.array([1.0 + 1j * (eta_f - h), 1.0 + 1j * (eta_f + h)]), [0.0]).K[0]
    assert abs(gap[0] - gap[1]) < 1e-5
    assert abs(cut[0] - cut[1]) > 1e-2


def test_numpy_and_mpmath_backends_agree():
    params = _params("tr")
    rng = np.random.default_rng(7)
    q = rng.uniform(0, 1.5, 20) + 1j * rng.uniform(-1, 1, 20)
    d = float(params.d)
    arr = TrackKernelArray(bind(params))(q, [0.0, d, -d], derivative=True)
    mpmath.mp.dps = 25
    for j in range(q.size):
        kv = TrackKernel(bind(params))(mpmath.mpc(q[j]), [0, d, -d], derivative=True)
        for k in range(3):
            assert abs(complex(kv.K[k]) - arr.K[k][j]) < 1e-11 * max(1, abs(arr.K[k][j]))
            assert abs(complex(kv.dK[k]) - arr.dK[k][j]) < 1e-10 * max(1, abs(arr.dK[k][j]))


def test_near_coalescing_p_roots_are_handled():
    """Where two roots of N(p, q) on the same side coincide, the separate residues blow up while their sum
    stays finite: K near such a q must still match quadrature (precision is raised automatically)."""
    params = _params("eb")
    mpmath.mp.dps = 30
    kernel = TrackKernel(bind(params))
    # locate a q where dN/dp and N vanish together (a double root in p) off the cut, by Newton on (p, q)
    mod = bind(params).foundation
    f = params.as_mp()
    args = foundation_arguments(bind(params), f)

    def system(p, q):
        c = mod.n_coeffs(q, **args)
        n = sum(ck * p ** (4 - k) for k, ck in enumerate(c))
        dn = sum(ck * (4 - k) * p ** (3 - k) for k, ck in enumerate(c[:-1]))
        return n, dn

    p0, q0 = mpmath.findroot(system, (mpmath.mpc(0.5, 1.0), mpmath.mpc(0.8, -0.8)))
    roots = kernel.p_roots(q0)
    same_side = sum(1 for p in roots if abs(p - p0) < 1e-6)
    assert same_side == 2
    q = q0 + mpmath.mpf("1e-12")
    kv = kernel(q, [0, float(params.d)])
    for k, xi in enumerate((0.0, float(params.d))):
        ref = quadrature_K(params, complex(q), xi)
        assert abs(complex(kv.K[k]) - ref) < 1e-8 * max(1, abs(ref))


@pytest.mark.parametrize("beam", ["eb", "tr"])
def test_a_large_batch_of_e_chr_is_evaluated_in_pieces_bit_for_bit(beam):
    """E_chr on more than ``CHUNK`` points (a count's contour) is evaluated in pieces: every value must be
    the one the whole batch in one piece gives, to the last bit (the polish starts and the far-field rho
    are printed from such values)."""
    from moving_bogie.kernels.characteristic import CHUNK, CharacteristicArray

    fast = CharacteristicArray(bind(_params(beam)))
    rng = np.random.default_rng(11)
    n = 2 * CHUNK + 37
    q = rng.uniform(-4, 4, n) + 1j * rng.uniform(-4, 4, n)
    whole = fast.system.e_chr_array(q, fast.kernel_values(q).K)
    pieces = fast(q)
    assert pieces.shape == q.shape
    assert np.array_equal(pieces, whole, equal_nan=True)
    square = fast(q[: 2 * CHUNK + 2].reshape(2, CHUNK + 1))  # any shape: pieces of the flattened batch
    assert np.array_equal(square.ravel(), whole[: 2 * CHUNK + 2], equal_nan=True)
