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
# # Parameter sweeps: a 3-D stability sweep explored with xarray
#
# `moving_bogie.sweep` computes the stability verdict (is there an induced frequency with Im q < 0,
# Eq. (35)?) at every point of a grid of any parameters, on Dask (a small sweep in this process), into a
# zarr store that xarray reads.
# Here: Case 1 of Table 1 over the velocity `alpha`, the wheel mass `eta_M` and the foundation damping
# `eta_f`. The same sweep from the command line:
#
# ```
# moving-bogie sweep --case 1 --vary alpha=0.5:1.15:60 --vary eta_M=2:120:60 \
#     --vary eta_f=0.03,0.06,0.1,0.2 --out sweep.zarr
# ```
#
# Every point's verdict is the one `induced_frequencies` gives there: whole columns of `eta_M` are counted
# at once by the argument principle, and points that count cannot settle get a full count (see
# `docs/sweeps.md`). Points no method could certify have `certain = False`.

# %%
import os
import tempfile
from fractions import Fraction
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

from moving_bogie import table1_case
from moving_bogie.api import induced_frequencies
from moving_bogie.sweep import sweep
from moving_bogie.sweep.plots import plot_sweep_slice

QUICK = os.environ.get("MOVING_BOGIE_QUICK", "").lower() in ("1", "true", "yes", "on")
n = 12 if QUICK else 60
folder = Path(tempfile.mkdtemp())
# quick mode's 576 points run in this process (a sweep of fewer than IN_PROCESS_POINTS = 1000 points: a
# cluster's start-up would cost more than they do); the full 14,400 on a local cluster, a process per core
ds = sweep(
    table1_case(1),
    {"alpha": f"0.5:1.15:{n}", "eta_M": f"2:120:{n}", "eta_f": "0.03,0.06,0.1,0.2"},
    folder / "sweep.zarr",
).load()  # small enough to hold in memory; a large store stays lazy (dask) until computed
ds  # noqa: B018 (the notebook shows it)

# %% [markdown]
# ## What the store holds
#
# One dimension per varied parameter (float coordinates, exact decimal values in the `exact` attribute),
# the verdict variables, and the base parameters, search window and package version as attributes.

# %%
print({k: v for k, v in ds.attrs.items() if k != "sweep"})
print("exact alpha values:", ds.alpha.attrs["exact"][:3], "...")
print("uncertain points:", int((~ds.certain).sum()), " settled by a full count:", int(ds.settled.sum()))

# %% [markdown]
# ## Fraction of unstable points, per foundation damping
#
# Section 3.5 of the paper finds that foundation damping *aggravates* the subcritical instability: the
# instability lines move to lower masses as eta_f grows. The last line below says whether this sweep's
# subcritical unstable fraction grows with eta_f too.

# %%
unstable = ds.n_unstable > 0
print(unstable.mean(dim=("alpha", "eta_M")).to_series().round(3))
subcritical = unstable.sel(alpha=slice(None, 0.999))
fraction = subcritical.mean(dim=("alpha", "eta_M"))
print("subcritical unstable fraction:")
print(fraction.to_series().round(3))
print("grows with eta_f:", bool((fraction.diff("eta_f") > 0).all()))

# %% [markdown]
# ## The lowest unstable velocity for each wheel mass and damping
#
# `argmax` along `alpha` of the unstable mask gives the first unstable velocity; masses that stay stable
# over the whole range get NaN.

# %%
first = ds.alpha[unstable.argmax(dim="alpha")].where(unstable.any(dim="alpha"))
fig, ax = plt.subplots(figsize=(6, 4))
for eta_f in ds.eta_f.values:
    ax.plot(ds.eta_M, first.sel(eta_f=eta_f), marker=".", label=f"eta_f = {eta_f:g}")
ax.set_xlabel("eta_M")
ax.set_ylabel("lowest unstable alpha")
ax.legend()

# %% [markdown]
# ## Slices with the instability boundary
#
# `plot_sweep_slice` (or `moving-bogie sweep-plot sweep.zarr --x alpha --y eta_M --sel eta_f=0.1`) draws
# the degree of instability with the boundary between stable and unstable points.

# %%
plot_sweep_slice(ds, "alpha", "eta_M", {"eta_f": 0.1})

# %% [markdown]
# ## One point against the full root search
#
# The verdict at any point equals `induced_frequencies` at the same exact parameters.

# %%
i, j, k = n // 2, n // 3, 1
exact = {
    name: Fraction(ds[name].attrs["exact"][idx]) for name, idx in (("alpha", i), ("eta_M", j), ("eta_f", k))
}
point = ds.isel(alpha=i, eta_M=j, eta_f=k)
ref = induced_frequencies(table1_case(1).replace(**exact), dps=20)
print(exact)
print("sweep:", int(point.n_unstable), float(point.degree_of_instability))
print("induced_frequencies:", len(ref.unstable_roots), float(ref.degree_of_instability))
assert int(point.n_unstable) == len(ref.unstable_roots)
assert np.isclose(float(point.degree_of_instability), float(ref.degree_of_instability), atol=1e-9)

# %% [markdown]
# The store was written to a temporary folder; remove it (the data above stay in memory).

# %%
import shutil  # noqa: E402

shutil.rmtree(folder)
