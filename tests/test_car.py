"""The car (derivations/vehicles.py) on n = 4 contacts: its frequencies against independent references.

References: the argument principle on a circle around each cluster of roots (a contour other than the
search's tiling), which must count both members of the close pairs that two bogies interacting only through
the rail produce; Newton's method on E_chr from every local minimum of |E_chr| on a dense grid; and the
reductions of the car to its parts (two bogies far apart on a damped track give each bogie's roots twice,
a one-wheel oscillator with a rigid spring is the moving mass of both masses).
"""

from __future__ import annotations

import cmath
import json
from pathlib import Path

import mpmath
import numpy as np
import pytest

from moving_bogie.api import induced_frequencies
from moving_bogie.cli import main
from moving_bogie.kernels.bound import bind
from moving_bogie.kernels.characteristic import Characteristic, CharacteristicArray
from moving_bogie.model.cases import table1_case
from moving_bogie.model.files import load_params_file

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def winding(E, centre, radius, floor=0.0, points=4000):
    """Roots of E inside |q - centre| = r (argument principle, trapezoid on the circle).

    r starts at ``radius`` and shrinks (down to ``floor``) while the circle meets the cut of K, where E
    jumps: a step of the argument of a radian or more between neighbouring points.
    """
    t = np.linspace(0, 2 * np.pi, points, endpoint=False)
    while True:
        values = E(centre + radius * np.exp(1j * t))
        steps = np.angle(np.roll(values, -1) / values)
        if np.max(np.abs(steps)) < 1.0:
            return int(round(np.sum(steps) / (2 * np.pi)))
        radius /= 4
        assert radius > floor, f"no circle around {centre} clear of the cut of K"


def clusters(qs, gap):
    """Groups of roots closer than ``gap`` to one another (single linkage), as lists."""
    groups = []
    for q in sorted(qs, key=lambda z: (z.real, z.imag)):
        for g in groups:
            if min(abs(q - x) for x in g) < gap:
                g.append(q)
                break
        else:
            groups.append([q])
    return groups


@pytest.fixture(scope="module")
def car():
    params, _ = load_params_file(EXAMPLES / "car.toml")
    return params, induced_frequencies(params, dps=20)


@pytest.mark.slow
def test_car_roots_are_counted_on_other_contours(car):
    params, result = car
    assert result.count_ok and result.verdict.state == "stable"
    E = CharacteristicArray(bind(params))
    qs = [complex(r.q) for r in result.roots]
    # Two bogies interact only through the rail: their roots come in pairs far closer than the others.
    assert min(abs(a - b) for i, a in enumerate(qs) for b in qs[:i]) < 1e-6
    for group in clusters(qs, 1e-5):
        centre = np.mean(group)
        others = [abs(q - centre) for q in qs if q not in group]
        span = max(abs(q - centre) for q in group)
        assert winding(E, centre, min(0.3 * min(others), 1e-3), 10 * span) == len(group), (
            f"cluster at {centre}"
        )


@pytest.mark.slow
def test_car_roots_against_a_dense_scan(car):
    """Every local minimum of |E_chr| on a grid that Newton turns into a root is a root found."""
    params, result = car
    E = CharacteristicArray(bind(params))
    x = np.linspace(0.004, 1.2, 600)
    y = np.linspace(0.0005, 0.3, 300)
    X, Y = np.meshgrid(x, y)
    values = np.abs(E(X + 1j * Y))
    inner = values[1:-1, 1:-1]
    is_min = np.ones_like(inner, dtype=bool)
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            if dx or dy:
                is_min &= inner < values[1 + dy : values.shape[0] - 1 + dy, 1 + dx : values.shape[1] - 1 + dx]
    precise = Characteristic(bind(params))
    found = [complex(r.q) for r in result.roots]
    newton = []
    with mpmath.workdps(20):
        for i, j in zip(*np.nonzero(is_min)):
            start = complex(X[i + 1, j + 1], Y[i + 1, j + 1])
            try:
                q = complex(mpmath.findroot(precise, mpmath.mpc(start), tol=1e-24, maxsteps=50))
            except (ValueError, ZeroDivisionError):
                continue
            if abs(q - start) < 0.05:
                newton.append(q)
    assert newton, "the scan found no root"
    for q in newton:
        assert min(abs(q - f) for f in found) < 1e-8 * max(1.0, abs(q)), f"scan root {q} not found"
    # The scan is not blind: it sees several distinct roots (the other direction, every root found is a
    # root, is the winding test above; roots next to the cut of K need not be grid minima).
    print([g[0] for g in clusters(newton, 1e-5)])
    assert len(clusters(newton, 1e-5)) >= 4


