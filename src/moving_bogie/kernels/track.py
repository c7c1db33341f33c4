"""The track kernel K(xi, q) of Eq. (29) and its q-derivative, by residues at the roots of N(p, q).

K(xi, q) = integral over real p of exp(i p xi) Q(p,q) / N(p,q) dp. For xi >= 0 the contour is closed in the
upper half p-plane, for xi < 0 in the lower one (Jordan's lemma: Q/N = O(p^-2)), so

    K(xi, q) =  2 pi i sum_{Im p_k > 0} exp(i p_k xi) Q(p_k) / N'(p_k)          (xi >= 0)
    K(xi, q) = -2 pi i sum_{Im p_k < 0} exp(i p_k xi) Q(p_k) / N'(p_k)          (xi < 0)

dK/dq = integral of exp(i p xi) (Q_q / N - Q N_q / N^2) dp: simple poles for the first term, double poles
for the second, whose residue at a simple root p_k of N is (g' N' - g N'') / N'^3 with g = exp(i p xi) Q N_q.

The sum is taken over whichever roots lie on each side of the real p-axis at the given q, so K is the
integral's value on either side of the cut locus (for Euler-Bernoulli the line Im q = eta_f, see
``kernels/cut.py``). Two backends share these formulas: :class:`TrackKernel` evaluates one q at the current
mpmath precision; :class:`TrackKernelArray` evaluates numpy arrays of q in double precision.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import mpmath
import numpy as np
from numpy.typing import ArrayLike

from moving_bogie.errors import MovingBogieError
from moving_bogie.kernels.coefficient_matrix import Coefficients
from moving_bogie.kernels.foundation import Foundation
from moving_bogie.kernels.polynomial import derivative_coefficients, horner
from moving_bogie.kernels.polyroots import poly_roots, polyder, polyval
from moving_bogie.typing import ComplexArray, Mpc, Mpf

if TYPE_CHECKING:
    from moving_bogie.kernels.bound import BoundModel


def foundation_arguments(bound: BoundModel, numbers: Any) -> dict[str, Any]:
    """Keyword arguments of the generated foundation functions (besides q or p) from a params namespace.

    The names come from the generated module (its ``ARGUMENTS``), so a model added in derivations/ with the
    existing groups needs no change here; a group the model does not use is passed as None.
    """
    return {name: getattr(numbers, name, None) for name in bound.foundation_model.names}


@dataclass(frozen=True)
class KernelValues:
    """K at the requested xi values and, if asked, dK/dq; ``roots`` are the p-roots of N used."""

    K: tuple[Any, ...]  # mpmath numbers (TrackKernel) or arrays over q (TrackKernelArray)
    dK: tuple[Any, ...] | None
    roots: tuple[Mpc, ...] | np.ndarray


class TrackKernel:
    """K(xi, q) and dK/dq at one complex q, at the current mpmath precision (Eq. (29)).

    Parameters
    ----------
    bound : BoundModel
        The parameters bound to their model; the track is its ``foundation_model``.
    coalescence_digits : int
        Where two p-roots on the same side are closer than 10**-k relative, their separate residues are
        large and nearly cancel (their sum stays finite). The evaluation then repeats at a precision
        raised by three times the digits lost (the double-pole residues of dK/dq lose 3x).
    """

    def __init__(self, bound: BoundModel, *, coalescence_digits: int = 3) -> None:
        self.bound = bound
        self.params = bound.params
        self.foundation: Foundation = bound.foundation_model
        self.module = self.foundation.module
        self.coalescence_digits = coalescence_digits

    def arguments(self) -> dict[str, Any]:
        """The foundation's parameters at the current mpmath precision (keyword arguments of its kernels)."""
        return self.bound.foundation_mp()

    def p_roots(self, q: Mpc | complex) -> list[Mpc]:
        """Roots of N(p, q) in p at the current precision (numpy start + Durand-Kerner polish)."""
        args = self.arguments()
        coeffs = [mpmath.mpc(c) for c in self.module.n_coeffs(q, **args)]
        return _roots_mp(coeffs)

    def __call__(
        self, q: Mpc | complex, xis: Iterable[Mpf | float], *, derivative: bool = False
    ) -> KernelValues:
        """K(xi, q) for every xi in ``xis`` (and dK/dq if ``derivative``)."""
        q = mpmath.mpc(q)
        for _ in range(4):
            values, sep = self._evaluate(q, xis, derivative)
            if sep is None or sep > mpmath.mpf(10) ** (-self.coalescence_digits):
                return values
            extra = int(3 * -mpmath.log10(sep)) + 10
            with mpmath.workdps(mpmath.mp.dps + extra):
                values, sep2 = self._evaluate(q, xis, derivative)
            return KernelValues(
                tuple(+k for k in values.K),
                None if values.dK is None else tuple(+k for k in values.dK),
                tuple(+p for p in values.roots),
            )
        return values  # pragma: no cover

    def _evaluate(
        self, q: Mpc, xis: Iterable[Mpf | float], derivative: bool
    ) -> tuple[KernelValues, Mpf | None]:
        args = self.arguments()
        n = [mpmath.mpc(c) for c in self.module.n_coeffs(q, **args)]
        roots = _roots_mp(n)
        qc = [mpmath.mpc(c) for c in self.module.q_coeffs(q, **args)]
        n1 = derivative_coefficients(n)
        if derivative:
            n2 = derivative_coefficients(n1)
            nq = [mpmath.mpc(c) for c in self.module.n_coeffs_dq(q, **args)]
            nqp = derivative_coefficients(nq)
            qq = [mpmath.mpc(c) for c in self.module.q_coeffs_dq(q, **args)]
            qp = derivative_coefficients(qc)
        upper = [p for p in roots if mpmath.im(p) > 0]
        lower = [p for p in roots if mpmath.im(p) < 0]
        if len(upper) + len(lower) != len(roots):
            raise MovingBogieError(
                f"K({q}) undefined: a root of N(p, q) lies on the real p-axis (q on the cut)"
            )
        two_pi_i = 2j * mpmath.pi
        # what does not depend on xi, once per root: the offsets share it
        at: dict[Mpc, tuple[Mpc, ...]] = {}
        for p in upper + lower:
            N1 = horner(n1, p)
            Qv = horner(qc, p)
            if derivative:
                Nq = horner(nq, p)
                at[p] = (N1, Qv, Nq, horner(n2, p), horner(qp, p), horner(nqp, p), horner(qq, p))
            else:
                at[p] = (N1, Qv)
        Ks, dKs = [], []
        for xi in xis:
            xi = mpmath.mpf(xi)
            side, sign = (upper, 1) if xi >= 0 else (lower, -1)
            total = mpmath.mpc(0)
            dtotal = mpmath.mpc(0)
            for p in side:
                e = mpmath.exp(1j * p * xi)
                N1, Qv = at[p][:2]
                total += e * Qv / N1
                if derivative:
                    Nq, N2, Qp, Nqp, Qq = at[p][2:]
                    g = e * Qv * Nq
                    gp = e * (1j * xi * Qv * Nq + Qp * Nq + Qv * Nqp)
                    dtotal += e * Qq / N1 - (gp * N1 - g * N2) / N1**3
            Ks.append(sign * two_pi_i * total)
            dKs.append(sign * two_pi_i * dtotal)
        sep = min_relative_separation(upper) if len(upper) > 1 else None
        sep_l = min_relative_separation(lower) if len(lower) > 1 else None
        if sep is None or (sep_l is not None and sep_l < sep):
            sep = sep_l
        return KernelValues(tuple(Ks), tuple(dKs) if derivative else None, tuple(roots)), sep


