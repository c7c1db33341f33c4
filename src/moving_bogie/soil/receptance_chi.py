"""chi at the receptance's first nodes for many speeds at once, interpolated in the speed (docs/soil.md,
Eq. (S9)).

A DAF curve asks the moving load's receptance at Omega = 0 for many speeds v, each on its own k panels:
their first panels are the same, so each first node k_j is met by every speed, at omega = k_j v. There
chi(k_j, k_j v) is tabulated at :data:`POINTS` Chebyshev points of the speeds' range (the strip quadrature
to :data:`TABLE_RTOL` times the receptance's tolerance) and interpolated to every speed, with the error
estimate

    e_j = sum of the last :data:`TAIL` Chebyshev coefficients' magnitudes + Lambda max_i e_ij,

the truncation of a geometrically decaying expansion (it errs by about the next coefficient, below the
last ones' sum) plus the table's own errors e_ij carried through the interpolation (Lambda, the Lebesgue
constant of the points, :data:`LEBESGUE`). Where chi varies sharply with v (a soil's wave speed between
the speeds, its waves lightly damped) the estimate is large and the node's chi is computed directly
(:mod:`.receptance`): only where the estimate meets what 1/D needs is the interpolated chi taken, its
error stated with the rest. tests/test_soil_receptance.py checks the estimate against chi computed
directly at speeds between the table's.
"""

from __future__ import annotations

import numpy as np
from numpy.polynomial import chebyshev

from moving_bogie.typing import ComplexArray, FloatArray

from .profile import SoilProfile
from .strip import strip_stiffness

__all__ = ["LEBESGUE", "POINTS", "TABLE_RTOL", "TAIL", "speed_table"]

#: Chebyshev points (of the first kind) in v, and the coefficients whose magnitudes estimate the truncation.
POINTS, TAIL = 16, 3
#: The table's strip quadratures run to this fraction of the receptance's tolerance.
TABLE_RTOL = 0.01
_X = np.cos(np.pi * (np.arange(POINTS) + 0.5) / POINTS)
_VANDERMONDE = chebyshev.chebvander(_X, POINTS - 1)
#: max over [-1, 1] of the sum of |Lagrange basis| of the points, on a fine grid.
LEBESGUE = float(
    np.abs(np.linalg.solve(_VANDERMONDE.T, chebyshev.chebvander(np.linspace(-1, 1, 4001), POINTS - 1).T))
    .sum(axis=0)
    .max()
)


def speed_table(
    k: FloatArray, speeds: FloatArray, soil: SoilProfile, b: float, tol: float
) -> tuple[ComplexArray, FloatArray]:
    """(chi, error estimate), each (speeds, nodes): chi(k_j, k_j v_i) interpolated in v from the table at
    every k_j > 0 of ``k`` (module docstring)."""
    lo, hi = float(np.min(speeds)), float(np.max(speeds))
    v = (hi + lo) / 2 + (hi - lo) / 2 * _X
    kk = np.repeat(k, POINTS)
    table = strip_stiffness(kk, kk * np.tile(v, k.size), soil, b, rtol=TABLE_RTOL * tol)
    values = table.chi.reshape(k.size, POINTS)
    coefficients = np.linalg.solve(_VANDERMONDE, values.T)  # (POINTS, nodes)
    error = np.abs(coefficients[-TAIL:]).sum(axis=0) + LEBESGUE * table.error.reshape(k.size, POINTS).max(
        axis=1
    )
    t = (2 * np.asarray(speeds, dtype=float) - hi - lo) / max(hi - lo, 1e-300)
    chi = chebyshev.chebval(t, coefficients).T  # (speeds, nodes)
    return np.asarray(chi, dtype=complex), np.broadcast_to(error, chi.shape).copy()
