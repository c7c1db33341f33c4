"""The one vehicle-rail coupling (kernels/coupling.py) in every number type the runtime uses.

The same random complex points, vehicles and receptance matrices go through mpmath (50 digits, the
reference), numpy (batched over the points), gmpy2 (113 bits) and Arb (64 bits, balls; entry by entry and
on Arb's matrices). References:

- the mpmath evaluation at 50 digits for the values (each type agrees to its own precision; every Arb ball
  contains the mpmath value);
- a central difference of the 50-digit evaluation for dA/dq (independent of the derivative's formula);
- the determinant condensed to the contacts by a Schur complement written out in numpy, for the harmonic
  blocks of a track on sleepers.

The coupling on SymPy numbers against the paper's Eq. (38) is tests/test_vehicles.py's block-determinant
check.
"""

from __future__ import annotations

import importlib

import gmpy2
import mpmath
import numpy as np
import pytest
from flint import acb, acb_mat, arb, ctx

from moving_bogie.kernels.arithmetic import Batched, Rows
from moving_bogie.kernels.coupling import coupled_system, dynamic_stiffness, harmonic_blocks
from moving_bogie.roots.proof.ball_block import ArbMatrices

VEHICLES = ("mass", "oscillator", "masses", "bogie", "car")
POINTS = 4


def _case(name: str, seed: int = 0):
    """A vehicle's module, parameters (doubles), points q and receptances G = G0 + q G1 + q^2 G2."""
    module = importlib.import_module(f"moving_bogie.generated.vehicle_{name}")
    rng = np.random.default_rng(100 + seed)
    params = {k: float(10 ** rng.uniform(-1, 1)) for k in module.MATRIX_ARGUMENTS}
    q = rng.uniform(-1.5, 1.5, POINTS) + 1j * rng.uniform(-0.5, 0.5, POINTS)
    n = module.CONTACTS
    G = rng.normal(size=(3, n, n)) + 1j * rng.normal(size=(3, n, n))
    return module, params, q, G


def _evaluate(module, params, q, G, ops, convert, matrix=None):
    """(A, b, dA) at one q in the arithmetic ``ops``, every input converted exactly by ``convert`` (and the
    matrices by ``matrix``, for Arb's acb_mat; lists of rows are returned)."""
    matrix = matrix or (lambda rows: rows)
    values = {k: convert(v) for k, v in params.items()}
    matrices = [
        matrix([[x if isinstance(x, int) and x == 0 else convert(x) for x in row] for row in f(**values)])
        for f in (module.mass_matrix, module.damping_matrix, module.stiffness_matrix)
    ]
    loads = [convert(s) for s in module.static_loads(**values)]
    z = convert(q)
    Gk = [[[convert(x) for x in row] for row in g] for g in G]
    n = len(Gk[0])
    Gq = [[Gk[0][r][c] + z * Gk[1][r][c] + z * z * Gk[2][r][c] for c in range(n)] for r in range(n)]
    dGq = [[Gk[1][r][c] + 2 * z * Gk[2][r][c] for c in range(n)] for r in range(n)]
    D, dD = dynamic_stiffness(z, matrices, ops, derivative=True)
    out = coupled_system(D, matrix(Gq), ops, loads=loads, dD=dD, dG=matrix(dGq))
    A, b, dA = (x.tolist() if isinstance(x, acb_mat) else x for x in (out.A, out.b, out.dA))
    return A, [row[0] for row in b], dA


def _mp(x) -> mpmath.mpc:
    return mpmath.mpc(x) if not isinstance(x, (gmpy2.mpc, gmpy2.mpfr)) else _from_gmpy2(x)


def _from_gmpy2(x) -> mpmath.mpc:
    """A gmpy2 number as mpmath, exactly (its own digits, not re-rounded in the default context)."""
    if isinstance(x, gmpy2.mpfr):
        return mpmath.mpc(mpmath.mpf(str(x)))
    return mpmath.mpc(mpmath.mpf(str(x.real)), mpmath.mpf(str(x.imag)))


def _reference(module, params, q, G):
    """(A, b, dA, det A) in mpmath at 50 digits."""
    with mpmath.workdps(50):
        ops = Rows(mpmath.pi, mpmath.mpc(0, 1))
        A, b, dA = _evaluate(module, params, q, G, ops, mpmath.mpmathify)
        return A, b, dA, mpmath.det(mpmath.matrix(A))