@pytest.mark.slow
def test_car_frequencies_json_in_si(capsys):
    assert main(["frequencies", "--file", str(EXAMPLES / "car.toml"), "--json", "--dps", "20"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["count_ok"] and data["verdict"]["state"] == "stable"
    assert all("omega" in root for root in data["roots"])


def _bogie_values(case=7):
    p = table1_case(case)
    return {
        k: p.to_exact_dict()[k] for k in ("alpha", "eta_f", "eta_M", "d", "mu_v", "J_b", "kappa_v", "eta_v")
    }


@pytest.mark.slow
def test_two_far_bogies_give_each_bogie_root_twice():
    """A car with a vanishing secondary suspension, bogies far apart on a damped track."""
    values = _bogie_values()
    bogie = table1_case(7).replace(eta_f="0.3")
    roots = induced_frequencies(bogie, dps=20)
    assert roots.count_ok
    car = table1_case(7).replace(
        vehicle="car", eta_f="0.3", L_c=40, mu_c=50, J_c=5000, kappa_sec="1e-9", eta_sec="1e-9"
    )
    assert {k: car.to_exact_dict()[k] for k in values} == values | {"eta_f": "0.3"}
    E = CharacteristicArray(bind(car))
    for root in roots.roots:
        q = complex(root.q)
        radius = 0.2 * min(
            abs(q.imag), min([abs(q - complex(o.q)) for o in roots.roots if o is not root] + [1])
        )
        assert winding(E, q, radius, 1e-9) == 2, f"bogie root {q}"


def test_rigid_oscillator_is_the_moving_mass():
    """kappa_v -> infinity: the sprung mass rides on the wheel, a moving mass eta_M + mu_v."""
    base = table1_case(7)
    mass = base.replace(vehicle="mass", eta_M=3)
    oscillator = base.replace(vehicle="oscillator", eta_M=1, mu_v=2, kappa_v="1e8", eta_v=0)
    Em, Eo = Characteristic(bind(mass)), Characteristic(bind(oscillator))
    with mpmath.workdps(30):
        # roots of the moving mass by Newton from a grid of starts (reference), then of the oscillator
        starts = [mpmath.mpc(x, y) for x in (0.3, 0.6, 0.9) for y in (0.05, 0.2)]
        seen = []
        for s in starts:
            try:
                q = mpmath.findroot(Em, s, tol=1e-25, maxsteps=60)
            except (ValueError, ZeroDivisionError):
                continue
            if all(abs(q - x) > 1e-10 for x in seen):
                seen.append(q)
        assert seen
        for q in seen:
            qo = mpmath.findroot(Eo, q, tol=1e-25, maxsteps=60)
            assert abs(qo - q) < 1e-6 * abs(q), (q, qo)


@pytest.mark.slow
def test_car_steady_state_against_quadrature():
    """Eq. (39) for the car: n_X(0) / E_chr(0) against the static solution written out by hand.

    The loads P act at the wheels, so in the steady state no suspension is strained: each wheel carries 2
    and W_i = (4 / pi) sum_j K(xi_i - xi_j, 0) (Eq. (28)), with K(xi, 0) by adaptive quadrature of
    e^{i p xi} Q / N over real p (mpmath.quad, not the residues); each bogie follows its wheels rigidly and
    the body its bogies.
    """
    params, _ = load_params_file(EXAMPLES / "car.toml")
    chr_ = Characteristic(bind(params))
    with mpmath.workdps(20):
        zero = mpmath.mpc(0)
        kv = chr_.kernel_values(zero)
        E0 = chr_.system.e_chr(zero, kv.K)
        steady = {name: n / E0 for name, n in chr_.numerators(zero, kv).items()}
        xi = [mpmath.mpf(x) for x in chr_.system.positions]
        track = chr_.kernel.module
        args = chr_.kernel.arguments()
        n = [mpmath.mpc(c) for c in track.n_coeffs(zero, **args)]
        qc = [mpmath.mpc(c) for c in track.q_coeffs(zero, **args)]

        def K(x):
            f = lambda p: mpmath.exp(1j * p * x) * mpmath.polyval(qc, p) / mpmath.polyval(n, p)  # noqa: E731
            # unit panels: e^{i p xi} oscillates about three times per panel at the largest offset
            return mpmath.quad(f, [-mpmath.inf, *range(-60, 61), mpmath.inf])

        # the 16 offsets xi_i - xi_j take 9 values (0 four times, +-d and +-L twice): one quadrature each,
        # keyed to 15 digits (d - 0 and (L + d) - L differ by 3e-21, K by as little there)
        quadratures: dict[str, mpmath.mpc] = {}

        def K_once(x):
            key = mpmath.nstr(x, 15)
            if key not in quadratures:
                quadratures[key] = K(x)
            return quadratures[key]

        for i in range(4):
            W = 4 / mpmath.pi * mpmath.fsum(K_once(xi[i] - xi[j]) for j in range(4))
            # the quadrature's absolute accuracy at the offsets L_c, L_c + d is about 1e-7
            assert abs(steady[f"w_{i + 1}"] - W) < 1e-6 * abs(W)
    w = [steady[f"w_{i + 1}"] for i in range(4)]
    d, L = xi[1], xi[2]
    for b, (rear, front) in enumerate(((w[0], w[1]), (w[2], w[3])), start=1):
        assert abs(steady[f"u_b{b}"] - (rear + front) / 2) < 1e-12
        assert abs(steady[f"theta_b{b}"] - (front - rear) / d) < 1e-12
    assert abs(steady["u_c"] - (steady["u_b1"] + steady["u_b2"]) / 2) < 1e-12
    assert abs(steady["theta_c"] - (steady["u_b2"] - steady["u_b1"]) / L) < 1e-12


@pytest.fixture(scope="module")
def two_layer_car():
    """The car on the two-layer track and its induced frequencies at 30 digits (searched once, for the
    two tests of its close pair below)."""
    params, _ = load_params_file(EXAMPLES / "car-two-layer.toml")
    return params, induced_frequencies(params, dps=30)


@pytest.mark.slow
def test_car_on_two_layers_resolves_a_pair_1e13_apart(two_layer_car):
    """On the two-layer track the bogies' pair is 7e-14 apart: both members found, polished, counted."""
    params, result = two_layer_car
    assert result.count_ok and result.verdict.state == "stable"
    assert all(r.multiplicity == 1 for r in result.roots)
    qs = [complex(r.q) for r in result.roots]
    gaps = sorted(abs(a - b) for i, a in enumerate(qs) for b in qs[:i])
    assert gaps[0] < 1e-12
    # Reference: Newton at 60 digits from either side of the pair converges to two roots 7e-14 apart.
    pair = [q for q in qs if min(abs(q - o) for o in qs if o != q) == gaps[0]]
    precise = Characteristic(bind(params))
    ends = []
    with mpmath.workdps(60):
        centre = mpmath.mpc(sum(pair) / 2)
        for side in (1, -1):
            q = centre + side * 1e-7 * (pair[0] - pair[1]) / abs(pair[0] - pair[1])
            for _ in range(60):  # plain Newton, linear until it is within the pair's distance
                E, dE = precise.value_and_derivative(q)
                q -= E / dE
            ends.append(q)
    assert abs(ends[0] - ends[1]) > 1e-15
    for q in pair:
        assert min(abs(q - complex(e)) for e in ends) < 1e-16


@pytest.mark.slow
def test_car_time_series_against_bromwich():
    """Every response of the car in closed form (residues at the 11 pairs + branch cut, Eqs. (35)-(43))
    against the direct quadrature of the Bromwich integral on Im q = -a (no residues, no cut)."""
    from moving_bogie.api import closed_form_response
    from moving_bogie.response.bromwich import bromwich_line

    params, _ = load_params_file(EXAMPLES / "car.toml")
    tau = np.array([5.0, 20.0, 60.0])
    series = closed_form_response(params, tau, dps=20)
    reference = bromwich_line(bind(params), tau)
    assert set(series.responses) == set(reference) and len(series.responses) == 10
    for name, values in series.responses.items():
        scale = max(np.max(np.abs(reference[name])), 1e-3)  # rotations are small: compare with w ~ 1
        assert np.max(np.abs(values - reference[name].real)) < 1e-6 * scale, name


def test_mirrors_keep_the_roots_precision():
    """The mirror -conj(q) of a 30-digit root is formed at 30 digits, not rounded to double precision.

    Reference: the mirror's real and imaginary parts are exactly -Re q and Im q (negation is exact), so
    the two members agree to the last digit; rounded to double they would differ by ~1e-17, which near a
    close pair (7e-14 apart on the two-layer car) spoils the residue in the fourth digit.
    """
    from types import SimpleNamespace

    from moving_bogie.response.residues import both_members

    with mpmath.workdps(30):
        q = mpmath.mpc("0.025302220383382850494123456789", "0.0062633858106962469663987654321")
    root = SimpleNamespace(q=q, multiplicity=1, decimals=28)
    result = SimpleNamespace(count_ok=True, roots=[root], dps=30, warnings=[])
    first, mirror = both_members(result)
    with mpmath.workdps(40):
        assert abs(mirror.real + q.real) < mpmath.mpf(10) ** -31
        assert abs(mirror.imag - q.imag) < mpmath.mpf(10) ** -31
        assert abs(first - q) < mpmath.mpf(10) ** -31


@pytest.mark.slow
def test_car_on_two_layers_residues_of_a_close_pair_are_mirrors(two_layer_car):
    """The residue of -conj(q) is the conjugate of that of q (E_chr is real on the imaginary axis), also for
    the pair 7e-14 apart, so that the imaginary parts of the residue sum cancel (they did not when the
    mirror was rounded to double precision)."""
    from moving_bogie.response.residues import residue_expansion

    params, result = two_layer_car
    expansion = residue_expansion(bind(params), result, shapes=False)
    q = expansion.q
    for name in expansion.names:
        a = expansion.amplitudes[name]
        scale = np.max(np.abs(a))
        for j in range(q.size):
            k = int(np.argmin(np.abs(q + np.conj(q[j]))))
            # 30 digits less the 13 that the pair 7e-14 apart cancels leave ~17: 1e-10 is generous
            assert abs(a[k] - np.conj(a[j])) < 1e-10 * scale, (name, q[j])
    harmonics = expansion.harmonics(np.linspace(0.0, 400.0, 81))
    assert all(np.all(np.isfinite(v)) for v in harmonics.values())


def _two_bogies_determinant(params):
    """E of two bogies that touch the rail at 0, d and L_c, L_c + d and share nothing but the rail.

    Built here with numpy from the bogie's own generated matrices, placed block-diagonally (no body, no
    secondary suspension): the block system [[pi I + 2 Kmat D_cc, 2 Kmat D_ci], [D_ic, D_ii]] of Eq. (28)
    over the two bogies' rows, with Kmat_ij = K(xi_i - xi_j, q) of the track.
    """
    from moving_bogie.generated import vehicle_bogie as bogie
    from moving_bogie.kernels.track import TrackKernelArray

    ns = params.as_float()
    args = {name: float(getattr(ns, name)) for name in bogie.MATRIX_ARGUMENTS}
    M1, C1, K1 = (
        np.array(f(**args), dtype=float)
        for f in (bogie.mass_matrix, bogie.damping_matrix, bogie.stiffness_matrix)
    )
    d, L = float(ns.d), float(ns.L_c)
    xi = np.array([0.0, d, L, L + d])
    # DOFs: w_1..w_4, then (u, theta) of bogie 1 and of bogie 2; bogie DOFs are (w_rear, w_front, u, theta)
    rows = [(0, 1, 4, 5), (2, 3, 6, 7)]
    mats = []
    for B in (M1, C1, K1):
        A = np.zeros((8, 8))
        for idx in rows:
            A[np.ix_(idx, idx)] = B
        mats.append(A)
    M, C, Kv = mats
    kernel = TrackKernelArray(bind(params))
    offsets = (xi[:, None] - xi[None, :]).ravel()

    def E(q):
        q = np.asarray(q, dtype=complex)
        flat = q.reshape(-1)
        Kmat = np.stack(kernel(flat, offsets).K, axis=-1).reshape(flat.shape + (4, 4))
        D = Kv + flat[:, None, None] * (1j * C - flat[:, None, None] * M)
        A = D.copy()
        A[:, :4, :] = 2 * Kmat @ D[:, :4, :]
        A[:, range(4), range(4)] += np.pi
        return np.linalg.det(A).reshape(q.shape)

    return E


def test_car_without_secondary_suspension_is_two_bogies_and_a_free_body():
    """kappa_sec, eta_sec -> 0 at the normal bogie spacing: the car's roots are those of its two bogies
    interacting through the rail (reference: the determinant of two bogie blocks built above, no body)
    plus the body's rigid modes on its two soft springs (reference: by hand, bounce q^2 = 2 kappa_sec / mu_c,
    pitch q^2 = 2 kappa_sec (L_c / 2)^2 / J_c, the bogies being rigid compared with kappa_sec)."""
    car = table1_case(7).replace(vehicle="car", L_c=9, mu_c=8, J_c=60, kappa_sec="1e-9", eta_sec="1e-9")
    result = induced_frequencies(car, dps=20)
    assert result.count_ok
    qs = [complex(r.q) for r in result.roots]
    body = [q for q in qs if abs(q) < 1e-3]
    bogies = [q for q in qs if abs(q) >= 1e-3]
    # the body's two rigid modes on two springs kappa_sec and two dampers (2 eta_sec each, the scaling of
    # the bogie's 2 eta_v in Eq. (38)) at -L_c/2 and +L_c/2 from its centre, the bogies held:
    # -q^2 m + i q c + k = 0 with (m, c, k) = (mu_c, 4 eta, 2 kappa) and (J_c, eta L_c^2, kappa L_c^2 / 2)
    kappa, eta, L = 1e-9, 1e-9, 9.0
    expected = [
        (1j * c + cmath.sqrt(4 * m * k - c**2)) / (2 * m)
        for m, c, k in ((8.0, 4 * eta, 2 * kappa), (60.0, eta * L**2, kappa * L**2 / 2))
    ]
    assert len(body) == 2
    for q, ref in zip(sorted(body, key=abs), sorted(expected, key=abs)):
        # the bogies are not quite rigid: they and the rail give way by ~kappa_sec / kappa_v relative
        assert abs(q - ref) < 1e-6 * abs(ref), (q, ref)
    # two bogies on the rail: every root of the reference determinant near the car's, and as many
    E_ref = _two_bogies_determinant(car)
    assert len(bogies) == 8
    # the two bogies' roots come in pairs (the rail couples them weakly at the spacing L_c = 9)
    for group in clusters(bogies, 1e-3):
        centre = np.mean(group)
        others = [abs(q - centre) for q in bogies if q not in group]
        span = max(abs(q - centre) for q in group)
        radius = min(0.3 * min(others), 1e-2, 0.5 * centre.imag)
        assert winding(E_ref, centre, radius, 10 * span) == len(group) == 2, f"pair at {centre}"
    for q in bogies:  # secant iteration on the reference from the car's root: it is a root of both
        a, b = q * (1 + 1e-6), q
        fa, fb = E_ref(np.array([a, b]))
        for _ in range(40):
            a, b, fa = b, b - fb * (b - a) / (fb - fa), fb
            fb = E_ref(np.array([b]))[0]
            if abs(b - a) < 1e-13 * abs(b):
                break
        else:
            raise AssertionError(f"secant on the reference did not converge from {q}")
        # the secondary suspension (1e-9) moves a root by ~1e-9 relative (measured 1.4e-9 for the lowest
        # pair, below 1e-11 for the others); the bogies' pairs are 3e-5 and more apart, so each member of
        # a pair converges to its own reference root
        assert abs(b - q) < 1e-7 * abs(q), (q, b)
