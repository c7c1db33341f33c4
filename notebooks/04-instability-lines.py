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
# # Instability lines: where the moving bogie becomes unstable
#
# With foundation damping ($\eta_f > 0$) the cut of $K$ lies at $\mathrm{Im}\,q = \eta_f > 0$, so the number
# of unstable induced frequencies ($\mathrm{Im}\,q < 0$) can only change where a root of $E_{chr}$ crosses the
# **real** $q$-axis. The paper (Section 3.5) traces these crossings, the *instability lines*, in the plane of
# the velocity $\alpha$ and the wheel mass $\eta_M$, instead of using the D-decomposition method. This
# notebook computes them with `moving_bogie.stability.lines.instability_lines.instability_lines` for the
# settings of Figures 3, 4, 7 and 8 (a figure's panels together, with `instability_lines_many`: the same
# lines as panel by panel, in fewer and larger evaluations), then maps the degree of instability over the
# same plane (`moving_bogie.stability.maps.map.stability_map`) and checks a point of the map against the
# root search.
#
# Quick mode (`MOVING_BOGIE_QUICK=1`, used in the test suite) uses coarser seed grids and continuation steps
# (those of `moving-bogie reproduce --quick`), fewer wheel spacings and fewer panels. `moving-bogie reproduce`
# rebuilds the paper's figures at full resolution.

# %%
import os
import time

import matplotlib.pyplot as plt
import numpy as np

from moving_bogie import DimensionlessParams, table1_case
from moving_bogie.api import induced_frequencies, instability_lines, instability_lines_many, stability_map

QUICK = os.environ.get("MOVING_BOGIE_QUICK", "").lower() in ("1", "true", "yes", "on")
GRID = dict(alpha_step=0.02, q_step=0.01, h_max=0.02) if QUICK else dict(alpha_step=0.01, q_step=0.004)
ETA_MAX = 200.0  # the paper extends the vertical axis to eta_M = 200 ("already only an academic value")


def spacings(last):
    """The paper's d = 1 : 0.25 : last (quick mode: every other one)."""
    ds = list(np.arange(1.0, last + 1e-9, 0.25))
    return ds[::2] if QUICK else ds


COLORS = dict(zip(np.arange(1.0, 2.26, 0.25), plt.cm.viridis(np.linspace(0, 0.9, 6))))


def base(**changes):
    """A bogie (or two masses) with everything but alpha and eta_M fixed (those two are the plane's axes)."""
    values = dict(eta_f="0.05", eta_M=20, d=1, cf1="1.7", cf2="0.01", kappa_v="0.02", eta_v=0, alpha="0.5")
    values.update(changes)
    return DimensionlessParams.from_coefficients(**{k: str(v) for k, v in values.items()})


def draw(ax, lines, *, style="-", scale=1.0, label_suffix=""):
    """Plot every branch of `lines` (eta_M divided by `scale`), one color per wheel spacing."""
    seen = set()
    for b in lines.branches:
        d = round(b.d, 2)
        label = f"d = {d:g}{label_suffix}" if (d, style) not in seen else None
        seen.add((d, style))
        ax.plot(b.alpha, b.theta / scale, style, color=COLORS[d], lw=1.2, label=label)


def frame(ax, title, alpha_max):
    ax.set_xlim(0, alpha_max)
    ax.set_ylim(0, ETA_MAX)
    ax.set_xlabel("α = v / v_ref")
    ax.set_ylabel("η_M")
    ax.set_title(title, fontsize=10)
    ax.grid(True, lw=0.3)


timings = {}

# %% [markdown]
# ## Figure 3: two moving masses, and foundation damping makes it worse
#
# Two equal masses a distance $\tilde d$ apart (paper, Figure 1a). Above a line (or inside a closed
# branch) one more induced frequency is unstable. The paper's conclusion: with increasing $\eta_f$ all
# branches move to **lower** masses and straighten, so more damping in the foundation enlarges the
# unstable region, the opposite of a single moving mass. The black dotted line is the critical velocity
# $\alpha = 1$ (Eq. (65)).

# %%
start = time.perf_counter()
etas = (0.05, 0.3) if QUICK else (0.05, 0.1, 0.15, 0.2, 0.25, 0.3)
fig, axes = plt.subplots(1, len(etas), figsize=(4.2 * len(etas), 3.8), layout="constrained", squeeze=False)
# the panels are traced together (instability_lines_many): each panel's lines are those instability_lines
# gives it alone, in fewer, larger evaluations of E_chr
panels = instability_lines_many(
    [
        (
            base(eta_f=eta_f).replace(vehicle="masses"),
            dict(spacings=spacings(2.25), theta_max=ETA_MAX, **GRID),
        )
        for eta_f in etas
    ]
)
for ax, eta_f, lines in zip(axes[0], etas, panels):
    draw(ax, lines)
    ax.axvline(1.0, color="k", ls=":", lw=1)
    frame(ax, f"two masses, η_f = {eta_f:g}", 1.2)
