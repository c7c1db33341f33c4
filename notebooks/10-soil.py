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
# # A track on the soil: its critical speed, the moving load, and a vehicle that loses stability
#
# On soft ground the critical speed of a railway track is set by the waves of the soil, not by the
# foundation springs: the Rayleigh waves of a soft clay travel at 40-100 m/s. This notebook takes the
# ballasted track of `examples/soil-ballasted.toml` (rails, railpads, sleepers and ballast on a layered
# soil, per track) and the rail on a soft homogeneous half-space of `examples/soil-unstable.toml`
# (docs/soil.md).
#
# 1. The critical speed of the ballasted track: the soil's surface-wave modes, the track's own curve and
#    the coupled guided waves (the dispersion figure).
# 2. The steady deflection under a moving constant load against speed: the dynamic amplification (DAF).
# 3. A heavy mass faster than the critical speed: its growing induced frequency and the threshold mass
#    above which it grows (Metrikine & Popp 1999: the waves it radiates backwards feed its vibration).

# %%
import os
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
from IPython.display import display

import moving_bogie as mb

QUICK = os.environ.get("MOVING_BOGIE_QUICK", "").lower() in ("1", "true", "yes", "on")
EXAMPLES = Path.cwd().parent / "examples"
if not EXAMPLES.exists():  # run from the repository root
    EXAMPLES = Path("examples")
BALLASTED = mb.load_soil_file(EXAMPLES / "soil-ballasted.toml")
print(f"{BALLASTED.track.kind} track, input per {BALLASTED.per}, on {len(BALLASTED.soil.layers)} layers")
for i, layer in enumerate(BALLASTED.soil.layers, start=1):
    h = "half-space" if not np.isfinite(layer.h) else f"h = {layer.h:g} m"
    print(
        f"  layer {i}: {h}, c_s = {layer.c_s:.1f} m/s, c_p = {layer.c_p:.1f} m/s, rho = {layer.rho:g} kg/m^3"
    )

# %% [markdown]
# ## 1. The critical speed of the ballasted track
#
# The coupled critical velocity is the least phase velocity of the guided waves of the track on the soil
# (both undamped); beside it, the estimate of Mezher et al. (2016), where the track's own curve (no soil
# under the ballast) meets the soil's fundamental mode. `moving-bogie critical-velocity --file
# examples/soil-ballasted.toml --plot disp.png` draws the same figure.

# %%
omega = np.geomspace(0.6, 600.0, 16 if QUICK else 32)
crit = mb.soil_critical_velocity(BALLASTED.track, BALLASTED.soil, omega)
modes = mb.soil_modes(omega, BALLASTED.soil)
print(f"coupled critical velocity   v_cr = {crit.v_cr:.2f} m/s ({crit.v_cr * 3.6:.0f} km/h)")
print(f"uncoupled estimate                 {crit.v_cr_uncoupled:.2f} m/s")
print("notes:", list(crit.notes) or "none")
display(mb.dispersion_figure(modes, crit, "ballasted track on a layered soil"))

# %% [markdown]
# ## 2. A moving constant load: the deflection under it against speed
#
# The steady deflection under the file's load P, over its static value: it peaks near the critical
# speed, where the track and the soil resonate with the load (the soil's damping keeps it finite).
# `moving-bogie moving-load --file examples/soil-ballasted.toml --range v=20:120 --plot daf.png`.

# %%
speeds = np.linspace(20.0, 120.0, 11 if QUICK else 41)
daf = mb.moving_load(BALLASTED.track, BALLASTED.soil, BALLASTED.load, speeds)
print(f"static deflection {daf.w_static * 1e3:.3f} mm; peak DAF {daf.daf_peak:.3f} at {daf.v_peak:.2f} m/s")
print(f"the peak speed over the critical velocity: {daf.v_peak / crit.v_cr:.3f}")
display(mb.moving_load_figure(daf, "ballasted track on a layered soil"))

# %% [markdown]
# ## 3. A heavy mass on a soft half-space, faster than the critical speed
#
# `examples/soil-unstable.toml`: a mass on one UIC60 rail lying on a soft homogeneous half-space
# ($c_s$ = 60 m/s, $c_R$ = 56.9 m/s), at 150 m/s. Its induced frequencies are the roots of
# $E_{chr}(\Omega) = 0$ with $\mathrm{Im}\,\Omega \le 0$, counted by the argument principle (no starting
# guess): a root with $\mathrm{Im}\,\Omega < 0$ grows (`moving-bogie frequencies --file ...`).

# %%
HEAVY = mb.load_soil_vehicle(EXAMPLES / "soil-unstable.toml")
result = mb.induced_frequencies(HEAVY)
print(result.verdict.state, "- count", result.count)
print(result.to_dataframe())

# %% [markdown]
# The threshold mass: the D-decomposition in the wheel mass along the real frequency axis gives the masses
# at which a root crosses the real axis, and the direction in which it crosses (`moving-bogie
# instability-lines --file examples/soil-unstable.toml`). Here at a few speeds: below the critical speed
# no root crosses; above it the threshold mass falls as the mass moves faster.

# %%
top = 240e3  # kg per rail: the mass axis 0..top


def threshold_at(v: float) -> float:
    """The threshold mass (kg per rail) of the file's vehicle at speed v (NaN: none up to ``top``)."""
    vehicle = mb.load_soil_vehicle(EXAMPLES / "soil-unstable.toml", settings={"v": v})
    found = mb.threshold_mass(vehicle, M_max=top).threshold
    return float("nan") if found is None else found["M"]


velocities = [150.0] if QUICK else [50.0, 130.0, 150.0, 180.0, 220.0]
thresholds = [threshold_at(v) for v in velocities]
for v, m in zip(velocities, thresholds, strict=True):
    text = "no crossing up to 240 t" if np.isnan(m) else f"{m / 1e3:.2f} t per rail"
    print(f"v = {v:5.0f} m/s: threshold mass {text}")

v_cr = mb.soil_critical_velocity(HEAVY.input.track, HEAVY.input.soil).v_cr
fig, ax = plt.subplots(figsize=(6, 3.5))
ax.plot(velocities, np.array(thresholds) / 1e3, "o-", label="threshold mass")
ax.axvline(v_cr, color="0.5", ls=":", label=f"critical velocity {v_cr:.1f} m/s")
ax.set_xlabel("v [m/s]")
ax.set_ylabel("M [t per rail]")
ax.set_title("above the line the mass's vibration grows")
ax.legend()
plt.show()
