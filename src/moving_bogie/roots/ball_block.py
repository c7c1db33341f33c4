"""E_chr of any vehicle in ball arithmetic: the block system's determinant over truncated Taylor series.

For a vehicle without the closed form of Eq. (38), :class:`~moving_bogie.roots.balls.BallCharacteristic`
evaluates E_chr = det [[pi I + 2 Kmat D_cc, 2 Kmat D_ci], [D_ic, D_ii]] (:mod:`moving_bogie.kernels.vehicle`)
with every entry an ``acb_series`` in t = q - c: D = -q^2 M + i q C + K from the generated matrices (balls
around the exact parameters), Kmat_ij = K(xi_i - xi_j) as series from the residue sum. Gaussian elimination
on series is exact algebra, so coefficient j of the result encloses E_chr^(j)(xi)/j! for every xi of the
ball (coefficient 1 is dE_chr/dq, Eq. (40), with no Jacobi formula needed). A pivot whose constant term
contains 0 cannot be divided by: the determinant is then not decided at this ball (``None``), never guessed.
"""

from __future__ import annotations

from flint import acb, acb_series, arb


class BlockBalls:
    """A generated vehicle module bound to ball parameter values.

    Parameters
    ----------
    module : module
        ``moving_bogie.generated.vehicle_<name>``.
    values : mapping
        Parameter name -> acb ball for every name of ``module.MATRIX_ARGUMENTS``.
    """

    def __init__(self, module, values):
        args = {name: values[name] for name in module.MATRIX_ARGUMENTS}
        self.contacts = int(module.CONTACTS)
        self.size = len(module.DOFS)
        self.matrices = tuple(
            f(**args) for f in (module.mass_matrix, module.damping_matrix, module.stiffness_matrix)
        )
        x = [acb(v) for v in module.contact_positions(**args)]
        n = self.contacts
        # offset 0 (the diagonal, exact) first, then one per pair i != j; side of each by its sign
        self.offsets = [acb(0)] + [x[i] - x[j] for i in range(n) for j in range(n) if i != j]
        self.index = [[0] * n for _ in range(n)]
        k = 1
        for i in range(n):
            for j in range(n):
                if i != j:
                    self.index[i][j] = k
                    k += 1

    def sides(self) -> list:
        """+1 (xi >= 0: roots with Im p > 0) or -1 for each offset; None if the sign is not decided."""
        out = []
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

    def det(self, qs, K, length):
        """E_chr as an acb_series of ``length`` terms, from q (series) and K (series, one per offset)."""
        n, N = self.contacts, self.size
        M, C, Kv = self.matrices
        iq = acb(0, 1) * qs
        q2 = qs * qs

        def entry(a, c):
            return -q2 * acb(M[a][c]) + iq * acb(C[a][c]) + acb(Kv[a][c])

        D = [[entry(a, c) for c in range(N)] for a in range(N)]
        pi = acb(arb.pi())
        A = []
        for r in range(n):
            row = []
            for c in range(N):
                total = acb_series([acb(0)], prec=length)
                for k in range(n):
                    total += 2 * K[self.index[r][k]] * D[k][c]
                row.append(total + pi if c == r else total)
            A.append(row)
        A += [list(D[r]) for r in range(n, N)]
        return series_det(A, length)


def series_det(A, length):
    """det A for a square list of acb_series rows (pivot: the largest constant-term midpoint); None if a
    pivot's constant term contains 0."""
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
        if c0.contains(0):
            return None
        if p != k:
            rows[k], rows[p] = rows[p], rows[k]
            det = -det
        det = det * pivot
        inv = 1 / pivot
        for r in range(k + 1, N):
            f = rows[r][k] * inv
            for c in range(k + 1, N):
                rows[r][c] = rows[r][c] - f * rows[k][c]
    return det
