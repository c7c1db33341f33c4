"""The receptance of a rail on discrete supports (moving_bogie.floquet) against independent references.

References: the issue's integral evaluated by mpmath.quad (brute force, no residues, no subtraction); a
finite periodic rail of 300 bays solved directly at one frequency with the exact dynamic stiffness of each
beam element (v = 0, no Floquet theory); the continuous rail's roots of roots/frequencies.py (l -> 0).
"""

from __future__ import annotations

import mpmath
import numpy as np
import pytest

from moving_bogie.generated import vehicle_mass, vehicle_masses
from moving_bogie.kernels.hill import FloquetSystem, VehicleMatrices
from moving_bogie.kernels.periodic_receptance import receptance
from moving_bogie.kernels.sleeper_track import SleeperTrack
from moving_bogie.kernels.smeared_rail import smeared_receptance
from moving_bogie.model.catalogue import default_catalogue

#: the catalogue's rails on periodic supports, (beam, track) -> their generated functions
PERIODIC = default_catalogue().periodic

GROUPS = {"lam": 1.0, "alpha": 0.2, "kappa_f": 0.0, "eta_f": 0.0, "eta_sup": 0.1}


def _track(**changes) -> SleeperTrack:
    return SleeperTrack(PERIODIC["eb", "sleepers"], {**GROUPS, **changes})


def test_lattice_sum_matches_direct_sum():
    """Eq. (S7): the cotangent sum over the four roots against the direct sum over 20001 terms."""
    tr = _track()
    p, w = np.array([0.3, 1.9]), np.array([0.7 - 0.2j, 1.3 + 0.05j])
    j = np.arange(-10_000, 10_001)
    direct = [np.sum(tr.green(pp + j * tr.K, np.full(j.size, ww))) for pp, ww in zip(p, w)]
    assert np.allclose(tr.lattice_sum(p, w), direct, rtol=1e-10, atol=0)


def test_a_kept_receptance_is_the_computed_one_and_a_copy():
    """receptance keeps what it computed by its arguments: asked again it hands out the same numbers (those
    of the computation itself, kernels.periodic_receptance._receptance) as a new array; another track's
    groups or another q are other arguments."""
    from moving_bogie.kernels import periodic_receptance as module

    tr, q, h, s = _track(), 0.8 - 0.3j, np.array([-1, 0]), np.array([0.3, 1.7])
    first = receptance(tr, q, h, s, tol=1e-10)
    first.matrix[0, 0] = 0  # a caller's change stays its own
    again = receptance(tr, q, h, s, tol=1e-10)
    direct = module._receptance(tr, q, h, s, 1e-10, None, 40)
    assert np.array_equal(again.matrix, direct.matrix) and again.matrix[0, 0] != 0
    assert (again.error, again.scale, again.panels) == (direct.error, direct.scale, direct.panels)
    damped = _track(eta_sup=0.2)
    other = receptance(damped, q, h, s, tol=1e-10)
    assert not np.array_equal(other.matrix, again.matrix)
    assert np.array_equal(other.matrix, module._receptance(damped, q, h, s, 1e-10, None, 40).matrix)


#: S(p, w) of :func:`_brute_force` by (lam, p, w, precision): its tests integrate entries at one q on the
#: same panels, so mpmath.quad asks for the lattice sum (two thirds of the integrand's cost) at the same
#: nodes again; each is summed once.
_LATTICE_SUMS: dict = {}


