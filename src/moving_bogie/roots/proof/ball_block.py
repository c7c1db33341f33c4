"""E_chr of any vehicle in ball arithmetic: the block system's determinant over truncated Taylor series.

For a vehicle without the closed form of Eq. (38), :class:`~moving_bogie.roots.proof.balls.BallCharacteristic`
evaluates E_chr = det [[pi I + 2 Kmat D_cc, 2 Kmat D_ci], [D_ic, D_ii]] (:mod:`moving_bogie.kernels.coupling`,
in Arb's numbers) with every entry an ``acb_series`` in t = q - c: D = -q^2 M + i q C + K from the generated
matrices (balls around the exact parameters), Kmat_ij = K(xi_i - xi_j) as series from the residue sum.
Gaussian elimination on series is exact algebra, so coefficient j of the result encloses E_chr^(j)(xi)/j! for
every xi of the ball (coefficient 1 is dE_chr/dq, Eq. (40), with no Jacobi formula needed). A pivot whose
constant term contains 0 cannot be divided by: the determinant is then not decided at this ball (``None``),
never guessed.

For the orders the proofs use (E_chr alone, or E_chr and dE_chr/dq: at most two terms) the series are split
into their coefficient matrices, A(t) = A_0 + A_1 t, and the determinant is taken by Arb's ``acb_mat``
(C code, preconditioned by the midpoint inverse, so that a wide ball does not blow up the way interval
Gaussian elimination does): E = det A_0 and, by Jacobi's formula, E' = E tr(A_0^-1 A_1) where A_0 is
proven regular, else E' = sum_k det(A_0 with row k replaced by row k of A_1) (a ball holding a root, as in
the Krawczyk test). Both are enclosures for every matrix in the balls, so the proofs stay proofs.
"""

from __future__ import annotations

from collections.abc import Hashable, Mapping, Sequence
from fractions import Fraction
from types import ModuleType
from typing import Any

from flint import acb, acb_mat, acb_series, arb

from moving_bogie.kernels.arithmetic import Rows, structural_zero
from moving_bogie.kernels.coupling import (
    coupled_system,
    dynamic_coefficients,
    dynamic_stiffness,
    kernel_matrix,
)
from moving_bogie.typing import Acb, AcbSeries, Matrix


