"""The branch-cut part I_bc of Eq. (35) for any track model: the jump across the traced cut, in p.

The cut of K is the union of the curves q_j(p), p real (:mod:`moving_bogie.kernels.cut`). Pushing the
Bromwich line Im q = -a upwards past a piece of such a curve leaves the integral of the jump of
f = X~(q) e^{i q tau} across it; along a curve run in the direction of increasing p,

    I_bc(tau) = (1/2 pi) sum_j integral over real p of [f_right - f_left](q_j(p)) q_j'(p) dp,

"right"/"left" of the direction of travel (the orientation cancels: reversing it swaps the sides and the
sign of dq). On the right side the real root p of N(., q) has moved to Im p < 0, on the left to Im p > 0:
q -> q - i e t/|t| (t = q_j'(p)) moves a root p_k by i e (N_q/N_p)(p_k) t/|t|. Any other real root of
N(., q) (a point where curves coincide or cross, e.g. the two halves of the Euler-Bernoulli ray) is placed
by the same rule, and each point of the cut is counted once by the weight 1/(number of real roots). The
parametrisation by p removes the square-root singularity of a cusp (q' = 0 there), and needs no
geometry of the cut: folds, lenses and the Timoshenko-Rayleigh curve near |Re q| = sqrt(S)/r all enter
as they are. By the mirror symmetry f(-conj q) = conj f(q) only the curves in Re q > 0 are integrated,
I_bc = (1/pi) Re sum over them.

Quadrature: composite 16-point Gauss-Legendre in p, panels first adapted to the non-oscillating integrand
(halved until the panel integral changes by less than ``panel_tol``), then subdivided to at most 3 pi of
phase Re q tau and 2 radians of e^{i p xi}. Each curve is truncated where Re q = S at both ends; the
tails are integrated by parts along the curve, e^{i q tau}(i F/tau - F'/tau^2 - i F''/tau^3) with F' in q
by divided differences, and S is chosen like the Euler-Bernoulli integral's (:mod:`branch_cut`).
"""

from __future__ import annotations

import numpy as np

from moving_bogie.errors import MovingBogieError
from moving_bogie.kernels.characteristic import vehicle_module
from moving_bogie.kernels.cut import CutTracer, trace_curves
from moving_bogie.kernels.polyroots import poly_roots, polyder, polyval, stack_coefficients
from moving_bogie.kernels.track import resolve_foundation
from moving_bogie.response.branch_cut import BranchCut, BranchCutUnavailable
from moving_bogie.response.quadrature import adapt_panels, by_bands, fourier_sum, subdivide

__all__ = ["CurveBranchCut", "branch_cut_for"]

_PANEL_PHASE = 3 * np.pi
_PANEL_XI = 2.0
_S_STEPS = tuple(2.0**k for k in range(1, 14))
_REACH = 2.0**14


def branch_cut_for(params, model: str = "bogie", *, foundation=None):
    """The branch-cut integral of ``params``: :class:`BranchCut` for the Euler-Bernoulli beam (its cut is a
    half-line, integrated in closed geometry), :class:`CurveBranchCut` for any other model."""
    if foundation is None and (params.beam, params.track) == ("eb", "one-layer"):
        return BranchCut(params, model)
    return CurveBranchCut(params, model, foundation=foundation)


class _Curve:
    """One traced curve q(p) (samples ``p`` increasing, ``q``), evaluated exactly by Newton."""

    def __init__(self, tracer, p, q):
        self.tracer, self.p, self.q = tracer, p, q
        self._ends: dict = {}
        self.x_min = float(q.real.min())

    def q_at(self, p):
        p = np.asarray(p, dtype=float)
        guess = np.interp(p, self.p, self.q.real) + 1j * np.interp(p, self.p, self.q.imag)
        return self.tracer.refine(p, guess)

    def p_ends(self, S):
        """(p_lo, p_hi): the outermost p on each side where Re q = S (Re q > S beyond)."""
        if S not in self._ends:
            self._ends[S] = self._find_ends(S)
        return self._ends[S]

    def _find_ends(self, S):
        """Both crossings of Re q = S: bracketed by the samples, then safeguarded Newton (vectorised)."""
        x = self.q.real
        inside = np.nonzero(x <= S)[0]
        k = np.array([inside[0] - 1, inside[-1]])  # the crossing lies in [p_k, p_k+1]
        a, b = self.p[k], self.p[k + 1]
        p = a + (S - x[k]) * (b - a) / (x[k + 1] - x[k])
        for _ in range(30):
            q = self.q_at(p)
            step = (q.real - S) / self.tracer.dq_dp(p, q).real
            new = np.clip(p - step, a, b)
            if np.all(np.abs(new - p) <= 1e-14 * np.maximum(1.0, np.abs(p))):
                p = new
                break
            p = new
        return float(p[0]), float(p[1])


