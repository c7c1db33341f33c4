"""Horner's scheme and the derivative's coefficients, for polynomials in any number type.

The polynomials in p of Eq. (24) (N(p, q), Q(p, q) and their q-derivatives) are evaluated at their roots
in mpmath (:mod:`moving_bogie.kernels.track`), in Python complex numbers (the Newton steps of
:mod:`moving_bogie.kernels.cut_curves`) and in ball arithmetic (:mod:`moving_bogie.roots.proof.p_balls`):
all with these two functions, which use only ``+`` and ``*`` of the coefficients and the point. The
coefficients may be numpy arrays (a stack along the first axis, ``coeffs[k]`` an array of k-th
coefficients): the scheme then evaluates many polynomials at once, broadcasting against ``x``, as the
column counts of :mod:`moving_bogie.stability.maps.column_count` do. The batched numpy path of
:mod:`moving_bogie.kernels.polyroots` (``polyval``, ``polyder``) runs the same steps on arrays of
polynomials, in place.

>>> horner([1, -3, 2], 5)  # 5^2 - 3 * 5 + 2
12
>>> derivative_coefficients([1, -3, 2])
[2, -3]
>>> import numpy as np
>>> horner(np.array([[1, 1], [-3, 0], [2, -1]]), np.array([[5], [2]]))  # x^2 - 3x + 2 and x^2 - 1
array([[12, 24],
       [ 0,  3]])
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

__all__ = ["derivative_coefficients", "horner"]


def horner(coeffs: Sequence[Any] | np.ndarray, x: Any) -> Any:
    """The polynomial with ``coeffs`` (highest power first) at ``x``: ((c_0 x + c_1) x + ...) + c_n.

    Parameters
    ----------
    coeffs : sequence or ndarray
        The coefficients, highest power first (at least one). An array of shape (n + 1, ...) holds a stack
        of polynomials: ``coeffs[k]`` are their k-th coefficients, broadcast against ``x``.
    x : number
        Any number type with ``+`` and ``*`` with the coefficients (mpmath, complex, acb, acb_series, arrays).

    Returns
    -------
    number
        c_0 x^n + ... + c_n, rounded step by step as Horner's scheme rounds it.
    """
    acc = coeffs[0]
    for c in coeffs[1:]:
        acc = acc * x + c
    return acc


def derivative_coefficients(coeffs: Sequence[Any]) -> list:
    """Coefficients (highest power first) of the derivative of the polynomial with ``coeffs``.

    Parameters
    ----------
    coeffs : sequence
        The coefficients, highest power first.

    Returns
    -------
    list
        (n - k) c_k for k < n, or ``[0]`` for a constant.
    """
    n = len(coeffs) - 1
    return [c * (n - k) for k, c in enumerate(coeffs[:-1])] or [0]