def min_relative_separation(roots: Sequence[Mpc]) -> Mpf | None:
    """The smallest distance between two of ``roots`` relative to max(|p|, 1), None for fewer than two."""
    best = None
    for i in range(len(roots)):
        for j in range(i + 1, len(roots)):
            scale = max(abs(roots[i]), abs(roots[j]), mpmath.mpf(1))
            sep = abs(roots[i] - roots[j]) / scale
            best = sep if best is None or sep < best else best
    return best


def _roots_mp(coeffs: list[Mpc]) -> list[Mpc]:
    """All roots of a polynomial (highest power first) at the current precision.

    Starts from numpy's double-precision roots and polishes all of them together by the Weierstrass
    (Durand-Kerner) iteration, which converges quadratically for simple roots; falls back to
    ``mpmath.polyroots`` if it does not converge.
    """
    while len(coeffs) > 1 and coeffs[0] == 0:
        coeffs = coeffs[1:]
    lead = coeffs[0]
    monic = [c / lead for c in coeffs]
    start = np.roots([complex(c) for c in monic])
    z = [mpmath.mpc(complex(x)) for x in start]
    tol = mpmath.mpf(10) ** (-mpmath.mp.dps + 3)
    for _ in range(60):
        deltas = []
        for i, zi in enumerate(z):
            den = mpmath.mpc(1)
            for j, zj in enumerate(z):
                if j != i:
                    den *= zi - zj
            if den == 0:
                break
            deltas.append(horner(monic, zi) / den)
        if len(deltas) != len(z):
            break
        z = [zi - di for zi, di in zip(z, deltas)]
        if max(abs(di) / max(abs(zi), 1) for di, zi in zip(deltas, z)) < tol:
            return z
    return list(mpmath.polyroots(monic, maxsteps=200, extraprec=2 * mpmath.mp.prec))


