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
as they are. By the mirror symmetry f(-conj q) = conj f(q) only the pieces of the curves with Re q >= 0
are integrated, I_bc = (1/pi) Re sum over them: a curve that crosses Re q = 0 (a layered track's mass
layer, whose curves sweep across all Re q; a damped track above the critical velocity) is split there,
and that end of a piece is an interior point of the cut whose mirror piece continues it (no tail term).
A cut through q = 0 itself (the pole of the steady part) is refused, and so is a curve that stays
bounded in Re q > 0 (a mass layer at alpha = 0).

Quadrature: composite 16-point Gauss-Legendre in p, panels first adapted to the non-oscillating integrand
(from panels of at most 5 % of max(1, Re q) along the curve and 3 pi of e^{i p xi} at the largest contact
offset, halved until the panel integral changes by less than ``panel_tol``), then subdivided to at most
3 pi of phase Re q tau and, for a shape, 2 radians of e^{i p xi} at its largest |xi| (the responses' jump
holds e^{i p xi} at the contact offsets only, which the adapted panels resolve: at most 3 pi of it). Each
piece is truncated where Re q = S at its far ends (where Re q grows without bound); the tails are
integrated by parts along the curve, e^{i q tau}(i F/tau - F'/tau^2 - i F''/tau^3) with F' in q by divided
differences, and S is chosen per piece like the Euler-Bernoulli integral's (:mod:`branch_cut`): a mass
layer's jump falls like p^-8 while its Re q grows only like alpha p, so its pieces stop at a small S.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from moving_bogie.errors import MovingBogieError
from moving_bogie.kernels.bound import BoundModel
from moving_bogie.kernels.cut import CutTracer, trace_curves
from moving_bogie.kernels.polyroots import polyder, polyval, stack_coefficients
from moving_bogie.response.branch_cut import BranchCut, BranchCutUnavailable
from moving_bogie.response.cut_pieces import CurvePiece, cut_pieces, roots_along
from moving_bogie.response.cut_values import JumpValues, PieceChannel
from moving_bogie.response.quadrature import (
    PANEL_PHASE,
    PANEL_XI,
    adapt_panels_with_values,
    band_top,
    by_bands,
    equidistribute,
    fourier_sum,
    oscillation_rule,
)

__all__ = ["CurveBranchCut", "branch_cut_for"]

_S_STEPS = tuple(2.0**k for k in range(1, 14))
_REACH = 2.0**14
#: A root of N(., q) counts as real (another curve through the same q) when |Im p| <= this * max(1, |p|):
#: the rounding of coinciding curves (the two halves of the Euler-Bernoulli ray), not curves that only
#: approach each other (the halves of a layered track's lens and its mass-layer curves converge like a
#: power of 1/p; merging them at 1e-9 left errors of 1e-8 w_st in the deflection shape).
_REAL_TOL = 1e-12
#: The widest starting panel in p is at least the half-line's (its _PANEL_DP).
_START_DP = 0.5


def branch_cut_for(bound: BoundModel) -> BranchCut | CurveBranchCut:
    """The branch-cut integral of ``bound``: :class:`BranchCut` where the derivation says the cut of K is a
    half-line (``cut_line_radicand`` of the generated track, the paper's Euler-Bernoulli beam) and the
    velocity is below the critical one (integrated in closed geometry), :class:`CurveBranchCut` for any
    other model and above the critical velocity (raises :class:`BranchCutUnavailable` when the cut passes
    through q = 0, e.g. eta_f = 0)."""
    try:
        return BranchCut(bound)
    except BranchCutUnavailable:
        pass  # above the critical velocity: the traced cut crosses Re q = 0 above q = 0 when damped
    return CurveBranchCut(bound)


class CurveBranchCut(JumpValues):
    """I_bc of Eq. (35) for any track model, integrated over the traced cut (module docstring).

    Same interface as :class:`~moving_bogie.response.branch_cut.BranchCut`: ``q_c`` (leftmost point of
    the cut), ``eta_f`` (lowest Im q of the cut: |I_bc| <= l1_bound e^{-eta_f tau}), :meth:`responses`,
    :meth:`shape`, :meth:`l1_bound`.

    Parameters
    ----------
    bound : BoundModel
    panel_tol : float
        Absolute tolerance per panel of the adapted partition (the halving test of
        :func:`~moving_bogie.response.quadrature.adapt_panels_with_values`).
    widest : float, optional
        Widest starting panel in p (default: PANEL_PHASE radians of e^{i p xi} at the largest contact
        offset, at least one unit of xi, and never below the half-line's 0.5).

    Raises
    ------
    BranchCutUnavailable
        When the cut passes through q = 0 (no steady state: an undamped track above the critical velocity,
        an undamped layered track), or a curve stays bounded in Re q > 0 (a layered track at alpha = 0).
    """

    def __init__(self, bound: BoundModel, *, panel_tol: float = 1e-13, widest: float | None = None) -> None:
        self.params = bound.params
        self.module = bound.foundation
        self.fargs = bound.foundation_floats()
        self.tracer = CutTracer(self.module, self.fargs)
        self.system, self.offsets, self.positions = bound.float_system, bound.offsets, bound.positions
        self.span, self.names = bound.span, bound.names
        self.panel_tol = panel_tol
        self.offset_dp = PANEL_PHASE / max(1.0, float(np.abs(self.offsets).max()))
        self.widest = max(_START_DP, self.offset_dp) if widest is None else widest
        P = 8.0
        while P < 1e4 and not np.all(np.abs(self.tracer.q_roots(np.array([-P, P])).real) > _REACH):
            P *= 2
        outer = np.geomspace(8.0, max(P, 16.0), 400)
        grid = np.unique(np.concatenate([-outer[::-1], np.linspace(-8.0, 8.0, 2001), outer]))
        ps, Q = trace_curves(self.tracer, -P, P, grid=grid)
        self.pieces = [piece for j in range(Q.shape[1]) for piece in cut_pieces(self.tracer, ps, Q[:, j])]
        if not self.pieces:
            raise BranchCutUnavailable("the cut of K has no curve in Re q > 0")
        self.q_c = float(min(c.x_min for c in self.pieces))
        self.eta_f = max(0.0, float(min(c.q.imag.min() for c in self.pieces)))
        JumpValues.__init__(self)

    # --- the jump ------------------------------------------------------------------------------
    def _sides(
        self, p: np.ndarray, q: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Roots P of N(., q), weights Q/N', which roots count as upper on the right/left side, which
        are real, and t = dq/dp = -N_p/N_q at the node's own root p (the curve's tangent)."""
        n = stack_coefficients(self.module.n_coeffs(q, **self.fargs), q.shape)
        P = roots_along(n)
        rows = np.arange(p.size)
        own = np.argmin(np.abs(P - p[:, None]), axis=-1)
        P[rows, own] = p
        real = np.abs(P.imag) <= _REAL_TOL * np.maximum(1.0, np.abs(P))
        P = np.where(real, P.real + 0j, P)
        Np = polyval(polyder(n), P)
        Nq = polyval(stack_coefficients(self.module.n_coeffs_dq(q, **self.fargs), q.shape), P)
        W = polyval(stack_coefficients(self.module.q_coeffs(q, **self.fargs), q.shape), P) / Np
        t = -Np[rows, own] / Nq[rows, own]
        moves_up = (Nq / Np * (t / np.abs(t))[:, None]).real > 0
        right = np.where(real, moves_up, P.imag > 0)
        left = np.where(real, ~moves_up, P.imag > 0)
        return P, W, right, left, real, t

    @staticmethod
    def _exponentials(P: np.ndarray, W: np.ndarray, real: np.ndarray, xi: ArrayLike) -> np.ndarray:
        """W e^{i P xi} per node, root and xi (shape (nodes, roots, len(xi))) for the roots that either
        side may take there: those with Im P xi >= 0 and the real ones (of the others, whose exponentials
        may overflow at large |xi|, only W)."""
        xi = np.asarray(xi, dtype=float)
        out = np.empty(P.shape + xi.shape, dtype=complex)
        out[..., xi == 0] = W[:, :, None]  # e^0 = 1
        x = xi[xi != 0]
        used = (np.multiply.outer(P.imag, x) >= 0) | real[:, :, None]
        out[..., xi != 0] = np.exp(1j * np.where(used, P[:, :, None], 0) * x) * W[:, :, None]
        return out

    @staticmethod
    def _kernel(E: np.ndarray, upper: np.ndarray, xi: ArrayLike) -> np.ndarray:
        """K(xi, q) from the roots with the given side assignment, shape (nodes, len(xi)); ``E`` from
        :meth:`_exponentials` (a side takes the roots above the real axis for xi >= 0, below for xi < 0:
        all among those evaluated there)."""
        pos = np.asarray(xi, dtype=float) >= 0
        mask = np.where(pos[None, None, :], upper[:, :, None], ~upper[:, :, None])
        return np.where(pos, 2j * np.pi, -2j * np.pi) * np.sum(np.where(mask, E, 0), axis=1)

    def _jump(
        self, piece: CurvePiece, p: ArrayLike, xi: np.ndarray | None = None
    ) -> tuple[np.ndarray, np.ndarray]:
        """(q, J): J = (X~_right - X~_left) q'(p) / (number of real roots), per response (or W~ at xi).

        At a node on a cusp (a double real root: W infinite, q' = 0) J is the mean of its values at
        p +- 1e-6 max(1, |p|) (J is smooth in p there)."""
        p = np.asarray(p, dtype=float)
        q = piece.q_at(p)
        with np.errstate(divide="ignore", invalid="ignore"):
            P, W, right, left, real, t = self._sides(p, q)
            E = self._exponentials(P, W, real, self.offsets)
            shifted = (
                []
                if xi is None
                else [(xi - x, self._exponentials(P, W, real, xi - x)) for x in self.positions]
            )
            out = []
            for upper in (right, left):
                Ks = list(self._kernel(E, upper, self.offsets).T)
                X, GE = self.system.solutions_array(q, Ks)
                if xi is None:
                    out.append(X / (1j * q)[:, None])
                else:
                    den = 2 * np.pi * 1j * q
                    out.append(
                        sum(
                            (GE[:, j] / den)[:, None] * self._kernel(Ej, upper, xj)
                            for j, (xj, Ej) in enumerate(shifted)
                        )
                    )
            J = (out[0] - out[1]) * (t / real.sum(axis=-1))[:, None]
        cusp = ~np.all(np.isfinite(J), axis=-1)
        if np.any(cusp):
            h = 1e-6 * np.maximum(1.0, np.abs(p[cusp]))
            J[cusp] = 0.5 * (self._jump(piece, p[cusp] - h, xi)[1] + self._jump(piece, p[cusp] + h, xi)[1])
        return q, J

    # --- quadrature ----------------------------------------------------------------------------
    def _panels(self, piece: CurvePiece, S: float, channel: PieceChannel) -> np.ndarray:
        key = (id(piece), S, channel)
        if key in self._base:
            return self._base[key]
        p_lo, p_hi = piece.p_ends(S)
        for (cid, S2, ch), edges in self._base.items():
            if cid == id(piece) and ch == channel and S2 >= S:  # reuse the partition of a longer range
                keep = edges[(edges > p_lo) & (edges < p_hi)]
                return np.concatenate([[p_lo], keep, [p_hi]])
        # start: panels of at most 5 % of max(1, Re q) along the curve (as for the half-line) and
        # ``widest`` in p: wide where the jump is smooth, the halving test refines the rest
        P = np.linspace(p_lo, p_hi, 4000)
        q = piece.q_at(P)
        along = np.abs(self.tracer.dq_dp(P, q)) / (0.05 * np.maximum(1.0, np.abs(q.real)))
        density = np.maximum(along, 1.0 / self.widest)

        def jump_and_q(nodes: np.ndarray) -> np.ndarray:
            q, J = self._chunked(piece, nodes, channel)
            return np.concatenate([J, q[:, None]], axis=1)

        edges, final = adapt_panels_with_values(
            equidistribute(P, density), jump_and_q, self.panel_tol, checked=-1
        )
        self._base[key] = edges
        self._store_adapted(piece, channel, edges, final)
        return edges

    def _rule(
        self, piece: CurvePiece, S: float, tau_hi: float, xi_max: float | None, channel: PieceChannel
    ) -> tuple[np.ndarray, np.ndarray]:
        """The adapted panels subdivided to at most PANEL_PHASE of Re q tau_hi and, for a jump with
        e^{i p xi} at other xi than the contact offsets (``xi_max``: their largest |xi|), PANEL_XI radians
        of it; with e^{i p xi} at the offsets only (``xi_max`` None: the responses, whose adapted panels
        resolve it), pieces of at most PANEL_PHASE of it (``offset_dp``)."""
        edges = self._panels(piece, S, channel)
        key = ("x", id(piece), S, channel)
        if key not in self._small:
            self._remember(key, piece.q_at(edges).real)
        x = self._small[key]
        dp = self.offset_dp if xi_max is None else PANEL_XI / (abs(xi_max) + 1.0)
        return oscillation_rule(edges, tau_hi * np.diff(x), dp)

    def _end_terms(self, piece: CurvePiece, S: float, channel: PieceChannel) -> list[tuple]:
        """Per far end of the piece: (sign, q, F, F', F'') of the jump F along the curve, in q."""
        key = ("ends", id(piece), S, channel)
        if key not in self._small:
            self._remember(key, self._end_terms_at(piece, S, channel))
        return self._small[key]

    def _end_terms_at(self, piece: CurvePiece, S: float, channel: PieceChannel) -> list[tuple]:
        out = []
        for sign, p_end in piece.far_ends(S):
            h = 1e-3 * max(1.0, abs(p_end))
            ps = np.array([p_end - h, p_end, p_end + h])
            q, F = channel(piece, ps)
            F = F / self.tracer.dq_dp(ps, q)[:, None]  # the jump itself, as a function of q
            d01 = (F[1] - F[0]) / (q[1] - q[0])
            d12 = (F[2] - F[1]) / (q[2] - q[1])
            d012 = (d12 - d01) / (q[2] - q[0])
            out.append((sign, q[1], F[1], d01 + d012 * (q[1] - q[0]), 2 * d012))
        return out

    def _tails(self, piece: CurvePiece, S: float, channel: PieceChannel, ts: np.ndarray) -> np.ndarray:
        """The truncated ends, integrated by parts along the curve (outward from each end)."""
        total: np.ndarray = np.zeros((ts.size, 1), dtype=complex)
        tt = ts[:, None]
        for sign, q, F0, F1, F2 in self._end_terms(piece, S, channel):
            total = total + sign * np.exp(1j * q * tt) * (1j * F0 / tt - F1 / tt**2 - 1j * F2 / tt**3)
        return total

    def choose_S(
        self, channel: PieceChannel, tau_lo: float, tol: float, s_min: float | None = None
    ) -> tuple[float, ...]:
        """Truncation Re q = S of each piece (a tuple), as for the Euler-Bernoulli cut (:mod:`branch_cut`):
        for tau_lo > 0 the first neglected term of its tails, |F''|/tau_lo^3, below its share of ``tol``;
        for the first band the neglected integral, estimated as |F| S, below it. S stays within the traced
        range of the far ends and above every induced frequency's Re q (``s_min``), so that the tails,
        integrated by parts, pass no pole."""
        share = tol / len(self.pieces)
        lowest = self.q_c if s_min is None else max(self.q_c, s_min)
        out = []
        for piece in self.pieces:
            # the piece must reach below S (a piece wholly beyond S has no end to integrate by parts from)
            floor = max(lowest, piece.x_min + 1.0)
            top = min([piece.q.real[0]] * piece.far[0] + [piece.q.real[-1]] * piece.far[1] + [np.inf])
            S = floor
            for step in _S_STEPS:
                if floor + step >= top:
                    break
                S = floor + step
                est = 0.0
                for _, _, F0, _, F2 in self._end_terms(piece, S, channel):
                    est += float(np.abs(F2).max()) / tau_lo**3 if tau_lo > 0 else float(np.abs(F0).max()) * S
                if est <= share:
                    break
            out.append(S)
        return tuple(out)

    def integrate(
        self,
        tau: ArrayLike,
        channel: PieceChannel,
        *,
        tol: float = 1e-10,
        s_min: float | None = None,
        xi_max: float | None = None,
        rule_tau: np.ndarray | None = None,
    ) -> np.ndarray:
        """I_bc(tau) per channel column: (1/pi) Re sum over the pieces of integral J e^{i q tau} dp.

        ``rule_tau``: other times whose rules a band of ``tau`` should share (their largest in the band sets
        its panels when it is larger than that of ``tau``): a probe of a few times then evaluates the jump
        at the nodes that the whole series will use, and the series finds them in the cache. ``xi_max``:
        the largest |xi| of the channel's e^{i p xi} when it has other xi than the contact offsets (a
        shape; None: the offsets only, :meth:`_rule`)."""
        tau = np.asarray(tau, dtype=float)
        if np.any(tau < 0) or not np.all(np.isfinite(tau)):
            raise MovingBogieError("branch-cut integral needs finite tau >= 0")
        first = self.pieces[0]
        m = channel(first, np.array([0.5 * (first.p_lo + first.p_hi)]))[1].shape[-1]

        def band(lo: float, ts: np.ndarray) -> np.ndarray:
            acc = np.zeros((ts.size, m), dtype=complex)
            top = band_top(lo, ts, rule_tau)
            for piece, S in zip(self.pieces, self.choose_S(channel, lo, tol, s_min)):
                nodes, weights = self._rule(piece, S, top, xi_max, channel)
                q, J = self._values(piece, nodes, channel, m)

                def weighted(
                    idx: np.ndarray, w: np.ndarray, q: np.ndarray = q, J: np.ndarray = J
                ) -> tuple[np.ndarray, np.ndarray]:
                    return q[idx], J[idx] * w[:, None]

                q_max = float(np.abs(q).max())
                acc += fourier_sum(ts, np.arange(nodes.size), weights, weighted, m, q_max, None)
                if lo > 0:
                    acc += self._tails(piece, S, channel, ts)
            return acc

        return by_bands(tau, m, band)

    def responses(
        self,
        tau: ArrayLike,
        *,
        tol: float = 1e-10,
        s_min: float | None = None,
        rule_tau: np.ndarray | None = None,
    ) -> dict:
        """I_bc(tau) of every response, as a dict name -> ndarray (``rule_tau``: :meth:`integrate`)."""
        values = self.integrate(tau, self._jump, tol=tol, s_min=s_min, rule_tau=rule_tau)
        return {name: values[..., k] for k, name in enumerate(self.names)}

    def shape(
        self, xi: ArrayLike, tau: float, *, tol: float = 1e-10, s_min: float | None = None
    ) -> np.ndarray:
        """I_bc of the deflection w(xi, tau) at one time, for an array xi."""
        xi = np.asarray(xi, dtype=float)
        flat = xi.reshape(-1)
        values = self.integrate(
            np.array([float(tau)]),
            lambda piece, p: self._jump(piece, p, flat),
            tol=tol,
            s_min=s_min,
            xi_max=float(np.max(np.abs(np.concatenate([flat, flat - self.span])))),
        )
        return values[0].reshape(xi.shape)

    def l1_bound(self, *, tol: float = 1e-10, s_min: float | None = None) -> dict:
        """(1/pi) sum of integrals of |J| dp: |I_bc(tau)| <= this * e^{-eta_f tau} for every tau."""
        total = np.zeros(len(self.names))
        for piece, S in zip(self.pieces, self.choose_S(self._jump, 0.0, tol, s_min)):
            nodes, weights = self._rule(piece, S, 0.0, None, self._jump)
            # the first band of times has these very nodes, most often those of the adapted panels
            q, J = self._values(piece, nodes, self._jump, len(self.names))
            total = total + (np.abs(J) * weights[:, None]).sum(axis=0) / np.pi
        return {name: float(total[k]) for k, name in enumerate(self.names)}