def _brute_force(tr, q, n, m, s_out, s_in, smeared_part=False):
    """(1/2 pi) int [delta G_n e^.. - z G_n G_m e^.. / D] dp by mpmath.quad (D from the direct lattice sum
    would take minutes; the closed-form sum is checked above). With ``smeared_part`` the smeared rail's
    integrand is subtracted (a two-contact entry: the difference decays like p^-8, the parts like p^-4 with
    an oscillating phase that mpmath.quad does not resolve on an infinite interval)."""
    K, a, lam, eta = tr.K, tr.alpha, tr.lam, tr.groups["eta_sup"]

    def G(p, w):
        return 4 / (p**4 - 4 * w**2)

    def S(p, w):
        key = (lam, p, w, mpmath.mp.prec)
        if key not in _LATTICE_SUMS:
            rs = [mpmath.sqrt(2 * w) * u for u in (1, -1)] + [mpmath.sqrt(-2 * w) * u for u in (1, -1)]
            _LATTICE_SUMS[key] = sum(lam / 2 * mpmath.cot(lam * (p - r) / 2) / r**3 for r in rs)
        return _LATTICE_SUMS[key]

    def f(p):
        w = q + a * p
        z = 1 + 2j * eta * w
        gn, gm = G(p - n * K, w), G(p - m * K, w)
        val = (
            -z * gn * gm * mpmath.exp(1j * (p - m * K) * s_in - 1j * (p - n * K) * s_out) / (1 + z * S(p, w))
        )
        if n == m:
            val += gn * mpmath.exp(1j * (p - n * K) * (s_in - s_out))
            if smeared_part:
                val -= gn / (1 + z * gn) * mpmath.exp(1j * (p - n * K) * (s_in - s_out))
        return val

    pts = [-mpmath.inf] + [k * K / 2 for k in range(-12, 13)] + [mpmath.inf]
    return complex(mpmath.quad(f, pts) / (2 * mpmath.pi))


@pytest.mark.slow
@pytest.mark.parametrize("n, m", [(0, 0), (-1, 0), (1, -2)])
def test_receptance_against_mpmath_quad(n, m):
    """Eq. (S9) by residues + Gauss-Kronrod against mpmath.quad of the issue's integral: 1e-11 of |H|."""
    tr, q = _track(), 0.8 - 0.3j
    harmonics = np.array([-2, -1, 0, 1])
    rec = receptance(tr, q, harmonics, [0.3], tol=1e-12)
    i, j = list(harmonics).index(n), list(harmonics).index(m)
    with mpmath.workdps(15):
        ref = _brute_force(tr, q, n, m, 0.3, 0.3)
    assert abs(rec.matrix[i, j] - ref) < 1e-11 * rec.scale


@pytest.mark.slow
def test_receptance_between_contacts_against_mpmath_quad():
    """A two-contact entry of one harmonic: smeared part by residues against mpmath.quadosc, the rest by
    mpmath.quad of (integrand - smeared integrand)."""
    tr, q, n = _track(), 0.8 - 0.3j, -1
    rec = receptance(tr, q, [-1, 0], [0.3, 1.7], tol=1e-12)
    with mpmath.workdps(15):
        rest = _brute_force(tr, q, n, n, 1.7, 0.3, smeared_part=True)
        qn = q + n * tr.Omega0

        def g(k):
            w = qn + tr.alpha * k
            G = 4 / (k**4 - 4 * w**2)
            return G / (1 + (1 + 0.2j * w) * G) * mpmath.exp(-1.4j * k)

        smeared = complex(
            (mpmath.quadosc(g, [-mpmath.inf, 0], omega=1.4) + mpmath.quadosc(g, [0, mpmath.inf], omega=1.4))
            / (2 * mpmath.pi)
        )
    assert abs(smeared_receptance(tr, qn, [-1.4])[0] - smeared) < 1e-13
    # row (contact 1, harmonic -1), column (contact 0, harmonic -1): index i_n * 2 + c
    assert abs(rec.matrix[1, 0] - (smeared + rest)) < 1e-11 * rec.scale


def _element(beta: complex, length: float) -> np.ndarray:
    """Exact dynamic stiffness of a beam element (1/4) y'''' - beta y = 0 (DOFs y, y' at both ends)."""
    r = (4 * beta + 0j) ** 0.25 * np.array([1, 1j, -1, -1j])
    e0, el = np.ones(4), np.exp(r * length)
    B = np.array([e0, r * e0, el, r * el])
    F = 0.25 * np.array([r**3 * e0, -(r**2) * e0, -(r**3) * el, r**2 * el])
    return F @ np.linalg.inv(B)