def _entries(A) -> list:
    return [x for row in A for x in (row if isinstance(row, list) else [row])]


@pytest.mark.parametrize("name", VEHICLES)
def test_numpy_gmpy2_and_arb_agree_with_mpmath(name):
    module, params, qs, G = _case(name)
    matrices = [
        np.array(f(**params), dtype=float)
        for f in (module.mass_matrix, module.damping_matrix, module.stiffness_matrix)
    ]
    Gq = G[0] + qs[:, None, None] * G[1] + (qs * qs)[:, None, None] * G[2]
    dGq = G[1] + 2 * qs[:, None, None] * G[2]
    D, dD = dynamic_stiffness(qs, matrices, Batched, derivative=True)
    batched = coupled_system(D, Gq, Batched, loads=module.static_loads(**params), dD=dD, dG=dGq)
    detA = np.linalg.det(batched.A)
    for k, q in enumerate(qs):
        A, b, dA, det = _reference(module, params, complex(q), G)
        for value, ref in ((batched.A[k], A), (batched.b[k, :, 0], b), (batched.dA[k], dA)):
            ref = np.array(_entries(ref), dtype=complex)
            scale = np.max(np.abs(ref))
            # double precision: a few roundings of terms no larger than the matrix's largest entry
            assert np.max(np.abs(np.ravel(value) - ref)) < 1e-14 * scale, name
        assert abs(detA[k] - complex(det)) < 1e-12 * abs(complex(det)), name

        with gmpy2.context(gmpy2.get_context(), precision=113):
            ops = Rows(gmpy2.const_pi(), gmpy2.mpc(0, 1))
            binary = _evaluate(module, params, complex(q), G, ops, gmpy2.mpc)
        with mpmath.workdps(50):
            for value, ref in zip(binary, (A, b, dA)):
                ref, value = _entries(ref), _entries(value)
                scale = max(abs(x) for x in ref)
                assert max(abs(_mp(x) - y) for x, y in zip(value, ref)) < mpmath.mpf(10) ** -31 * scale, name

        # Arb: entry by entry (acb, as the series of the proofs) and on its matrices (acb_mat)
        for arithmetic, matrix in ((lambda: Rows(acb(arb.pi()), acb(0, 1)), None), (ArbMatrices, _acb_mat)):
            with ctx.workprec(64):
                balls = _evaluate(module, params, complex(q), G, arithmetic(), acb, matrix)
                ball_det = _acb_mat(balls[0]).det()
            with ctx.workprec(400):  # the reference's own digits as (nearly) exact balls
                for value, ref in zip(balls, (A, b, dA)):
                    for x, y in zip(_entries(value), _entries(ref)):
                        assert acb(x).contains(_ball(y)), (name, x, y)
                assert ball_det.contains(_ball(det)), name
                assert ball_det.rad() < 1e-12 * abs(complex(det)), name  # and the balls are tight


def _acb_mat(rows) -> acb_mat:
    return acb_mat([[acb(x) for x in row] for row in rows])


def _ball(x) -> acb:
    """An mpmath number as an acb at the context's precision (its 50 digits, parsed)."""
    re, im = (x.real, x.imag) if isinstance(x, mpmath.mpc) else (x, 0)
    return acb(arb(mpmath.nstr(re, 55)), arb(mpmath.nstr(im, 55)))


@pytest.mark.parametrize("name", VEHICLES)
def test_q_derivative_against_a_central_difference(name):
    """dA/dq (the coupling's derivative, dD/dq and dG/dq in) against (A(q + h) - A(q - h)) / 2h at 50
    digits: the difference's error is h^2 |A'''| / 6 ~ 1e-40 and its rounding 1e-50 / h ~ 1e-30."""
    module, params, qs, G = _case(name, seed=1)
    for q in qs:
        with mpmath.workdps(50):
            h = mpmath.mpf(10) ** -20
            _, _, dA, _ = _reference(module, params, complex(q), G)
            ops = Rows(mpmath.pi, mpmath.mpc(0, 1))
            plus = _evaluate(module, params, mpmath.mpc(q) + h, G, ops, mpmath.mpmathify)[0]
            minus = _evaluate(module, params, mpmath.mpc(q) - h, G, ops, mpmath.mpmathify)[0]
            scale = max(abs(x) for x in _entries(dA))
            for r, row in enumerate(dA):
                for c, x in enumerate(row):
                    fd = (plus[r][c] - minus[r][c]) / (2 * h)
                    assert abs(x - fd) < mpmath.mpf(10) ** -25 * scale, (name, r, c)


