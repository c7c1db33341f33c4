"""D-decomposition (Verichev & Metrikine 2002, ref. [48]) at fixed velocity: an independent cross-check.

At fixed alpha, E_chr(q; theta) = 0 defines theta(q) for every q. The D-curves are the images of the real
q-axis, theta_k(q) for real q > 0 (the other half of the axis gives the mirror pairs): a root q crosses the
real axis exactly when theta is on a D-curve. Their crossings with the real theta-axis are the values
theta* where the number of unstable induced frequencies changes, i.e. the points of the instability
lines (:mod:`instability_lines`) on the vertical line alpha = const.

The rule of hatching gives the direction of the change: q -> theta(q) is conformal, so the image of the
lower half q-plane (unstable roots) lies to the right of a D-curve traversed with increasing q. At a
crossing with tangent dtheta/dq, increasing theta enters that side when Im(dtheta/dq) > 0: the count of
unstable roots increases by one with theta there, and decreases by one otherwise.

This module samples the real q-axis, follows the (complex) roots theta_k(q) of the polynomial in theta
(:mod:`stability_kernel`) by matching them from sample to sample, locates the sign changes of
Im theta_k and refines each by Newton's method in (q, theta) at fixed alpha. Nothing is shared with the
3-D continuation of :mod:`instability_lines` except E_chr itself.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from moving_bogie.errors import ParameterError
from moving_bogie.kernels.bound import BoundModel
from moving_bogie.kernels.sweep_characteristic import SweepCharacteristic, poly_roots

__all__ = ["DCrossing", "DDecomposition", "d_decomposition"]


@dataclass(frozen=True)
class DCrossing:
    """A D-curve crossing the real theta-axis: theta*, the real induced frequency q* there, and the change
    (+1 or -1) of the number of unstable induced frequencies when theta increases through theta*."""

    theta: float
    q: float
    change: int


@dataclass(frozen=True)
class DDecomposition:
    """D-curves and their crossings with the real axis at one alpha."""

    alpha: float
    parameter: str
    q: np.ndarray  # real samples of q
    curves: np.ndarray  # (len(q), degree) complex theta_k(q), labels followed continuously in q
    crossings: tuple[DCrossing, ...]  # sorted by theta

    def counts(
        self, thetas: float | Sequence[float] | np.ndarray, reference_theta: float, reference_count: int
    ) -> np.ndarray:
        """Unstable induced frequencies at ``thetas`` from one reference count (rule of hatching)."""
        at = np.atleast_1d(np.asarray(thetas, dtype=float))
        out = np.full(at.shape, reference_count, dtype=int)
        for c in self.crossings:
            out += np.where((at > c.theta) & (reference_theta < c.theta), c.change, 0)
            out -= np.where((at < c.theta) & (reference_theta > c.theta), c.change, 0)
        return out

    def to_dict(self) -> dict:
        return {
            "alpha": self.alpha,
            "parameter": self.parameter,
            "crossings": [{"theta": c.theta, "q": c.q, "change": c.change} for c in self.crossings],
        }


def d_decomposition(
    bound: BoundModel,
    alpha: float | None = None,
    *,
    parameter: str | None = None,
    theta_max: float = 200.0,
    q_max: float = 1.5,
    samples: int = 6000,
    tol: float = 1e-12,
) -> DDecomposition:
    """D-decomposition of the ``parameter`` axis at one velocity (default: the parameters' alpha).

    Parameters
    ----------
    bound : BoundModel
        Requires eta_f > 0 (the real q-axis must lie below the cut of K).
    alpha : float, optional
    parameter : str, optional
        The swept vehicle parameter (eta_M, kappa_v, eta_v, ...; default the wheel mass,
        ``Model.wheel_mass``).
    theta_max : float
        Crossings with 0 < theta <= theta_max are kept.
    q_max, samples : float, int
        The real q-axis is sampled at ``samples`` points in (0, q_max].
    tol : float
        Newton tolerance of the refined crossings.
    """
    params = bound.params
    parameter = parameter or params.model.wheel_mass
    if params.eta_f <= 0:
        raise ParameterError(
            "eta_f",
            "D-decomposition needs eta_f > 0 (the cut of K lies on the real axis; stability/maps/undamped.py "
            "locates the boundaries of an undamped foundation by counts)",
        )
    alpha = float(params.alpha if alpha is None else alpha)
    sweep = SweepCharacteristic(bound, parameter)
    qs = np.linspace(q_max / samples, q_max, samples)
    K, _, _ = sweep.kernel(qs, alpha)
    roots = poly_roots(sweep.coefficients(qs, K, scale=theta_max)) * theta_max
    curves = _follow(roots)
    crossings: list[DCrossing] = []
    im = curves.imag
    for k in range(curves.shape[1]):
        flips = np.nonzero(
            np.isfinite(im[:-1, k]) & np.isfinite(im[1:, k]) & (np.sign(im[:-1, k]) * np.sign(im[1:, k]) < 0)
        )[0]
        for i in flips:
            w = im[i, k] / (im[i, k] - im[i + 1, k])
            q0 = qs[i] + w * (qs[i + 1] - qs[i])
            th0 = (curves[i, k] + w * (curves[i + 1, k] - curves[i, k])).real
            found = _refine(sweep, alpha, q0, th0, tol)
            if found is not None and found[0] < 0:  # Newton went to the mirror root -q: same pair
                found = _refine(sweep, alpha, -found[0], found[1], tol)
            if found is None or found[0] <= 0:
                continue
            q, th, change = found
            if 0 < th <= theta_max and all(
                abs(th - c.theta) > 1e-7 * max(1, th) or abs(q - c.q) > 1e-7 for c in crossings
            ):
                crossings.append(DCrossing(float(th), float(q), change))
    crossings.sort(key=lambda c: c.theta)
    return DDecomposition(alpha, parameter, qs, curves, tuple(crossings))


def _follow(roots: np.ndarray) -> np.ndarray:
    """Relabel the roots sample by sample so that each column is continuous in q (nearest assignment)."""
    n, deg = roots.shape
    out = roots.copy()
    perms = np.array(list(itertools.permutations(range(deg))))
    for i in range(1, n):
        prev, cur = out[i - 1], roots[i]
        if not np.all(np.isfinite(prev)) or not np.all(np.isfinite(cur)):
            continue
        cost = np.abs(cur[perms] - prev[None, :]).sum(axis=1)
        out[i] = cur[perms[np.argmin(cost)]]
    return out


def _refine(
    sweep: SweepCharacteristic, alpha: float, q: float, theta: float, tol: float, max_iter: int = 30
) -> tuple[float, float, int] | None:
    """Newton on E(q, theta) = 0 with q, theta real (2x2 real system); returns (q, theta, change) or None."""
    for _ in range(max_iter):
        E, E_q, _, E_t = sweep.derivatives(np.array([q], dtype=complex), np.array([alpha]), np.array([theta]))
        assert E_t is not None  # theta is given

        J = np.array([[E_q[0].real, E_t[0].real], [E_q[0].imag, E_t[0].imag]])
        try:
            dq, dt = np.linalg.solve(J, -np.array([E[0].real, E[0].imag]))
        except np.linalg.LinAlgError:
            return None
        q, theta = q + dq, theta + dt
        if abs(dq) < tol * max(1, abs(q)) and abs(dt) < tol * max(1, abs(theta)):
            dtheta_dq = -E_q[0] / E_t[0]
            return q, theta, (1 if dtheta_dq.imag > 0 else -1)
    return None
