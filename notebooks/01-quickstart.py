# ---
# jupyter:
#   jupytext:
#     formats: py:percent
#     text_representation:
#       extension: .py
#       format_name: percent
#   kernelspec:
#     display_name: Python 3
#     language: python
#     name: python3
# ---

# %% [markdown]
# # Quickstart: a bogie in SI units, from parameters to vibrations
#
# This notebook takes one bogie on one rail, given in SI units, through the whole chain of
# Dimitrovová (2025):
#
# 1. SI parameters -> the dimensionless parameters of Eqs. (15)-(17);
# 2. the induced frequencies (roots of $E_{chr}$, Eq. (48)) and the stability verdict;
# 3. the closed-form time series at the wheels and of the bogie bar (Eqs. (35)-(43)), back in metres,
#    radians and seconds;
# 4. the deflection shape of the beam around the bogie (Eqs. (44)-(47)).
#
# The model (paper, Figure 1b) is planar: one rail on a Winkler foundation with viscous damping, carrying
# a rigid bar (mass $M_b$, pitch inertia $J_b$) on two spring-damper supports ($k_v$, $c_v$) over two
# wheel masses $M$ a distance $d$ apart, each pressed on the rail by a constant load $P$.

# %%
import os
import time

import matplotlib.pyplot as plt
import numpy as np

from moving_bogie import PhysicalParams
from moving_bogie.api import induced_frequencies

QUICK = os.environ.get("MOVING_BOGIE_QUICK", "").lower() in ("1", "true", "yes", "on")

# %% [markdown]
# ## 1. The bogie and the track, in SI units
#
# Because the model is planar and the beam is **one rail**, everything on it is per rail: half a
# wheelset per contact point, half a bogie frame for the bar. The values and where they come from:
#
# | quantity | value | source / assumption |
# |---|---|---|
# | `EI` | 6.38 MN m² | UIC60 (60E1) rail, EN 13674-1: $I_y$ = 3038.3 cm⁴, $E$ = 210 GPa; |
# | | | the paper's range is 4.7-6.4 MN m² (Section 3.4) |
# | `m` | 60.21 kg/m | UIC60 rail mass per metre (EN 13674-1); paper's range 54-60 kg/m |
# | `k_f` | 5 MN/m² | a soft support, in the paper's range 0.22-1000 MN/m² (Section 3.4); assumption |
# | `c_f` | 3.5 kN s/m² | so that $\eta_f \approx 0.1$, in the range the paper explores (0-0.3); assumption |
# | `M` | 900 kg | half of an 1800 kg wheelset (passenger wheelsets: about 1.5-2 t); assumption |
# | `M_b` | 1300 kg | half of a 2.6 t bogie frame ($cf_1 \approx 1.4$; the paper: 1.7-2); assumption |
# | `J_b` | 750 kg m² | half of a 1.5 t m² frame pitch inertia ($cf_2 \approx 0.13$; paper: 0.01-0.1) |
# | `k_v` | 1.2 MN/m | primary vertical spring per axle box; typical order for passenger bogies; assumption |
# | `c_v` | 10 kN s/m | primary vertical damper per axle box; typical order; assumption |
# | `d` | 2.5 m | wheel base of a passenger bogie |
# | `v` | 83.33 m/s | 300 km/h |
# | `P` | 80 kN | wheel load of a 16 t axle load |
#
# The bogie values are assumptions of a typical order of magnitude, not the data of a particular
# vehicle; change them freely. The same parameters can be kept in a TOML file with a `[physical]`
# table and used from the command line: `moving-bogie params --file bogie.toml`.

# %%
bogie = PhysicalParams(
    EI="6.38e6",  # N m^2
    m="60.21",  # kg/m
    k_f="5e6",  # N/m^2
    c_f="3500",  # N s/m^2
    M="900",  # kg, per wheel
    M_b="1300",  # kg
    J_b="750",  # kg m^2
    k_v="1.2e6",  # N/m, per support
    c_v="1e4",  # N s/m, per support
    d="2.5",  # m
    v="83.33",  # m/s
    P="80e3",  # N, per wheel
)
scales = bogie.scales()
params = bogie.to_dimensionless()  # the same conversion closed_form_response makes
print(scales)

