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
# # Table 2 of the paper, recomputed with confirmed digits
#
# Table 2 of Dimitrovová (2025) lists the induced frequencies of the 13 cases of Table 1: the roots
# $q$ of the characteristic equation $E_{chr}(q) = 0$ (Eq. (48)), one root of each pair
# $q, -q^*$. The print gives six decimals for Cases 1-6; the rows of Cases 7-13 are withheld from the
# reference data on purpose, so they are computed here and compared with nothing.
#
# Every root is found without starting guesses (argument principle on contours that avoid the cut of
# $K$), polished at `dps` digits and **confirmed** by recomputation at higher precision: only digits that
# agree at both precisions are shown. How the search works: `docs/frequencies.md`.
#
# The same table from the command line: `moving-bogie table2`.

# %%
import os
import time
from decimal import Decimal

import matplotlib.pyplot as plt
import mpmath

from moving_bogie import table1_case
from moving_bogie.api import induced_frequencies
from moving_bogie.roots.table2 import compute_table2, format_table2

QUICK = os.environ.get("MOVING_BOGIE_QUICK", "").lower() in ("1", "true", "yes", "on")
DPS = 20 if QUICK else 30  # working precision in decimal digits; the confirmation adds max(10, dps/2)
print(f"quick mode: {QUICK}, dps = {DPS}")

# %% [markdown]
# ## The whole table
#
# `compute_table2` runs the root search for each case and matches the computed roots to the printed
# ones by proximity. The text layout below is the one `moving-bogie table2` prints: computed value
# (rounded to the print's six decimals), the printed value, and the difference.

# %%
start = time.perf_counter()
table = compute_table2(dps=DPS)
print(f"13 cases in {time.perf_counter() - start:.1f} s\n")
print(format_table2(table))

# %% [markdown]
# ## Side by side, with every confirmed digit
#
# Each computed root is shown with all its confirmed decimals (here `dps` of them), next to the printed
# six decimals. A difference within half a unit of the sixth decimal (5e-7) means the print is
# reproduced to its last digit.

# %%
tolerance = Decimal("5e-7")
for row in table.rows:
    printed = list(row.printed)
    verdict = (
        "stable"
        if row.result.stable
        else f"UNSTABLE (degree {mpmath.nstr(row.result.degree_of_instability, 3)})"
    )
    print(f"Case {row.case}: {verdict}; count ok: {row.result.count_ok}")
    for root, diff in zip(row.result.roots, row.differences):
        sign = "-" if root.im_text.startswith("-") else "+"
        computed = f"q = ±{root.re_text} {sign} {root.im_text.lstrip('-')} i"
        if diff is None:
            print(f"   {computed}   [{root.digits} digits; not printed]")
        else:
            ok = abs(diff[0]) <= tolerance and abs(diff[1]) <= tolerance
            print(f"   {computed}   [{root.digits} digits; print {'reproduced' if ok else 'DIFFERS'}]")
print("\nall printed values reproduced:", table.ok)

# %% [markdown]
# ## A picture of the table
#
# The induced frequencies of all cases in the complex $q$-plane (the member of each pair with
# $\mathrm{Re}\, q \ge 0$). Open circles: computed; crosses: printed (Cases 1-6). Points below the real
# axis are unstable: $e^{iq\tau}$ grows when $\mathrm{Im}\, q < 0$ (Eq. (35)). The imaginary axis is
# symmetric-log so that the tiny unstable parts (about $-10^{-4}$) are visible next to the large stable ones.

# %%
fig, ax = plt.subplots(figsize=(9, 5), layout="constrained")
colors = plt.cm.tab10.colors
for k, row in enumerate(table.rows):
    qs = [complex(r.q) for r in row.result.roots]
    marker = "o" if k < 10 else "s"
    style = dict(color=colors[k % 10], mfc="none", ls="none")
    ax.plot([q.real for q in qs], [q.imag for q in qs], marker, **style, label=f"Case {row.case}")
    pr = [(float(re), float(im)) for re, im in row.printed]
    if pr:
        ax.plot([x for x, _ in pr], [y for _, y in pr], "x", color=colors[k % 10], ms=9)
ax.axhline(0, color="k", lw=0.8)
ax.set_yscale("symlog", linthresh=1e-4)
ax.set_xlabel("Re q")
ax.set_ylabel("Im q  (below 0: unstable)")
ax.set_title("Induced frequencies of Table 1's cases (o computed, x printed)")
ax.legend(ncol=2, fontsize=8, loc="upper left", bbox_to_anchor=(1.0, 1.0))
plt.show()

# %% [markdown]
# ## Precision ladder: the digits do not depend on the working precision
#
# The same case at increasing working precision. The confirmed digits at each level agree with those of
# the level above: the printed digits are not an artefact of one precision.

# %%
ladder = (20, 30) if QUICK else (20, 30, 45)
case = 5
results = {dps: induced_frequencies(table1_case(case), dps=dps) for dps in ladder}
for dps, res in results.items():
    root = min(res.roots, key=lambda r: float(mpmath.im(r.q)))  # the unstable one
    print(f"dps {dps:>2}: q = {root.re_text} {root.im_text} i  ({root.digits} digits confirmed)")
low, high = results[ladder[0]], results[ladder[-1]]
for a, b in zip(low.roots, high.roots):
    n = a.decimals
    assert abs(a.q - b.q) <= 10 ** (-n + 1), (a.q, b.q)
print("every lower-precision root agrees with the higher-precision one to its confirmed digits")

# %% [markdown]
# ## What the table says
#
# * Cases 2-4 are undamped: all induced frequencies are real (constant amplitude, no numerical damping
#   needed; they lie in the gap of the cut of $K$, `docs/frequencies.md`).
# * Cases 1 and 5 are unstable in the subcritical range ($\alpha = 0.8, 0.7 < 1$) with a tiny negative
#   imaginary part: the growth time $1/|\mathrm{Im}\,q|$ is thousands of dimensionless time units, so the
#   instability only shows at long times (Figures 6, 13).
# * Case 6 is Case 5 with suspension damping $\eta_v = 0.05$: stable.
# * Of the computed-only rows, Cases 12 and 13 are unstable, as the paper's text says (Figures A4-A7).

# %%
for row in table.rows:
    res = row.result
    growth = "" if res.stable else f", growth time 1/|Im q| = {mpmath.nstr(res.growth_time, 4)}"
    print(f"Case {row.case:>2}: {'stable' if res.stable else 'UNSTABLE'}{growth}")
unstable = [row.case for row in table.rows if not row.result.stable]
assert unstable == [1, 5, 12, 13], unstable
assert all(row.result.count_ok for row in table.rows)
assert table.ok
