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
# # A bogie on a layered (ballasted) track
#
# The paper's track is one layer. A ballasted track is a UIC60 rail on railpads, over sleepers, on the
# ballast: here the **two-layer track** of `docs/layered_tracks.md` (rail on pads k_1, c_1 over a continuous
# sleeper mass m_2 on the ballast k_2, c_2). It comes from `derivations/` like the paper's track; every
# analysis of the package runs on it unchanged. The scaling takes the pads as the reference stiffness:
# chi, v_ref, w_st and the time scale are Eqs. (15)-(16) with k_1 for k_f.
#
# This notebook: the track's critical velocity (the smallest local minimum of the phase speed over the
# dispersion branches), the induced frequencies of a bogie over the speed, and where a heavy bogie becomes
# unstable, next to the one-layer track with the same pads.

# %%
import io
import os

import numpy as np
from IPython.display import Image, display
from matplotlib.figure import Figure

from moving_bogie.api import induced_frequencies
from moving_bogie.kernels.bound import bind
from moving_bogie.model.physical import PhysicalParams
from moving_bogie.stability.figures.track_comparison import compare_tracks, figure_track_comparison
from moving_bogie.stability.velocity.critical_velocity import critical_velocity, dispersion_branches

QUICK = os.environ.get("MOVING_BOGIE_QUICK", "").lower() in ("1", "true", "yes", "on")


def show(fig):
    """Show a bare matplotlib Figure (no pyplot) as an image."""
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=90)
    display(Image(buffer.getvalue()))


# %% [markdown]
# ## The track and the bogie in SI units (the values of `examples/two-layer.toml`)

# %%
physical = PhysicalParams(
    track="two-layer",
    EI="6.42e6",  # N m^2, UIC60 rail
    m="60.21",  # kg/m
    k_1="3.0e8",  # N/m^2, railpads (180 MN/m per pad, sleepers at 0.6 m)
    c_1="5.0e4",  # N s/m^2
    m_2=245,  # kg/m, sleepers (half a B70 sleeper per 0.6 m)
    k_2="1.5e8",  # N/m^2, ballast and subgrade
    c_2="1.0e5",  # N s/m^2
    P="8.0e4",  # N per wheel
    M=900,  # kg, wheel (half a wheelset)
    M_b=1300,  # kg, half a bogie frame
    J_b=1100,  # kg m^2
    k_v="1.2e6",  # N/m, primary suspension
    c_v="1.0e4",  # N s/m
    d="2.5",  # m, wheelbase
    v=60,  # m/s
)
params = physical.to_dimensionless()
scales = physical.scales()
print(params)
print(f"chi = {scales.chi:.4f} 1/m, v_ref = {scales.v_ref:.1f} m/s, t_scale = {scales.t_scale:.3e} s")

# %% [markdown]
# ## Critical velocity
#
# A constant force resonates where its line Omega = alpha p touches a dispersion branch: a local minimum of
# the phase speed Omega_j(p)/p. The sleeper branch is bounded (it tends to the sleepers' own frequency on
# pads and ballast), so its phase speed falls to 0: that infimum is no critical velocity.

# %%
cv = critical_velocity(params)
print(
    f"alpha_cr = {float(cv.alpha_cr):.12f} on branch {cv.branch} of {cv.branches}, "
    f"v_cr = {float(cv.alpha_cr) * scales.v_ref:.1f} m/s ({cv.digits} digits confirmed)"
)
for m in cv.minima:
    print(f"  local minimum on branch {m.branch}: alpha = {float(m.alpha):.10f} at p = {float(m.p):.6f}")
print("branches without a local minimum:", cv.without_minimum)
one = critical_velocity(params.replace(track="one-layer"))
print(f"one-layer track with the same pads: alpha_cr = {float(one.alpha_cr):.12f}")

# A check of the numbers above, independent of the package's kernels: the dispersion relation of the
# undamped two-layer track in SI units (docs/layered_tracks.md, (L1)), free waves e^{i(k x - w t)}:
#   (EI k^4 + k_1 - m w^2)(k_1 + k_2 - m_2 w^2) - k_1^2 = 0,  a quadratic in w^2 at every k;
# v_cr is the smallest local minimum of the phase speed w/k (dense grid of k, parabola through the minimum).
# On the one-layer track with the same pads, Eq. (65) gives alpha_cr = 1.
si = {name: float(getattr(physical, name)) for name in ("EI", "m", "k_1", "m_2", "k_2")}
k = np.linspace(0.05, 20.0, 40_000)
rail = si["EI"] * k**4 + si["k_1"]
a2, a1 = si["m"] * si["m_2"], -(rail * si["m_2"] + si["m"] * (si["k_1"] + si["k_2"]))
a0 = rail * (si["k_1"] + si["k_2"]) - si["k_1"] ** 2
w2 = np.stack([(-a1 - s * np.sqrt(a1**2 - 4 * a2 * a0)) / (2 * a2) for s in (1, -1)])
minima = []
for speed in np.sqrt(w2) / k:
    for i in np.flatnonzero((speed[1:-1] < speed[:-2]) & (speed[1:-1] < speed[2:])) + 1:
        y0, y1, y2 = speed[i - 1 : i + 2]
        minima.append(y1 - (y2 - y0) ** 2 / (8 * (y2 - 2 * y1 + y0)))
