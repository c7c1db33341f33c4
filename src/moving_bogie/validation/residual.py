"""Residual flexibility of the truncated modes at the contact points (static correction).

A finite beam in ``N`` sine modes misses the response of the modes ``k > N``. Their natural
frequencies ``omega_k >= omega(k_max)`` lie far above the frequencies of the contact forces, so
they follow the forces quasi-statically; this is the static correction (mode-acceleration method)
of structural dynamics (R. R. Craig and A. J. Kurdila, *Fundamentals of Structural Dynamics*,
2nd ed., Wiley 2006, Section 14.4). Here the forces also *move*: mode ``k`` is driven by
``(2/L) F_l sin(lambda_k x_l(tau))`` with ``x_l = x_l(0) + alpha tau``, whose steady response to a
constant ``F_l`` is ``(2/L) F_l Im[exp(i lambda_k x_l) / Omega(lambda_k)]`` with

    Omega(p) = N(-p, 0) / (4 Q(-p, 0)),

the symbol of the moving-load operator: Eq. (24) at ``q = 0`` of the track model, read from its
generated kernel (:meth:`~moving_bogie.validation.track_modes.ModalTrack.symbol_polynomials`; the
``exp(i p xi)`` of the transform runs the other way). On the one-layer Euler-Bernoulli track it is
``(p^4 - 4 (alpha^2 - eta_s) p^2 + 8 i eta_f alpha p + 4) / 4``. The truncated modes'
deflection at wheel ``j`` is therefore ``sum_l R_jl F_l`` with the residual flexibility

    R_jl = sum_{k > N} (1/L) Re[(exp(i lambda_k (x_l - x_j)) - exp(i lambda_k (x_j + x_l)))
                                / Omega(lambda_k)].

The whole series (``k >= 1``) is summed in closed form by Poisson summation: with the moving-load
Green's function ``G(s) = (1/2 pi) int exp(i p s) / Omega(p) dp`` of the infinite beam,

    sum_{k >= 1} (1/L) Re[exp(i lambda_k s) / Omega(lambda_k)] = sum_m G(s + 2 m L) - 1 / (2 L),

(the ``k = 0`` terms cancel in the difference of the two exponentials), which is the method of
images for the simply supported beam. ``R`` is the closed form minus the ``N`` retained terms; the
images ``m = +-1`` are kept although the geometry makes them ``exp(-gamma L)`` small.

``G`` itself follows from the residues at the roots ``p_r`` of the symbol's denominator: for
``s >= 0`` it is ``i sum_{Im p_r > 0} exp(i p_r s) num(p_r) / den'(p_r)``, for ``s < 0`` minus the
same sum over the roots below the real axis. Its value at ``s = 0`` is 1/2 for a static load (static
deflection 1 under the dimensionless wheel load 2).
"""

from __future__ import annotations

import numpy as np

from moving_bogie.errors import MovingBogieError

__all__ = ["ResidualFlexibility", "moving_green_function", "polynomial_residues"]


def polynomial_residues(num: np.ndarray, den: np.ndarray, where: str) -> tuple[np.ndarray, np.ndarray]:
    """Roots ``p_r`` of ``den`` and the weights ``num(p_r) / den'(p_r)`` of ``1 / Omega = num / den``.

    Raises
    ------
    MovingBogieError
        When ``den`` has a real or a double root (no decaying moving-load deflection), naming `where`.
    """
    roots = np.roots(den)
    if np.min(np.abs(roots.imag)) < 1e-9:
        raise MovingBogieError(
            "the static correction needs a moving-load deflection that decays away from the load "
            f"(at {where} the velocity is at or above the undamped critical velocity); run without "
            "the correction (static_correction=False, --no-correction)"
        )
    gaps = np.abs(roots[:, None] - roots[None, :]) + np.eye(roots.size)
    if np.min(gaps) < 1e-6:
        raise MovingBogieError(
            f"the moving-load symbol has a double root at {where}; run without the static correction"
        )
    return roots, np.polyval(num, roots) / np.polyval(np.polyder(den), roots)


def moving_green_function(s: np.ndarray, polynomials: tuple[np.ndarray, np.ndarray]) -> np.ndarray:
    """``G(s) = (1/2 pi) int exp(i p s) / Omega(p) dp`` by residues (module docstring).

    Parameters
    ----------
    s : array_like
        Distance from the load (observation minus load position).
    polynomials : tuple of two ndarrays
        ``(num, den)`` of the track's moving-load symbol ``Omega = den / num``
        (:meth:`~moving_bogie.validation.track_modes.ModalTrack.symbol_polynomials`).

    Returns
    -------
    ndarray
        Real; ``G(0) = 1/2`` at ``alpha = 0`` on the one-layer Euler-Bernoulli track without shear layer.

    Raises
    ------
    MovingBogieError
        When ``Omega`` has a real or a double root (undamped at or above the critical velocity).
    """
    roots, weights = polynomial_residues(*polynomials, "these parameters")
    return _green_from_roots(np.asarray(s, dtype=float), roots, weights)


