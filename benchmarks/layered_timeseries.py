"""Time series on the two-layer track: the branch-cut part over the mass layer's cut (docs/layered_tracks.md).

Run: ``python benchmarks/layered_timeseries.py``. Nothing is asserted; tests/test_response_layered.py checks
the same quantities. Prints two markdown tables:

1. the closed form (steady + residues + I_bc) of examples/two-layer.toml against the vectorised Bromwich
   integral on two lines (a = 0.02 and 0.05), relative to the larger steady wheel deflection, with and
   without I_bc;
2. the time of a 2001-point time series on 0 <= tau <= 200 with the ``auto`` rule, beside residues only
   and beside the one-layer track (Table 1, Case 7), measured in the same run (CPU seconds, the induced
   frequencies computed beforehand and timed separately).
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from moving_bogie.api import closed_form_response, induced_frequencies
from moving_bogie.kernels.bound import bind
from moving_bogie.model.cases import table1_case
from moving_bogie.model.files import load_params_file
from moving_bogie.response.bromwich import bromwich_line

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "two-layer.toml"
TAUS = (0.5, 2.0, 20.0, 50.0)
NAMES = ("w_rear", "w_front", "u", "theta")


def agreement_table(params, result):
    ref = bromwich_line(bind(params), TAUS, a=0.02)
    other = bromwich_line(bind(params), TAUS, a=0.05)
    on = closed_form_response(params, TAUS, frequencies=result, branch_cut=True)
    off = closed_form_response(params, TAUS, frequencies=result, branch_cut=False)
    scale = max(abs(on.steady["w_rear"]), abs(on.steady["w_front"]))
    print("| tau | w_rear | I_bc w_rear | max rel. diff with I_bc | without I_bc | two lines |")
    print("|---:|---:|---:|---:|---:|---:|")
    for k, tau in enumerate(TAUS):

        def diff(a, b, k=k):
            return max(abs(a[n][k] - b[n][k]) for n in NAMES) / scale

        with_bc = {n: on[n] for n in NAMES}
        without = {n: off[n] for n in NAMES}
        print(
            f"| {tau:g} | {on['w_rear'][k]:.10f} | {on['w_rear'][k] - off['w_rear'][k]:.2e} "
            f"| {diff(with_bc, ref):.1e} | {diff(without, ref):.1e} | {diff(ref, other):.0e} |"
        )


def timing_table(cases):
    taus = np.linspace(0.0, 200.0, 2001)
    print(
        "| track | frequencies (CPU s) | series with I_bc (CPU s) | I_bc kept for | residues only (CPU s) |"
    )
    print("|---|---:|---:|---|---:|")
    for label, params in cases:
        t0 = time.process_time()
        result = induced_frequencies(params)
        t1 = time.process_time()
        ts = closed_form_response(params, taus, frequencies=result)
        t2 = time.process_time()
        closed_form_response(params, taus, frequencies=result, branch_cut=False)
        t3 = time.process_time()
        print(f"| {label} | {t1 - t0:.1f} | {t2 - t1:.1f} | tau <= {ts.branch_cut_until:g} | {t3 - t2:.2f} |")


def main():
    params, _ = load_params_file(EXAMPLE)
    agreement_table(params, induced_frequencies(params))
    print()
    timing_table(
        [("one-layer (Table 1, Case 7)", table1_case(7)), ("two-layer (examples/two-layer.toml)", params)]
    )


if __name__ == "__main__":
    main()
