"""The soil's surface-wave modes c(omega) (docs/soil.md).

References: the Rayleigh cubic of a homogeneous half-space; two independent dispersion codes used only
here, disba (Dunkin's method) and pysurf96 (surf96, single precision: about 1e-5 relative). Both are
compared where they are reliable: away from a higher mode's cut-off (where Dunkin and surf96 can miss it) and
not with disba's fast-delta algorithm at low frequency (wrong there, its issues 26 and 38).
"""

from __future__ import annotations

import numpy as np
import pytest

from moving_bogie.soil.profile import soil_profile
from moving_bogie.soil.rayleigh import soil_modes

#: A soft layered soil that stiffens with depth (the example of a public critical-speed code).
LAYERED = [
    {"h": 5, "rho": 1900, "E": 2.67e7, "nu": 0.33},
    {"h": 10, "rho": 1900, "E": 1.14e8, "nu": 0.33},
    {"h": 15, "rho": 1900, "E": 2.63e8, "nu": 0.33},
    {"rho": 1900, "E": 4.71e8, "nu": 0.33},
]
#: A stiff crust over a soft layer (inversely dispersive at low frequency).
CRUST = [
    {"h": 2, "rho": 2000, "c_s": 180, "c_p": 400},
    {"h": 6, "rho": 1700, "c_s": 90, "c_p": 1500},
    {"rho": 2000, "c_s": 250, "c_p": 700},
]


@pytest.mark.parametrize("nu", [0.0, 0.25, 0.33, 0.45])
def test_rayleigh_cubic(nu):
    soil = soil_profile([{"rho": 2000.0, "c_s": 100.0, "nu": nu}])
    kappa2 = 2 * (1 - nu) / (1 - 2 * nu)  # (c_p / c_s)^2
    xi = np.roots([1, -8, 24 - 16 / kappa2, -16 * (1 - 1 / kappa2)])
    ref = 100.0 * np.sqrt(min(x.real for x in xi if abs(x.imag) < 1e-12 and 0 < x.real < 1))
    modes = soil_modes(np.array([0.5, 20.0, 700.0]), soil)
    assert modes.c.shape[1] == 1  # one trapped wave, at every frequency
    assert np.allclose(modes.c[:, 0], ref, rtol=1e-11)


def _reference(tables, omega, mode, tool):
    th = np.array([t.get("h", 0.0) for t in tables]) / 1e3
    profile = soil_profile(tables)
    vp = np.array([layer.c_p for layer in profile.layers]) / 1e3
    vs = np.array([layer.c_s for layer in profile.layers]) / 1e3
    rho = np.array([layer.rho for layer in profile.layers]) / 1e3
    period = 2 * np.pi / omega[::-1]
    if tool == "disba":
        disba = pytest.importorskip("disba")
        c = disba.PhaseDispersion(th, vp, vs, rho, algorithm="dunkin", dc=1e-5)(period, mode=mode).velocity
    else:
        pysurf96 = pytest.importorskip("pysurf96")
        c = pysurf96.surf96(th, vp, vs, rho, period, wave="rayleigh", mode=mode + 1, velocity="phase")
    return np.asarray(c)[::-1] * 1e3


# disba compiles its numba kernels at the first call (about 12 s): slow; surf96 runs in the fast subset
@pytest.mark.parametrize(
    ("tool", "rtol"), [pytest.param("disba", 2e-6, marks=pytest.mark.slow), ("pysurf96", 3e-5)]
)
@pytest.mark.parametrize(
    ("tables", "omegas"), [(LAYERED, (31.2, 91.6, 212.4)), (CRUST, (80.0, 150.0, 250.0))]
)
def test_layered_against_independent_codes(tool, rtol, tables, omegas):
    omega = np.array(omegas)
    modes = soil_modes(omega, soil_profile(tables))
    for mode in range(3):
        ref = _reference(tables, omega, mode, tool)
        ok = ref > 0  # surf96 reports 0 where it finds no mode
        assert ok.sum() >= 2
        assert np.allclose(modes.c[ok, mode], ref[ok], rtol=rtol), (mode, modes.c[:, mode], ref)


def test_mode_count_grows_with_frequency():
    """Modes appear at cut-offs and never vanish; a grid 20 times finer finds the same modes (no pair
    of close modes is lost between grid points)."""
    omega, soil = np.linspace(5.0, 300.0, 40), soil_profile(LAYERED)
    modes = soil_modes(omega, soil)
    count = np.isfinite(modes.c).sum(axis=1)
    assert count[0] >= 1 and np.all(np.diff(count) >= 0) and count[-1] > 5
    top = omega[-8:]  # where modes crowd
    modes, fine = soil_modes(top, soil), soil_modes(top, soil, points=2000)
    assert np.array_equal(np.isnan(modes.c), np.isnan(fine.c))
    assert np.allclose(modes.c, fine.c, rtol=1e-10, equal_nan=True)
