"""E_chr of any vehicle on arrays of points, with its parameters per point: the block system batched.

The vehicle's side of :class:`~moving_bogie.kernels.sweep_characteristic.SweepCharacteristic` for vehicles
without a closed-form E_chr (any number of wheels). At every point, with D = -q^2 M + i q C + K the vehicle's
dynamic stiffness (its generated matrices at that point's parameters) and Kmat_ij = K(xi_i - xi_j, q),

    E_chr = det A,  A = [[pi I + 2 Kmat D_cc, 2 Kmat D_ci], [D_ic, D_ii]]   (Eq. (38) for n wheels),

as :mod:`moving_bogie.kernels.coupling` defines it (batched, with the vehicle's matrices per point), and
every derivative by Jacobi's formula
dE/ds = E tr(A^-1 dA/ds) (Eq. (40)): s = q (dD/dq = -2 q M + i C, dK/dq), s = alpha (dK/dalpha only) and
s = theta, a vehicle parameter (D is affine in each group, so dD/dtheta is a central difference, exact).
Where A is singular to working precision, dE/ds = sum_k det(A with row k replaced by row k of dA/ds).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from types import ModuleType
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from moving_bogie.kernels.arithmetic import Batched
from moving_bogie.kernels.coupling import coupled_derivative, coupled_system, dynamic_stiffness, kernel_matrix

__all__ = ["BlockSweep"]


def _matrix(rows: Sequence[Sequence[Any]], shape: Sequence[int]) -> np.ndarray:
    """A generated matrix (rows of numbers or arrays) as an array of shape ``shape + (N, N)``."""
    N = len(rows)
    out = np.zeros(tuple(shape) + (N, N), dtype=complex)
    for a, row in enumerate(rows):
        for c, value in enumerate(row):
            if not (np.ndim(value) == 0 and value == 0):
                out[..., a, c] = value
    return out


class BlockSweep:
    """A generated vehicle module evaluated on arrays of points (parameters may vary per point).

    Parameters
    ----------
    module : module
        ``moving_bogie.generated.vehicle_<name>`` (``MATRIX_ARGUMENTS``, the matrices, ``contact_positions``).
    """

    def __init__(self, module: ModuleType) -> None:
        self.module = module
        self.contacts = int(module.CONTACTS)
        self.size = len(module.DOFS)
        n = self.contacts
        # offset 0 (the diagonal) first, then xi_i - xi_j for every i != j
        self.pairs = [(i, j) for i in range(n) for j in range(n) if i != j]
        self.index = np.zeros((n, n), dtype=int)
        for k, (i, j) in enumerate(self.pairs):
            self.index[i, j] = k + 1

    def offsets(self, args: Mapping[str, Any]) -> list[Any]:
        """xi_i - xi_j at the parameters ``args`` (floats or arrays), in the order of :attr:`index`."""
        x = self.module.contact_positions(**self.matrix_args(args))
        return [0.0] + [x[i] - x[j] for i, j in self.pairs]

    def matrix_args(self, args: Mapping[str, Any]) -> dict[str, Any]:
        """The parameters of ``args`` that the vehicle's generated matrices take."""
        return {name: args[name] for name in self.module.MATRIX_ARGUMENTS}

    def dynamic(self, q: np.ndarray, args: Mapping[str, Any]) -> tuple[np.ndarray, np.ndarray]:
        """(D, dD/dq) of shape ``q.shape + (N, N)`` at the parameters ``args``."""
        margs = self.matrix_args(args)
        matrices = tuple(
            _matrix(f(**margs), q.shape)
            for f in (self.module.mass_matrix, self.module.damping_matrix, self.module.stiffness_matrix)
        )
        return dynamic_stiffness(q, matrices, Batched, derivative=True)

    def kernel_matrix(self, K: Sequence[np.ndarray]) -> np.ndarray:
        """Kmat_ij = K(xi_i - xi_j) from the kernel values at :meth:`offsets`."""
        return kernel_matrix(K, self.index, Batched)

    def block(self, K: Sequence[np.ndarray], D: np.ndarray) -> np.ndarray:
        """The block system A at the kernel values ``K`` and the vehicle's D."""
        return coupled_system(D, self.kernel_matrix(K), Batched).A

    def e_chr(self, q: ArrayLike, K: Sequence[np.ndarray], args: Mapping[str, Any]) -> np.ndarray:
        """E_chr = det A at arrays ``q`` and kernel values ``K`` (one array per offset)."""
        q = np.asarray(q, dtype=complex)
        D, _ = self.dynamic(q, args)
        return np.linalg.det(self.block(K, D))

    def derivatives(
        self,
        q: ArrayLike,
        K: Sequence[np.ndarray],
        args: Mapping[str, Any],
        *,
        dKq: Sequence[np.ndarray] | None = None,
        dKa: Sequence[np.ndarray] | None = None,
        theta_args: tuple[Mapping[str, Any], Mapping[str, Any], ArrayLike] | None = None,
    ) -> tuple[np.ndarray, np.ndarray | None, np.ndarray | None, np.ndarray | None]:
        """``(E, E_q, E_alpha, E_theta)`` (each derivative None unless its input is given).

        ``dKq``, ``dKa``: the kernel's q- and alpha-derivatives at the offsets; ``theta_args``: a pair of
        parameter dicts (theta - h, theta + h) and h, for E_theta by the exact central difference of D.
        """
        q = np.asarray(q, dtype=complex)
        D, dDq = self.dynamic(q, args)
        G = self.kernel_matrix(K)
        A = coupled_system(D, G, Batched).A
        blocks = []
        if dKq is not None:
            blocks.append(coupled_derivative(D, G, Batched, dD=dDq, dG=self.kernel_matrix(dKq)))
        if dKa is not None:
            blocks.append(coupled_derivative(D, G, Batched, dG=self.kernel_matrix(dKa)))
        if theta_args is not None:
            lo, hi, h = theta_args
            dDt = (self.dynamic(q, hi)[0] - self.dynamic(q, lo)[0]) / (2 * np.asarray(h)[..., None, None])
            blocks.append(coupled_derivative(D, G, Batched, dD=dDt))
        E = np.linalg.det(A)
        out = iter(jacobi(A, E, blocks))
        return (
            E,
            next(out) if dKq is not None else None,
            next(out) if dKa is not None else None,
            next(out) if theta_args is not None else None,
        )


def jacobi(A: np.ndarray, E: np.ndarray, blocks: Sequence[np.ndarray]) -> list[np.ndarray]:
    """dE = E tr(A^-1 dA) for each dA of ``blocks``; row replacement where A is singular."""
    if not blocks:
        return []
    try:
        with np.errstate(all="ignore"):
            solved = np.linalg.solve(A, np.concatenate(blocks, axis=-1))
        N = A.shape[-1]
        out = [E * np.trace(solved[..., k * N : (k + 1) * N], axis1=-2, axis2=-1) for k in range(len(blocks))]
        if all(np.all(np.isfinite(x)) for x in out):
            return out
    except np.linalg.LinAlgError:
        pass
    out = []
    for dA in blocks:
        total = np.zeros_like(E)
        for k in range(A.shape[-1]):
            Ak = A.copy()
            Ak[..., k, :] = dA[..., k, :]
            total = total + np.linalg.det(Ak)
        out.append(total)
    return out
