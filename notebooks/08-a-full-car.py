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
# # A full car: induced frequencies over speed, the car against one of its bogies
#
# A railway car is a body on two bogies on four wheelsets (the 10-DOF model of Zhai & Sun 1994). Here it
# is declared per rail in `derivations/vehicles.py` (vehicle `car`): a body ($M_c$, $J_c$) on two secondary
# suspensions ($k_{sec}$, $c_{sec}$) at the bogie centres, over two bogies ($M_b$, $J_b$) on primary
# suspensions ($k_v$, $c_v$) over four wheels ($M$, load $P$) at $0, d, L_c, L_c + d$. Its characteristic
# function is the determinant of the block system of the four contacts (`kernels/vehicle.py`); no runtime
# code knows the car.
#
# The question: over the speed, does the car become unstable where one of its bogies alone would not,
# or the other way round? The degree of instability is the smallest $\mathrm{Im}\,q$ over the induced
# frequencies (negative: a growing vibration).

# %%
import os
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

from moving_bogie.api import induced_frequencies
from moving_bogie.model.files import load_params_file

QUICK = os.environ.get("MOVING_BOGIE_QUICK", "").lower() in ("1", "true", "yes", "on")
EXAMPLE = Path.cwd().parent / "examples" / "car.toml"
if not EXAMPLE.exists():  # run from the repository root
    EXAMPLE = Path("examples") / "car.toml"

# %% [markdown]
# ## 1. The car of `examples/car.toml` and one of its bogies
#
# The bogie alone carries the same wheels, frame and primary suspension, and the same load per wheel.

# %%
car, _ = load_params_file(EXAMPLE)
values = car.to_exact_dict()
BOGIE = ("eta_f", "eta_s", "eta_M", "d", "mu_v", "J_b", "kappa_v", "eta_v")
bogie = car.replace(vehicle="bogie", **{k: values[k] for k in BOGIE})
print(car.to_dict())

# %% [markdown]
# ## 2. Induced frequencies over the speed
#
# alpha = v / v_ref (Eq. (16)); the example runs at alpha = 0.09 (60 m/s on a soft track). Every search
# counts its roots and checks the far field, so each verdict is about every root with Im q < 0.

# %%
alphas = [0.1, 0.5, 0.9] if QUICK else list(np.round(np.linspace(0.1, 1.3, 13), 3))
rows = []
for alpha in alphas:
    row = {"alpha": alpha}
    for name, params in (("car", car), ("bogie", bogie)):
        result = induced_frequencies(params.replace(alpha=str(alpha)), dps=20)
        ims = [float(r.q.imag) for r in result.roots]
        row[name] = (min(ims) if ims else np.nan, result.verdict.state, len(result.roots))
    rows.append(row)
    print(f"alpha {alpha:5.3f}: car {row['car']}, bogie {row['bogie']}")

# %% [markdown]
# ## 3. Where the car and its bogie become unstable

# %%
fig, ax = plt.subplots(figsize=(7, 4))
for name, style in (("car", "o-"), ("bogie", "s--")):
    ax.plot([r["alpha"] for r in rows], [r[name][0] for r in rows], style, label=name)
ax.axhline(0, color="k", lw=0.8)
ax.set_xlabel(r"$\alpha = v / v_{ref}$")
ax.set_ylabel(r"smallest Im $q$ (negative: unstable)")
ax.legend()
plt.show()
for name in ("car", "bogie"):
    unstable = [r["alpha"] for r in rows if r[name][1] == "unstable"]
    print(name, "first unstable at alpha =", unstable[0] if unstable else "none in the range")

# %% [markdown]
# The two bogies of the car interact only through the rail and through the body; their induced
# frequencies come in close pairs (`tests/test_car.py` counts both members of each pair on small circles).
# The body adds its own low frequencies (bounce and pitch on the secondary suspension).
