"""The decaying roots of a vehicle on the soil, on the physical sheet (roots/decaying_band.py).

References: the singular lines of a Kelvin-Voigt half-space in closed form (the branch points and the
Rayleigh pole of chi at a real wavenumber, solved here from omega^2 = k^2 c^2 (1 + i omega eta)), which
the band's depth must stay under; and the continuous Winkler track of k_ref by residues
(roots/frequencies.py, no code of soil/ in it), whose decaying root the band must find on a ballasted track
over a stiff soil (the case of tests/test_soil_search.py, its module docstring).
"""

from __future__ import annotations

import copy

import mpmath
import numpy as np
import pytest

from moving_bogie.soil.profile import SoilLayer, SoilProfile


def _half_space(c_s: float, nu: float, eta: float) -> SoilProfile:
    rho = 1900.0
    mu = rho * c_s**2
    lam = 2 * mu * nu / (1 - 2 * nu)
    return SoilProfile((SoilLayer(np.inf, rho, mu, lam, eta),))


def _line(c: float, eta: float, k: np.ndarray, v: float) -> np.ndarray:
    """Omega = omega - k v of the free wave of speed c (undamped) at real k: omega^2 = k^2 c^2 (1 + i omega
    eta), the root with Re omega > 0 (Kelvin-Voigt scales every modulus, so every wave speed alike)."""
    a = k**2 * c**2
    omega = (1j * eta * a + np.sqrt(4 * a - eta**2 * a**2 + 0j)) / 2
    return omega - k * v


@pytest.mark.parametrize("v", [20.0, 50.0, 150.0])
def test_the_soil_depth_stays_under_the_singular_lines(v: float) -> None:
    from moving_bogie.soil.sheet import soil_depth

    soil = _half_space(60.0, 0.33, 2e-3)
    layer = soil.halfspace
    c_r = 0.9335 * layer.c_s  # the Rayleigh speed of nu = 0.33 (the cubic's root, to 4 digits)
    k = np.concatenate([-np.geomspace(1e-3, 10.0, 400), np.geomspace(1e-3, 10.0, 400)])
    lowest = np.inf
    for c in (c_r, layer.c_s, layer.c_p):
        Omega = _line(c, layer.eta, k, v)
        Omega = Omega[Omega.real > 0]
        bound = np.array([soil_depth(soil, v, x) for x in Omega.real])
        assert np.all(Omega.imag >= bound * (1 - 1e-12))
        lowest = min(lowest, float(np.min(Omega.imag / bound)))
    # not vacuous: the Rayleigh line comes within a factor (c_r / (0.87 c_s))^2 (1 + ...)^2 of the bound
    assert lowest < 2.0


def test_no_damping_no_band() -> None:
    from moving_bogie.soil.sheet import soil_depth

    assert soil_depth(_half_space(60.0, 0.33, 0.0), 50.0, 100.0) == 0.0


@pytest.mark.slow
def test_stiff_soil_band_finds_the_winkler_tracks_decaying_root() -> None:
    from test_soil_search import MODEL, STIFF

    from moving_bogie.api import induced_frequencies, soil_vehicle
    from moving_bogie.model.physical import PhysicalParams
    from moving_bogie.soil.file import soil_input

    case = copy.deepcopy(STIFF)
    case["soil"][0]["eta"] = 1e-3  # damping that puts the soil's singular lines below the band
    vehicle = soil_vehicle(soil_input(case))
    got = induced_frequencies(vehicle, band_steps=3)
    si = {key: float(getattr(vehicle.physical, key)) for key in vehicle.physical.units()}
    winkler = PhysicalParams(beam="eb", vehicle="bogie", **(si | {"c_f": STIFF["physical"]["c_pad"]}))
    ref = [complex(r.q) for r in induced_frequencies(winkler).roots if mpmath.im(r.q) > 0]
    band = got.band
    assert band is not None and band.rects
    inside = [q for q in ref if any(r.contains(q, 0.0) for r in band.rects)]
    assert band.count == len(band.roots) == len(inside) >= 1
    for root in band.roots:
        q = complex(root.q)
        q_ref = min(inside, key=lambda z: abs(z - q))
        assert abs(q - q_ref) <= 10.0**-root.decimals + MODEL * abs(q_ref)
    assert band.margin == pytest.approx(min(float(mpmath.im(r.q)) for r in band.roots))


