"""Brent's method of kernels/brent.py against SciPy's ``brentq`` (the reference): the same root, bit for bit,
with the same number of evaluations, on smooth, steep, flat and piecewise functions and the tolerances the
cut tracing uses."""

from __future__ import annotations

import math

import numpy as np
import pytest

from moving_bogie.kernels.brent import brentq

FUNCTIONS = [
    (lambda x: x**3 - 2 * x - 5, 2.0, 3.0),
    (lambda x: math.cos(x) - x, 0.0, 1.0),
    (lambda x: math.exp(x) - 1e6, 0.0, 20.0),
    (lambda x: math.atan(1e6 * (x - 0.3)), 0.0, 1.0),  # steep
    (lambda x: (x - 0.7) ** 5, 0.0, 1.0),  # flat: a root of multiplicity 5
    (lambda x: x - 0.25 if x < 0.5 else x - 0.25 + 3 * (x - 0.5), 0.0, 2.0),  # a kink
    (lambda x: math.sin(1 / x), 0.2, 0.5),
    (lambda x: -x + 1e-300, -1.0, 1.0),
]


@pytest.mark.parametrize("k", range(len(FUNCTIONS)))
@pytest.mark.parametrize("tols", [(1e-15, 1e-15), (2e-12, 4 * np.finfo(float).eps), (1e-6, 1e-10)])
def test_brentq_equals_scipy_bit_for_bit(k, tols):
    from scipy import optimize  # imported where used: every worker collects this module

    f, a, b = FUNCTIONS[k]
    xtol, rtol = tols
    calls: dict[str, list[float]] = {"ours": [], "scipy": []}

    def counted(who):
        def g(x, shift=0.0):
            calls[who].append(x)
            return f(x) + shift

        return g

    outcome = {}
    for who, solve in (("ours", brentq), ("scipy", optimize.brentq)):
        try:
            outcome[who] = solve(counted(who), a, b, args=(0.0,), xtol=xtol, rtol=rtol)
        except RuntimeError:  # no convergence in 100 iterations (the root of multiplicity 5)
            outcome[who] = None
    assert outcome["ours"] == outcome["scipy"]
    assert calls["ours"] == calls["scipy"]  # the same iterates


def test_brentq_random_cubics_equal_scipy():
    from scipy import optimize  # imported where used: every worker collects this module

    rng = np.random.default_rng(7)
    for _ in range(200):
        c = rng.normal(size=4)
        f = np.polynomial.Polynomial(c)
        a, b = -3.0, 3.0
        if f(a) * f(b) >= 0:
            continue

        def g(x: float, f: np.polynomial.Polynomial = f) -> float:
            return float(f(x))

        assert brentq(g, a, b, xtol=1e-15, rtol=1e-15) == optimize.brentq(g, a, b, xtol=1e-15, rtol=1e-15)


def test_brentq_refuses_a_bracket_without_a_sign_change():
    with pytest.raises(ValueError):
        brentq(lambda x: x * x + 1, -1.0, 1.0)