# %% [markdown]
# ## 2. The dimensionless parameters (Eqs. (15)-(17), (63))
#
# The reference scales are $\chi = (k_f / 4EI)^{1/4}$ (1/m), $v_{ref} = (4 k_f EI / m^2)^{1/4}$, the
# static deflection under one wheel $w_{st} = P\chi / 2k_f$ and the time unit $\sqrt{m/k_f}$ (Eqs. (15)-(16)).
# The critical velocity of a constant moving force on this beam is $\alpha = 1$, i.e. $v = v_{ref}$ (Eq. (65)
# without a shear layer).

# %%
print(f"chi     = {scales.chi:.4f} 1/m        (a length unit of {1 / scales.chi:.2f} m)")
print(f"v_ref   = {scales.v_ref:.1f} m/s       = {scales.v_ref * 3.6:.0f} km/h: critical velocity (Eq. (65))")
print(f"w_st    = {scales.w_st * 1e3:.3f} mm       static deflection under one wheel load")
print(f"t_scale = {scales.t_scale * 1e3:.3f} ms       tau = t / t_scale\n")
for name, value in params.to_dict().items():
    if value is not None:
        print(f"{name:>8} = {value}")

# The scales and groups above against Eqs. (15)-(17), evaluated here from the SI values
EI, m, k_f, c_f, P = 6.38e6, 60.21, 5e6, 3500.0, 80e3
chi = (k_f / (4 * EI)) ** 0.25
assert np.isclose(scales.chi, chi, rtol=1e-12)
assert np.isclose(scales.v_ref, (4 * k_f * EI / m**2) ** 0.25, rtol=1e-12)
assert np.isclose(scales.w_st, P * chi / (2 * k_f), rtol=1e-12)
assert np.isclose(float(params.alpha), 83.33 / scales.v_ref, rtol=1e-12)
assert np.isclose(float(params.eta_M), 900 * chi / m, rtol=1e-12)
assert np.isclose(float(params.eta_f), c_f / (2 * np.sqrt(m * k_f)), rtol=1e-12)

# %% [markdown]
# The bogie travels at $\alpha \approx 0.19$ of the critical velocity. For comparison, the cases of the
# paper's Table 1 use $\alpha$ = 0.4-0.95, $\eta_M$ = 15-50 and $\kappa_v$ = 0.02-0.2. (A one-layer model with
# the rail's own mass puts the critical velocity of a soft support far above train speeds; on real soft soils
# the critical velocity is set by the soil, which this model does not represent. $\alpha$ closer to 1 needs
# a very soft foundation, $k_f$ near the bottom of the paper's range.)
#
# ## 3. Induced frequencies and the stability verdict
#
# The induced frequencies are the roots $q$ of $E_{chr}(q) = 0$. They come in pairs $q, -q^*$; the
# motion grows like $e^{-\mathrm{Im}\,q\,\tau}$, so it is **unstable as soon as one root has
# $\mathrm{Im}\, q < 0$** (Eq. (35)). The search counts the roots by the argument principle before
# locating them, and prints only digits confirmed at a higher precision.

# %%
start = time.perf_counter()
freq = induced_frequencies(bogie, dps=20 if QUICK else 30)  # SI parameters: the result keeps their scales
print(
    f"found {freq.found} of {freq.count} counted roots in {time.perf_counter() - start:.1f} s; "
    f"count ok: {freq.count_ok}"
)
print(f"verdict: {'stable' if freq.stable else 'UNSTABLE'}\n")
print(f"{'Re q':>12} {'Im q':>12} {'f [Hz]':>9} {'decay [1/s]':>12}")
for root in freq.roots:
    omega = scales.angular_frequency(complex(root.q))  # rad/s, the conjugate of t
    print(
        f"{float(root.q.real):12.6f} {float(root.q.imag):12.6f} "
        f"{omega.real / (2 * np.pi):9.2f} {omega.imag:12.2f}"
    )
assert freq.count_ok and freq.stable
# what the text below says: four pairs q, -conj(q) (one of each listed), all with Im q > 0, at 6-22 Hz
hz = [abs(scales.angular_frequency(complex(root.q)).real) / (2 * np.pi) for root in freq.roots]
assert len(freq.roots) == 4 and all(float(root.q.imag) > 0 for root in freq.roots)
assert 6 <= min(hz) and max(hz) <= 22, hz