class BlockBalls:
    """A generated vehicle module bound to ball parameter values.

    Parameters
    ----------
    module : module
        ``moving_bogie.generated.vehicle_<name>``.
    values : mapping
        Parameter name -> acb ball for every name of ``module.MATRIX_ARGUMENTS``.
    exact : mapping, optional
        Parameter name -> exact value (Fraction): offsets xi_i - xi_j equal exactly share a kernel value.
    """

    def __init__(
        self,
        module: ModuleType,
        values: Mapping[str, Acb],
        exact: Mapping[str, Fraction | None] | None = None,
    ) -> None:
        args = {name: values[name] for name in module.MATRIX_ARGUMENTS}
        self.contacts = int(module.CONTACTS)
        self.size = len(module.DOFS)
        self.matrices = tuple(
            [[x if structural_zero(x) else acb(x) for x in row] for row in f(**args)]
            for f in (module.mass_matrix, module.damping_matrix, module.stiffness_matrix)
        )
        x = [acb(v) for v in module.contact_positions(**args)]
        n = self.contacts
        # offset 0 (the diagonal, exact) first, then one per pair i != j; side of each by its sign. With the
        # exact parameter values (``exact``: name -> Fraction) offsets that are equal exactly (L_c + d - d and
        # L_c) share one kernel value: each ball contains the exact offset, so either ball serves both.
        keys = None
        if exact is not None and all(exact[name] is not None for name in module.MATRIX_ARGUMENTS):
            x_exact = module.contact_positions(**{name: exact[name] for name in module.MATRIX_ARGUMENTS})
            keys = {(i, j): x_exact[i] - x_exact[j] for i in range(n) for j in range(n)}
        self.offsets = [acb(0)]
        seen: dict[Hashable, int] = {0: 0} if keys is not None else {}
        self.index = [[0] * n for _ in range(n)]
        for i in range(n):
            for j in range(n):
                if i == j:
                    continue
                key = keys[(i, j)] if keys is not None else (i, j)
                if key not in seen:
                    seen[key] = len(self.offsets)
                    self.offsets.append(x[i] - x[j])
                self.index[i][j] = seen[key]
        self.ops = Rows(acb(arb.pi()), acb(0, 1))
        self.arb = ArbMatrices()
        self.dynamic = dynamic_coefficients(self.matrices, self.ops)
        self.mats = dynamic_coefficients(tuple(_matrix(m) for m in self.matrices), self.arb)

    def sides(self) -> list[int | None]:
        """+1 (xi >= 0: roots with Im p > 0) or -1 for each offset; None if the sign is not decided."""
        out: list[int | None] = []
        for xi in self.offsets:
            if xi.real.is_zero():
                out.append(1)
            elif xi.real > 0:
                out.append(1)
            elif xi.real < 0:
                out.append(-1)
            else:
                out.append(None)
        return out

    def det(self, qs: AcbSeries, K: Sequence[AcbSeries], length: int) -> AcbSeries | None:
        """E_chr as an acb_series of ``length`` terms, from q (series) and K (series, one per offset)."""
        if length <= 2:
            return self.det_linear(qs, K, length)
        D, _ = dynamic_stiffness(qs, self.dynamic, self.ops)
        A = coupled_system(D, kernel_matrix(K, self.index, self.ops), self.ops).A
        zero = acb_series([acb(0)], prec=length)
        return series_det([[zero + x for x in row] for row in A], length)

    def coefficient_matrices(self, qs: AcbSeries, K: Sequence[AcbSeries], length: int) -> list[acb_mat]:
        """[A_0] or [A_0, A_1]: the block matrix A(t) = A_0 + A_1 t from q and K as series in t."""
        ops = self.arb
        q0, q1 = coefficient(qs, 0), coefficient(qs, 1)
        D0, dD = dynamic_stiffness(q0, self.mats, ops, derivative=length > 1)
        K0 = kernel_matrix([coefficient(k, 0) for k in K], self.index, ops)
        if length == 1:
            return [coupled_system(D0, K0, ops).A]
        K1 = kernel_matrix([coefficient(k, 1) for k in K], self.index, ops)
        system = coupled_system(D0, K0, ops, dD=ops.scale(q1, dD), dG=K1)
        return [system.A, system.dA]

    def log_derivative(self, qs: AcbSeries, K: Sequence[AcbSeries]) -> tuple[Acb, Acb] | None:
        """(E_chr, E_chr'/E_chr = tr(A_0^-1 A_1)) over the ball, or None where A_0 is not proven regular."""
        A0, A1 = self.coefficient_matrices(qs, K, 2)
        try:
            return A0.det(), A0.solve(A1).trace()
        except ZeroDivisionError:
            return None

    def det_linear(self, qs: AcbSeries, K: Sequence[AcbSeries], length: int) -> AcbSeries:
        """:meth:`det` for ``length`` 1 or 2 on the coefficient matrices A_0, A_1 (module docstring)."""
        A = self.coefficient_matrices(qs, K, length)
        E = A[0].det()
        if length == 1:
            return acb_series([E], prec=1)
        A0, A1 = A
        try:
            dE = E * A0.solve(A1).trace()
        except ZeroDivisionError:  # A_0 not proven regular: the row-replacement form of Jacobi's formula
            dE = acb(0)
            N = self.size
            for k in range(N):
                row = acb_mat([[1 if (r == c == k) else 0 for c in range(N)] for r in range(N)])
                dE += (A0 + row * (A1 - A0)).det()
        return acb_series([E, dE], prec=2)


class _Below:
    """The rows of ``P`` below its first rows ``top`` (= Sel P), left in P: only :meth:`ArbMatrices.stack`
    takes them, back under new first rows."""

    def __init__(self, P: acb_mat, top: acb_mat) -> None:
        self.P, self.top = P, top