axes[0][0].legend(fontsize=7)
plt.show()
timings["Figure 3"] = time.perf_counter() - start

# %% [markdown]
# ## Figure 4: a bogie against two masses of the same total mass
#
# The bogie has $cf_1 = 1.7$ (bar mass $1.7\,M$), a small pitch inertia $cf_2 = 0.01$ and a soft suspension
# $\kappa_v = 0.02$, "to make its influence as less as possible". For a fair comparison the two masses carry
# the bogie's total mass $(2 + cf_1) M$, i.e. each is $(1 + cf_1/2)$ times a wheel: their lines are drawn
# against the wheel mass $\eta_M$ of the equivalent bogie (the paper's "a", adapted). Below the critical
# velocity the bogie's lines lie above the masses' ones, so the bogie is the safer vehicle, except for the
# smallest spacing $\tilde d = 1$, as the paper notes (its Case 1 is such a bogie).

# %%
start = time.perf_counter()
etas = (0.05,) if QUICK else (0.05, 0.1, 0.15, 0.2, 0.25, 0.3)
adapt = 1 + 1.7 / 2  # two masses of the bogie's total mass: eta_M(masses) = (1 + cf1/2) eta_M(bogie)
fig, axes = plt.subplots(1, len(etas), figsize=(4.6 * len(etas), 3.8), layout="constrained", squeeze=False)
common = dict(spacings=spacings(2.25), alpha_range=(0, 1), **GRID)
requests = []
for eta_f in etas:
    requests.append((base(eta_f=eta_f), dict(common, theta_max=ETA_MAX)))
    requests.append((base(eta_f=eta_f).replace(vehicle="masses"), dict(common, theta_max=ETA_MAX * adapt)))
panels = instability_lines_many(requests)
for ax, eta_f, bogie, masses in zip(axes[0], etas, panels[::2], panels[1::2]):
    draw(ax, bogie)
    draw(ax, masses, style="--", scale=adapt, label_suffix=" (a)")
    frame(ax, f"bogie (full) vs masses (dashed), η_f = {eta_f:g}", 1.0)
axes[0][0].legend(fontsize=7, ncol=2)
plt.show()
timings["Figure 4"] = time.perf_counter() - start

# %% [markdown]
# ## Figure 7: suspension damping helps, most with a heavy bar
#
# Now a stiffer suspension $\kappa_v = 0.2$ and weak foundation damping $\eta_f = 0.05$; full lines without
# suspension damping, dashed lines with $\eta_v = 0.05$. With the larger pitch inertia $cf_2 = 0.1$ (a),
# the damped suspension removes practically every line from the subcritical range.

# %%
start = time.perf_counter()
cf2s = (0.1,) if QUICK else (0.1, 0.01)
fig, axes = plt.subplots(1, len(cf2s), figsize=(4.8 * len(cf2s), 3.8), layout="constrained", squeeze=False)
styles = ((0, "-"), (0.05, "--"))
options = dict(spacings=spacings(2.0), alpha_range=(0, 1), theta_max=ETA_MAX, **GRID)
panels = iter(
    instability_lines_many(
        [(base(cf2=cf2, kappa_v="0.2", eta_v=eta_v), options) for cf2 in cf2s for eta_v, _ in styles]
    )
)
for ax, cf2 in zip(axes[0], cf2s):
    for eta_v, style in styles:
        draw(ax, next(panels), style=style, label_suffix=f", η_v = {eta_v:g}")
    frame(ax, f"cf_2 = {cf2:g}: η_v = 0 (full), 0.05 (dashed)", 1.0)
axes[0][0].legend(fontsize=7)
plt.show()
timings["Figure 7"] = time.perf_counter() - start

# %% [markdown]
# ## Figure 8: Euler-Bernoulli or Timoshenko-Rayleigh
#
# The same bogie ($cf_2 = 0.1$, $\kappa_v = 0.2$, $\eta_v = 0$) on a Timoshenko-Rayleigh beam (dashed):
# $\tilde S = 100$, $\tilde r = 0.03$ for a soft foundation and $\tilde S = 10$, $\tilde r = 0.09$ for a stiff
# one (Eq. (59)). For the soft foundation the two beam theories practically coincide.

# %%
start = time.perf_counter()
beams = ((100, 0.03),) if QUICK else ((100, 0.03), (10, 0.09))
fig, axes = plt.subplots(1, len(beams), figsize=(4.8 * len(beams), 3.8), layout="constrained", squeeze=False)
for ax, (S, r) in zip(axes[0], beams):
    p = base(cf2="0.1", kappa_v="0.2")
    kw = dict(spacings=spacings(2.25), alpha_range=(0, 1), theta_max=ETA_MAX, **GRID)
    draw(ax, instability_lines(p, **kw), label_suffix=", E-B")
    draw(
        ax,
        instability_lines(p.replace(beam="tr", S=S, r=str(r)), **kw),
        style="--",
        label_suffix=", T-R",
    )
    frame(ax, f"E-B (full) vs T-R (dashed), S = {S}, r = {r}", 1.0)