def _green_from_roots(s: np.ndarray, roots: np.ndarray, weights: np.ndarray) -> np.ndarray:
    upper = roots.imag > 0
    s_flat = s.reshape(-1, 1)
    # s >= 0: close above, i sum w exp(i p s); s < 0: close below, -i sum w exp(i p s).
    side = np.where(s_flat >= 0, upper, ~upper)
    sign = np.where(s_flat[:, 0] >= 0, 1j, -1j)
    # On the side closed, Im(p) s = |Im p| |s|: the decaying form never overflows on the other.
    decaying = np.exp(1j * roots.real * s_flat - np.abs(roots.imag) * np.abs(s_flat))
    terms = np.where(side, weights * decaying, 0.0)
    return (sign * terms.sum(axis=1)).real.reshape(s.shape)


class ResidualFlexibility:
    """``R(tau)``, the ``n x n`` residual flexibility of the modes ``k > N`` at the ``n`` contacts.

    Parameters
    ----------
    wavenumbers : ndarray
        Retained ``lambda_k = k pi / L``, ``k = 1..N``.
    length : float
        Beam length ``L``.
    offsets : array_like, shape (n,)
        Contact positions relative to the rear contact (``(0, d)`` for the paper's bogie).
    polynomials : tuple of two ndarrays
        ``(num, den)`` of the track's moving-load symbol ``Omega = den / num``
        (:meth:`~moving_bogie.validation.track_modes.ModalTrack.symbol_polynomials`).
    where : str, optional
        The parameters, for the message when the symbol has a real root.
    """

    def __init__(
        self,
        wavenumbers: np.ndarray,
        length: float,
        offsets: np.ndarray,
        polynomials: tuple[np.ndarray, np.ndarray],
        where: str = "these parameters",
    ) -> None:
        self.length = float(length)
        num, den = polynomials
        roots, weights = polynomial_residues(num, den, where)
        self._green = lambda s: _green_from_roots(s, roots, weights)
        # For 0 <= s <= 2L the images s and s + 2L close above, s - 2L below (see _image_part).
        up = roots.imag > 0
        self._upper = (roots[up], 1j * weights[up] * (1.0 + np.exp(2j * self.length * roots[up])))
        self._lower = (roots[~up], -1j * weights[~up])
        self._weight = np.polyval(num, wavenumbers) / (self.length * np.polyval(den, wavenumbers))
        # The direct (translation-invariant) part depends only on x_l - x_j, fixed by the offsets.
        offsets = np.asarray(offsets, dtype=float)
        self.contacts = offsets.size
        shifts = (offsets[None, :] - offsets[:, None]).reshape(-1)
        direct_full = self._images(shifts) - 0.5 / self.length
        direct_kept = (np.exp(1j * np.outer(shifts, wavenumbers)) @ self._weight).real
        self._direct = (direct_full - direct_kept).reshape(self.contacts, self.contacts)
        self._upper_pairs = np.triu_indices(self.contacts)

    def _images(self, s: np.ndarray) -> np.ndarray:
        two_l = 2.0 * self.length
        return self._green(np.concatenate([s, s - two_l, s + two_l])).reshape(3, -1).sum(axis=0)

    def _image_part(self, s: np.ndarray) -> np.ndarray:
        """``G(s) + G(s - 2L) + G(s + 2L)`` for ``0 <= s <= 2L`` (the sums ``x_j + x_l``), fast."""
        p_up, w_up = self._upper
        p_lo, w_lo = self._lower
        above = np.exp(1j * np.outer(s, p_up)) @ w_up
        below = np.exp(1j * np.outer(s - 2.0 * self.length, p_lo)) @ w_lo
        return (above + below).real

    def matrix(self, positions: np.ndarray, phases: np.ndarray) -> np.ndarray:
        """``R_jl`` at the contact positions `positions` (rear first, in the order of the offsets).

        Parameters
        ----------
        positions : ndarray, shape (n,)
            Contact positions ``x_j``.
        phases : ndarray, complex, shape (n, N)
            ``exp(i lambda_k x_j)`` for the retained modes (the caller has their real and imaginary
            parts already).

        Returns
        -------
        ndarray, shape (n, n)
            Deflection at contact ``j`` (row) per unit force at contact ``l`` (column):
            ``direct(x_l - x_j) - image(x_j + x_l)``.
        """
        rows, cols = self._upper_pairs
        positions = np.asarray(positions, dtype=float)
        sums = positions[rows] + positions[cols]
        image_full = self._image_part(sums) - 0.5 / self.length
        kept = (phases[rows] * phases[cols]) @ self._weight
        upper = image_full - kept.real
        image = np.empty((self.contacts, self.contacts))
        image[rows, cols] = upper
        image[cols, rows] = upper
        return self._direct - image