def _finite_rail(w: complex, lam: float, z: complex, node: int, bays: int = 300) -> complex:
    """Deflection at a node (0: a support, 1: mid-span) of the middle bay under a unit force there."""
    Ke = _element(w**2, lam / 2)
    nel = 2 * bays
    A = np.zeros((2 * nel + 2, 2 * nel + 2), dtype=complex)
    for e in range(nel):
        A[2 * e : 2 * e + 4, 2 * e : 2 * e + 4] += Ke
    for k in range(0, nel + 1, 2):
        A[2 * k, 2 * k] += z * lam
    f = np.zeros(2 * nel + 2, dtype=complex)
    at = 2 * (bays + node)
    f[at] = 1
    return complex(np.linalg.solve(A, f)[at])


def test_element_stiffness_is_the_static_one_at_zero_frequency():
    """The exact element tends to the cubic-Hermite stiffness (EI = 1/4) as beta -> 0."""
    L = 0.7
    k0 = (0.25 / L**3) * np.array(
        [
            [12, 6 * L, -12, 6 * L],
            [6 * L, 4 * L * L, -6 * L, 2 * L * L],
            [-12, -6 * L, 12, -6 * L],
            [6 * L, 2 * L * L, -6 * L, 4 * L * L],
        ]
    )
    assert np.max(np.abs(_element(1e-10, L) - k0)) < 1e-7


@pytest.mark.parametrize(
    "s, node, w",
    [
        (0.0, 0, 0.3 - 0.05j),
        # the same check at mid-span and at a higher frequency (slow: the fast one covers the same code)
        pytest.param(0.5, 1, 0.3 - 0.05j, marks=pytest.mark.slow),
        pytest.param(0.0, 0, 1.1 - 0.2j, marks=pytest.mark.slow),
        pytest.param(0.5, 1, 1.1 - 0.2j, marks=pytest.mark.slow),
    ],
)
def test_receptance_at_rest_against_a_finite_periodic_rail(s, node, w):
    """v = 0: sum over n of H[n, 0] at a support and at mid-span against 300 bays solved directly.

    H[n, 0] falls like n^-4 (G(p - n K) ~ 4 / (n K)^4): the harmonics beyond N = 16 add about
    (H[N, 0] + H[-N, 0]) (N / 3 - 1 / 2) (Euler-Maclaurin; half a term for the alternating mid-span
    series), added here; what is left is below the outermost terms, 3e-7 of |H|.
    """
    tr = _track(alpha=0.0)
    N = 16
    rec = receptance(tr, w, np.arange(-N, N + 1), [s], tol=1e-12)
    column = rec.matrix[:, N]
    # at a support the terms keep their sign; at mid-span e^{i n K s} = (-1)^n makes them alternate
    factor = N / 3 - 0.5 if node == 0 else -0.5
    total = column.sum() + (column[0] + column[-1]) * factor
    ref = _finite_rail(w, tr.lam, 1 + 0.2j * w, node)
    # the correction is good to a fraction of the outermost terms: they bound what is left
    assert abs(total - ref) < 1e-10 * abs(ref) + abs(column[0] + column[-1])
    assert abs(column[0] + column[-1]) < 3e-7 * abs(ref)


def _newton(f, q, h=1e-7):
    for _ in range(30):
        step = f(q) / ((f(q + h) - f(q - h)) / (2 * h))
        q -= step
        if abs(step) < 1e-12:
            break
    return q


@pytest.mark.slow
def test_short_bays_give_the_one_layer_roots_at_rate_l4():
    """l -> 0 with k_sup / l fixed: the wheel's root tends to the continuous rail's (roots/frequencies.py,
    eta_f = eta_sup, same alpha, eta_M), the error falls like lam^4 (ratio 16 per halving)."""
    from moving_bogie.api import induced_frequencies
    from moving_bogie.model.params import DimensionlessParams

    params = DimensionlessParams.from_mapping(
        {"beam": "eb", "vehicle": "mass", "eta_f": "0.2", "alpha": "0.3", "eta_M": 2}
    )
    (root,) = [complex(r.q) for r in induced_frequencies(params).roots]
    vehicle = VehicleMatrices.from_module(vehicle_mass, {"eta_M": 2.0})
    errors = []
    for lam in (0.4, 0.2, 0.1):
        tr = _track(lam=lam, alpha=0.3, eta_sup=0.2)
        errors.append(abs(_newton(FloquetSystem(tr, vehicle, N=1, tol=1e-12), root) - root))
    ratios = [a / b for a, b in zip(errors, errors[1:])]
    assert all(14 < r < 18 for r in ratios), ratios


