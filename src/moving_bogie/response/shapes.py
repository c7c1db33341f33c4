"""K(xi, q) on whole arrays of xi at a fixed q: roots and residue weights once in mpmath, then numpy.

K(xi, q) = +2 pi i sum_{Im p_k > 0} e^{i p_k xi} Q(p_k)/N'(p_k) for xi >= 0 and -2 pi i times the sum over
Im p_k < 0 for xi < 0 (Eq. (29), :mod:`moving_bogie.kernels.track`). The deflection shape of Eqs.
(44)-(47) needs
K at many xi for the same few q (0 and the induced frequencies): the p-roots and weights Q/N' are computed
once at the roots' precision, and the exponentials are evaluated for all xi in numpy. Where two roots on the
same side nearly coincide their separate weights are large and nearly cancel; then every xi is evaluated by
:class:`~moving_bogie.kernels.track.TrackKernel` at raised precision instead.
"""

from __future__ import annotations

import mpmath
import numpy as np
from numpy.typing import ArrayLike

from moving_bogie.kernels.bound import BoundModel
from moving_bogie.kernels.polynomial import derivative_coefficients, horner
from moving_bogie.kernels.track import TrackKernel, min_relative_separation

__all__ = ["KernelGrid"]


class KernelGrid:
    """K(., q) for arrays of xi at one complex q.

    Parameters
    ----------
    bound : BoundModel
    q : complex or mpc
        Off the cut of K (an induced frequency or q = 0).
    dps : int
        Precision of the roots and weights.
    coalescence : float
        Relative separation of two same-side roots below which the slow exact path is used.
    """

    def __init__(self, bound: BoundModel, q: complex, *, dps: int = 30, coalescence: float = 1e-3) -> None:
        self.dps = dps
        self.kernel = TrackKernel(bound)
        self.params = self.kernel.params
        with mpmath.workdps(dps):
            self.q = mpmath.mpc(q)
            args = self.kernel.arguments()
            roots = self.kernel.p_roots(self.q)
            n1 = derivative_coefficients([mpmath.mpc(c) for c in self.kernel.module.n_coeffs(self.q, **args)])
            qc = [mpmath.mpc(c) for c in self.kernel.module.q_coeffs(self.q, **args)]
            weights = [horner(qc, p) / horner(n1, p) for p in roots]
            upper = [p for p in roots if mpmath.im(p) > 0]
            lower = [p for p in roots if mpmath.im(p) < 0]
            seps = [
                s for s in (min_relative_separation(upper), min_relative_separation(lower)) if s is not None
            ]
        self.exact = bool(seps) and min(seps) < coalescence
        self.roots = np.array([complex(p) for p in roots])
        self.weights = np.array([complex(w) for w in weights])

    def __call__(self, xi: ArrayLike) -> np.ndarray:
        """K(xi, q) for an array xi (complex array of the same shape)."""
        xi = np.asarray(xi, dtype=float)
        if self.exact:
            with mpmath.workdps(self.dps):
                values = [complex(self.kernel(self.q, [x]).K[0]) for x in xi.reshape(-1)]
            return np.array(values, dtype=complex).reshape(xi.shape)
        e = np.exp(1j * np.multiply.outer(xi, self.roots)) * self.weights
        up = self.roots.imag > 0
        plus = 2j * np.pi * e[..., up].sum(axis=-1)
        minus = -2j * np.pi * e[..., ~up].sum(axis=-1)
        return np.where(xi >= 0, plus, minus)
