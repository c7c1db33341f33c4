"""Names of the number types the runtime computes with, for annotations.

mpmath, gmpy2 and python-flint ship no type information, so their numbers are ``Any`` to a type checker;
the names below say in a signature which one is meant. The numpy names are numpy's own arrays.
"""

from __future__ import annotations

from typing import Any, TypeAlias

import numpy as np
import numpy.typing as npt

__all__ = [
    "Acb",
    "AcbPoly",
    "AcbSeries",
    "Arb",
    "ComplexArray",
    "FloatArray",
    "Matrix",
    "Mpc",
    "Mpf",
    "Scalar",
]

#: An mpmath real (``mpmath.mpf``).
Mpf: TypeAlias = Any
#: An mpmath complex number (``mpmath.mpc``).
Mpc: TypeAlias = Any
#: An Arb complex ball (``flint.acb``). ``Any``: python-flint ships type information only from 0.9 on
#: (the project supports older releases), and a ball meets mpmath numbers, Fractions and integers in
#: the same expressions.
Acb: TypeAlias = Any
#: An Arb real ball (``flint.arb``); ``Any`` as :data:`Acb`.
Arb: TypeAlias = Any
#: A truncated power series with Arb complex ball coefficients (``flint.acb_series``); ``Any`` as :data:`Acb`.
AcbSeries: TypeAlias = Any
#: A polynomial with Arb complex ball coefficients (``flint.acb_poly``); ``Any`` as :data:`Acb`.
AcbPoly: TypeAlias = Any
#: A number of any backend the kernels evaluate: float, complex, numpy scalars or arrays (batched),
#: mpmath, gmpy2, Arb's balls.
Scalar: TypeAlias = Any
#: A matrix as a list of rows of such numbers (mpmath, gmpy2, Arb; the integer 0 a structural zero).
Matrix: TypeAlias = list[list[Any]]
#: A numpy array of real doubles.
FloatArray: TypeAlias = npt.NDArray[np.float64]
#: A numpy array of complex doubles.
ComplexArray: TypeAlias = npt.NDArray[np.complex128]