# %% [markdown]
# A result of SI parameters shows itself in SI: the last value of a cell, `freq`, is its table in rad/s,
# 1/s and Hz (no dimensionless $q$), and `freq.to_dataframe()` (or `.to_xarray()`) is the same table for
# pandas (xarray), the units of each column in `.attrs["units"]`.

# %%
freq

# %% [markdown]
# Four pairs, all with $\mathrm{Im}\,q > 0$: the vibrations excited when the bogie "appears" on the track at
# $t = 0$ die out, at rates of a few per second. In SI, the induced frequencies lie between about 6 and 22 Hz.
#
# ## 4. Vibrations in time (Eqs. (35)-(43))
#
# `closed_form_response` sums the steady part (Eq. (39)), the residues at every induced frequency and,
# where it matters, the branch-cut integral. Given `PhysicalParams`, it takes times in seconds and
# returns metres and radians. The start is abrupt (homogeneous initial conditions: the loads switch on at
# $t = 0$), which is why the wheels overshoot the static deflection.

# %%
response = None
try:
    from moving_bogie.api import closed_form_response
except ImportError as exc:  # the response feature is not in this installation
    print(f"closed-form response not available: {exc}")
else:
    t = np.linspace(0.0, 0.5, 801)  # seconds
    response = closed_form_response(bogie, t, frequencies=freq)
    fig, axes = plt.subplots(3, 1, figsize=(8, 7), sharex=True, layout="constrained")
    axes[0].plot(t, response["w_rear"] * 1e3, label="rear wheel")
    axes[0].plot(t, response["w_front"] * 1e3, "--", label="front wheel")
    axes[0].axhline(response.steady["w_rear"] * 1e3, color="0.5", lw=0.8, ls=":", label="steady state")
    axes[0].set_ylabel("rail deflection [mm]")
    axes[0].legend(fontsize=8)
    axes[1].plot(t, response["u"] * 1e3)
    axes[1].set_ylabel("bar bounce $u_v$ [mm]")
    axes[2].plot(t, response["theta"] * 1e3)
    axes[2].set_ylabel("bar pitch θ [mrad]")
    axes[2].set_xlabel("t [s]")
    fig.suptitle(f"Closed-form response at {float(bogie.v) * 3.6:.0f} km/h (downward positive)")
    plt.show()
    print(
        f"steady deflection under the wheels: rear {response.steady['w_rear'] * 1e3:.3f} mm, "
        f"front {response.steady['w_front'] * 1e3:.3f} mm; notes: {response.notes or 'none'}"
    )

# %% [markdown]
# ## 5. The deflected rail around the bogie (Eqs. (44)-(47))
#
# `deflection_shape` gives $w(\xi, t)$ along the rail in the moving frame ($\xi$ = 0 at the rear wheel,
# $d$ at the front one), here at a few instants and in the steady state (late time). Ahead of and behind
# the bogie the rail lifts slightly: the familiar uplift of a beam on an elastic foundation.

# %%
try:
    from moving_bogie.api import deflection_shape
except ImportError as exc:
    print(f"deflection shapes not available: {exc}")
else:
    x = np.linspace(-8.0, 10.5, 61 if QUICK else 181)  # metres, moving frame
    fig, ax = plt.subplots(figsize=(8, 3.5), layout="constrained")
    for when in (0.02, 0.06, 0.5):
        w = deflection_shape(bogie, x, when, frequencies=freq)
        ax.plot(x, w * 1e3, label=f"t = {when:g} s")
    for xw in (0.0, float(bogie.d)):
        ax.axvline(xw, color="0.5", lw=0.8, ls=":")
    ax.invert_yaxis()
    ax.set_xlabel("distance from the rear wheel [m] (travel to the right)")
    ax.set_ylabel("deflection [mm] (down)")
    ax.legend(fontsize=8)
    plt.show()

# %% [markdown]
# ## Where next
#
# * `02-table2.py`: the paper's Table 2 recomputed with confirmed digits.
# * `03-vibrations-and-validation.py`: the closed form against a finite beam.
# * `04-instability-lines.py`: where in (velocity, mass) the motion becomes unstable.
# * `05-change-the-model.py`: add a foundation model in `derivations/` and rerun the analysis.
# * The same from the command line: `moving-bogie params --file bogie.toml`, `moving-bogie frequencies
#   --file bogie.toml` (`moving-bogie COMMAND --help`, or the command line reference of the documentation
#   site).
