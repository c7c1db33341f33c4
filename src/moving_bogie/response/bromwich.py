"""Independent inversion of the Laplace transform by direct quadrature of the Bromwich integral, Eq. (35).

    x(tau) = (1/2 pi) * integral over real s of X~(q) e^{i q tau} ds,    q = s - i a,

with X~ = n_X / (i q E_chr) evaluated directly from K of Eq. (29) (numpy, double precision). The line lies
below every singularity: a > 0 and a > -min Im q_j. No residues, no induced frequencies and no branch cut
enter, so the result checks the closed form (steady + harmonic + I_bc) independently.

Because x is real, X~(-conj q) = conj X~(q), and the integral folds onto s >= 0:

    x(tau) = (e^{a tau} / pi) * integral_0^inf [Re X~ cos(s tau) - Im X~ sin(s tau)] ds,

which is a Fourier integral done by QUADPACK's QAWF (``scipy.integrate.quad`` with ``weight='cos'`` /
``'sin'`` and an infinite upper limit): X~ = O(s^-3) for the wheels and faster for the bar, so the
Fourier integral converges absolutely and QAWF's cycle-by-cycle extrapolation handles the tail.
At tau = 0 there is no oscillation and the integrand is integrated by QAGI. The factor e^{a tau}
amplifies the absolute quadrature error: keep a tau moderate (a tau <= ~10).
"""

from __future__ import annotations

import warnings
from collections.abc import Callable, Iterable

import numpy as np
from numpy.typing import ArrayLike
from scipy import integrate

from moving_bogie.errors import MovingBogieError
from moving_bogie.kernels.bound import BoundModel
from moving_bogie.kernels.track import TrackKernelArray
from moving_bogie.kernels.vehicle import VehicleSystem
from moving_bogie.response.quadrature import adapt_panels, subdivide

__all__ = ["BromwichResult", "bromwich_line", "bromwich_line_shape", "bromwich_response", "bromwich_shape"]


class BromwichResult(dict[str, np.ndarray]):
    """name -> ndarray of x(tau), with ``.errors`` (name -> quadrature error estimates) and ``.a``."""

    errors: dict[str, np.ndarray]
    a: float


def _transform(bound: BoundModel) -> tuple[tuple[str, ...], Callable[[float, float], np.ndarray]]:
    system = bound.float_system
    kernel = TrackKernelArray(bound)
    offsets = [float(x) for x in system.offsets]
    cache: dict[tuple[float, float], np.ndarray] = {}

    def values(s: float, a: float) -> np.ndarray:
        key = (s, a)
        if key not in cache:
            q = np.array([s - 1j * a])
            E, nums, _ = system.responses_array(q, kernel(q, offsets).K)
            cache[key] = (nums / (1j * q * E)[:, None])[0]
        return cache[key]

    return system.names, values


def bromwich_shape(
    bound: BoundModel,
    xi: ArrayLike,
    tau: float,
    *,
    a: float = 0.02,
    epsabs: float = 1e-12,
    limit: int = 2000,
    limlst: int = 400,
) -> np.ndarray:
    """w(xi, tau) for each xi by direct quadrature of the Bromwich integral of W~(xi, q), Eq. (28).

    i q W~(xi, q) = sum_j G_j K(xi - xi_j, q) / (2 pi E_chr) (n contacts), evaluated directly (no residues,
    no branch cut); the same fold onto s >= 0 and QAWF quadrature as :func:`bromwich_response`.
    """
    if not a > 0:
        raise MovingBogieError("the Bromwich line needs a > 0")
    system = bound.float_system
    kernel = TrackKernelArray(bound)
    offsets = [float(x) for x in system.offsets]
    positions = [float(x) for x in system.positions]
    xi = np.atleast_1d(np.asarray(xi, dtype=float))
    out = np.empty(xi.shape)
    tau = float(tau)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", integrate.IntegrationWarning)
        for k, x in np.ndenumerate(xi):
            cache: dict[float, complex] = {}

            def value(s: float, x: float = x, cache: dict[float, complex] = cache) -> complex:
                if s not in cache:
                    q = np.array([s - 1j * a])
                    with np.errstate(over="ignore", invalid="ignore"):
                        # exponentials of the roots on the unused side may overflow at large |xi|
                        kv = kernel(q, offsets + [x - xj for xj in positions])
                    E, _, G = system.responses_array(q, kv.K[: len(offsets)])
                    Kx = kv.K[len(offsets) :]
                    w = sum(G[:, j] * Kx[j] for j in range(len(positions)))
                    cache[s] = complex((w / (2 * np.pi * 1j * q * E))[0])
                return cache[s]

            if tau == 0:
                v1 = integrate.quad(lambda s: value(s).real, 0, np.inf, epsabs=epsabs, limit=limit)[0]
                v2 = 0.0
            else:
                opts = {"wvar": tau, "epsabs": epsabs, "limlst": limlst, "limit": limit}
                v1 = integrate.quad(lambda s: value(s).real, 0, np.inf, weight="cos", **opts)[0]
                v2 = integrate.quad(lambda s: value(s).imag, 0, np.inf, weight="sin", **opts)[0]
            out[k] = np.exp(a * tau) / np.pi * (v1 - v2)
    return out


