"""A vehicle on n wheels on the track: the block system, E_chr as its determinant (Eq. (38) for n wheels).

Every declared vehicle (``derivations/vehicles.py``) is generated as its mass, damping and stiffness matrices
M, C, K, its contact positions xi_j and static loads s_j, in the dimensionless scaling of Eqs. (15)-(17).
With D(q) = -q^2 M + i q C + K (d/dtau -> i q, Eq. (21)) and Kmat_ij = K(xi_i - xi_j, q) (Eq. (29)), the
wheel deflections W (n of them) and the internal DOFs Y of the vehicle (times i q, as in Eq. (30)) solve

    [[pi I + 2 Kmat D_cc, 2 Kmat D_ci], [D_ic, D_ii]] [W; Y] = [2 Kmat s; 0],

the beam rows of Eq. (28) (pi W_i = 2 sum_j K(xi_i - xi_j) f_j with the wheel forces f_j = s_j - (D x)_j) over
the vehicle's own rows, as :mod:`moving_bogie.kernels.coupling` defines it once for every number type (here
mpmath at one q and numpy arrays of q). Then

- E_chr(q) = det A (for the paper's bogie -1/2 times Eq. (38), for two masses Eq. (38)'s analogue itself: a
  constant factor changes neither the roots nor a residue);
- dE_chr/dq = sum_k det(A with row k replaced by row k of dA/dq) (Jacobi's formula), with
  dA/dq from dD/dq = -2 q M + i C and dK/dq of :mod:`moving_bogie.kernels.track`;
- the residue numerators n_X = det(A with column X replaced by the right-hand side) (Cramer's rule),
  so that X = n_X / E_chr (Eqs. (36), (39)-(43));
- the shape weights G_j = 4 (E_chr s_j - (D n)_j), so that
  i q W~(xi, q) = sum_j G_j K(xi - xi_j, q) / (2 pi E_chr) (Eqs. (44)-(47) for n contacts).

The kernel values are evaluated once per distinct offset xi_i - xi_j (:attr:`VehicleSystem.offsets`).
At one q in mpmath, E_chr and dE_chr/dq come from the system condensed to its wheels
(:mod:`moving_bogie.kernels.condensed`: det A = det D_ii det(pi I + 2 Kmat S)), the same number at a fraction
of the cost of eliminating the whole block system.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from types import ModuleType
from typing import Any

import mpmath
import numpy as np
from numpy.typing import ArrayLike

from moving_bogie.kernels.arithmetic import Batched, Rows
from moving_bogie.kernels.condensed import binary_matrices, condensed_characteristic
from moving_bogie.kernels.coupling import (
    Coupled,
    Dynamic,
    coupled_system,
    dynamic_coefficients,
    dynamic_stiffness,
    kernel_matrix,
)
from moving_bogie.kernels.elimination import lu_factor, lu_solve
from moving_bogie.typing import Matrix, Mpc, Scalar

#: The arithmetic of the one-q backend (:mod:`moving_bogie.kernels.coupling`): mpmath numbers at the
#: working precision (``mpmath.pi`` is evaluated at the precision in force).
_MPMATH = Rows(mpmath.pi, mpmath.mpc(0, 1))


def distinct_offsets(positions: Sequence[Scalar]) -> tuple[list[Scalar], list[list[int]]]:
    """The distinct xi_i - xi_j (0 first) and, for each (i, j), the index of its offset."""
    offsets: list[Scalar] = []
    keys: dict[float, int] = {}
    ordered = [(i, j) for i in range(len(positions)) for j in range(len(positions))]
    ordered.sort(key=lambda ij: ij[0] != ij[1])  # the diagonal (offset 0) first
    table: dict[tuple[int, int], int] = {}
    for i, j in ordered:
        x = positions[i] - positions[j]
        key = round(float(mpmath.re(x)), 12) + 0.0
        if key not in keys:
            keys[key] = len(offsets)
            offsets.append(x)
        table[(i, j)] = keys[key]
    n = len(positions)
    index = [[table[(i, j)] for j in range(n)] for i in range(n)]
    return offsets, index


class VehicleSystem:
    """A generated vehicle module bound to parameter values of one backend (mpmath numbers or floats).

    Parameters
    ----------
    module : module
        ``moving_bogie.generated.vehicle_<name>``.
    values : mapping
        Parameter name -> value for every name in ``module.MATRIX_ARGUMENTS``.
    """

    def __init__(self, module: ModuleType, values: Mapping[str, Any]) -> None:
        args = {name: values[name] for name in module.MATRIX_ARGUMENTS}
        self.module = module
        self.names = tuple(module.DOFS)
        self.contacts = int(module.CONTACTS)
        self.size = len(self.names)
        self.mass = module.mass_matrix(**args)
        self.damping = module.damping_matrix(**args)
        self.stiffness = module.stiffness_matrix(**args)
        self.positions = tuple(module.contact_positions(**args))
        self.loads = tuple(module.static_loads(**args))
        self.offsets, self.index = distinct_offsets(self.positions)

    def natural_frequencies(self) -> list[float]:
        """Natural frequencies (in tau) of the vehicle's bodies with the wheels held: K_ii v = q^2 M_ii v."""
        n = self.contacts
        M = np.array(self.mass, dtype=float)[n:, n:]
        K = np.array(self.stiffness, dtype=float)[n:, n:]
        if M.size == 0:
            return []
        squares = np.linalg.eigvals(np.linalg.solve(M, K)).real
        return [float(np.sqrt(x)) for x in sorted(squares) if x > 0]

    # --- one q, mpmath ---------------------------------------------------------------------------------

    @property
    def matrices(self) -> tuple[Matrix, Matrix, Matrix]:
        """(M, C, K) as generated: lists of rows, the integer 0 where the vehicle couples nothing."""
        return self.mass, self.damping, self.stiffness

    def dynamic(self, q: Mpc, derivative: bool = False) -> tuple[Matrix, Matrix | None]:
        """(D(q), dD/dq or None) at one q, lists of rows with an exact 0 where the vehicle has no coupling
        (so that sums and eliminations can skip it): D = -q^2 M + i q C + K (Eq. (21))."""
        if not hasattr(self, "_dynamic"):
            self._dynamic = dynamic_coefficients(self.matrices, _MPMATH)
        return dynamic_stiffness(q, self._dynamic, _MPMATH, derivative)

    def block(
        self, q: Mpc, K: Sequence[Mpc], dK: Sequence[Mpc] | None = None
    ) -> tuple[Matrix, list[Mpc], Matrix | None, Matrix]:
        """(A, b, dA/dq or None, D) at one q (lists of rows); ``K`` (``dK``) at :attr:`offsets`
        (:func:`~moving_bogie.kernels.coupling.coupled_system`)."""
        D, dD = self.dynamic(q, derivative=dK is not None)
        G = kernel_matrix(K, self.index, _MPMATH)
        dG = None if dK is None else kernel_matrix(dK, self.index, _MPMATH)
        system = coupled_system(D, G, _MPMATH, loads=self.loads, dD=dD, dG=dG)
        return system.A, [row[0] for row in system.b], system.dA, D

    def e_chr(self, q: Mpc, K: Sequence[Mpc]) -> Mpc:
        """E_chr(q) = det A (:meth:`condensed`; the full block system where that does not apply)."""
        reduced = self.condensed(q, K)
        if reduced is not None:
            return reduced[0]
        A, _, _, _ = self.block(q, K)
        return lu_factor(A)[2]

    def condensed(
        self, q: Mpc, K: Sequence[Mpc], dK: Sequence[Mpc] | None = None
    ) -> tuple[Mpc, Mpc | None] | None:
        """(E_chr, dE_chr/dq or None) on the block system condensed to its wheels, or None where that does not
        apply (:func:`moving_bogie.kernels.condensed.condensed_characteristic`)."""
        if not hasattr(self, "_binary"):
            self._binary = binary_matrices(self.mass, self.damping, self.stiffness)
        return condensed_characteristic(q, self._binary, K, self.index, dK)

    def value_and_derivative(self, q: Mpc, K: Sequence[Mpc], dK: Sequence[Mpc]) -> tuple[Mpc, Mpc]:
        """(E_chr, dE_chr/dq) by Jacobi's formula: dE = E tr(A^-1 dA/dq) (on the condensed wheel system,
        :meth:`condensed`), or, where A is singular to working precision, the sum over k of det(A with row
        k replaced by row k of dA/dq)."""
        reduced = self.condensed(q, K, dK)
        if reduced is not None:
            return reduced
        A, _, dA, _ = self.block(q, K, dK)
        assert dA is not None  # block() with dK gives dA/dq
        lu, perm, E = lu_factor(A)
        if E != 0:
            columns = [lu_solve(lu, perm, [dA[r][k] for r in range(self.size)]) for k in range(self.size)]
            return E, E * sum(columns[k][k] for k in range(self.size))
        total = 0
        for k in range(self.size):
            total += lu_factor([dA[r] if r == k else A[r] for r in range(self.size)])[2]
        return E, total

    def numerators(self, q: Mpc, K: Sequence[Mpc]) -> dict[str, Mpc]:
        """n_X = det(A with column X replaced by b) for every DOF X (Cramer's rule): X = n_X / E_chr."""
        A, b, _, _ = self.block(q, K)
        lu, perm, E = lu_factor(A)
        if E != 0:
            x = lu_solve(lu, perm, b)
            return {name: E * x[k] for k, name in enumerate(self.names)}
        out = {}
        for k, name in enumerate(self.names):
            Ak = [[b[r] if c == k else A[r][c] for c in range(self.size)] for r in range(self.size)]
            out[name] = lu_factor(Ak)[2]
        return out

    def shape_weights(
        self,
        q: Mpc,
        K: Sequence[Mpc],
        numerators: Mapping[str, Mpc] | None = None,
        E: Mpc | None = None,
    ) -> tuple[Mpc, ...]:
        """G_j = 4 (E_chr s_j - (D n)_j): i q W~(xi, q) = sum_j G_j K(xi - xi_j) / (2 pi E_chr)."""
        A, _, _, D = self.block(q, K)
        E = lu_factor(A)[2] if E is None else E
        nums = self.numerators(q, K) if numerators is None else numerators
        vec = [nums[name] for name in self.names]
        return tuple(
            4 * (E * self.loads[j] - sum(D[j][k] * vec[k] for k in range(self.size)))
            for j in range(self.contacts)
        )

    # --- arrays of q, numpy -------------------------------------------------------------------------------

    def _float_dynamic(self) -> Dynamic:
        """D(q)'s coefficients from (M, C, K) as float arrays (N, N), converted once."""
        if not hasattr(self, "_floats"):
            floats = tuple(np.array(A, dtype=float) for A in self.matrices)
            self._floats = dynamic_coefficients(floats, Batched)
        return self._floats

    def block_array(
        self, q: ArrayLike, K: Sequence[np.ndarray], dK: Sequence[np.ndarray] | None = None
    ) -> tuple[np.ndarray, np.ndarray | None]:
        """A (shape q.shape + (N, N)) and dA/dq (or None) for kernel arrays ``K[k]`` at :attr:`offsets`."""
        system, _ = self._coupled_array(q, K, dK)
        return system.A, system.dA

    def _coupled_array(
        self,
        q: ArrayLike,
        K: Sequence[np.ndarray],
        dK: Sequence[np.ndarray] | None = None,
        loads: bool = False,
    ) -> tuple[Coupled, np.ndarray]:
        """(the block system on arrays, with b if ``loads``; the vehicle's D(q) it was built from)."""
        q = np.asarray(q, dtype=complex)
        D, dD = dynamic_stiffness(q, self._float_dynamic(), Batched, derivative=dK is not None)
        if not hasattr(self, "_index_array"):
            self._index_array = np.array(self.index)
        G = kernel_matrix(K, self._index_array, Batched)
        dG = None if dK is None else kernel_matrix(dK, self._index_array, Batched)
        system = coupled_system(D, G, Batched, loads=self.loads if loads else None, dD=dD, dG=dG)
        return system, D

    def e_chr_array(self, q: ArrayLike, K: Sequence[np.ndarray]) -> np.ndarray:
        """E_chr = det A on arrays of q (``K[k]`` at :attr:`offsets`)."""
        A, _ = self.block_array(q, K)
        return np.linalg.det(A)

    def value_and_derivative_array(
        self, q: ArrayLike, K: Sequence[np.ndarray], dK: Sequence[np.ndarray]
    ) -> tuple[np.ndarray, np.ndarray]:
        """(E_chr, dE_chr/dq) on arrays: dE = E tr(A^-1 dA) (Jacobi), row by row where A is singular."""
        A, dA = self.block_array(q, K, dK)
        assert dA is not None  # block_array() with dK gives dA/dq
        E = np.linalg.det(A)
        try:
            with np.errstate(all="ignore"):
                dE = E * np.trace(np.linalg.solve(A, dA), axis1=-2, axis2=-1)
            if np.all(np.isfinite(dE)):
                return E, dE
        except np.linalg.LinAlgError:
            pass
        dE = np.zeros_like(E)
        for k in range(self.size):
            Ak = A.copy()
            Ak[..., k, :] = dA[..., k, :]
            dE = dE + np.linalg.det(Ak)
        return E, dE

    def rhs_array(self, q: ArrayLike, K: Sequence[np.ndarray]) -> np.ndarray:
        """b = [2 Kmat s; 0] on arrays, shape q.shape + (N,)."""
        q = np.asarray(q, dtype=complex)
        system, _ = self._coupled_array(q, K, loads=True)
        return np.broadcast_to(system.b[..., 0], q.shape + (self.size,))

    def _system_and_rhs(
        self, q: ArrayLike, K: Sequence[np.ndarray]
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(A, b of shape A.shape[:-1], D) on arrays."""
        system, D = self._coupled_array(q, K, loads=True)
        return system.A, np.broadcast_to(system.b[..., 0], system.A.shape[:-1]), D

    def solutions_array(self, q: ArrayLike, K: Sequence[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
        """(X, G / E_chr) on arrays: the responses X = n_X / E_chr (shape q.shape + (N,)) from one solve of
        the block system A X = b, and the shape weights over E_chr, 4 (s_j - (D X)_j) (shape q.shape + (n,)).

        What the branch-cut quadratures need, without the determinant; inf or NaN where A is singular.
        """
        q = np.asarray(q, dtype=complex)
        A, b, D = self._system_and_rhs(q, K)
        with np.errstate(all="ignore"):
            try:
                X = np.linalg.solve(A, b[..., None])[..., 0]
            except np.linalg.LinAlgError:
                E, nums, _ = self.responses_array(q, K)
                X = nums / E[..., None]
            loads = np.array(self.loads, dtype=float)
            GE = 4 * (loads - np.einsum("...jk,...k->...j", D[..., : self.contacts, :], X))
        return X, GE

    def responses_array(
        self, q: ArrayLike, K: Sequence[np.ndarray]
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(E_chr, numerators (shape q.shape + (N,)), shape weights (q.shape + (n,))) on arrays.

        The numerators of every response come from one solve of the block system, n = E_chr A^-1 b
        (Cramer's rule for all responses at once); only where A is singular to double precision (E_chr = 0
        or a non-finite solve) are they the determinants of A with column X replaced by b.
        """
        q = np.asarray(q, dtype=complex)
        A, b, D = self._system_and_rhs(q, K)
        E = np.linalg.det(A)
        nums = np.full(b.shape, np.nan, dtype=complex)
        regular = E != 0
        if np.any(regular):
            with np.errstate(all="ignore"):
                x = np.linalg.solve(A[regular], b[regular][..., None])[..., 0]
            nums[regular] = E[regular][..., None] * x
        singular = ~np.all(np.isfinite(nums), axis=-1)
        if np.any(singular):
            As, bs = A[singular], b[singular]
            for k in range(self.size):
                Ak = As.copy()
                Ak[..., :, k] = bs
                nums[singular, k] = np.linalg.det(Ak)
        loads = np.array(self.loads, dtype=float)
        G = 4 * (E[..., None] * loads - np.einsum("...jk,...k->...j", D[..., : self.contacts, :], nums))
        return E, nums, G