def test_two_wheels_at_short_bays_are_the_continuous_two_masses():
    """Two contacts and their phases: at lam = 0.1 the two masses' roots are the continuous ones to 1e-5."""
    from moving_bogie.api import induced_frequencies
    from moving_bogie.model.params import DimensionlessParams

    params = DimensionlessParams.from_mapping(
        {"beam": "eb", "vehicle": "masses", "eta_f": "0.2", "alpha": "0.3", "eta_M": 2, "d": "1.5"}
    )
    roots = [complex(r.q) for r in induced_frequencies(params).roots]
    vehicle = VehicleMatrices.from_module(vehicle_masses, {"eta_M": 2.0, "d": 1.5})
    system = FloquetSystem(_track(lam=0.1, alpha=0.3, eta_sup=0.2), vehicle, N=0, tol=1e-12)
    for q in roots:
        assert abs(_newton(system, q) - q) < 1e-5


def test_periodic_in_q_and_independent_of_the_bay_the_vehicle_starts_in():
    """f(q + Omega_0) = f(q) up to the truncation; a shift of the vehicle by one bay (or any offset) leaves
    the determinant unchanged (Eq. (S14))."""
    vehicle = VehicleMatrices.from_module(vehicle_masses, {"eta_M": 2.0, "d": 1.3})
    tr = _track(lam=1.0, alpha=0.2, eta_sup=0.1)
    q = 0.4 - 0.2j
    base = FloquetSystem(tr, vehicle, N=3, tol=1e-12)
    f0 = base(q)
    assert abs(FloquetSystem(tr, vehicle, N=3, offset=tr.lam, tol=1e-12)(q) - f0) < 1e-9 * abs(f0)
    assert abs(FloquetSystem(tr, vehicle, N=3, offset=0.37, tol=1e-12)(q) - f0) < 1e-9 * abs(f0)
    # H[n + 1, m + 1](q) = H[n, m](q + Omega_0): the Hill matrix at q + Omega_0 is that at q shifted by one
    h = np.arange(-2, 2)
    a = receptance(tr, q, h, vehicle.positions, tol=1e-12).matrix
    b = receptance(tr, q + tr.Omega0, h, vehicle.positions, tol=1e-12).matrix
    assert np.max(np.abs(a[2:, 2:] - b[:-2, :-2])) < 1e-11 * np.max(np.abs(a))
    # the symmetry q -> Omega_0 - conj(q) is exact for the harmonics -N-1..N
    assert abs(base(tr.Omega0 - np.conj(q)) - np.conj(f0)) < 1e-9 * abs(f0)


@pytest.mark.parametrize("positions", [[0.3], [0.3, 1.7]])
def test_panel_sums_match_the_assembled_integrand(positions):
    """The factored panel sums against Gauss-Kronrod applied to the assembled (nodes, R, R) integrand."""
    from moving_bogie.kernels.periodic_receptance import GAUSS, KRONROD, NODES, _integrand, _panel_sums

    tr, q, harmonics = _track(), 0.7 - 0.05j, np.arange(-2, 3)
    a = np.linspace(-9.0, 8.0, 7)
    b = a + tr.K / 4
    kron, gauss = _panel_sums(tr, q, harmonics, np.array(positions), a, b)
    half = (b - a) / 2
    p = ((a + b)[:, None] / 2 + half[:, None] * NODES[None, :]).ravel()
    f = _integrand(tr, q, harmonics, np.array(positions), p).reshape(a.size, 15, *kron.shape[1:])
    for weights, sums in ((KRONROD, kron), (GAUSS, gauss)):
        reference = np.einsum("k,pkrs->prs", weights, f) * half[:, None, None]
        assert np.allclose(sums, reference, rtol=1e-13, atol=1e-15 * np.max(np.abs(reference)))