def test_harmonic_blocks_against_the_schur_complement():
    """A track on sleepers: D over three harmonics Omega_m = q + m Omega_0 and a full receptance between
    (contact, harmonic) pairs. det A against det D_ii det(pi I + 2 G S) with S, the vehicle condensed to its
    contacts, written out harmonic by harmonic; with a receptance that couples no harmonics, det A is the
    product of the single-harmonic systems."""
    module, params, qs, _ = _case("car", seed=2)
    matrices = [
        np.array(f(**params), dtype=float)
        for f in (module.mass_matrix, module.damping_matrix, module.stiffness_matrix)
    ]
    n, N, omega0 = module.CONTACTS, len(module.DOFS), 0.7
    rng = np.random.default_rng(5)
    G = rng.normal(size=(POINTS, 3 * n, 3 * n)) + 1j * rng.normal(size=(POINTS, 3 * n, 3 * n))
    blocks = [dynamic_stiffness(qs + m * omega0, matrices, Batched)[0] for m in (-1, 0, 1)]
    det = np.linalg.det(coupled_system(harmonic_blocks(blocks, n, Batched), G, Batched).A)
    S = np.zeros((POINTS, 3 * n, 3 * n), dtype=complex)
    inner = np.ones(POINTS, dtype=complex)
    for m, D in enumerate(blocks):
        Dcc, Dci, Dic, Dii = D[:, :n, :n], D[:, :n, n:], D[:, n:, :n], D[:, n:, n:]
        S[:, m * n : (m + 1) * n, m * n : (m + 1) * n] = Dcc - Dci @ np.linalg.solve(Dii, Dic)
        inner *= np.linalg.det(Dii)
    reference = inner * np.linalg.det(np.pi * np.eye(3 * n) + 2 * G @ S)
    assert np.allclose(det, reference, rtol=1e-9, atol=0), np.abs(det / reference - 1)
    assert N * 3 == harmonic_blocks(blocks, n, Batched).shape[-1]

    uncoupled = np.zeros_like(G)
    for m in range(3):
        uncoupled[:, m * n : (m + 1) * n, m * n : (m + 1) * n] = G[
            :, m * n : (m + 1) * n, m * n : (m + 1) * n
        ]
    det = np.linalg.det(coupled_system(harmonic_blocks(blocks, n, Batched), uncoupled, Batched).A)
    product = np.prod(
        [
            np.linalg.det(
                coupled_system(D, uncoupled[:, m * n : (m + 1) * n, m * n : (m + 1) * n], Batched).A
            )
            for m, D in enumerate(blocks)
        ],
        axis=0,
    )
    assert np.allclose(det, product, rtol=1e-9, atol=0)

    # the same assembly in the list-of-rows arithmetic (mpmath) is the same matrix
    ops = Rows(mpmath.pi, mpmath.mpc(0, 1))
    rows = [
        dynamic_stiffness(mpmath.mpc(qs[0] + m * omega0), matrices_rows(module, params), ops)[0]
        for m in (-1, 0, 1)
    ]
    embedded = harmonic_blocks(rows, n, ops)
    batched = harmonic_blocks([D[0] for D in blocks], n, Batched)
    assert np.allclose(np.array(embedded, dtype=complex), batched, rtol=1e-14, atol=1e-14)
    arb_blocks = [_acb_mat([[acb(complex(x)) for x in row] for row in D]) for D in rows]
    arb_embedded = harmonic_blocks(arb_blocks, n, ArbMatrices())
    assert np.allclose(np.array(arb_embedded.mid().tolist(), dtype=complex), batched, rtol=1e-14, atol=1e-14)


def matrices_rows(module, params) -> list:
    return [f(**params) for f in (module.mass_matrix, module.damping_matrix, module.stiffness_matrix)]
