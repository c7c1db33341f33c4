"""E_chr vectorised over q, the velocity alpha, the wheel spacing and one vehicle parameter.

The stability tools of Sections 3.5-3.8 (frequency lines, instability lines, D-decomposition, critical
stiffness, stability maps) evaluate the characteristic function E_chr of Eq. (38) (bogie) or of two
moving masses on large sets of points in double precision. Three facts make this cheap:

* K(xi, q) of Eq. (29) depends on the track and on alpha only, not on the vehicle: the p-roots of
  N(p, q) are computed once per (q, alpha) and shared by every wheel spacing and every vehicle.
* The p-roots of a quartic N come from a vectorised closed form (Ferrari) polished by two
  Durand-Kerner sweeps: about ten times faster than batched companion eigenvalues on large batches,
  with the same accuracy (``tests/test_stability_kernel.py``); other degrees use batched companion
  eigenvalues polished by Newton's method (:func:`~moving_bogie.kernels.polyroots.poly_roots`).
* The vehicle enters E_chr through B1..B4 of Eq. (37), which are linear in eta_M (with mu_v = cf1 eta_M
  and J_b = cf2 eta_M d^2, Eq. (63)), in kappa_v and in eta_v. At fixed (q, alpha), E_chr is therefore a
  polynomial in each of these parameters: degree 2 in eta_M for two masses, 4 in eta_M for the bogie,
  2 in kappa_v and in eta_v. Its coefficients follow from deg + 1 evaluations at fixed K (exact
  interpolation at Chebyshev nodes of the range of interest, well conditioned there).

K and its derivatives in q and alpha are residue sums over the p-roots of N, exactly as in
:mod:`moving_bogie.kernels.track` (which this module is checked against): for xi >= 0 the roots with Im p > 0,
for xi < 0 those with Im p < 0; dK/ds = integral of e^{i p xi} (Q_s / N - Q N_s / N^2) dp for s = q or
alpha (double poles for the second term).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from moving_bogie.errors import ParameterError
from moving_bogie.kernels.bound import BoundModel
from moving_bogie.kernels.polyroots import poly_roots, quartic_roots
from moving_bogie.kernels.polyroots import polyder as _polyder
from moving_bogie.kernels.polyroots import polyval as _polyval
from moving_bogie.kernels.sweep_vehicle import BlockSweep

__all__ = ["SweepCharacteristic", "follower_groups", "poly_roots", "polynomial_degree", "quartic_roots"]

_ALPHA_STENCIL = 0.25  # the coefficients of N and Q are polynomials of degree <= 4 in alpha


def polynomial_degree(bound: BoundModel, parameter: str, held: Iterable[str] = ()) -> int:
    """Degree of E_chr in the vehicle parameter ``parameter`` at fixed (q, alpha), from the derivation.

    The generated ``POLYNOMIAL_DEGREES`` of the vehicle, derived from its block system (for the paper's bogie
    4 in eta_M (B1, B2, B3 all scale with it at fixed cf1, cf2), 2 in kappa_v and in eta_v (the B4^4 and
    B4^2 B1 B3 terms of Eq. (38) cancel down to degree 2); for two masses 2 in eta_M; for the car 8 in eta_M).
    ``held`` names groups that an alternative sets but that stay fixed (mu_v, J_b in a sweep in SI units over
    the wheel mass): when every group that would follow ``parameter`` is held, the degree is the generated
    ``FIXED_POLYNOMIAL_DEGREES`` (the bogie: 2 in eta_M, its two wheel masses).

    Raises
    ------
    ParameterError
        Naming ``parameter`` when E_chr is not a polynomial in it (the spacing d also moves K), or when only
        some of the groups that follow it are held.
    """
    followers = follower_groups(bound, parameter)
    fixed = followers & set(held)
    degrees = bound.polynomial_degrees
    if fixed:
        degrees = dict(getattr(bound.vehicle, "FIXED_POLYNOMIAL_DEGREES", {}))
    if parameter not in degrees:
        raise ParameterError(
            "parameter", f"parameter must be one of {', '.join(degrees)} for this vehicle (got {parameter!r})"
        )
    if fixed and fixed != followers:
        raise ParameterError(
            "parameter",
            f"E_chr is not a polynomial in {parameter} with {', '.join(sorted(fixed))} held and "
            f"{', '.join(sorted(followers - fixed))} following it: hold all of them or none",
        )
    return degrees[parameter]


def follower_groups(bound: BoundModel, parameter: str) -> set[str]:
    """The vehicle's groups that an alternative sets from ``parameter`` (mu_v, J_b from eta_M, Eq. (63))."""
    return {
        info["sets"]
        for info in bound.params.model.alternatives.values()
        if parameter in info["depends"] and info["sets"] in bound.vehicle.PARAMETERS
    }