class ArbMatrices:
    """The arithmetic of :mod:`moving_bogie.kernels.coupling` on Arb's matrices (``acb_mat``): products and
    sums in C; rows are picked and placed by products with 0/1 matrices, which are exact."""

    def __init__(self) -> None:
        self.pi, self.i = acb(arb.pi()), acb(0, 1)
        self._units: dict[tuple[int, int, Any, bool], acb_mat] = {}

    def _unit(self, rows: int, columns: int, shift: int = 0, transpose: bool = False) -> acb_mat:
        """The rows x columns matrix with ones at (r, r + shift), or its transpose (cached)."""
        key = (rows, columns, shift, transpose)
        if key not in self._units:
            unit = acb_mat([[1 if c == r + shift else 0 for c in range(columns)] for r in range(rows)])
            self._units[key] = unit.transpose() if transpose else unit
        return self._units[key]

    @staticmethod
    def count(G: acb_mat) -> int:
        return G.nrows()

    @staticmethod
    def scale(s: Acb, P: acb_mat) -> acb_mat:
        """s P; 2 P and -P exactly by a sum and a negation (cheaper than Arb's scalar product here)."""
        if isinstance(s, int) and s in (2, -1):
            return P + P if s == 2 else -P
        return P * s

    @staticmethod
    def add(P: acb_mat, Q: acb_mat) -> acb_mat:
        return P + Q

    @staticmethod
    def matmul(P: acb_mat, Q: acb_mat) -> acb_mat:
        return P * Q

    @staticmethod
    def polynomial(q: Acb, coefficients: Sequence[acb_mat]) -> acb_mat:
        powers = [1, q]
        for _ in range(2, len(coefficients)):
            powers.append(powers[-1] * q)
        out = coefficients[-1] * powers[-1]
        for k in range(len(coefficients) - 2, 0, -1):
            out = out + coefficients[k] * powers[k]
        return out + coefficients[0]

    def plus_identity(self, P: acb_mat, s: Acb) -> acb_mat:
        key = (P.nrows(), P.ncols(), "times", s is self.pi)
        if key not in self._units:  # pi I once per shape
            self._units[key] = self._unit(P.nrows(), P.ncols()) * s
        return P + (self._units[key] if s is self.pi else self._unit(P.nrows(), P.ncols()) * s)

    def split(self, P: acb_mat, n: int) -> tuple[acb_mat, _Below]:
        """(the first n rows, the others): these stay in P (:class:`_Below`), never picked."""
        top = self._unit(n, P.nrows()) * P
        return top, _Below(P, top)

    def stack(self, top: acb_mat, bottom: acb_mat | _Below) -> acb_mat:
        """The rows of ``top`` over ``bottom`` (P + place (top - P's first rows) for P's own rows)."""
        n = top.nrows()
        if isinstance(bottom, _Below):
            return bottom.P + self._unit(n, bottom.P.nrows(), transpose=True) * (top - bottom.top)
        m = bottom.nrows()
        if m == 0:
            return top
        return self._unit(n, n + m, transpose=True) * top + self._unit(m, n + m, n, transpose=True) * bottom

    @staticmethod
    def zeros(rows: int, columns: int) -> acb_mat:
        return acb_mat(rows, columns)

    @staticmethod
    def column(values: Sequence[Acb]) -> acb_mat:
        return acb_mat([[acb(v)] for v in values])

    def embed(self, blocks: Sequence[acb_mat], places: Sequence[Sequence[int]], size: int) -> acb_mat:
        """size x size zeros with block k at rows and columns ``places[k]`` (P B P^T, P of 0/1)."""
        out = acb_mat(size, size)
        for block, place in zip(blocks, places):
            P = acb_mat([[1 if place[c] == row else 0 for c in range(len(place))] for row in range(size)])
            out = out + P * block * P.transpose()
        return out

    @staticmethod
    def gather(values: Sequence[Acb], index: Sequence[Sequence[int]]) -> acb_mat:
        return acb_mat([[values[k] for k in row] for row in index])


def _matrix(rows: Matrix) -> acb_mat:
    """An acb_mat from lists of rows of acb (a structural zero as the exact ball 0)."""
    return acb_mat([[acb(x) for x in row] for row in rows])


def coefficient(series: AcbSeries | Acb, j: int) -> Acb:
    """Coefficient ``j`` of an acb_series (0 beyond its stored terms) or, for j = 0, an acb itself."""
    if not isinstance(series, acb_series):
        return acb(series) if j == 0 else acb(0)
    coeffs = series.coeffs()
    return acb(coeffs[j]) if j < len(coeffs) else acb(0)


def series_det(A: Sequence[Sequence[AcbSeries]], length: int) -> AcbSeries | None:
    """det A for a square list of acb_series rows (pivot: the largest constant-term midpoint); None if a
    pivot it must divide by has a constant term that contains 0."""
    N = len(A)
    rows = [list(r) for r in A]
    det = acb_series([acb(1)], prec=length)
    for k in range(N):
        p = max(
            range(k, N),
            key=lambda r: abs(complex(acb(rows[r][k].coeffs()[0] if rows[r][k].coeffs() else 0).mid())),
        )
        pivot = rows[p][k]
        c0 = acb(pivot.coeffs()[0]) if pivot.coeffs() else acb(0)
        if p != k:
            rows[k], rows[p] = rows[p], rows[k]
            det = -det
        det = det * pivot
        if k == N - 1:
            break  # the last pivot is a factor only, never a divisor: it may contain 0 (a ball with a root)
        if c0.contains(0):
            return None
        inv = 1 / pivot
        for r in range(k + 1, N):
            f = rows[r][k] * inv
            for c in range(k + 1, N):
                rows[r][c] = rows[r][c] - f * rows[k][c]
    return det
