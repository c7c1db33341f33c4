"""The branch-cut part I_bc of Eq. (35) where the cut of K is a straight half-line (the paper's beam).

Orientation. x(tau) = (1/2 pi) * integral of f(q) dq along the Bromwich line Im q = -a (left to right),
f = X~(q) e^{i q tau} = [n_X / (i q E_chr)] e^{i q tau}. Closing upward, the cut of K (here the
half-lines Im q = c, |Re q| >= q_c; c = eta_f for the paper's Euler-Bernoulli beam) is wrapped: the
strip below the cut is traversed with its lower side going west, the region above with the upper side
going east. The residue theorem for the region above the Bromwich line then gives

    x(tau) = i sum Res f + (1/2 pi) * integral over the cut (Re q increasing) of [f_below - f_above] dq,

so I_bc is the jump "value from below minus value from above". The mirror symmetry f(-conj q) =
conj f(q) (x is real) maps the left ray onto the right one, hence

    I_bc(tau) = (1/pi) Re integral_{q_c}^{inf} j(q) e^{i q tau} ds,
    q = s + i c,  j = X~_below - X~_above.

Parametrisation. ``derivations/cut_line.py`` finds the tracks whose N(p, q) is quadratic in q with roots
q = alpha p + i c +- sqrt(R(p))/2 for real p, c free of p, R a real polynomial, and generates
``cut_line_im`` (c) and ``cut_line_radicand`` (R) for them; for the paper's beam c = eta_f and
R = p^4 + 4 eta_s p^2 + 4 - 4 eta_f^2. Where R > 0 for every real p (checked here), a point of the right
ray is

    q(p) = alpha p + i c + sqrt(R(p))/2

for real p (the real root of N(., q) itself, ``kernels/cut.py``); s(p) is convex with its minimum q_c at p_c,
and p > p_c covers the ray once. In p the square-root branch point disappears (ds = s'(p) dp with
s'(p_c) = 0, K ~ 1/(p - p_1)), so a composite Gauss-Legendre rule in p converges fast. At such a q the
two real roots p and p_1 of N are assigned to a side by the direction they move when q leaves the
cut: q -> q - i eps moves a root by i eps N_q/N_p, so from below a real root counts as "upper" iff
N_q/N_p > 0, from above iff N_q/N_p < 0 (checked against K at q -+ i eps in the tests).

Quadrature. Panels in p are sized so that each spans at most 3 pi of phase s tau at the largest tau of a
band of times (bands double: [0, 1/2], (1/2, 1], (1, 2], ...), 16 Gauss-Legendre nodes each. The ray is
truncated at s = S: for the first band where the neglected tail integral of |j| is below ``tol``;
for the others the tail is added by integration by parts, e^{i q_S tau} (i j/tau - j'/tau^2 - i j''/tau^3),
with S chosen so that the first neglected term |j'''|/tau^4 (estimated by |j''|/tau^3) is below ``tol``.

Any other track (a curved cut with folds, lenses and further curves; no ``cut_line_radicand`` in its
generated module, a quartic N(p, q) assumed by the root ordering below) is integrated by
:class:`~moving_bogie.response.cut_integral.CurveBranchCut`; this class raises :class:`BranchCutUnavailable`
for it.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike

from moving_bogie.errors import MovingBogieError
from moving_bogie.kernels.bound import BoundModel
from moving_bogie.kernels.polyroots import polyder, polyval, stack_coefficients
from moving_bogie.response import quadrature as quad
from moving_bogie.response.quadrature import cis
from moving_bogie.response.right_ray import RightRay

__all__ = ["BranchCut", "BranchCutUnavailable"]

#: Largest panel in p: at most PANEL_XI radians of e^{i p xi} at the largest |xi| and never above _PANEL_DP;
#: largest panel in s relative to max(1, s): resolves poles of f near the cut.
_PANEL_DP = 0.5
_PANEL_DS_REL = 0.05
#: Bisection levels of the adaptive base partition (a peak 2^-40 of a panel wide is still resolved).
_MAX_SPLITS = 40
_S_STEPS = tuple(2.0**k for k in range(-1, 16))
#: Truncation points estimated together, in one evaluation of the channel (:meth:`BranchCut.choose_S`).
_S_BATCH = 4


#: The jump of a branch-cut integral at nodes in p: ``channel(p) -> (q, J)``, J of shape (len(p), m).
Channel = Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]]


class BranchCutUnavailable(MovingBogieError):
    """The branch-cut integral is not available for these parameters (the track's cut, or no gap at q = 0)."""


class BranchCut(RightRay):
    """The jump of the transformed responses across the cut and the integral I_bc of Eq. (35).

    Parameters
    ----------
    bound : BoundModel
        A track whose cut is a half-line (generated ``cut_line_radicand``, R > 0), subcritical (the cut
        leaves a gap around q = 0).
    panel_tol : float
        Absolute tolerance per panel of the adaptive partition of the cut (:meth:`base_edges`).

    Raises
    ------
    BranchCutUnavailable
        For a track whose cut is not a half-line (e.g. Timoshenko-Rayleigh), or when the cut reaches q = 0
        (supercritical velocity).
    """

    def __init__(self, bound: BoundModel, *, panel_tol: float = 1e-13) -> None:
        params = bound.params
        self.foundation = bound.foundation
        if not hasattr(self.foundation, "cut_line_radicand") or self.foundation.DEGREE_N != 4:
            raise BranchCutUnavailable(
                f"the cut of K of {bound.name} is not a half-line (no cut_line_radicand in its generated "
                "module): the traced cut is integrated instead (CurveBranchCut)"
            )
        self.params = params
        f = bound.floats
        self.fargs = bound.foundation_floats()
        self.alpha = f.alpha
        self.eta_f = float(self.foundation.cut_line_im(**self.fargs))  # Im q of the line
        self._radicand = np.array([float(c) for c in self.foundation.cut_line_radicand(**self.fargs)])
        self._radicand_dp = np.polyder(self._radicand) / 4.0
        critical = np.roots(np.polyder(self._radicand))
        lowest = min(np.polyval(self._radicand, critical[np.abs(critical.imag) < 1e-12].real), default=np.inf)
        if not (self._radicand[0] > 0 and lowest > 0):
            raise BranchCutUnavailable(
                "the cut of K leaves the line Im q = c where R(p) < 0: the traced cut is integrated instead"
            )
        self.system, self.offsets, self.positions = bound.float_system, bound.offsets, bound.positions
        self.span, self.names = bound.span, bound.names
        self.p_c = self._minimum()
        self.q_c = float(self.s(self.p_c))
        self.panel_tol = panel_tol
        self._base: dict[float, np.ndarray] = {}
        if not self.q_c > 0:
            raise BranchCutUnavailable(
                f"the cut of K reaches q = 0 (q_c = {self.q_c:.6g} <= 0): supercritical velocity, no gap "
                "around the steady state"
            )

    # --- kernel values on both sides ------------------------------------------------------------
    def _roots_and_sides(self, p0: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(q, P, weights): the roots of N(., q(p0)) ordered by side (see :meth:`_both_sides`), Q/N'."""
        p0 = np.asarray(p0, dtype=float)
        q = self.q(p0)
        c = stack_coefficients(self.foundation.n_coeffs(q, **self.fargs), q.shape)
        # deflate by (p - p0): p0 is an exact root; the cubic's roots stay well separated near p_c
        b: np.ndarray = np.empty(c.shape[:-1] + (c.shape[-1] - 1,), dtype=complex)
        b[..., 0] = c[..., 0]
        for k in range(1, b.shape[-1]):
            b[..., k] = c[..., k] + p0 * b[..., k - 1]
        monic = b[..., 1:] / b[..., :1]
        deg = monic.shape[-1]
        comp = np.zeros(q.shape + (deg, deg), dtype=complex)
        comp[..., 0, :] = -monic
        comp[..., np.arange(1, deg), np.arange(deg - 1)] = 1
        cubic = np.linalg.eigvals(comp)
        k = np.argmin(np.abs(cubic.imag), axis=-1)
        p1 = np.take_along_axis(cubic, k[..., None], axis=-1)[..., 0].real
        others = cubic[np.arange(deg)[None, :] != k[..., None]].reshape(q.shape + (deg - 1,))
        P = np.concatenate([p0[..., None] + 0j, p1[..., None] + 0j, others], axis=-1)
        Np = polyval(polyder(c), P)
        dq = stack_coefficients(self.foundation.n_coeffs_dq(q, **self.fargs), q.shape)
        Nq = polyval(dq, P)
        Qc = stack_coefficients(self.foundation.q_coeffs(q, **self.fargs), q.shape)
        weight = polyval(Qc, P) / Np
        # order the roots: [upper real root seen from below, other real root, upper complex, lower complex]
        from_below = (Nq[..., 0] / Np[..., 0]).real > 0
        up_c = others.imag[..., 0] > 0
        order = np.stack(
            [
                np.where(from_below, 0, 1),
                np.where(from_below, 1, 0),
                np.where(up_c, 2, 3),
                np.where(up_c, 3, 2),
            ],
            axis=-1,
        )
        return q, np.take_along_axis(P, order, -1), np.take_along_axis(weight, order, -1)

    @staticmethod
    def _both_sides(P: np.ndarray, weight: np.ndarray, xi: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
        """(K_below, K_above) at every xi, shape (nodes, len(xi)), sharing the exponentials.

        Upper roots: from below {P0, P2}, from above {P1, P2}; lower: from below {P1, P3}, from above
        {P0, P3}. So K = sign(xi) * (complex term + real term) with the real term swapped between sides.
        """
        xi = np.asarray(xi, dtype=float)
        pos = xi >= 0
        sign = np.where(pos, 2j * np.pi, -2j * np.pi)
        common = np.empty((P.shape[0], xi.size), dtype=complex)
        for mask, k in ((pos, 2), (~pos, 3)):
            if np.any(mask):
                x = xi[mask]
                root = P[:, k : k + 1]
                common[:, mask] = cis(root.real * x) * (np.exp(-root.imag * x) * weight[:, k : k + 1])
        e0 = cis(P[:, 0:1].real * xi) * weight[:, 0:1]
        e1 = cis(P[:, 1:2].real * xi) * weight[:, 1:2]
        below = sign * (common + np.where(pos, e0, e1))
        above = sign * (common + np.where(pos, e1, e0))
        return below, above

    def kernels(self, p0: ArrayLike, xis: ArrayLike, side: str) -> np.ndarray:
        """K(xi, q(p0)) on one side of the cut ("below" or "above"), shape (len(p0), len(xis))."""
        _, P, weight = self._roots_and_sides(np.atleast_1d(p0))
        below, above = self._both_sides(P, weight, np.atleast_1d(np.asarray(xis, dtype=float)))
        return below if side == "below" else above

    def _contact_kernels(
        self, P: np.ndarray, weight: np.ndarray
    ) -> tuple[list[np.ndarray], list[np.ndarray]]:
        """K at every distinct contact offset xi_i - xi_j, below and above the cut."""
        below, above = self._both_sides(P, weight, self.offsets)
        count = len(self.offsets)
        return [below[:, k] for k in range(count)], [above[:, k] for k in range(count)]

    # --- jumps of the transformed responses -----------------------------------------------------
    def response_jumps(self, p0: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
        """(q, J): J[:, k] = X~_below - X~_above of response ``names[k]`` at q(p0); X~ = n_X/(i q E_chr)."""
        q, P, weight = self._roots_and_sides(np.atleast_1d(p0))
        out = []
        for Ks in self._contact_kernels(P, weight):
            X, _ = self.system.solutions_array(q, Ks)
            out.append(X / (1j * q)[:, None])
        return q, out[0] - out[1]

    def shape_jumps(self, p0: ArrayLike, xi: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
        """(q, J) with J[:, k] = W~_below - W~_above at xi[k], i q W~ = sum_j G_j K(xi - xi_j) / (2 pi E)."""
        q, P, weight = self._roots_and_sides(np.atleast_1d(p0))
        xi = np.asarray(xi, dtype=float)
        Kx = [self._both_sides(P, weight, xi - x) for x in self.positions]
        out = []
        for k, Ks in enumerate(self._contact_kernels(P, weight)):
            _, GE = self.system.solutions_array(q, Ks)
            den = 2 * np.pi * 1j * q
            out.append(sum((GE[:, j] / den)[:, None] * Kx[j][k] for j in range(len(self.positions))))
        return q, out[0] - out[1]

    # --- the integral ---------------------------------------------------------------------------
    def base_edges(self, S: float) -> np.ndarray:
        """Panel edges in p on [p_c, p(S)] adapted to the jump itself (no oscillation), cached.

        Start from panels of at most _PANEL_DP in p and 5 % in s, then split every panel where the
        16-point Gauss-Legendre integral of the response jumps differs from the sum over its two halves by
        more than ``panel_tol``: this resolves induced frequencies (or poles of the continuation across the
        cut) lying close to the cut, whose Lorentzian peaks can be far narrower than any fixed panel.
        """
        for S2, edges in self._base.items():
            if S2 >= S:
                p_hi = float(self.p_of_s(S))
                keep = edges[edges < p_hi]
                return np.append(keep, p_hi)
        p_hi = float(self.p_of_s(S))
        n = max(4000, int(400 * (p_hi - self.p_c)))
        P = np.linspace(self.p_c, p_hi, n)
        sp = np.maximum(self.ds(P), 0.0)
        density = np.maximum(sp / (_PANEL_DS_REL * np.maximum(1.0, self.s(P))), 1 / _PANEL_DP)
        edges = quad.adapt_panels(quad.equidistribute(P, density), self._jump_ds, self.panel_tol, _MAX_SPLITS)
        self._base[S] = edges
        return edges

    def _jump_ds(self, nodes: np.ndarray) -> np.ndarray:
        return self.response_jumps(nodes)[1] * self.ds(nodes)[:, None]

    def rule(self, S: float, tau_hi: float, xi_max: float | None = None) -> tuple[np.ndarray, np.ndarray]:
        """Composite 16-point Gauss-Legendre nodes and weights in p on [p_c, p(S)].

        The panels of :meth:`base_edges` are subdivided to span at most 3 pi of the phase s tau_hi and
        PANEL_XI radians of e^{i p xi} for |xi| <= xi_max (default: the wheel spacing d).
        """
        xi_max = self.span if xi_max is None else xi_max
        edges = self.base_edges(S)
        phase = tau_hi * np.diff(self.s(edges))
        return quad.oscillation_rule(edges, phase, min(_PANEL_DP, quad.PANEL_XI / (abs(xi_max) + 1.0)))

    def _difference_step(self, S: np.ndarray) -> np.ndarray:
        """The step h in s of the central differences at s = S (per S): 1 % of S, of the wavelength of
        e^{i p xi} over the wheel spacing, and at most a quarter of the way back to q_c."""
        h = 0.01 * np.minimum(S, np.maximum(1.0, self.p_of_s(S)) / max(self.span, 1.0))
        return np.minimum(h, 0.25 * (S - self.q_c))

    def _tail_terms(self, channel: Channel, S: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(j, j', j'') in s at s = S by central differences (max over channels when estimating)."""
        g0, g1, g2 = self._differences(channel, np.array([S]))
        return g0[0], g1[0], g2[0]

    def _differences(self, channel: Channel, S: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(j, j', j'') in s at every s = S (rows) by central differences, one evaluation of the channel."""
        n, h = S.size, self._difference_step(S)
        _, g = channel(self.p_of_s(np.concatenate([S - h, S, S + h])))
        lo, mid, hi = g[:n], g[n : 2 * n], g[2 * n :]
        return mid, (hi - lo) / (2 * h)[:, None], (hi - 2 * mid + lo) / (h**2)[:, None]

    def choose_S(self, channel: Channel, tau_lo: float, tol: float, s_min: float | None = None) -> float:
        """Truncation point S >= s_min of the ray for the band of times from tau_lo (module docstring): the
        first of floor + _S_STEPS whose estimate passes, ``_S_BATCH`` of them per evaluation of the
        channel."""
        floor = self.q_c if s_min is None else max(self.q_c, s_min - 0.5)
        for k in range(0, len(_S_STEPS), _S_BATCH):
            S = floor + np.array(_S_STEPS[k : k + _S_BATCH])
            passed = np.nonzero(self._truncation_estimates(channel, S, tau_lo) <= tol)[0]
            if passed.size:
                return float(S[passed[0]])
        return floor + _S_STEPS[-1]

    def _truncation_estimates(self, channel: Channel, S: np.ndarray, tau_lo: float) -> np.ndarray:
        """Per truncation point S: for tau_lo > 0 the first neglected term of the tail integrated by parts,
        max |j''(S)| / tau_lo^3; for the first band the neglected integral, |j(S)| S / (kappa - 1) with
        kappa the decay exponent of |j| between S and 2 S (at least 1.5)."""
        n = S.size
        with np.errstate(all="ignore"):
            if tau_lo <= 0:
                _, g = channel(self.p_of_s(np.concatenate([S, 2 * S])))
                a, b = np.abs(g[:n]).max(axis=1), np.abs(g[n:]).max(axis=1)
                kappa = np.where((a > 0) & (b > 0), np.log2(a / b), 10.0)
                return a * S / np.maximum(kappa - 1.0, 0.5)
            _, _, g2 = self._differences(channel, S)
            return np.abs(g2).max(axis=1) / tau_lo**3

    def integrate(
        self,
        tau: ArrayLike,
        channel: Channel,
        *,
        tol: float = 1e-10,
        s_min: float | None = None,
        xi_max: float | None = None,
    ) -> np.ndarray:
        """I_bc(tau) for every channel: (1/pi) Re integral over the right ray of J e^{i q tau} dq.

        Parameters
        ----------
        tau : array_like of float, >= 0
        channel : callable
            ``channel(p_nodes) -> (q, J)`` with J of shape (len(p_nodes), m): the jump in the s variable
            (e.g. :meth:`response_jumps`).
        tol : float
            Absolute tolerance of the truncation/tail estimates (the quadrature itself is ~1e-13).
        s_min : float, optional
            Truncate the ray no earlier than this Re q (keep poles near the cut inside the quadrature).
        xi_max : float, optional
            Largest |xi| in the kernels of the channel (default the wheel spacing d).

        Returns
        -------
        ndarray of shape tau.shape + (m,)
        """
        tau = np.asarray(tau, dtype=float)
        if np.any(tau < 0) or not np.all(np.isfinite(tau)):
            raise MovingBogieError("branch-cut integral needs finite tau >= 0")
        m = channel(np.array([self.p_c + 1.0]))[1].shape[-1]

        def band(lo: float, ts: np.ndarray) -> np.ndarray:
            S = self.choose_S(channel, lo, tol, s_min)
            nodes, weights = self.rule(S, float(ts.max()), xi_max)
            q_max = float(np.abs(self.q(nodes)).max())
            weighted = lambda c, w: _weighted(channel, self, c, w)  # noqa: E731
            acc = quad.fourier_sum(ts, nodes, weights, weighted, m, q_max, self.eta_f)
            if lo > 0:
                g0, g1, g2 = self._tail_terms(channel, S)
                e = np.exp(1j * (S + 1j * self.eta_f) * ts)[:, None]
                t = ts[:, None]
                acc += e * (1j * g0 / t - g1 / t**2 - 1j * g2 / t**3)
            return acc

        return quad.by_bands(tau, m, band)

    def responses(
        self,
        tau: ArrayLike,
        *,
        tol: float = 1e-10,
        s_min: float | None = None,
        rule_tau: np.ndarray | None = None,
    ) -> dict:
        """I_bc(tau) of every response, as a dict name -> ndarray. ``rule_tau`` is taken for the interface
        of :meth:`CurveBranchCut.responses <moving_bogie.response.cut_integral.CurveBranchCut.responses>`
        and not used: the half-line's rules keep no values across calls."""
        values = self.integrate(tau, self.response_jumps, tol=tol, s_min=s_min)
        return {name: values[..., k] for k, name in enumerate(self.names)}

    def shape(
        self, xi: ArrayLike, tau: float, *, tol: float = 1e-10, s_min: float | None = None
    ) -> np.ndarray:
        """I_bc of the deflection w(xi, tau) at one time, for an array xi."""
        xi = np.asarray(xi, dtype=float)
        values = self.integrate(
            np.array([float(tau)]),
            lambda p: self.shape_jumps(p, xi.reshape(-1)),
            tol=tol,
            s_min=s_min,
            xi_max=float(np.max(np.abs(np.concatenate([xi.ravel(), xi.ravel() - self.span])))),
        )
        return values[0].reshape(xi.shape)

    def l1_bound(self, *, tol: float = 1e-10, s_min: float | None = None) -> dict:
        """(1/pi) integral of |J| ds per response: |I_bc(tau)| <= this * e^{-eta_f tau} for every tau."""
        S = self.choose_S(self.response_jumps, 0.0, tol, s_min)
        nodes, weights = self.rule(S, 0.0)
        _, J = self.response_jumps(nodes)
        values = (np.abs(J) * (weights * self.ds(nodes))[:, None]).sum(axis=0) / np.pi
        return {name: float(values[k]) for k, name in enumerate(self.names)}


def _weighted(
    channel: Channel, cut: BranchCut, chunk: np.ndarray, w: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    q, J = channel(chunk)
    return q, J * (w * cut.ds(chunk))[:, None]
