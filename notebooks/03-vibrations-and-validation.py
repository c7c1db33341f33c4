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
# # Vibrations in closed form, checked against a finite beam
#
# The paper gives the vibrations of the infinite beam and the bogie in closed form: a steady part
# (Eq. (39)), one harmonic per induced frequency (the residues of Eqs. (36), (40)-(43)) and a branch-cut
# integral $I_{bc}$ (Eq. (35)) that is "mostly negligible". It validates them on a long simply supported
# beam in 500 sine modes (Section 3.2, Eqs. (49)-(54)); Figures 5, 9-12, 14 and A1 show both.
#
# This notebook does the same for **Case 7** of Table 1 (Figure A1), then looks at what each part of the
# closed form contributes, and finally runs the closed form to times no finite beam could reach
# (Case 5, Figure 13).

# %%
import io
import os

import matplotlib.pyplot as plt
import numpy as np
from IPython.display import Image, display

from moving_bogie import table1_case
from moving_bogie.api import closed_form_response, induced_frequencies, validate
from moving_bogie.validation.compare import plot_validation

QUICK = os.environ.get("MOVING_BOGIE_QUICK", "").lower() in ("1", "true", "yes", "on")
CASE = 7
params = table1_case(CASE)
print(params)

# %% [markdown]
# ## Finite beam against closed form
#
# `validate` runs the finite beam (its length and the wheels' entry point are chosen so that no wave
# reflected at a support reaches the wheels within the comparison window; the quasi-static response of
# the truncated modes is added back), a second run with twice the time step to estimate the finite
# beam's own error, and the closed form on the same time grid. They agree when every quantity is within
# a fixed 1 % of its largest value over the window (`moving_bogie.validation.verdict`).
# Quick mode uses 200 modes on a shorter beam and a shorter window.

# %%
run = dict(n_modes=200, tau_max=60.0) if QUICK else {}
result = validate(params, **run)
print(
    f"finite beam: L = {result.finite.length:.1f}, {result.finite.n_modes} modes, "
    f"{result.finite_beam_s:.1f} s; "
    f"closed form: {result.closed_form_s:.1f} s (frequency search included)"
)
print(f"comparison window: tau <= {result.window[1]:.1f}\n")
print(f"{'quantity':>8} {'max |finite - closed|':>22} {'amplitude':>10} {'relative':>9} {'tolerance':>9}")
for name, q in result.quantities.items():
    print(f"{name:>8} {q.max_abs_diff:22.3g} {q.amplitude:10.3g} {q.relative:9.3%} {q.tolerance:9.0%}")
print("\nagree:", result.agrees)
assert result.agrees

# %%
fig = plot_validation(result, title=f"Case {CASE} (Figure A1): finite beam (full) vs closed form (dashed)")
buffer = io.BytesIO()
fig.savefig(buffer, format="png", dpi=90)  # a bare matplotlib Figure (no pyplot): show it as an image
display(Image(buffer.getvalue()))

# %% [markdown]
# ## What the closed form is made of
#
# The response at the rear wheel is the steady part plus the unsteady harmonic part (the residues at the
# four pairs of induced frequencies) plus $I_{bc}$. Switching the branch-cut integral off shows its size:
# it is what makes the homogeneous initial conditions hold exactly at $\tau = 0$, it is small (here below
# $10^{-3}$ of the static deflection) and it decays: the paper's "mostly negligible".

# %%
freq = induced_frequencies(params, dps=20 if QUICK else 30)
tau = np.linspace(0.0, 60.0 if QUICK else 150.0, 1201)
full = closed_form_response(params, tau, frequencies=freq, branch_cut="auto")
residues_only = closed_form_response(params, tau, frequencies=freq, branch_cut=False)
fig, axes = plt.subplots(2, 1, figsize=(8, 5), sharex=True, layout="constrained")
axes[0].plot(tau, full["w_rear"], label="steady + residues + branch cut")
axes[0].plot(tau, residues_only["w_rear"], "--", label="steady + residues only")
axes[0].axhline(full.steady["w_rear"], color="0.5", ls=":", lw=0.8, label="steady part, Eq. (39)")
axes[0].set_ylabel("w(0, τ)")
axes[0].legend(fontsize=8)
axes[1].semilogy(tau, np.abs(full["w_rear"] - residues_only["w_rear"]) + 1e-16)
axes[1].set_ylabel("|I_bc| at the rear wheel")
axes[1].set_xlabel("τ")
plt.show()
print(
    f"at tau = 0: with I_bc w = {full['w_rear'][0]:.2e}, without it w = {residues_only['w_rear'][0]:.3f} "
    "(the initial condition w = 0 needs I_bc)"
)
print(f"I_bc included for tau <= {full.branch_cut_until:g}; notes: {full.notes or 'none'}")
assert np.abs(full["w_rear"] - residues_only["w_rear"]).max() < 1e-3  # "below 1e-3 of the static deflection"

# %% [markdown]
# ## Long times: where the closed form has no competitor
#
# Case 5 is unstable in the subcritical range (Table 2: $\mathrm{Im}\,q = -0.000472$), but its growth time
# $1/|\mathrm{Im}\,q| \approx 2100$ is so long that the first few hundred time units look perfectly stable
# (Figure 12). The closed form costs the same at any time, so the instability can be followed until the
# unstable harmonic overtakes the decaying ones (Figure 13). A finite beam would need to be thousands of
# units long (and its modes many more) to stay free of reflections that long.

# %%
p5 = table1_case(5)
f5 = induced_frequencies(p5, dps=20 if QUICK else 30)
unstable = [r for r in f5.roots if r.unstable]
print("unstable root(s):", [f"{r.re_text[:10]} {r.im_text[:10]}i" for r in unstable])
tau_long = np.linspace(0.0, 4000.0 if QUICK else 12000.0, 8001 if QUICK else 24001)
long = closed_form_response(p5, tau_long, frequencies=f5)
fig, ax = plt.subplots(figsize=(8, 3), layout="constrained")
ax.plot(tau_long, long["w_rear"], lw=0.6)
growth = float(1 / abs(unstable[0].q.imag))
ax.set_title(f"Case 5, rear-wheel deflection (growth time 1/|Im q| = {growth:.0f})", fontsize=10)
ax.set_xlabel("τ")
ax.set_ylabel("w(0, τ)")
plt.show()
assert np.abs(long["w_rear"][-2000:]).max() > np.abs(long["w_rear"][:2000]).max()
