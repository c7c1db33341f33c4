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

import numpy as np
from scipy import integrate

from moving_bogie.errors import MovingBogieError
from moving_bogie.kernels.characteristic import vehicle_module
from moving_bogie.kernels.track import TrackKernelArray

__all__ = ["BromwichResult", "bromwich_response", "bromwich_shape"]


class BromwichResult(dict):
    """name -> ndarray of x(tau), with ``.errors`` (name -> quadrature error estimates) and ``.a``."""

    errors: dict
    a: float


def _transform(params, model):
    vehicle = vehicle_module(model, params)
    kernel = TrackKernelArray(params)
    f = params.as_float()
    args = {name: getattr(f, name) for name in vehicle.PARAMETERS} | {"pi": np.pi}
    d = f.d
    cache: dict[float, np.ndarray] = {}

    def values(s: float, a: float) -> np.ndarray:
        key = (s, a)
        if key not in cache:
            q = np.array([s - 1j * a])
            kv = kernel(q, [0.0, d, -d])
            E = vehicle.e_chr(q, *kv.K, **args)
            nums = vehicle.numerators(q, *kv.K, **args)
            cache[key] = np.array([complex((n / (1j * q * E))[0]) for n in nums])
        return cache[key]

    return vehicle.RESPONSES, values


def bromwich_shape(
    params,
    xi,
    tau: float,
    *,
    model: str | None = None,
    a: float = 0.02,
    epsabs: float = 1e-12,
    limit: int = 2000,
    limlst: int = 400,
) -> np.ndarray:
    """w(xi, tau) for each xi by direct quadrature of the Bromwich integral of W~(xi, q), Eq. (28).

    i q W~(xi, q) = (G_rear K(xi, q) + G_front K(xi - d, q)) / (2 pi E_chr), evaluated directly (no residues,
    no branch cut); the same fold onto s >= 0 and QAWF quadrature as :func:`bromwich_response`.
    """
    model = model or params.vehicle
    if not a > 0:
        raise MovingBogieError("the Bromwich line needs a > 0")
    vehicle = vehicle_module(model, params)
    kernel = TrackKernelArray(params)
    f = params.as_float()
    args = {name: getattr(f, name) for name in vehicle.PARAMETERS} | {"pi": np.pi}
    d = f.d
    xi = np.atleast_1d(np.asarray(xi, dtype=float))
    out = np.empty(xi.shape)
    tau = float(tau)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", integrate.IntegrationWarning)
        for k, x in np.ndenumerate(xi):
            cache: dict[float, complex] = {}

            def value(s, x=x, cache=cache):
                if s not in cache:
                    q = np.array([s - 1j * a])
                    with np.errstate(over="ignore", invalid="ignore"):
                        # exponentials of the roots on the unused side may overflow at large |xi|
                        kv = kernel(q, [0.0, d, -d, x, x - d])
                    K0, Kp, Km, Kx, Kxd = kv.K
                    E = vehicle.e_chr(q, K0, Kp, Km, **args)
                    G_r, G_f = vehicle.shape_weights(q, K0, Kp, Km, **args)
                    cache[s] = complex(((G_r * Kx + G_f * Kxd) / (2 * np.pi * 1j * q * E))[0])
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
    params,
    tau,
    *,
    model: str | None = None,
    a: float = 0.02,
    names=None,
    epsabs: float = 1e-12,
    epsrel: float = 1e-12,
    limit: int = 2000,
    limlst: int = 400,
) -> BromwichResult:
    """x(tau) of each response by direct numerical quadrature of the Bromwich integral (Eq. (35)).

    Parameters
    ----------
    params : DimensionlessParams
    tau : array_like of float, >= 0
    model : {"bogie", "masses"}
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
    model = model or params.vehicle
    if not a > 0:
        raise MovingBogieError("the Bromwich line needs a > 0")
    responses, values = _transform(params, model)
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

                def re(s, j=j):
                    return values(s, a)[j].real

                def im(s, j=j):
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
