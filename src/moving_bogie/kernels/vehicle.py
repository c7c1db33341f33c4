"""A vehicle on n wheels on the track: the block system, E_chr as its determinant (Eq. (38) for n wheels).

Every declared vehicle (``derivations/vehicles.py``) is generated as its mass, damping and stiffness matrices
M, C, K, its contact positions xi_j and static loads s_j, in the dimensionless scaling of Eqs. (15)-(17).
With D(q) = -q^2 M + i q C + K (d/dtau -> i q, Eq. (21)) and Kmat_ij = K(xi_i - xi_j, q) (Eq. (29)), the
wheel deflections W (n of them) and the internal DOFs Y of the vehicle (times i q, as in Eq. (30)) solve

    [[pi I + 2 Kmat D_cc, 2 Kmat D_ci], [D_ic, D_ii]] [W; Y] = [2 Kmat s; 0],

the beam rows of Eq. (28) (pi W_i = 2 sum_j K(xi_i - xi_j) f_j with the wheel forces f_j = s_j - (D x)_j) over
the vehicle's own rows. Then

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

import mpmath
import numpy as np

from moving_bogie.kernels.condensed import binary_matrices, condensed_characteristic
from moving_bogie.kernels.elimination import exact_zero, lu_factor, lu_solve


def distinct_offsets(positions) -> tuple[list, list]:
    """The distinct xi_i - xi_j (0 first) and, for each (i, j), the index of its offset."""
    offsets, keys, index = [], {}, []
    ordered = [(i, j) for i in range(len(positions)) for j in range(len(positions))]
    ordered.sort(key=lambda ij: ij[0] != ij[1])  # the diagonal (offset 0) first
    table = {}
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

    def __init__(self, module, values):
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

    def natural_frequencies(self) -> list:
        """Natural frequencies (in tau) of the vehicle's bodies with the wheels held: K_ii v = q^2 M_ii v."""
        n = self.contacts
        M = np.array(self.mass, dtype=float)[n:, n:]
        K = np.array(self.stiffness, dtype=float)[n:, n:]
        if M.size == 0:
            return []
        squares = np.linalg.eigvals(np.linalg.solve(M, K)).real
        return [float(np.sqrt(x)) for x in sorted(squares) if x > 0]

    # --- one q, mpmath ----------------------------------------------------------------------------------

    def dynamic(self, q, derivative=False):
        """(D(q), dD/dq or None) at one q, lists of rows with an exact 0 where the vehicle has no coupling
        (so that sums and eliminations can skip it): D = -q^2 M + i q C + K (Eq. (21))."""
        N = self.size
        q2, iq, i = q**2, mpmath.mpc(0, 1) * q, mpmath.mpc(0, 1)

        def entry(m, c, k):
            terms = [
                t for t in (-q2 * m if m else 0, iq * c if c else 0, k) if not (isinstance(t, int) and t == 0)
            ]
            return sum(terms[1:], terms[0]) if terms else 0

        def slope(m, c):
            terms = [t for t in (-2 * q * m if m else 0, i * c if c else 0) if not exact_zero(t)]
            return sum(terms[1:], terms[0]) if terms else 0

        M, C, Kv = self.mass, self.damping, self.stiffness
        D = [[entry(M[a][c], C[a][c], Kv[a][c]) for c in range(N)] for a in range(N)]
        if not derivative:
            return D, None
        return D, [[slope(M[a][c], C[a][c]) for c in range(N)] for a in range(N)]

    def block(self, q, K, dK=None):
        """(A, b, dA/dq or None, D) at one q (lists of rows); ``K`` (``dK``) at :attr:`offsets`."""
        n, N = self.contacts, self.size
        D, _ = self.dynamic(q)
        Kmat = [[K[self.index[r][k]] for k in range(n)] for r in range(n)]
        A = [
            [
                sum((2 * Kmat[r][k] * D[k][c] for k in range(n) if not exact_zero(D[k][c])), 0)
                for c in range(N)
            ]
            for r in range(n)
        ]
        for r in range(n):
            A[r][r] += mpmath.pi
        A += [list(D[r]) for r in range(n, N)]
        b = [sum(2 * Kmat[r][k] * self.loads[k] for k in range(n)) for r in range(n)] + [0] * (N - n)
        dA = None
        if dK is not None:
            i = mpmath.mpc(0, 1)
            dD = [[-2 * q * self.mass[a][c] + i * self.damping[a][c] for c in range(N)] for a in range(N)]
            dKmat = [[dK[self.index[r][k]] for k in range(n)] for r in range(n)]
            dA = [
                [sum(2 * (dKmat[r][k] * D[k][c] + Kmat[r][k] * dD[k][c]) for k in range(n)) for c in range(N)]
                for r in range(n)
            ]
            dA += [list(dD[r]) for r in range(n, N)]
        return A, b, dA, D

    def e_chr(self, q, K):
        """E_chr(q) = det A (:meth:`condensed`; the full block system where that does not apply)."""
        reduced = self.condensed(q, K)
        if reduced is not None:
            return reduced[0]
        A, _, _, _ = self.block(q, K)
        return lu_factor(A)[2]

    def condensed(self, q, K, dK=None):
        """(E_chr, dE_chr/dq or None) on the block system condensed to its wheels, or None where that does not
        apply (:func:`moving_bogie.kernels.condensed.condensed_characteristic`)."""
        if not hasattr(self, "_binary"):
            self._binary = binary_matrices(self.mass, self.damping, self.stiffness)
        return condensed_characteristic(q, self._binary, K, self.index, dK)

    def value_and_derivative(self, q, K, dK):
        """(E_chr, dE_chr/dq) by Jacobi's formula: dE = E tr(A^-1 dA/dq) (on the condensed wheel system,
        :meth:`condensed`), or, where A is singular to working precision, the sum over k of det(A with row
        k replaced by row k of dA/dq)."""
        reduced = self.condensed(q, K, dK)
        if reduced is not None:
            return reduced
        A, _, dA, _ = self.block(q, K, dK)
        lu, perm, E = lu_factor(A)
        if E != 0:
            columns = [lu_solve(lu, perm, [dA[r][k] for r in range(self.size)]) for k in range(self.size)]
            return E, E * sum(columns[k][k] for k in range(self.size))
        total = 0
        for k in range(self.size):
            total += lu_factor([dA[r] if r == k else A[r] for r in range(self.size)])[2]
        return E, total

    def numerators(self, q, K) -> dict:
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

    def shape_weights(self, q, K, numerators=None, E=None) -> tuple:
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

    def _dynamic_array(self, q, derivative=True):
        """D(q) = -q^2 M + i q C + K (and dD/dq, or None) for an array of q, shape q.shape + (N, N)."""
        if not hasattr(self, "_float_matrices"):
            self._float_matrices = tuple(
                np.array(A, dtype=float) for A in (self.mass, self.damping, self.stiffness)
            )
        M, C, Kv = self._float_matrices
        N = self.size
        if not hasattr(self, "_stacked"):
            self._stacked = np.stack([Kv.ravel(), 1j * C.ravel(), -M.ravel()])  # D = [1, q, q^2] @ this
        powers = np.stack([np.ones_like(q), q, q * q], axis=-1)
        D = (powers @ self._stacked).reshape(q.shape + (N, N))
        if not derivative:
            return D, None
        qq = q[..., None, None]
        return D, 1j * C - 2 * qq * M

    def block_array(self, q, K, dK=None):
        """A (shape q.shape + (N, N)) and dA/dq (or None) for kernel arrays ``K[k]`` at :attr:`offsets`."""
        A, dA, _ = self._blocks_and_dynamic(q, K, dK)
        return A, dA

    def _blocks_and_dynamic(self, q, K, dK=None):
        """(A, dA/dq or None, D) on arrays: :meth:`block_array` and the vehicle's D(q) it was built from."""
        q = np.asarray(q, dtype=complex)
        n = self.contacts
        D, dD = self._dynamic_array(q, derivative=dK is not None)
        shape = q.shape
        index = np.array(self.index)
        Kmat = np.stack([np.broadcast_to(k, shape) for k in K], axis=-1)[..., index]
        A = D.copy()
        A[..., :n, :] = 2 * Kmat @ D[..., :n, :]
        A[..., range(n), range(n)] += np.pi
        if dK is None:
            return A, None, D
        dKmat = np.stack([np.broadcast_to(k, shape) for k in dK], axis=-1)[..., index]
        dA = dD.copy()
        dA[..., :n, :] = 2 * (dKmat @ D[..., :n, :] + Kmat @ dD[..., :n, :])
        return A, dA, D

    def e_chr_array(self, q, K):
        A, _ = self.block_array(q, K)
        return np.linalg.det(A)

    def value_and_derivative_array(self, q, K, dK):
        """(E_chr, dE_chr/dq) on arrays: dE = E tr(A^-1 dA) (Jacobi), row by row where A is singular."""
        A, dA = self.block_array(q, K, dK)
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

    def rhs_array(self, q, K):
        q = np.asarray(q, dtype=complex)
        n = self.contacts
        b = np.zeros(q.shape + (self.size,), dtype=complex)
        for i in range(n):
            for k in range(n):
                b[..., i] += 2 * np.broadcast_to(K[self.index[i][k]], q.shape) * self.loads[k]
        return b

    def solutions_array(self, q, K):
        """(X, G / E_chr) on arrays: the responses X = n_X / E_chr (shape q.shape + (N,)) from one solve of
        the block system A X = b, and the shape weights over E_chr, 4 (s_j - (D X)_j) (shape q.shape + (n,)).

        What the branch-cut quadratures need, without the determinant; inf or NaN where A is singular.
        """
        q = np.asarray(q, dtype=complex)
        A, _, D = self._blocks_and_dynamic(q, K)
        b = self.rhs_array(q, K)
        with np.errstate(all="ignore"):
            try:
                X = np.linalg.solve(A, b[..., None])[..., 0]
            except np.linalg.LinAlgError:
                E, nums, _ = self.responses_array(q, K)
                X = nums / E[..., None]
            loads = np.array(self.loads, dtype=float)
            GE = 4 * (loads - np.einsum("...jk,...k->...j", D[..., : self.contacts, :], X))
        return X, GE

    def responses_array(self, q, K):
        """(E_chr, numerators (shape q.shape + (N,)), shape weights (q.shape + (n,))) on arrays.

        The numerators of every response come from one solve of the block system, n = E_chr A^-1 b
        (Cramer's rule for all responses at once); only where A is singular to double precision (E_chr = 0
        or a non-finite solve) are they the determinants of A with column X replaced by b.
        """
        q = np.asarray(q, dtype=complex)
        A, _, D = self._blocks_and_dynamic(q, K)
        b = self.rhs_array(q, K)
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