class TrackKernelArray:
    """K(xi, q) and dK/dq for numpy arrays of q in double precision (counting contours, sweeps).

    ``bound`` as in :class:`TrackKernel`.
    """

    def __init__(self, bound: BoundModel) -> None:
        self.bound = bound
        self.params = bound.params
        self.foundation: Foundation = bound.foundation_model
        self.module = self.foundation.module
        self.args = bound.foundation_floats()
        self._coeffs = Coefficients(self.args)

    def p_roots(self, q: ArrayLike, coeffs: ComplexArray | None = None) -> ComplexArray:
        """Roots in p, shape q.shape + (DEGREE_N,) (closed form for quartics, else companion + Newton);
        ``coeffs``: those of N(., q) if already evaluated."""
        return poly_roots(self._coeffs(self.module.n_coeffs, q) if coeffs is None else coeffs)

    def __call__(
        self,
        q: ArrayLike,
        xis: Iterable[float],
        *,
        derivative: bool = False,
        sides: tuple[ArrayLike, ArrayLike] | None = None,
    ) -> KernelValues:
        """K at the offsets ``xis`` (and dK/dq). ``sides``: ``(refs, above)``, the side of the real p-axis
        fixed for the root of N nearest to each ``refs[j]`` (``above[j]``) instead of read off its Im p: the
        analytic continuation of K across the cut where those roots cross it (:func:`fixed_sides`)."""
        q = np.asarray(q, dtype=complex)
        n = self._coeffs(self.module.n_coeffs, q)
        roots = self.p_roots(q, n)
        qc = self._coeffs(self.module.q_coeffs, q)
        n1 = polyder(n)
        P = roots
        finite = np.isfinite(P)  # a root at infinity (degree drop, nan) is on neither side
        P = np.where(finite, P, 0)
        N1 = np.where(finite, polyval(n1, P), 1)
        Qv = polyval(qc, P)
        if derivative:
            n2 = polyder(n1)
            nq = self._coeffs(self.module.n_coeffs_dq, q)
            qq = self._coeffs(self.module.q_coeffs_dq, q)
            N2 = polyval(n2, P)
            Nq = polyval(nq, P)
            Nqp = polyval(polyder(nq), P)
            Qp = polyval(polyder(qc), P)
            Qq = polyval(qq, P)
        upper = (P.imag > 0) & finite
        unclear = None
        if sides is not None:
            upper, unclear = fixed_sides(P, upper, *sides)
        lower = ~upper & finite
        # every offset at once: axis -2 runs over xis, axis -1 over the roots of N
        xi = np.array([float(x) for x in xis])
        if not xi.size:
            return KernelValues((), () if derivative else None, roots)
        ahead = xi >= 0
        mask = np.where(ahead[:, None], upper[..., None, :], lower[..., None, :])
        sign = np.where(ahead, 2j * np.pi, -2j * np.pi)
        xi_ = xi[:, None]
        e = np.exp(1j * np.where(mask, P[..., None, :], 0) * xi_)  # |e| <= 1 on the side that enters
        residue = (Qv / N1)[..., None, :]
        K = sign * np.sum(np.where(mask, e * residue, 0), axis=-1)
        if unclear is not None:
            K[unclear] = np.nan  # the root nearest to a reference is not clearly one root: no value
        Ks = tuple(K[..., j] for j in range(xi.size))
        if not derivative:
            return KernelValues(Ks, None, roots)
        QN = (Qv * Nq)[..., None, :]
        gp = e * (1j * xi_ * QN + (Qp * Nq + Qv * Nqp)[..., None, :])
        g = e * QN
        N1_, N2_ = N1[..., None, :], N2[..., None, :]
        term = e * (Qq / N1)[..., None, :] - (gp * N1_ - g * N2_) / N1_**3
        dK = sign * np.sum(np.where(mask, term, 0), axis=-1)
        if unclear is not None:
            dK[unclear] = np.nan
        return KernelValues(Ks, tuple(dK[..., j] for j in range(xi.size)), roots)


#: A root is "the root nearest to a reference" only when it is closer than this fraction of the distance
#: from the reference to every other root (:func:`fixed_sides`).
NEAREST = 0.4


def fixed_sides(
    P: ComplexArray, upper: np.ndarray, refs: ArrayLike, above: ArrayLike
) -> tuple[np.ndarray, np.ndarray]:
    """``upper`` (the roots ``P`` (..., DEGREE_N) taken above the real p-axis) with the side of the root
    nearest to each ``refs[j]`` set to ``above[j]``: K then sums the residue of that root on the same side
    at every q, the analytic continuation of K through the cut where it crosses the real p-axis.

    Returns (upper, unclear): ``unclear`` marks the q where some nearest root is not clearly one (closer
    than :data:`NEAREST` times the distance to the next), where the continuation is not defined.
    """
    upper = upper.copy()
    unclear = np.zeros(P.shape[:-1], dtype=bool)
    for ref, side in zip(np.atleast_1d(refs), np.atleast_1d(above)):
        with np.errstate(invalid="ignore"):
            d = np.abs(np.where(np.isfinite(P), P, np.inf) - ref)
        order = np.argsort(d, axis=-1)
        near = np.take_along_axis(d, order[..., :2], axis=-1)
        unclear |= ~(near[..., 0] < NEAREST * near[..., 1])
        np.put_along_axis(upper, order[..., :1], bool(side), axis=-1)
    return upper, unclear
