"""Timoshenko-Rayleigh tables of docs/frequencies.md and docs/vibrations.md (printed as markdown).

Run: ``python benchmarks/tr_tables.py``. Nothing is asserted; the tests check the same quantities.
For each TR parameter set: the induced frequencies with the height of the unsearched sliver, and the
closed form (steady + residues + I_bc) against the vectorised Bromwich integral on two lines.
"""

from __future__ import annotations

import time

import mpmath

from moving_bogie.api import closed_form_response, induced_frequencies
from moving_bogie.kernels.bound import bind
from moving_bogie.model.cases import table1_case
from moving_bogie.response.bromwich import bromwich_line
from moving_bogie.roots.count.contour import Rectangle

SETS = [("10", "0.09", "0.05"), ("10", "0.09", "0"), ("100", "0.03", "0.05")]
TAUS = (0.5, 2.0, 20.0, 100.0)


def frequencies_table():
    print("| S | r | Re q | Im q | side | digits | unsearched height | seconds |")
    print("|---:|---:|---:|---:|---|---:|---:|---:|")
    for S, r, _ in SETS[::2]:
        params = table1_case(7).replace(beam="tr", S=S, r=r)
        t0 = time.perf_counter()
        result = induced_frequencies(params)
        sec = time.perf_counter() - t0
        height = max(u.height for u in result.unsearched)
        for root in result.roots:
            print(
                f"| {S} | {r} | {root.re_text[:14]} | {root.im_text[:14]} | {root.side} | {root.digits} "
                f"| {height:.0e} | {sec:.1f} |"
            )


def vibrations_table():
    print("| S | r | eta_v | tau | w_rear | I_bc w_rear | max rel. diff with I_bc | without I_bc ", end="")
    print("| two lines |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for S, r, eta_v in SETS:
        params = table1_case(7).replace(beam="tr", S=S, r=r, eta_v=eta_v)
        far = 3 * float(mpmath.sqrt(int(S))) / float(r)  # beyond the first roots near the cut at sqrt(S)/r
        window = Rectangle(-0.01, max(100.0, far), -1.0, 1.0)
        result = induced_frequencies(params, dps=20, window=window, check_window=False)
        on = closed_form_response(params, TAUS, frequencies=result, branch_cut=True)
        off = closed_form_response(params, TAUS, frequencies=result, branch_cut=False)
        ref = bromwich_line(bind(params), TAUS, a=0.02)
        other = bromwich_line(bind(params), TAUS, a=0.05)
        scale = max(abs(on.steady["w_rear"]), abs(on.steady["w_front"]))
        for k, tau in enumerate(TAUS):
            d_on = max(abs(on[n][k] - ref[n][k]) for n in ref) / scale
            d_off = max(abs(off[n][k] - ref[n][k]) for n in ref) / scale
            lines = max(abs(ref[n][k] - other[n][k]) for n in ref) / scale
            print(
                f"| {S} | {r} | {eta_v} | {tau:g} | {on['w_rear'][k]:.10f} "
                f"| {on['w_rear'][k] - off['w_rear'][k]:.2e} "
                f"| {d_on:.1e} | {d_off:.1e} | {lines:.0e} |"
            )


if __name__ == "__main__":
    frequencies_table()
    print()
    vibrations_table()
