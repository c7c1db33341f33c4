"""The vehicle-rail coupling, written once for every number type: D(q), the block system, dA/dq and b.

A vehicle with N DOFs, its n contacts first, has the dynamic stiffness (d/dtau -> i q, Eq. (21))

    D(q) = -q^2 M + i q C + K,        dD/dq = -2 q M + i C,

from its generated matrices M, C, K. The rail answers a contact force f_j with the deflection
pi W_i = 2 sum_j G_ij f_j (the beam rows of Eq. (28)); on a continuous track G is the kernel matrix
G_ij = K(xi_i - xi_j, q) of Eq. (29). With the wheel forces f = s - (D x)_c (s the static loads) the
deflections x = [W; Y] (Y the internal DOFs, times i q as in Eq. (30)) solve

    A x = b,   A = [[pi I + 2 G D_cc, 2 G D_ci], [D_ic, D_ii]],   b = [2 G s; 0],

whose determinant is E_chr (Eq. (38) for n wheels, up to a constant factor), and

    dA/dq = [[2 (dG/dq D_cc + G dD_cc/dq), 2 (dG/dq D_ci + G dD_ci/dq)], [dD_ic/dq, dD_ii/dq]]

(Eq. (40) by Jacobi's formula). :func:`coupled_system` takes D and G as given, so the rail side is any
receptance matrix between contacts and the derivative may be taken along any parameter (dG, dD given).

The functions below use only the operations of an arithmetic (:mod:`moving_bogie.kernels.arithmetic`):
``Rows`` for lists of rows of scalars (mpmath, gmpy2, Arb's acb and acb_series, SymPy), ``Batched`` for numpy
arrays over a batch of points, ``ArbMatrices`` (:mod:`moving_bogie.roots.proof.ball_block`) for Arb's
matrices. D is the matrix polynomial in q with the coefficients K, i C, -M, which each arithmetic evaluates
its own way (numpy: one matrix product [1, q, q^2] @ [K, i C, -M] over the batch).

**Harmonics (a track on sleepers).** On a periodically supported rail a contact force at frequency Omega
excites the harmonics Omega_m = Omega + m Omega_0, and the rail's receptance couples them: the contact
deflection at harmonic m is w_m = sum_m' H_mm'(Omega) F_m', with one entry per (contact, harmonic) pair
(n contacts at their phases: an n x n block per pair of harmonics). The vehicle answers each harmonic at its
own frequency, F_m = -D(Omega_m) x_m over its contact rows (D_vehicle = -D: m Omega^2 for a mass). The
coupled system is then the block system above with

- D = :func:`harmonic_blocks` of ``[D(Omega_{-h}), ..., D(Omega_{h})]``, block diagonal over the harmonics
  with every contact DOF (contact, harmonic) first, then the internal DOFs of every harmonic;
- G = (pi / 2) H, the receptance between (contact, harmonic) pairs in the rows and columns of D's contacts;

so that det A = det D_ii det(pi I + 2 G S) = pi^P det D_ii det(I + H S) (P the number of (contact, harmonic)
pairs), S the Schur complement on D_ii (the vehicle condensed to its contacts, harmonic by harmonic). For a
vehicle of contact masses (D_ii empty) this is det[delta_mm' + H_mm' D(Omega_m')] = det[delta_mm' -
D_vehicle(Omega_m) H_mm'] (Sylvester's determinant identity), the Hill determinant of the sleeper track's
characteristic function in the e^{i Omega t} convention. With one harmonic and G the kernel matrix, it is the
continuous track's system above.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from moving_bogie.kernels.arithmetic import Arithmetic

__all__ = [
    "Coupled",
    "Dynamic",
    "coupled_derivative",
    "coupled_system",
    "dynamic_coefficients",
    "dynamic_stiffness",
    "harmonic_blocks",
    "kernel_matrix",
]


@dataclass(frozen=True)
class Coupled:
    """The block system A x = b at one q (or a batch), and dA (None unless a derivative was asked for)."""

    A: Any
    b: Any
    dA: Any


@dataclass(frozen=True)
class Dynamic:
    """A vehicle's D(q) as the matrix polynomial K + q (i C) + q^2 (-M): its coefficients, lowest first."""

    coefficients: tuple


def dynamic_coefficients(matrices: Sequence[Any], ops: Arithmetic) -> Dynamic:
    """The coefficients (K, i C, -M) of D(q) from the generated (M, C, K): once per vehicle and type."""
    M, C, K = matrices
    return Dynamic((K, ops.scale(ops.i, C), ops.scale(-1, M)))