axes[0][0].legend(fontsize=7, ncol=2)
plt.show()
timings["Figure 8"] = time.perf_counter() - start

# %% [markdown]
# ## A stability map, and a check against the root search
#
# The instability lines only say where the number of unstable roots changes. `stability_map` counts the
# unstable induced frequencies on a whole grid (argument principle below the cut) and returns the degree of
# instability, the most negative $\mathrm{Im}\,q$. The lines must be the boundaries of the coloured regions.
# Here: the bogie of Figure 4 with $\tilde d = 1$, $\eta_f = 0.1$, the parameters of Case 1 (which is the
# point $\alpha = 0.8$, $\eta_M = 20$, marked).

# %%
start = time.perf_counter()
p = base(eta_f="0.1")
alphas = np.linspace(0.02, 1.2, 20 if QUICK else 120)
thetas = np.linspace(2.0, ETA_MAX, 20 if QUICK else 120)
smap = stability_map(p, alphas=alphas, thetas=thetas, workers=1)
lines = instability_lines(p, theta_max=ETA_MAX, **GRID)
fig, ax = plt.subplots(figsize=(6.5, 4.5), layout="constrained")
degree = np.where(smap.degree < 0, -smap.degree, np.nan)
mesh = ax.pcolormesh(
    smap.alphas, smap.thetas, degree, shading="nearest", cmap="magma_r", norm=plt.matplotlib.colors.LogNorm()
)
fig.colorbar(mesh, ax=ax, label="degree of instability  −min Im q")
for b in lines.branches:
    ax.plot(b.alpha, b.theta, "c-", lw=1.5)
ax.plot([0.8], [20], "w*", ms=12, mec="k")
ax.axvline(1.0, color="k", ls=":", lw=1)
frame(ax, "bogie, d = 1, η_f = 0.1: unstable where coloured; instability lines in cyan", 1.2)
plt.show()
timings["stability map"] = time.perf_counter() - start

# The map at Case 1 against the full root search with confirmed digits
case1 = p.replace(alpha="0.8", eta_M=20)
roots = induced_frequencies(case1, dps=20)
i, j = np.argmin(abs(smap.alphas - 0.8)), np.argmin(abs(smap.thetas - 20))
print(
    f"root search at Case 1: {'stable' if roots.stable else 'UNSTABLE'}, "
    f"degree {float(roots.degree_of_instability):.6f} (Table 2: -0.000130)"
)
print(
    f"map at alpha = {smap.alphas[i]:.3f}, eta_M = {smap.thetas[j]:.1f}: unstable roots {smap.count[j, i]}, "
    f"degree {smap.degree[j, i]:.6f}"
)
# Checks: the root search gives Table 2's printed Im q of Case 1 (root 2: -0.000130, to its 6 decimals);
# the parameters built here are Case 1 of Table 1 exactly.
assert case1 == table1_case(1)
assert not roots.stable and abs(float(roots.degree_of_instability) - (-0.000130)) <= 5e-7

# %% [markdown]
# ## Explore: how the damping moves the lines
#
# With `ipywidgets` installed (`pip install -e '.[notebook]'`) the slider below redraws the lines of two
# masses for any $\eta_f$. Without it (or when the notebook runs headless, as in the tests) the same
# function is drawn for a few fixed values.


# %%
def lines_for(eta_f=0.1, d=1.5):
    lines = instability_lines(base(eta_f=eta_f, d=d).replace(vehicle="masses"), theta_max=ETA_MAX, **GRID)
    fig, ax = plt.subplots(figsize=(5, 3.5), layout="constrained")
    for b in lines.branches:
        ax.plot(b.alpha, b.theta, "-", color="C0")
    ax.axvline(1.0, color="k", ls=":", lw=1)
    frame(ax, f"two masses, d = {d:g}, η_f = {eta_f:g}", 1.2)
    plt.show()


try:
    import ipywidgets
except ImportError:
    ipywidgets = None

if ipywidgets is not None:
    ipywidgets.interact(
        lines_for,
        eta_f=ipywidgets.FloatSlider(value=0.1, min=0.01, max=0.3, step=0.01, description="η_f"),
        d=ipywidgets.FloatSlider(value=1.5, min=1.0, max=2.5, step=0.25, description="d"),
    )
else:
    print("ipywidgets is not installed: static views instead of a slider")
    for eta_f in (0.05, 0.3) if QUICK else (0.05, 0.15, 0.3):
        lines_for(eta_f)

# %%
for name, seconds in timings.items():
    print(f"{name:>14}: {seconds:5.1f} s")
