"""The search for a vehicle's induced frequencies on a track on the soil, end to end (docs/soil.md, "A vehicle
on the soil"): the soil file read, the vehicle bound to the soil's receptance (Eq. (S9), strip quadratures of
the layered soil's flexibility), the window counted and searched (roots/quadrature_window.py), the verdict.

Reference: the continuous Winkler track of roots/frequencies.py (kernel by residues of a rational function,
roots confirmed at 30 digits), no code of soil/ in it. A ballasted track whose railpads carry the damping
(k_pad + i omega c_pad), on a ballast rod and a soil both a million times stiffer than the pads, is the
Winkler track of k_f = k_ref, c_f = c_pad to a few parts in 10^6: the support is the pads, the rod and the
strip's chi in series, k_pad k_b chi / (k_pad k_b + ...), with E_b A_b / h_b = 5e14 N/m^2 and chi >= 2e14
N/m^2 (mu = 9.8e14 Pa, chi ~ pi mu / ((1 - nu) ln(2 / (k b)))) against |k_pad + i omega c_pad| <= 6e8 N/m^2
in the window, and a massless rod (rho_b = 1e-3). The vehicle is the bogie of Table 1's case 1 in SI
(alpha = 0.7995, eta_f = 0.1000, ...): one growing root, a weak instability (Im q = -1.3e-4).
"""

from __future__ import annotations

import mpmath
import pytest

from moving_bogie.api import induced_frequencies, soil_vehicle
from moving_bogie.model.physical import PhysicalParams
from moving_bogie.roots.verdict import UNSTABLE
from moving_bogie.soil.file import soil_input

STIFF = {
    "model": {"track": "ballasted-soil", "vehicle": "bogie"},
    "physical": {
        "EI": 1.29e7, "m": 120.0, "k_pad": 5e8, "c_pad": 4.9e4, "m_s": 0.0, "E_b": 1.4e14, "rho_b": 1e-3,
        "h_b": 0.35, "A_b": 1.25, "b": 1.25, "P": 1e5,
        "M": 1360.0, "M_b": 2313.0, "J_b": 4.37, "k_v": 5.67e6, "c_v": 0.0, "d": 0.567, "v": 925.0,
    },
    "soil": [{"rho": 2000.0, "c_s": 7e5, "nu": 0.33, "eta": 1e-6}],
}  # fmt: skip
#: The kernel of the stiff track differs from the Winkler track's by |k_p| / k_b + |k_p| / chi <= 4e-6 of
#: it (module docstring); a simple root moves by about as much, relative.
MODEL = 4e-6


@pytest.mark.slow
def test_vehicle_on_a_stiff_soil_has_the_winkler_tracks_growing_root():
    vehicle = soil_vehicle(soil_input(STIFF))
    got = induced_frequencies(vehicle)
    # the reference: the same SI vehicle on the Winkler track of k_ref with the pads' damping
    si = {key: float(getattr(vehicle.physical, key)) for key in vehicle.physical.units()}
    winkler = PhysicalParams(beam="eb", vehicle="bogie", **(si | {"c_f": STIFF["physical"]["c_pad"]}))
    ref = induced_frequencies(winkler)
    growing = [complex(r.q) for r in ref.roots if mpmath.im(r.q) < 0]
    assert ref.verdict.state == got.verdict.state == UNSTABLE
    assert got.far_field is not None and got.far_field.radius is not None
    window = got.window
    inside = [q for q in growing if window.contains(q, 0.0)]
    assert got.count == len(got.roots) == len(inside) == len(growing) == 1
    q, q_ref = complex(got.roots[0].q), inside[0]
    assert abs(q - q_ref) <= 10.0 ** -got.roots[0].decimals + MODEL * abs(q_ref)
    assert q.imag < -MODEL * abs(q_ref)
