"""Soil-track cases shared by the soil tests (data only, read with ``moving_bogie.soil.file.soil_input``)."""

from __future__ import annotations

#: A wheel mass on a ballasted track over a soil a million times stiffer than the pads (c_s = 1e5 m/s), its
#: pads undamped: the Winkler track of the pads' and ballast's static stiffness is its limit.
RIGID = {
    "model": {"track": "ballasted-soil", "vehicle": "mass"},
    "physical": {
        "EI": 1.29e7, "m": 120.0, "k_pad": 5e8, "c_pad": 0.0, "m_s": 0.0, "E_b": 130e6, "rho_b": 1e-3,
        "h_b": 0.35, "A_b": 1.25, "b": 1.25, "P": 1e5, "M": 3000.0, "v": 60.0,
    },
    "soil": [{"rho": 2000.0, "c_s": 1e5, "nu": 0.33, "eta": 1e-6}],
}  # fmt: skip