def bromwich_response(
    bound: BoundModel,
    tau: ArrayLike,
    *,
    a: float = 0.02,
    names: Iterable[str] | None = None,
    epsabs: float = 1e-12,
    epsrel: float = 1e-12,
    limit: int = 2000,
    limlst: int = 400,
) -> BromwichResult:
    """x(tau) of each response by direct numerical quadrature of the Bromwich integral (Eq. (35)).

    Parameters
    ----------
    bound : BoundModel
    tau : array_like of float, >= 0
    a : float
        Distance of the Bromwich line Im q = -a below the real axis; must exceed -Im q of every unstable
        induced frequency (the caller's responsibility: this function does not look for them).
    names : iterable of str, optional
        Responses to compute (default all of the model).
    epsabs, epsrel, limit, limlst : QUADPACK controls (see ``scipy.integrate.quad``).

    Returns
    -------
    BromwichResult
        dict name -> ndarray like tau; ``.errors`` holds QUADPACK's error estimates times e^{a tau}/pi.
    """
    if not a > 0:
        raise MovingBogieError("the Bromwich line needs a > 0")
    responses, values = _transform(bound)
    names = tuple(names or responses)
    index = {name: responses.index(name) for name in names}
    tau = np.atleast_1d(np.asarray(tau, dtype=float))
    out = BromwichResult({name: np.empty(tau.shape) for name in names})
    out.errors = {name: np.empty(tau.shape) for name in names}
    out.a = a
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", integrate.IntegrationWarning)
        for k, t in np.ndenumerate(tau):
            for name in names:
                j = index[name]

                def re(s: float, j: int = j) -> float:
                    return values(s, a)[j].real

                def im(s: float, j: int = j) -> float:
                    return values(s, a)[j].imag

                if t == 0:
                    v1, e1 = integrate.quad(re, 0, np.inf, epsabs=epsabs, epsrel=epsrel, limit=limit)
                    v2, e2 = 0.0, 0.0
                else:
                    v1, e1 = integrate.quad(
                        re, 0, np.inf, weight="cos", wvar=t, epsabs=epsabs, limlst=limlst, limit=limit
                    )
                    v2, e2 = integrate.quad(
                        im, 0, np.inf, weight="sin", wvar=t, epsabs=epsabs, limlst=limlst, limit=limit
                    )
                scale = np.exp(a * t) / np.pi
                out[name][k] = scale * (v1 - v2)
                out.errors[name][k] = scale * (e1 + e2)
    return out


def bromwich_line(
    bound: BoundModel,
    tau: ArrayLike,
    *,
    a: float = 0.02,
    s_max: float = 400.0,
    panel_tol: float = 1e-14,
) -> dict[str, np.ndarray]:
    """x(tau) of every response by a vectorised Bromwich quadrature on the line Im q = -a (Eq. (35)).

    The same integral as :func:`bromwich_response`, folded onto s >= 0,

        x(tau) = (e^{a tau} / pi) Re integral_0^inf X~(s - i a) e^{i s tau} ds,

    done by composite 16-point Gauss-Legendre panels: first adapted to X~ itself (a panel is halved until
    its integral changes by less than ``panel_tol`` times max |X~|: this resolves the fine structure X~ has
    on the line where the cut of K or a pole passes close above it, e.g. the Timoshenko-Rayleigh cut
    touching the real axis at Re q = sqrt(S)/r), then subdivided to at most 3 pi of phase s tau. Beyond
    ``s_max`` the tail is integrated by parts, e^{i S tau} (i X~/tau - X~'/tau^2 - i X~''/tau^3), the
    derivatives by central differences. Any beam or track model (that of ``bound``); times must be > 0.

    Returns
    -------
    dict name -> ndarray like tau
    """
    tau, system, kernel = _line_setup(bound, tau, a)
    offsets = [float(x) for x in system.offsets]

    def transform(s: np.ndarray) -> np.ndarray:
        q = np.asarray(s, dtype=float) - 1j * a
        E, nums, _ = system.responses_array(q, kernel(q, offsets).K)
        return nums / (1j * q * E)[:, None]

    x = _line_quadrature(transform, tau, a, s_max, panel_tol)
    return {name: x[:, k] for k, name in enumerate(system.names)}


