"""The finite rail's per-mode blocks, moving-load symbol and free waves, read from the generated track model.

On a simply supported finite length every unknown of a track model (the rail's deflection, its rotation for a
Timoshenko-Rayleigh beam, the deflection of each mass layer of a layered track, docs/layered_tracks.md) is
expanded in sine (or, for the rotation, cosine) modes of the same wavenumbers ``lambda_k = k pi / L``; the
layers have no bending stiffness, so mode ``k`` of one unknown couples only with mode ``k`` of the others.
``python -m derivations`` writes the per-mode blocks into each foundation module (``modal_mass``,
``modal_damping``, ``modal_stiffness``, ``MODAL_PARITY``; ``derivations/modal.py``): with ``y_k`` the mode's
amplitudes (rail deflection first),

    M(lambda_k) y_k'' + C(lambda_k) y_k' + K(lambda_k) y_k = (2/L) sum_j F_j sin(lambda_k x_j) e_0,

the rail row being Eq. (49)'s modal row (unit modal mass). :class:`ModalTrack` evaluates them for one set
of parameters and derives from the same model what the finite rail needs besides:

* the moving-load symbol ``Omega(p)``: the steady response of a mode of wavenumber ``p`` to a force
  moving at ``alpha`` (time dependence ``exp(i p alpha tau)``) is ``1 / Omega(p)``, and Eq. (24)'s
  ``D(p, 0) = N(p, 0) / Q(p, 0)`` of the moving frame gives it in closed form,
  ``Omega(p) = N(-p, 0) / (4 Q(-p, 0))`` (the transform's ``exp(i p xi)`` runs the other way);
* the undamped dispersion branches ``omega_j(p)`` of free waves (eigenvalues of ``(K, M)``), their
  group velocities ``d omega_j / d p`` and the slowest decay rate of any free wave (the eigenvalues of the
  damped block), for the beam's length and its reflection-free window.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from types import ModuleType
from typing import Any

import numpy as np

from moving_bogie.errors import MovingBogieError
from moving_bogie.model.catalogue import get_model
from moving_bogie.typing import Scalar

__all__ = ["ModalTrack"]

#: Samples of the wavenumber range for the group velocity and the decay rate of free waves.
_SAMPLES = 4001


def _number(value: Scalar | None) -> float:
    return 0.0 if value is None else float(value)


@dataclass(frozen=True)
class ModalTrack:
    """A track model's finite-rail blocks for one set of parameters.

    Attributes
    ----------
    module : module
        The generated foundation kernel (``params.model.foundation``).
    values : dict
        Values (floats) of the groups its functions take; ``alpha`` among them.
    """

    module: ModuleType
    values: dict[str, float]

    @classmethod
    def of(cls, params: Any) -> ModalTrack:
        """The track of a parameters object.

        ``DimensionlessParams`` (its ``model``), or any namespace of numbers naming its ``beam`` and
        ``track`` (the paper's Euler-Bernoulli beam on the one-layer track when it names neither).

        Raises
        ------
        MovingBogieError
            For a beam or track that the catalogue does not hold, naming it.
        """
        model = getattr(params, "model", None)
        if model is None or isinstance(model, str):
            model = get_model(beam=getattr(params, "beam", None), track=getattr(params, "track", None))
        module = model.foundation
        names = set(module.MODAL_ARGUMENTS[1:]) | set(module.ARGUMENTS[1:])
        return cls(module, {name: _number(getattr(params, name, None)) for name in sorted(names)})

    @property
    def size(self) -> int:
        """Unknowns per mode (rail deflection, its rotation for TR, one per mass layer)."""
        return len(self.module.MODAL_PARITY)

    @property
    def damped(self) -> bool:
        """Whether any damping group of the track (``DAMPING`` of the generated module) is positive."""
        return any(self.values.get(name, 0.0) > 0 for name in self.module.DAMPING)

    def blocks(self, lam: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``M, C, K`` of the modes of wavenumbers `lam`, each of shape ``(len(lam), size, size)``."""
        lam = np.atleast_1d(np.asarray(lam, dtype=float))
        args = {name: self.values[name] for name in self.module.MODAL_ARGUMENTS[1:]}
        s = self.size
        out = []
        for function in (self.module.modal_mass, self.module.modal_damping, self.module.modal_stiffness):
            entries = [np.broadcast_to(np.asarray(e, dtype=float), lam.shape) for e in function(lam, **args)]
            out.append(np.stack(entries, axis=-1).reshape(lam.size, s, s))
        return out[0], out[1], out[2]

    def symbol_polynomials(self, alpha: float | None = None) -> tuple[np.ndarray, np.ndarray]:
        """``Omega(p) = den(p) / num(p)``: complex coefficients, highest power first (module docstring).

        ``den = N(-p, 0) / 4`` and ``num = Q(-p, 0)`` from the generated ``n_coeffs`` and ``q_coeffs``;
        leading zeros (a degree that drops, e.g. at ``alpha = 0``) are trimmed. `alpha` replaces the
        velocity of :attr:`values` (``alpha = 0``: the static symbol).
        """
        args = {name: self.values[name] for name in self.module.ARGUMENTS[1:]}
        if alpha is not None:
            args["alpha"] = float(alpha)

        def flipped(coeffs: Sequence[Scalar]) -> np.ndarray:
            c = np.array([complex(x) for x in coeffs])
            signs = (-1.0) ** np.arange(c.size - 1, -1, -1)
            return np.trim_zeros(c * signs, "f")

        return flipped(self.module.q_coeffs(0, **args)), 0.25 * flipped(self.module.n_coeffs(0, **args))

    def static_spectrum(self, p: np.ndarray) -> np.ndarray:
        """Share per unit wavenumber of a static point load's deflection under the load, at ``p >= 0``.

        ``(1/pi) Re[1 / Omega_0(p)] / G_0(0)`` with ``Omega_0`` the symbol at ``alpha = 0`` and
        ``G_0(0) = (1/pi) int_0^inf Re[1 / Omega_0] dp`` the deflection under a unit static load (by
        residues), so that it integrates to 1 over ``p >= 0``. Euler-Bernoulli without a shear layer:
        ``(8/pi) / (p^4 + 4)``.
        """
        num, den = self.symbol_polynomials(alpha=0.0)
        roots = np.roots(den)
        if roots.size == 0 or np.min(np.abs(roots.imag)) < 1e-12:
            raise MovingBogieError(
                "the static moving-load symbol has a real root: the track has no static deflection"
            )
        weights = np.polyval(num, roots) / np.polyval(np.polyder(den), roots)
        g0 = float((1j * np.sum(weights[roots.imag > 0])).real)
        p = np.asarray(p, dtype=float)
        return (np.polyval(num, p) / np.polyval(den, p)).real / (np.pi * g0)

    def spectrum_tail(self, p: np.ndarray, k_max: float) -> np.ndarray:
        """Share of a static point load's deflection carried by the wavenumbers between `p` and `k_max`.

        The integral of :meth:`static_spectrum` from `p` to `k_max` (trapezoidal rule on 4001 points per
        unit of ``k_max``); zero where ``p >= k_max``.
        """
        grid = np.linspace(0.0, k_max, _SAMPLES)
        density = self.static_spectrum(grid)
        cumulative = np.concatenate([[0.0], np.cumsum(0.5 * (density[1:] + density[:-1]) * np.diff(grid))])
        p = np.clip(np.asarray(p, dtype=float), 0.0, k_max)
        return np.clip(cumulative[-1] - np.interp(p, grid, cumulative), 0.0, 1.0)

    def truncation_share(self, k_max: float) -> float:
        """Share of a static point load's deflection carried by wavenumbers above `k_max`.

        ``1 - int_0^k_max static_spectrum``, the part of the point-load spectrum beyond the modes
        (Euler-Bernoulli: at most ``8 / (3 pi k_max^3)``).
        """
        return max(0.0, 1.0 - float(self.spectrum_tail(np.array(0.0), k_max)))

    def rail_frequency(self, lam: float) -> float:
        """``sqrt(K_eff / M_00)`` of the mode `lam`: the rail row with every other unknown static.

        ``K_eff = 1 / [K^-1]_00`` (the other unknowns condensed out statically) and ``M_00`` the rail
        row's mass; on the one-layer Euler-Bernoulli track ``sqrt(1 + eta_s lam^2 + lam^4 / 4)``.
        """
        m, _, k = self.blocks(np.array([lam]))
        e0 = np.zeros((self.size, 1))
        e0[0, 0] = 1.0
        compliance = float(np.linalg.solve(k[0], e0)[0, 0])
        return float(np.sqrt(1.0 / (compliance * m[0, 0, 0])))

    def symbol(self, p: np.ndarray) -> np.ndarray:
        """``Omega(p)`` at real wavenumbers `p` (closed form of :meth:`symbol_polynomials`)."""
        num, den = self.symbol_polynomials()
        p = np.asarray(p, dtype=float)
        return np.polyval(den, p) / np.polyval(num, p)

    def block_symbol(self, p: np.ndarray) -> np.ndarray:
        """``Omega(p)`` from the blocks: ``1 / [(K - (alpha p)^2 M + i alpha p C)^-1]_00`` (a check)."""
        p = np.atleast_1d(np.asarray(p, dtype=float))
        m, c, k = self.blocks(p)
        w = (self.values["alpha"] * p)[:, None, None]
        dynamic = k - w * w * m + 1j * w * c
        e0 = np.zeros((p.size, self.size, 1), dtype=complex)
        e0[:, 0, 0] = 1.0
        return 1.0 / np.linalg.solve(dynamic, e0)[:, 0, 0]

    def near_field_decay_rate(self) -> float:
        """Smallest ``|Im p|`` over the roots of ``Omega``: how fast the moving-load deflection decays."""
        return float(np.min(np.abs(np.roots(self.symbol_polynomials()[1]).imag)))

    def dispersion(self, p: np.ndarray) -> np.ndarray:
        """Undamped free-wave frequencies ``omega_j(p) >= 0``, ascending, shape ``(len(p), size)``."""
        m, _, k = self.blocks(p)
        omega2 = np.linalg.eigvals(np.linalg.solve(m, k)).real
        return np.sqrt(np.clip(np.sort(omega2, axis=-1), 0.0, None))

    def group_velocity_envelope(self, p: np.ndarray) -> np.ndarray:
        """``max d omega_j / d p`` over every branch and every wavenumber up to `p` (sorted grid `p`).

        Non-decreasing in ``p``: the fastest wave that modes up to ``p`` carry (central differences of
        the sorted branches of :meth:`dispersion`).
        """
        p = np.asarray(p, dtype=float)
        return np.maximum.accumulate(np.max(np.gradient(self.dispersion(p), p, axis=0), axis=1))

    def fastest_wave(self, k_top: float) -> Callable[[float], float]:
        """``k_max -> max d omega_j / d p`` over ``0 < p <= k_max <= k_top`` and every branch.

        Sampled once on ``[0, k_top]`` (central differences of the sorted branches) and returned as a
        function, since the beam's length is found by bisection over ``k_max``.
        """
        p = np.linspace(0.0, k_top, 4 * _SAMPLES)
        envelope = self.group_velocity_envelope(p)
        return lambda k_max: float(np.interp(k_max, p, envelope))

    def free_wave_decay_rate(self, k_max: float) -> float:
        """Slowest decay rate ``min -Re s`` of free waves ``exp(s tau)`` with wavenumbers up to `k_max`.

        The eigenvalues of the damped block, ``det(s^2 M + s C + K) = 0``, through its companion matrix.
        On the one-layer Euler-Bernoulli track every under-damped wave decays at ``eta_f``.
        """
        p = np.linspace(k_max / _SAMPLES, k_max, _SAMPLES)
        m, c, k = self.blocks(p)
        s = self.size
        companion = np.zeros((p.size, 2 * s, 2 * s))
        companion[:, :s, s:] = np.eye(s)
        companion[:, s:, :s] = -np.linalg.solve(m, k)
        companion[:, s:, s:] = -np.linalg.solve(m, c)
        return float(np.min(-np.linalg.eigvals(companion).real))
