"""A vehicle added in derivations/ only: a three-axle bogie, regenerated and analysed with no runtime edit.

The scratch vehicle is a frame (M_b, J_b) on three primary suspensions (k_v, c_v) over three wheels (M, P)
at 0, d and 2 d, declared in a temporary copy of derivations/vehicles.py. References, independent of the
search: Newton's method on E_chr from every local minimum of |E_chr| on a dense grid (every root it
reaches must be among the roots found), and the argument principle on a small circle around each root
found (a contour other than the search's tiling).
"""

from __future__ import annotations

import mpmath
import numpy as np
import pytest
from derivation_support import regenerated_copy, require_sympy

from moving_bogie import DimensionlessParams, table1_case
from moving_bogie.api import induced_frequencies
from moving_bogie.kernels.bound import bind
from moving_bogie.kernels.characteristic import Characteristic, CharacteristicArray
from moving_bogie.model.catalogue import Model, load_catalogue

require_sympy()

VEHICLE = '''

def three_axle() -> Vehicle:
    """A three-axle bogie: a frame on three primary suspensions over three wheels d apart."""
    d = s.d_phys
    return Vehicle(
        three_axle.__doc__.splitlines()[0],
        tuple(Wheel(f"w_{j + 1}", s.M, j * d) for j in range(3)),
        (Body("u", s.M_b, d, s.J_phys, "theta"),),
        tuple(Link(f"w_{j + 1}", "u", j * d, s.k_v, s.c_v) for j in range(3)),
    )


VEHICLES["three_axle"] = three_axle
'''


@pytest.fixture(scope="module")
def scratch(tmp_path_factory):
    """A copy of the source tree with the three-axle bogie, regenerated (``--only three_axle``)."""
    return regenerated_copy(
        tmp_path_factory.mktemp("vehicle"), {"vehicles.py": VEHICLE}, only=("three_axle",)
    )


@pytest.fixture(scope="module")
def params(scratch):
    catalogue = load_catalogue(scratch / "src" / "moving_bogie" / "generated")
    model = Model("eb", "one-layer", "three_axle", catalogue)
    values = {k: v for k, v in table1_case(7).to_exact_dict().items() if k in model.parameters}
    return DimensionlessParams(model=model, **(values | {"eta_f": "0.1"}))


@pytest.mark.slow
def test_three_axle_bogie_is_generated(params):
    module = params.model.vehicle_kernels
    assert module.CONTACTS == 3 and module.DOFS == ("w_1", "w_2", "w_3", "u", "theta")
    d = float(params.d)
    assert [
        float(x)
        for x in module.contact_positions(
            **{k: float(params.as_float().__dict__[k]) for k in module.MATRIX_ARGUMENTS}
        )
    ] == [0, d, 2 * d]


@pytest.mark.slow
def test_three_axle_roots_against_a_dense_scan(params):
    result = induced_frequencies(params, dps=20)
    assert result.count_ok and result.verdict.determined, result.verdict.reasons
    found = [complex(r.q) for r in result.roots]
    assert found
    E = CharacteristicArray(bind(params))
    # every root found: one zero on a small circle around it (radius shrunk while it meets the cut of K)
    t = np.linspace(0, 2 * np.pi, 3000, endpoint=False)
    for q in found:
        radius = min([1e-3] + [0.3 * abs(q - o) for o in found if o != q])
        while True:
            values = E(q + radius * np.exp(1j * t))
            steps = np.angle(np.roll(values, -1) / values)
            if np.max(np.abs(steps)) < 1.0:
                break
            radius /= 4
            assert radius > 1e-9
        assert round(np.sum(steps) / (2 * np.pi)) == 1, q
    # every grid minimum that Newton turns into a nearby root is a root found
    x = np.linspace(0.004, 1.5, 400)
    y = np.linspace(-0.3, 0.4, 200)
    X, Y = np.meshgrid(x, y)
    values = np.abs(E(X + 1j * Y))
    inner = values[1:-1, 1:-1]
    is_min = np.ones_like(inner, dtype=bool)
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            if dx or dy:
                is_min &= inner < values[1 + dy : values.shape[0] - 1 + dy, 1 + dx : values.shape[1] - 1 + dx]
    precise = Characteristic(bind(params))
    newton = []
    with mpmath.workdps(20):
        for i, j in zip(*np.nonzero(is_min)):
            start = complex(X[i + 1, j + 1], Y[i + 1, j + 1])
            try:
                q = complex(mpmath.findroot(precise, mpmath.mpc(start), tol=1e-24, maxsteps=50))
            except (ValueError, ZeroDivisionError):
                continue
            if abs(q - start) < 0.05 and q.real > 0:
                newton.append(q)
    assert newton, "the scan found no root"
    for q in newton:
        assert min(abs(q - f) for f in found) < 1e-8, f"scan root {q} not found"