v_cr = min(minima)
print(f"v_cr from the SI dispersion relation: {v_cr:.3f} m/s")
assert abs(float(cv.alpha_cr) * scales.v_ref - v_cr) < 1e-5 * v_cr
assert abs(float(one.alpha_cr) - 1) < 1e-12

ps = np.linspace(0.02, 6, 600)
omega = dispersion_branches(params, ps)
fig = Figure(figsize=(6, 4), layout="constrained")
ax = fig.subplots()
for j in range(omega.shape[1]):
    ax.plot(ps, omega[:, j], label=f"branch {j + 1}")
ax.plot(ps, float(cv.alpha_cr) * ps, "k:", label=r"$\Omega = \alpha_{cr}\,p$")
ax.set_xlabel("p (dimensionless wavenumber)")
ax.set_ylabel(r"$\Omega$ (dimensionless)")
ax.set_ylim(0, 2 * omega[-1, -1] / 3)
ax.legend()
show(fig)

# %% [markdown]
# ## Induced frequencies over the speed
#
# Every induced frequency in the window, counted by the argument principle (the count certified) and
# polished; no starting guesses.

# %%
speeds = (60,) if QUICK else (30, 60, 90, 120)
for v in speeds:
    p = physical.with_dimensionless(params.replace(alpha=v / scales.v_ref)).to_dimensionless()
    res = induced_frequencies(p, dps=15)
    status = "certified" if res.count_ok else "NOT certified"
    print(f"v = {v:5.1f} m/s: {res.count} roots ({status}); stable: {res.stable}")
    for r in res.roots:
        w = complex(r.q) / scales.t_scale
        print(f"    omega = {w.real:+10.3f} {w.imag:+9.3f}i rad/s  ({w.real / (2 * np.pi):8.3f} Hz)")
    # the roots found are the roots counted (argument principle); the verdict is the sign of Im q (Eq. (35))
    assert res.count_ok and res.count == len(res.roots)
    assert res.stable == all(float(r.q.imag) >= 0 for r in res.roots)

# %% [markdown]
# ## Where a heavy bogie becomes unstable
#
# The instability lines in the plane (alpha, eta_M) of the same bogie on the one-layer track (pads only)
# and on the two-layer track. Where the horizontal line of a wheel mass ratio crosses an instability line,
# an induced frequency of that vehicle crosses the real axis (Section 3.7): the first crossing is the
# lowest speed at which its stability changes. A heavy wheel (M = 3000 kg) is marked.

# %%
spacings = (float(params.d),)
base = params.replace(track="one-layer")
comparison = compare_tracks(
    bind(base),
    "two-layer",
    {"mu_2": params.mu_2, "kappa_2": params.kappa_2, "eta_2": params.eta_2},
    spacings=spacings,
    quick=QUICK,
)
heavy = float(params.eta_M) * 3000 / 900
fig = figure_track_comparison(comparison)
for ax in fig.axes:
    ax.axhline(heavy, color="grey", lw=0.8)
for lines, a_cr in zip(comparison.lines, comparison.alpha_cr):
    crossings = []
    for b in lines.branches:
        t = np.asarray(b.theta) - heavy
        k = np.flatnonzero(np.sign(t[:-1]) * np.sign(t[1:]) < 0)
        a = np.asarray(b.alpha)
        crossings += [float(a[i] + (a[i + 1] - a[i]) * t[i] / (t[i] - t[i + 1])) for i in k]
    first = min(crossings) if crossings else None
    if first is None:
        text = "no line below alpha = 1.2"
    else:
        text = f"alpha = {first:.3f}, v = {first * scales.v_ref:.0f} m/s"
    print(f"{lines.params.track}: alpha_cr = {a_cr:.4f}; heavy bogie (eta_M = {heavy:.1f}): {text}")
show(fig)