class SweepCharacteristic:
    """E_chr(q; alpha, d, theta) for numpy arrays, theta a vehicle parameter E_chr is a polynomial in.

    Parameters
    ----------
    bound : BoundModel
        Everything but alpha, the spacing d (when given per point) and ``parameter`` is taken from here
        (the vehicle and the track too); with the wheel mass as ``parameter`` the bar's mass and inertia
        follow it with the coefficients cf1, cf2 of its parameters (Eq. (63)).
    parameter : str, optional
        The vehicle parameter swept (default: the wheel mass, ``Model.wheel_mass``, eta_M).
    block : bool
        Evaluate E_chr as the determinant of the block system (:mod:`~moving_bogie.kernels.sweep_vehicle`)
        even when the vehicle's module has the closed form of Eq. (38) (default False: the closed form
        where there is one; vehicles without one always use the block system).
    held : iterable of str
        Groups an alternative sets that stay at their value in ``params`` instead of following
        ``parameter`` (mu_v, J_b in a sweep in SI units over the wheel mass); E_chr then has the degree of
        the generated ``FIXED_POLYNOMIAL_DEGREES`` (:func:`polynomial_degree`).
    below : bool
        Limit from below on the cut (default False): a p-root of N within ``REAL_P`` (relative) of the
        real axis counts as upper iff Re(N_q / N_p) > 0, the side it moves to when q -> q - i0 (as in
        :mod:`~moving_bogie.response.branch_cut`). With eta_f = 0 the cut lies on the real q-axis and this
        gives K there its physical value, the limit eta_f -> 0+; without it such a root's side is the
        sign of a rounding error.
    """

    REAL_P = 1e-9

    def __init__(
        self,
        bound: BoundModel,
        parameter: str | None = None,
        *,
        held: Iterable[str] = (),
        below: bool = False,
        block: bool = False,
    ) -> None:
        params = bound.params
        parameter = parameter or params.model.wheel_mass
        self.bound = bound
        self.below = bool(below)
        self.params = params
        self.parameter = parameter
        following = follower_groups(bound, parameter)
        self.held = frozenset(held) & following
        self.degree = polynomial_degree(bound, parameter, self.held)
        self.module = bound.vehicle
        self.blocks = None if hasattr(self.module, "e_chr") and not block else BlockSweep(self.module)
        self.foundation = bound.foundation
        ns = bound.floats
        self.track_args = {k: v for k, v in bound.foundation_floats().items() if k != "alpha"}
        self.d = ns.d
        # Eq. (63): groups set by an alternative that depends on the swept parameter follow it unless held
        # (the bar's mass and inertia follow eta_M at fixed cf1, cf2): (group, its function, the value of the
        # alternative).
        meta = params.model.catalogue.parameters
        self.followers = [
            (info["sets"], getattr(meta, f"set_by_{name}"), float(getattr(params, name)), info["depends"])
            for name, info in params.model.alternatives.items()
            if parameter in info["depends"] and info["sets"] in following - self.held
        ]
        names = self.module.PARAMETERS if self.blocks is None else self.module.MATRIX_ARGUMENTS
        self.base = {name: getattr(ns, name) for name in names}

    # -- track ---------------------------------------------------------------------------------------
    def _coeffs(self, func: Callable[..., Any], q: ArrayLike, alpha: ArrayLike) -> np.ndarray:
        cs = func(q, **self.track_args, alpha=alpha)
        out = np.empty(np.shape(q) + (len(cs),), dtype=complex)
        for k, c in enumerate(cs):
            out[..., k] = c
        return out

    def _d_alpha(self, func: Callable[..., Any], q: np.ndarray, alpha: np.ndarray) -> np.ndarray:
        """Coefficients of dN/dalpha (or dQ/dalpha): five-point stencil, exact for degree <= 4."""
        h = _ALPHA_STENCIL
        shifts = np.array([-2.0, -1.0, 1.0, 2.0]).reshape((4,) + (1,) * q.ndim)
        f = self._coeffs(func, np.broadcast_to(q, (4,) + q.shape), alpha[None] + h * shifts)
        return (f[0] - 8 * f[1] + 8 * f[2] - f[3]) / (12 * h)

    def p_roots(self, q: ArrayLike, alpha: ArrayLike) -> np.ndarray:
        """Roots of N(p, q) in p, shape ``q.shape + (DEGREE_N,)`` (closed form for quartics)."""
        q, alpha = _prepare(q, alpha)
        return _roots(self._coeffs(self.foundation.n_coeffs, q, alpha))

    def upper_root_count(self, q: ArrayLike, alpha: ArrayLike) -> np.ndarray:
        """Number of p-roots with Im p > 0: it changes exactly where q crosses the cut of K."""
        return np.sum(self.p_roots(q, alpha).imag > 0, axis=-1)

    def kernel(
        self,
        q: ArrayLike,
        alpha: ArrayLike,
        *,
        d: ArrayLike | None = None,
        derivative: bool = False,
        derivative_alpha: bool = False,
        spacings: Any = None,
    ) -> tuple[Any, Any, Any]:
        """K at the contact offsets, at arrays ``q``, ``alpha`` (and per-point spacing ``d``) broadcast.

        K is (K0, K+, K-) = K(0), K(d), K(-d) for a vehicle with the closed form of Eq. (38), else one value
        per offset of :meth:`offsets` (0, then xi_i - xi_j for i != j).
        Returns ``(K, dK_dq, dK_dalpha)``, the derivatives None unless asked. With ``spacings`` (a list of
        floats), K and the derivatives are lists with one triple per spacing, sharing the p-roots.
        """
        q, alpha = _prepare(q, alpha)
        fnd = self.foundation
        n = self._coeffs(fnd.n_coeffs, q, alpha)
        qc = self._coeffs(fnd.q_coeffs, q, alpha)
        P = _roots(n)
        finite = np.isfinite(P)  # a root at infinity (degree drop, nan) is on neither side
        P = np.where(finite, P, 0)
        n1 = _polyder(n)
        N1 = np.where(finite, _polyval(n1, P), 1)
        Qv = _polyval(qc, P)
        N2 = Qp = None
        if derivative or derivative_alpha:
            N2 = _polyval(_polyder(n1), P)
            Qp = _polyval(_polyder(qc), P)
        parts: list[tuple[Any, ...]] = []
        if derivative:
            parts.append((self._coeffs(fnd.n_coeffs_dq, q, alpha), self._coeffs(fnd.q_coeffs_dq, q, alpha)))
        if derivative_alpha:
            parts.append((self._d_alpha(fnd.n_coeffs, q, alpha), self._d_alpha(fnd.q_coeffs, q, alpha)))
        parts = [(_polyval(ns, P), _polyval(_polyder(ns), P), _polyval(qs, P)) for ns, qs in parts]
        upper = P.imag > 0
        if self.below:
            real = np.abs(P.imag) <= self.REAL_P * np.maximum(1.0, np.abs(P))
            if np.any(real):
                Nq = _polyval(self._coeffs(fnd.n_coeffs_dq, q, alpha), P)
                with np.errstate(all="ignore"):
                    upper = np.where(real, np.real(Nq / N1) > 0, upper)
        lower = ~upper & finite
        upper = upper & finite
        ds = [self.d] if spacings is None else list(spacings)
        if d is not None:
            ds = [np.broadcast_to(np.asarray(d, dtype=float), q.shape)]
        keys = ["dq"] * derivative + ["da"] * derivative_alpha
        out: dict[str, list[Any]] = {"K": [], "dq": [], "da": []}
        for dd in ds:
            # every offset at once: axis -2 of the sums runs over the offsets, axis -1 over the p-roots
            offsets = [np.broadcast_to(np.asarray(xi, dtype=float), q.shape) for xi in self.offsets(dd)]
            xi = np.stack(offsets, axis=-1)[..., None]
            mask = np.where(xi >= 0, upper[..., None, :], lower[..., None, :])
            factor = np.where(xi >= 0, 2j * np.pi, -2j * np.pi)
            Pk, Qk, N1k = P[..., None, :], Qv[..., None, :], N1[..., None, :]
            # only the roots on the decaying side enter: |e| <= 1 there (no overflow elsewhere)
            e = np.exp(1j * np.where(mask, Pk, 0) * xi)
            sums = {"K": np.sum(np.where(mask, factor * e * Qk / N1k, 0), axis=-1)}
            N2k = None if N2 is None else N2[..., None, :]
            Qpk = None if Qp is None else Qp[..., None, :]
            for key, (Ns, Nsp, Qs) in zip(keys, parts):
                Ns, Nsp, Qs = Ns[..., None, :], Nsp[..., None, :], Qs[..., None, :]
                g = e * Qk * Ns
                gp = e * (1j * xi * Qk * Ns + Qpk * Ns + Qk * Nsp)
                term = e * Qs / N1k - (gp * N1k - g * N2k) / N1k**3
                sums[key] = np.sum(np.where(mask, factor * term, 0), axis=-1)
            for key in out:
                out[key].append(tuple(np.moveaxis(sums[key], -1, 0)) if key in sums else None)
        if spacings is None:
            return out["K"][0], out["dq"][0], out["da"][0]
        return out["K"], out["dq"] if derivative else None, out["da"] if derivative_alpha else None

    def offsets(self, d: Any) -> list:
        """The offsets xi at which :meth:`kernel` evaluates K, for the spacing ``d`` (float or array)."""
        if self.blocks is None:
            return [0.0, d, -d]
        return self.blocks.offsets(self.vehicle_args(None, d))

    # -- vehicle -------------------------------------------------------------------------------------
    def vehicle_args(self, theta: ArrayLike | None = None, d: ArrayLike | None = None) -> dict:
        """Keyword arguments of the generated e_chr with ``parameter = theta`` (arrays allowed)."""
        args = dict(self.base)
        if d is not None and "d" in args:
            args["d"] = d
        if theta is not None:
            args[self.parameter] = theta
            for group, set_by, value, depends in self.followers:
                args[group] = set_by(value, **{name: args[name] for name in depends})
        return args | {"pi": np.pi}

    def e_chr(
        self, q: np.ndarray, K: Any, theta: ArrayLike | None = None, d: ArrayLike | None = None
    ) -> np.ndarray:
        """E_chr at ``q`` from precomputed K (:meth:`kernel`)."""
        if self.blocks is not None:
            return self.blocks.e_chr(q, K, self.vehicle_args(theta, d))
        return self.module.e_chr(q, *K, **self.vehicle_args(theta, d))

    def _e_and_dq(self, q: np.ndarray, K: Any, dK: Any, args: dict) -> tuple[np.ndarray, np.ndarray]:
        if self.blocks is not None:
            E, E_q, _, _ = self.blocks.derivatives(q, K, args, dKq=dK)
            assert E_q is not None  # asked for with dKq
            return E, E_q
        E = self.module.e_chr(q, *K, **args)
        E_q, E_K0, E_Kp, E_Km = self.module.e_chr_partials(q, *K, **args)
        return E, E_q + E_K0 * dK[0] + E_Kp * dK[1] + E_Km * dK[2]

    def e_and_dq_from(
        self, q: ArrayLike, K: Any, dK: Any, theta: ArrayLike | None = None, d: ArrayLike | None = None
    ) -> tuple[np.ndarray, np.ndarray]:
        """(E_chr, dE_chr/dq) at ``q`` from precomputed K and dK/dq (:meth:`kernel`), Eq. (40)."""
        q = np.asarray(q, dtype=complex)
        E, E_q = self._e_and_dq(q, K, dK, self.vehicle_args(theta, d))
        return np.broadcast_to(E, q.shape), np.broadcast_to(E_q, q.shape)

    def __call__(
        self, q: ArrayLike, alpha: ArrayLike, theta: ArrayLike | None = None, d: ArrayLike | None = None
    ) -> np.ndarray:
        """E_chr at arrays q, alpha (and theta, d)."""
        q = np.asarray(q, dtype=complex)
        K, _, _ = self.kernel(q, alpha, d=d)
        return self.e_chr(q, K, theta, d)

    def e_and_dq(
        self, q: ArrayLike, alpha: ArrayLike, theta: ArrayLike | None = None, d: ArrayLike | None = None
    ) -> tuple[np.ndarray, np.ndarray]:
        """(E_chr, dE_chr/dq) at arrays q, alpha (and theta, d): Eq. (40) chain rule through dK/dq."""
        q = np.asarray(q, dtype=complex)
        K, dK, _ = self.kernel(q, alpha, d=d, derivative=True)
        return self._e_and_dq(q, K, dK, self.vehicle_args(theta, d))

    def derivatives(
        self, q: ArrayLike, alpha: ArrayLike, theta: Any, d: ArrayLike | None = None
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray | None]:
        """``(E, E_q, E_alpha, E_theta)`` at arrays (q complex or real, alpha, theta, d).

        E_theta by a five-point stencil in theta, exact since E_chr has degree <= 4 in theta (closed form
        of Eq. (38)), or by Jacobi's formula (block system); None when ``theta`` is None: the parameter
        values of ``params`` are used.
        """
        q = np.asarray(q, dtype=complex)
        K, dKq, dKa = self.kernel(q, alpha, d=d, derivative=True, derivative_alpha=True)
        args = self.vehicle_args(theta, d)
        if self.blocks is not None:
            stencil = None
            if theta is not None:
                h = np.maximum(np.abs(theta), 1.0) * 0.25
                stencil = (self.vehicle_args(theta - h, d), self.vehicle_args(theta + h, d), h)
            E, E_q, E_a, E_t = self.blocks.derivatives(q, K, args, dKq=dKq, dKa=dKa, theta_args=stencil)
            assert E_q is not None and E_a is not None  # asked for with dKq and dKa
            return E, E_q, E_a, E_t
        E = self.module.e_chr(q, *K, **args)
        E_q, E0, Ep, Em = self.module.e_chr_partials(q, *K, **args)
        E_q = E_q + E0 * dKq[0] + Ep * dKq[1] + Em * dKq[2]
        E_a = E0 * dKa[0] + Ep * dKa[1] + Em * dKa[2]
        if theta is None:
            return E, E_q, E_a, None
        h = np.maximum(np.abs(theta), 1.0) * 0.25
        # the four stencil points in one call of the generated e_chr (a leading axis of length 4)
        shifts = np.array([-2.0, -1.0, 1.0, 2.0]).reshape((4,) + (1,) * np.ndim(theta))
        stacked = self.vehicle_args(theta + shifts * h, d)
        f = self.module.e_chr(q, *K, **stacked)
        E_t = (f[0] - 8 * f[1] + 8 * f[2] - f[3]) / (12 * h)
        return E, E_q, E_a, E_t

    # -- polynomial structure ------------------------------------------------------------------------
    def nodes(self, scale: float) -> np.ndarray:
        """Chebyshev nodes of [0, scale] used to interpolate the polynomial in the parameter."""
        n = self.degree + 1
        return 0.5 * scale * (1 - np.cos((2 * np.arange(n) + 1) * np.pi / (2 * n)))

    def coefficients(
        self, q: ArrayLike, K: Any, *, scale: float = 1.0, dK: Any = None, d: ArrayLike | None = None
    ) -> Any:
        """Coefficients of E_chr (and of dE/dq with ``dK``) in t = theta / scale, highest power first.

        Parameters
        ----------
        q : ndarray
        K : tuple of ndarray
            (K0, K+, K-) at q (from :meth:`kernel`).
        scale : float
            The range of interest of theta: the interpolation nodes lie in [0, scale].
        dK : tuple of ndarray, optional
            q-derivatives of K; if given, the coefficients of dE/dq are returned too.
        d : float or ndarray, optional
            Wheel spacing (default that of ``params``), entering the vehicle's matrices.

        Returns
        -------
        ndarray of shape ``q.shape + (degree + 1,)`` (or a pair of them with ``dK``)
        """
        q = np.asarray(q, dtype=complex)
        nodes = self.nodes(scale)
        inv = np.linalg.inv(np.vander(nodes / scale, self.degree + 1))
        values, dvalues = [], []
        for theta in nodes:
            if dK is None:
                values.append(np.broadcast_to(self.e_chr(q, K, theta, d), q.shape))
            else:
                E, E_q = self._e_and_dq(q, K, dK, self.vehicle_args(theta, d))
                values.append(np.broadcast_to(E, q.shape))
                dvalues.append(np.broadcast_to(E_q, q.shape))
        c = np.einsum("ij,j...->...i", inv, np.stack(values))
        if dK is None:
            return c
        return c, np.einsum("ij,j...->...i", inv, np.stack(dvalues))


def _prepare(q: ArrayLike, alpha: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    q = np.asarray(q, dtype=complex)
    alpha = np.asarray(alpha, dtype=float)
    q, alpha = np.broadcast_arrays(q, alpha)
    return np.ascontiguousarray(q), np.ascontiguousarray(alpha)


def _roots(coeffs: np.ndarray) -> np.ndarray:
    if coeffs.shape[-1] == 5:
        return quartic_roots(coeffs)
    return poly_roots(coeffs)
