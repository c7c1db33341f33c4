"""Brent's bounded minimisation (kernels/fminbound.py) against SciPy's ``minimize_scalar(method="bounded")``:
the same iterates, so the same point and value and the same number of evaluations."""

from __future__ import annotations

import math

import pytest
from scipy import optimize

from moving_bogie.kernels.fminbound import fminbound

CASES = [
    (lambda x: (x - 0.3) ** 2 + 0.1 * (x - 0.3) ** 3, -1.0, 2.0, 1e-5),  # smooth: parabolic steps
    (lambda x: abs(x - 1.7), 0.0, 3.0, 1e-8),  # a kink: golden sections
    (lambda x: -1.8 / (1 + ((x - 70.4) / 3.0) ** 2), 69.5, 71.5, 2e-4),  # a resonance peak
    (lambda x: math.cos(x), 0.0, 10.0, 1e-6),  # several minima: the one Brent's steps reach
    (lambda x: x, 0.0, 1.0, 1e-6),  # the minimum at an end
]


@pytest.mark.parametrize(("f", "a", "b", "xatol"), CASES)
def test_fminbound_iterates_as_scipy(f, a, b, xatol):
    ours, theirs = [], []
    x, fx = fminbound(lambda t: ours.append(t) or f(t), a, b, xatol=xatol)
    ref = optimize.minimize_scalar(
        lambda t: theirs.append(t) or f(t), bounds=(a, b), method="bounded", options={"xatol": xatol}
    )
    assert ours == theirs
    assert (x, fx) == (ref.x, ref.fun)
