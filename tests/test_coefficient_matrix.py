"""The monomial matrices of the generated coefficient functions (kernels/coefficient_matrix.py).

Reference: the generated functions themselves, evaluated directly on numpy arrays (the code the matrices
replace), at random complex q (real p for ``n_coeffs_in_q``) of every generated track model, with random
groups; the agreement must be at rounding level relative to the size of the terms (sum |M_kj| |x|^j).
"""

from __future__ import annotations

import importlib
import pkgutil

import numpy as np
import pytest

import moving_bogie.generated as generated
from moving_bogie.kernels.coefficient_matrix import CoefficientMatrix, Coefficients

FOUNDATIONS = sorted(
    m.name for m in pkgutil.iter_modules(generated.__path__) if m.name.startswith("foundation_")
)
FUNCTIONS = ("n_coeffs", "n_coeffs_dq", "q_coeffs", "q_coeffs_dq", "n_coeffs_in_q")


def _direct(func, x, args):
    cs = func(x, **args)
    return np.stack([np.broadcast_to(np.asarray(c, dtype=complex), x.shape) for c in cs], axis=-1)


@pytest.mark.parametrize("name", FOUNDATIONS)
def test_matrix_equals_the_generated_function(name):
    module = importlib.import_module(f"moving_bogie.generated.{name}")
    rng = np.random.default_rng(sum(map(ord, name)))
    args = {a: float(rng.uniform(0.05, 3.0)) for a in module.ARGUMENTS[1:]}
    for fn in FUNCTIONS:
        func = getattr(module, fn)
        cm = CoefficientMatrix(func, args)
        assert cm.matrix is not None, f"{name}.{fn} is a polynomial in its argument"
        x = rng.normal(size=200) * 4 + 1j * rng.normal(size=200) * 4
        if fn == "n_coeffs_in_q":
            x = np.concatenate([x.real, x.real * 1e3])
        got, want = cm(x), _direct(func, x, args)
        m = cm.matrix
        bound = np.abs(x[:, None]) ** np.arange(m.shape[1]) @ np.abs(m).T
        assert got.shape == want.shape
        assert np.all(np.abs(got - want) <= 1e-13 * bound), f"{name}.{fn}"
        # the batch shape is kept, one point and a 2-d batch alike
        assert cm(x[:1]).shape == (1, m.shape[0])
        assert np.array_equal(cm(x[:6].reshape(2, 3)), cm(x[:6]).reshape(2, 3, m.shape[0]))


def test_not_polynomial_falls_back_to_the_function():
    """A coefficient with a division by the variable cannot be a matrix: it is evaluated directly."""

    def rational(q, a):
        return (a * q, 1 / q + a)

    def hidden(q, a):  # polynomial on the probe object but a different function on numbers
        return (q * a if not isinstance(q, np.ndarray) else q * a + 1e-3,)

    x = np.array([0.5 + 1j, 2.0 - 0.25j])
    for func in (rational, hidden):
        cm = CoefficientMatrix(func, {"a": 2.0})
        assert cm.matrix is None
        np.testing.assert_array_equal(cm(x), _direct(func, x, {"a": 2.0}))
    assert Coefficients({"a": 2.0})(rational, x).shape == (2, 2)