class CurveBranchCut:
    """I_bc of Eq. (35) for any track model, integrated over the traced cut (module docstring).

    Same interface as :class:`~moving_bogie.response.branch_cut.BranchCut`: ``q_c`` (leftmost point of
    the cut), ``eta_f`` (lowest Im q of the cut: |I_bc| <= l1_bound e^{-eta_f tau}), :meth:`responses`,
    :meth:`shape`, :meth:`l1_bound`.

    Raises
    ------
    BranchCutUnavailable
        When the cut reaches Re q = 0 (supercritical velocity: no gap around the steady state).
    """

    def __init__(self, params, model: str = "bogie", *, foundation=None, panel_tol: float = 1e-13):
        self.params, self.model = params, model
        track = resolve_foundation(params, foundation)
        self.module = track.module
        self.fargs = track.float_arguments(params)
        self.tracer = CutTracer(self.module, self.fargs)
        f = params.as_float()
        self.d = f.d
        self.vehicle = vehicle_module(model, params)
        self.vargs = {name: getattr(f, name) for name in self.vehicle.PARAMETERS} | {"pi": np.pi}
        self.names = tuple(self.vehicle.RESPONSES)
        self.panel_tol = panel_tol
        P = 8.0
        while P < 1e4 and not np.all(np.abs(self.tracer.q_roots(np.array([-P, P])).real) > _REACH):
            P *= 2
        outer = np.geomspace(8.0, max(P, 16.0), 400)
        grid = np.unique(np.concatenate([-outer[::-1], np.linspace(-8.0, 8.0, 2001), outer]))
        ps, Q = trace_curves(self.tracer, -P, P, grid=grid)
        self.curves = []
        for j in range(Q.shape[1]):
            x = Q[:, j].real
            if np.all(x > 0):
                self.curves.append(_Curve(self.tracer, ps, Q[:, j]))
            elif not np.all(x < 0):
                raise BranchCutUnavailable(
                    "the cut of K reaches Re q = 0: supercritical velocity, no gap around the steady state"
                )
        if not self.curves:
            raise BranchCutUnavailable("the cut of K has no curve in Re q > 0")
        self.q_c = float(min(c.q.real.min() for c in self.curves))
        self.eta_f = max(0.0, float(min(c.q.imag.min() for c in self.curves)))
        self._base: dict = {}

    # --- the jump ------------------------------------------------------------------------------
    def _sides(self, p, q, t):
        """Roots P of N(., q), weights Q/N', and which roots count as upper on the right/left side."""
        n = stack_coefficients(self.module.n_coeffs(q, **self.fargs), q.shape)
        P = poly_roots(n)
        own = np.argmin(np.abs(P - p[:, None]), axis=-1)
        P[np.arange(p.size), own] = p
        real = np.abs(P.imag) <= 1e-9 * np.maximum(1.0, np.abs(P))
        P = np.where(real, P.real + 0j, P)
        Np = polyval(polyder(n), P)
        Nq = polyval(stack_coefficients(self.module.n_coeffs_dq(q, **self.fargs), q.shape), P)
        W = polyval(stack_coefficients(self.module.q_coeffs(q, **self.fargs), q.shape), P) / Np
        moves_up = (Nq / Np * (t / np.abs(t))[:, None]).real > 0
        right = np.where(real, moves_up, P.imag > 0)
        left = np.where(real, ~moves_up, P.imag > 0)
        return P, W, right, left, real.sum(axis=-1)

    @staticmethod
    def _kernel(P, W, upper, xi):
        """K(xi, q) from the roots with the given side assignment, shape (nodes, len(xi))."""
        xi = np.asarray(xi, dtype=float)
        e = np.exp(1j * P[:, :, None] * xi) * W[:, :, None]
        pos = xi >= 0
        mask = np.where(pos[None, None, :], upper[:, :, None], ~upper[:, :, None])
        return np.where(pos, 2j * np.pi, -2j * np.pi) * np.sum(np.where(mask, e, 0), axis=1)

    def _jump(self, curve, p, xi=None):
        """(q, J): J = (X~_right - X~_left) q'(p) / (number of real roots), per response (or W~ at xi)."""
        p = np.asarray(p, dtype=float)
        q = curve.q_at(p)
        t = self.tracer.dq_dp(p, q)
        P, W, right, left, m = self._sides(p, q, t)
        contact = np.array([0.0, self.d, -self.d])
        out = []
        for upper in (right, left):
            K0, Kp, Km = self._kernel(P, W, upper, contact).T
            E = self.vehicle.e_chr(q, K0, Kp, Km, **self.vargs)
            if xi is None:
                nums = self.vehicle.numerators(q, K0, Kp, Km, **self.vargs)
                out.append(np.stack([n / (1j * q * E) for n in nums], axis=-1))
            else:
                G_r, G_f = self.vehicle.shape_weights(q, K0, Kp, Km, **self.vargs)
                den = 2 * np.pi * 1j * q * E
                Kx, Kxd = self._kernel(P, W, upper, xi), self._kernel(P, W, upper, xi - self.d)
                out.append((G_r / den)[:, None] * Kx + (G_f / den)[:, None] * Kxd)
        return q, (out[0] - out[1]) * (t / m)[:, None]

    # --- quadrature ----------------------------------------------------------------------------
    def _panels(self, curve, S, channel):
        key = (id(curve), S, channel)
        if key in self._base:
            return self._base[key]
        p_lo, p_hi = curve.p_ends(S)
        for (cid, S2, ch), edges in self._base.items():
            if cid == id(curve) and ch == channel and S2 >= S:  # reuse the partition of a longer range
                keep = edges[(edges > p_lo) & (edges < p_hi)]
                return np.concatenate([[p_lo], keep, [p_hi]])
        # start: panels of at most 0.5 in p and 5 % of max(1, Re q) along the curve (as for the half-line)
        P = np.linspace(p_lo, p_hi, 4000)
        q = curve.q_at(P)
        density = np.maximum(np.abs(self.tracer.dq_dp(P, q)) / (0.05 * np.maximum(1.0, np.abs(q.real))), 2.0)
        cum = np.concatenate([[0.0], np.cumsum(0.5 * (density[1:] + density[:-1]) * np.diff(P))])
        start = np.interp(np.linspace(0.0, cum[-1], max(2, int(np.ceil(cum[-1]))) + 1), cum, P)
        edges = adapt_panels(start, lambda nodes: channel(curve, nodes)[1], self.panel_tol)
        self._base[key] = edges
        return self._base[key]

    def _rule(self, curve, S, tau_hi, xi_max, channel):
        edges = self._panels(curve, S, channel)
        x = curve.q_at(edges).real
        phase = tau_hi * np.abs(np.diff(x)) / _PANEL_PHASE
        return subdivide(edges, np.ceil(np.maximum(phase, np.diff(edges) * (abs(xi_max) + 1.0) / _PANEL_XI)))

    def _end_terms(self, curve, S, channel):
        """Per end of the curve (lower, upper): (q, F, F', F'') of the jump F along the curve, in q."""
        out = []
        for p_end in curve.p_ends(S):
            h = 1e-3 * max(1.0, abs(p_end))
            ps = np.array([p_end - h, p_end, p_end + h])
            q, F = channel(curve, ps)
            F = F / self.tracer.dq_dp(ps, q)[:, None]  # the jump itself, as a function of q
            d01 = (F[1] - F[0]) / (q[1] - q[0])
            d12 = (F[2] - F[1]) / (q[2] - q[1])
            d012 = (d12 - d01) / (q[2] - q[0])
            out.append((q[1], F[1], d01 + d012 * (q[1] - q[0]), 2 * d012))
        return out

    def _tails(self, curve, S, channel, ts):
        """Both truncated ends, integrated by parts along the curve (outward from each end)."""
        total = 0
        tt = ts[:, None]
        for sign, (q, F0, F1, F2) in zip((-1, 1), self._end_terms(curve, S, channel)):
            total = total + sign * np.exp(1j * q * tt) * (1j * F0 / tt - F1 / tt**2 - 1j * F2 / tt**3)
        return total

    def choose_S(self, channel, tau_lo, tol, s_min=None):
        """Truncation Re q = S of every curve, as for the Euler-Bernoulli cut (:mod:`branch_cut`): for
        tau_lo > 0 the first neglected term of the tails, |F''|/tau_lo^3, below ``tol``; for the first band
        the neglected integral, estimated as |F| S, below ``tol``."""
        # every curve must reach below S (a curve wholly beyond S has no end to integrate by parts from)
        lowest = self.q_c if s_min is None else max(self.q_c, s_min)
        floor = max([lowest] + [c.x_min + 1.0 for c in self.curves])
        S = floor
        for step in _S_STEPS:
            S = floor + step
            est = 0.0
            for curve in self.curves:
                for _, F0, _, F2 in self._end_terms(curve, S, channel):
                    est += float(np.abs(F2).max()) / tau_lo**3 if tau_lo > 0 else float(np.abs(F0).max()) * S
            if est <= tol:
                return S
        return S

    def integrate(self, tau, channel, *, tol=1e-10, s_min=None, xi_max=None):
        """I_bc(tau) per channel column: (1/pi) Re sum over the curves of integral J e^{i q tau} dp."""
        tau = np.asarray(tau, dtype=float)
        if np.any(tau < 0) or not np.all(np.isfinite(tau)):
            raise MovingBogieError("branch-cut integral needs finite tau >= 0")
        xi_max = self.d if xi_max is None else xi_max
        mid = self.curves[0].p[self.curves[0].p.size // 2]
        m = channel(self.curves[0], np.array([mid]))[1].shape[-1]

        def band(lo, ts):
            S = self.choose_S(channel, lo, tol, s_min)
            acc = np.zeros((ts.size, m), dtype=complex)
            for curve in self.curves:
                nodes, weights = self._rule(curve, S, float(ts.max()), xi_max, channel)

                def weighted(chunk, w, curve=curve):
                    q, J = channel(curve, chunk)
                    return q, J * w[:, None]

                q_max = float(np.abs(curve.q_at(nodes)).max())
                acc += fourier_sum(ts, nodes, weights, weighted, m, q_max, None)
                if lo > 0:
                    acc += self._tails(curve, S, channel, ts)
            return acc

        return by_bands(tau, m, band)

    def responses(self, tau, *, tol: float = 1e-10, s_min: float | None = None) -> dict:
        """I_bc(tau) of every response, as a dict name -> ndarray."""
        values = self.integrate(tau, self._jump, tol=tol, s_min=s_min)
        return {name: values[..., k] for k, name in enumerate(self.names)}

    def shape(self, xi, tau: float, *, tol: float = 1e-10, s_min: float | None = None) -> np.ndarray:
        """I_bc of the deflection w(xi, tau) at one time, for an array xi."""
        xi = np.asarray(xi, dtype=float)
        flat = xi.reshape(-1)
        values = self.integrate(
            np.array([float(tau)]),
            lambda curve, p: self._jump(curve, p, flat),
            tol=tol,
            s_min=s_min,
            xi_max=float(np.max(np.abs(np.concatenate([flat, flat - self.d])))),
        )
        return values[0].reshape(xi.shape)

    def l1_bound(self, *, tol: float = 1e-10, s_min: float | None = None) -> dict:
        """(1/pi) sum of integrals of |J| dp: |I_bc(tau)| <= this * e^{-eta_f tau} for every tau."""
        S = self.choose_S(self._jump, 0.0, tol, s_min)
        total = 0.0
        for curve in self.curves:
            nodes, weights = self._rule(curve, S, 0.0, self.d, self._jump)
            total = total + (np.abs(self._jump(curve, nodes)[1]) * weights[:, None]).sum(axis=0) / np.pi
        return {name: float(total[k]) for k, name in enumerate(self.names)}
