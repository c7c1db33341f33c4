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

from dataclasses import dataclass
from types import ModuleType
from typing import Any

import numpy as np

from moving_bogie.kernels.track import foundation_arguments, foundation_module

__all__ = ["ModalTrack"]

#: Samples of the wavenumber range for the group velocity and the decay rate of free waves.
_SAMPLES = 4001


def _number(value: Any) -> float:
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
    values: dict

    @classmethod
    def of(cls, params: Any) -> ModalTrack:
        """The track of a parameters object (``DimensionlessParams`` or any namespace with ``model``)."""
        module = foundation_module(params)
        names = set(module.MODAL_ARGUMENTS[1:]) | set(foundation_arguments(params, params))
        return cls(module, {name: _number(getattr(params, name, None)) for name in sorted(names)})

    @property
    def size(self) -> int:
        """Unknowns per mode (rail deflection, its rotation for TR, one per mass layer)."""
        return len(self.module.MODAL_PARITY)

    @property
    def layered(self) -> bool:
        """Whether the track has mass layers: deflections (sine modes) besides the rail's."""
        return sum(1 for parity in self.module.MODAL_PARITY if parity == 0) > 1

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

    def symbol_polynomials(self) -> tuple[np.ndarray, np.ndarray]:
        """``Omega(p) = den(p) / num(p)``: complex coefficients, highest power first (module docstring).

        ``den = N(-p, 0) / 4`` and ``num = Q(-p, 0)`` from the generated ``n_coeffs`` and ``q_coeffs``;
        leading zeros (a degree that drops, e.g. at ``alpha = 0``) are trimmed.
        """
        args = {name: self.values[name] for name in self.module.ARGUMENTS[1:]}

        def flipped(coeffs) -> np.ndarray:
            c = np.array([complex(x) for x in coeffs])
            signs = (-1.0) ** np.arange(c.size - 1, -1, -1)
            return np.trim_zeros(c * signs, "f")

        return flipped(self.module.q_coeffs(0, **args)), 0.25 * flipped(self.module.n_coeffs(0, **args))

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

    def fastest_wave(self, k_top: float):
        """``k_max -> max d omega_j / d p`` over ``0 < p <= k_max <= k_top`` and every branch.

        Sampled once on ``[0, k_top]`` (central differences of the sorted branches) and returned as a
        function, since the beam's length is found by bisection over ``k_max``.
        """
        p = np.linspace(0.0, k_top, 4 * _SAMPLES)
        envelope = np.maximum.accumulate(np.max(np.gradient(self.dispersion(p), p, axis=0), axis=1))
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