def dynamic_stiffness(q: Any, matrices: Any, ops: Arithmetic, derivative: bool = False) -> tuple:
    """(D(q), dD/dq or None): D = -q^2 M + i q C + K, dD/dq = -2 q M + i C (Eq. (21), d/dtau -> i q).

    Parameters
    ----------
    q : number or array
        The point (an array of the batch shape for :class:`~moving_bogie.kernels.arithmetic.Batched`).
    matrices : (M, C, K) or Dynamic
        The vehicle's generated matrices in the number type of ``ops``, or their
        :func:`dynamic_coefficients`.
    ops : Arithmetic
        The arithmetic.
    derivative : bool
        Also dD/dq.
    """
    if not isinstance(matrices, Dynamic):
        matrices = dynamic_coefficients(matrices, ops)
    K, iC, minus_M = matrices.coefficients
    D = ops.polynomial(q, (K, iC, minus_M))
    if not derivative:
        return D, None
    return D, ops.add(ops.scale(2 * q, minus_M), iC)


def kernel_matrix(values: Sequence[Any], index: Any, ops: Arithmetic) -> Any:
    """G_ij = K(xi_i - xi_j, q) (Eq. (29)) from the kernel ``values`` at the distinct offsets and
    ``index[i][j]`` (nested sequences or an integer array), the offset of xi_i - xi_j: the receptance
    of a continuous track."""
    return ops.gather(values, index)


def harmonic_blocks(blocks: Sequence[Any], contacts: int, ops: Arithmetic) -> Any:
    """The dynamic stiffness over harmonics: block diagonal in [D(Omega_m) for each harmonic m], every
    (contact, harmonic) DOF first (harmonic by harmonic), then the internal DOFs of every harmonic.

    Parameters
    ----------
    blocks : sequence
        D at each harmonic (N x N, the ``contacts`` first), from :func:`dynamic_stiffness`.
    contacts : int
        The vehicle's contacts n.
    ops : Arithmetic
        The arithmetic.
    """
    H = len(blocks)
    size = ops.count(blocks[0])
    inside = size - contacts
    places = [
        [h * contacts + j for j in range(contacts)] + [H * contacts + h * inside + a for a in range(inside)]
        for h in range(H)
    ]
    return ops.embed(blocks, places, H * size)


def coupled_system(
    D: Any,
    G: Any,
    ops: Arithmetic,
    *,
    loads: Sequence[Any] | None = None,
    dD: Any = None,
    dG: Any = None,
) -> Coupled:
    """The block system of the vehicle on the rail (module docstring; Eqs. (28), (30), (38) for n wheels).

    Parameters
    ----------
    D : matrix
        The vehicle's dynamic stiffness (contacts first), :func:`dynamic_stiffness` or
        :func:`harmonic_blocks`.
    G : matrix
        The rail's receptance between the contacts (n x n; :func:`kernel_matrix` on a continuous track).
    ops : Arithmetic
        The arithmetic of D and G.
    loads : sequence, optional
        The static loads s_j at the contacts: b = [2 G s; 0] (else b is None).
    dD, dG : matrix, optional
        Derivatives of D and G along one variable (q, or a parameter): dA along it (None if neither).

    Returns
    -------
    Coupled
        A, b and dA in the arithmetic of ``ops``.
    """
    n, size = ops.count(G), ops.count(D)
    Dc, Di = ops.split(D, n)
    A = ops.stack(ops.plus_identity(ops.scale(2, ops.matmul(G, Dc)), ops.pi), Di)
    b = None
    if loads is not None:
        b = ops.stack(ops.scale(2, ops.matmul(G, ops.column(loads))), ops.zeros(size - n, 1))
    dA = None if dD is None and dG is None else _derivative(Dc, G, ops, dD, dG, size)
    return Coupled(A, b, dA)


def coupled_derivative(D: Any, G: Any, ops: Arithmetic, *, dD: Any = None, dG: Any = None) -> Any:
    """dA = [[2 (dG D_c + G dD_c)], [dD_i]] of :func:`coupled_system` along one variable (Eq. (40)).

    Parameters
    ----------
    D, G : matrix
        As for :func:`coupled_system`.
    ops : Arithmetic
        The arithmetic.
    dD, dG : matrix, optional
        The derivatives of D and G along the variable (a term whose derivative is None is left out; at least
        one is given).

    Returns
    -------
    matrix
        dA in the arithmetic of ``ops``.
    """
    return _derivative(ops.split(D, ops.count(G))[0], G, ops, dD, dG, ops.count(D))


def _derivative(Dc: Any, G: Any, ops: Arithmetic, dD: Any, dG: Any, size: int) -> Any:
    """dA from the contact rows D_c of D (see :func:`coupled_derivative`)."""
    n = ops.count(G)
    terms = []
    if dG is not None:
        terms.append(ops.matmul(dG, Dc))
    if dD is not None:
        dDc, bottom = ops.split(dD, n)
        terms.append(ops.matmul(G, dDc))
    else:
        bottom = ops.zeros(size - n, size)
    top = terms[0] if len(terms) == 1 else ops.add(terms[0], terms[1])
    return ops.stack(ops.scale(2, top), bottom)