def bromwich_line_shape(
    bound: BoundModel,
    xi: ArrayLike,
    tau: float,
    *,
    a: float = 0.02,
    s_max: float = 400.0,
    panel_tol: float = 1e-14,
) -> np.ndarray:
    """w(xi, tau) at one time for an array xi by the quadrature of :func:`bromwich_line` (Eq. (28)).

    i q W~(xi, q) = sum_j G_j K(xi - xi_j, q) / (2 pi E_chr) on the line Im q = -a, every xi
    at once (the panels adapt to all of them); no residues, no branch cut. Any beam or track model.
    """
    times, system, kernel = _line_setup(bound, tau, a)
    offsets = [float(x) for x in system.offsets]
    positions = [float(x) for x in system.positions]
    xi = np.asarray(xi, dtype=float)
    flat = xi.reshape(-1)
    m, F = len(offsets), flat.size

    def transform(s: np.ndarray) -> np.ndarray:
        q = np.asarray(s, dtype=float) - 1j * a
        with np.errstate(over="ignore", invalid="ignore"):
            # exponentials of the roots on the unused side may overflow at large |xi|
            kv = kernel(q, np.concatenate([offsets, *[flat - x for x in positions]]))
        E, _, G = system.responses_array(q, kv.K[:m])
        w = sum(G[:, j] * np.array(kv.K[m + j * F : m + (j + 1) * F]) for j in range(len(positions)))
        return (w / (2 * np.pi * 1j * q * E)).T

    return _line_quadrature(transform, times, a, s_max, panel_tol)[0].reshape(xi.shape)


def _line_setup(
    bound: BoundModel, tau: ArrayLike, a: float
) -> tuple[np.ndarray, VehicleSystem, TrackKernelArray]:
    """(tau array, vehicle block system, kernel) after checking a and the times."""
    if not a > 0:
        raise MovingBogieError("the Bromwich line needs a > 0")
    tau = np.atleast_1d(np.asarray(tau, dtype=float))
    if np.any(tau <= 0) or not np.all(np.isfinite(tau)):
        raise MovingBogieError("bromwich_line needs finite tau > 0")
    return tau, bound.float_system, TrackKernelArray(bound)


def _line_quadrature(
    transform: Callable[[np.ndarray], np.ndarray], tau: np.ndarray, a: float, s_max: float, panel_tol: float
) -> np.ndarray:
    """(e^{a tau}/pi) Re integral_0^inf transform(s) e^{i s tau} ds, shape (len(tau), columns)."""
    start = [0.0]
    while start[-1] < s_max:
        start.append(min(s_max, start[-1] + min(0.5, 0.05 * max(1.0, start[-1]))))
    scale = np.abs(transform(np.linspace(0.0, 2.0, 64))).max()
    edges = adapt_panels(np.array(start), transform, panel_tol * scale)
    nodes, weights = subdivide(edges, np.ceil(np.diff(edges) * tau.max() / (3 * np.pi)))
    total = 0
    for start_n in range(0, nodes.size, 20000):
        sl = slice(start_n, start_n + 20000)
        total = total + np.exp(1j * np.multiply.outer(tau, nodes[sl])) @ (
            transform(nodes[sl]) * weights[sl, None]
        )
    h = 0.01 * s_max
    F = transform(np.array([s_max - h, s_max, s_max + h]))
    F0, F1, F2 = F[1], (F[2] - F[0]) / (2 * h), (F[2] - 2 * F[1] + F[0]) / h**2
    t = tau[:, None]
    total = total + np.exp(1j * s_max * t) * (1j * F0 / t - F1 / t**2 - 1j * F2 / t**3)
    return (np.exp(a * tau)[:, None] / np.pi * total).real