#: A bogie with an undamped suspension on a ballasted track on a soft, lossy half-space: its bounce mode
#: decays slowly, under the soil's singular lines (found at about 68 + 2i rad/s).
SOFT_BOGIE = {
    "model": {"track": "ballasted-soil", "vehicle": "bogie"},
    "physical": {
        "EI": 1.29e7, "m": 120.0, "k_pad": 5e8, "c_pad": 2.5e5, "m_s": 490.0, "E_b": 130e6, "rho_b": 1700.0,
        "h_b": 0.35, "A_b": 1.25, "b": 1.25, "P": 1e5, "M": 1360.0, "M_b": 2313.0, "J_b": 4.37,
        "k_v": 5.67e6, "c_v": 0.0, "d": 0.567, "v": 30.0,
    },
    "soil": [{"rho": 1900.0, "c_s": 100.0, "nu": 0.33, "eta": 1e-2}],
}  # fmt: skip


@pytest.mark.slow
def test_soft_soil_band_against_a_grid_of_winding_numbers() -> None:
    from moving_bogie.api import bind_with_scales, soil_vehicle
    from moving_bogie.roots.count.contour import winding_number
    from moving_bogie.roots.decaying_band import decaying_band
    from moving_bogie.roots.quadrature_window import COUNT_TOL, QuadratureCharacteristic
    from moving_bogie.soil.file import soil_input

    bound = bind_with_scales(soil_vehicle(soil_input(SOFT_BOGIE)))[0]
    E = QuadratureCharacteristic(bound)
    band = decaying_band(E, 200.0 / bound.track.omega_0)  # Re omega from 50 to 200 rad/s
    assert band.count is not None and band.count == len(band.roots) >= 1
    # the reference: the winding number of the same E_chr along every cell of a 3 x 2 grid over each
    # rectangle (brute force, cells sampled on their own)
    cells, total = [], 0
    for rect in band.rects:
        xs, ys = np.linspace(rect.x0, rect.x1, 4), np.linspace(rect.y0, rect.y1, 3)
        for i in range(3):
            for j in range(2):
                cell = type(rect)(xs[i], xs[i + 1], ys[j], ys[j + 1])
                with E.tolerance(COUNT_TOL):
                    n = winding_number(E, cell, spacing=cell.width / 6, max_points=4000)
                cells.append((cell, n))
                total += n
    assert total == band.count
    for root in band.roots:
        q = complex(root.q)
        assert q.imag > 0
        assert [n for cell, n in cells if cell.contains(q, 0.0)] == [1]


def test_the_margin_needs_a_matched_count() -> None:
    """The band's margin is the least Im q of its roots only when every rectangle's count stands and the
    roots located match it; the statement says which rectangles were searched and what was not."""
    from moving_bogie.roots.count.contour import Rectangle
    from moving_bogie.roots.decaying_band import DecayingBand
    from moving_bogie.roots.frequency_result import InducedFrequency

    rects = (Rectangle(1.0, 2.0, 0.0, 0.1), Rectangle(0.5, 1.0, 0.0, 0.02))
    root = InducedFrequency(mpmath.mpc(1.5, 0.04), "above", 1, mpmath.mpf(0), 6, 6)
    band = DecayingBand(rects, (1, 0), (root,), (), 0.5, 100.0)
    assert band.margin == pytest.approx(0.04) and band.to_dict()["margin_1_s"] == pytest.approx(4.0)
    assert "1 decaying root(s)" in band.statement() and "Re omega < 50 rad/s" in band.statement()
    assert DecayingBand(rects, (1, 1), (root,), (), 0.5, 100.0).margin is None  # one root missing
    assert DecayingBand(rects, (None, 0), (), (), 0.5, 100.0).margin is None  # a count not established
    undamped = DecayingBand((), (), (), (), 2.0, 100.0, damped=False)
    assert undamped.margin is None and "not searched" in undamped.statement()
