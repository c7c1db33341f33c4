"""The cut locus of K(xi, q) in the q-plane: where a root of N(p, q) crosses the real p-axis.

K of Eq. (29) is analytic in q except where N(p, q) = 0 has a real root p; there the set of roots used by
the residue sum changes and K jumps (the branch cuts of Eq. (35)). For a real p the roots q of the
polynomial N(p, .) trace curves. For the Euler-Bernoulli beam (eta_f < 1)

    q = alpha p + i eta_f +- sqrt((p^4 + 4 eta_s p^2 + 4)/4 - eta_f^2),

two half-lines on Im q = eta_f starting at +-q_c: between them the line can be crossed (this is why the
undamped induced frequencies of Cases 2-4 are real). For Timoshenko-Rayleigh the rotary inertia bends
the curves slightly below eta_f. The search for induced frequencies never lets a contour meet these curves.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from moving_bogie.kernels.polyroots import poly_roots, stack_coefficients
from moving_bogie.kernels.track import resolve_foundation


@dataclass(frozen=True)
class CutLocus:
    """Sampled cut curves in the half-plane Re q >= x_min, up to Re q <= x_max.

    Attributes
    ----------
    points : ndarray of complex
        Sample points of the cut curves inside the strip.
    x_start : float
        Smallest Re q of the cut in the strip (the branch point q_c; ``-inf`` if the cut reaches x_min).
    im_low, im_high : float
        Range of Im q of the cut inside the strip (both eta_f for Euler-Bernoulli).
    """

    points: np.ndarray
    x_start: float
    im_low: float
    im_high: float

    def im_range_between(self, x_left: float, x_right: float):
        """(low, high) Im q of the cut with x_left <= Re q <= x_right, or None if it does not pass there."""
        sel = self.points[(self.points.real >= x_left) & (self.points.real <= x_right)]
        if sel.size == 0:
            return None
        return float(sel.imag.min()), float(sel.imag.max())


def cut_locus(params, x_min: float, x_max: float, *, samples: int = 20001, foundation=None) -> CutLocus:
    """Trace the cut of K for ``params`` over x_min <= Re q <= x_max.

    Real p is sampled on a grid that reaches beyond every p whose cut point has Re q <= x_max
    (|q| grows like p^2/2, so |p| <= 2 sqrt(|x| + 1) + 4 suffices for |alpha| < 2), refined near the
    minimum of Re q so that the branch point q_c is located to about 1e-9.
    """
    track = resolve_foundation(params, foundation)
    module = track.module
    args = track.float_arguments(params)
    span = 2.0 * np.sqrt(max(abs(x_min), abs(x_max)) + 1.0) + 4.0 + 4.0 * float(params.alpha)
    ps = np.linspace(-span, span, samples)
    pts = _q_roots(module, args, ps)
    inside = pts[(pts.real >= x_min) & (pts.real <= x_max)]
    if inside.size == 0:
        return CutLocus(inside, np.inf, np.nan, np.nan)
    # refine around the leftmost point of the cut in the strip (the branch point)
    k = np.argmin(np.where(pts.real >= x_min, pts.real, np.inf), axis=None)
    p0 = ps[k // pts.shape[1]]
    h = ps[1] - ps[0]
    for _ in range(3):
        fine = np.linspace(p0 - 2 * h, p0 + 2 * h, 2001)
        fpts = _q_roots(module, args, fine)
        masked = np.where(fpts.real >= x_min, fpts.real, np.inf)
        k = np.argmin(masked)
        p0 = fine[k // fpts.shape[1]]
        h = fine[1] - fine[0]
        inside = np.concatenate([inside, fpts[(fpts.real >= x_min) & (fpts.real <= x_max)]])
    x_start = float(inside.real.min())
    # a cut that reaches the strip's left edge has no gap (supercritical speed)
    if x_start <= x_min + 1e-12:
        x_start = -np.inf
    return CutLocus(inside, x_start, float(inside.imag.min()), float(inside.imag.max()))


def _q_roots(module, args, ps):
    cs = stack_coefficients(module.n_coeffs_in_q(ps, **args), ps.shape)
    while np.all(cs[:, 0] == 0):
        cs = cs[:, 1:]
    return poly_roots(cs)
