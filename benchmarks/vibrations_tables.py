"""Tables of docs/vibrations.md: size of the branch-cut part and agreement with the Bromwich integral.

Run: ``python benchmarks/vibrations_tables.py [--write]``. Prints two Markdown tables; with ``--write``
it replaces the blocks between the ``<!-- BEGIN/END generated: ... -->`` markers of docs/vibrations.md
(the tables are computed, never typed by hand).

1. For every Table 1 case: I_bc(tau) of Eq. (35) at tau = 0, 20, 100 (rear-wheel deflection, and the
   largest of |I_bc| over w_rear, w_front, u, theta), the bound B e^{-eta_f tau} and where the ``auto``
   rule stops including it. At tau = 0, I_bc = -(steady + harmonic part): it is by how much the residues
   alone miss the homogeneous initial conditions.
2. Closed form (steady + residues + I_bc) against the independent Bromwich quadrature, and without I_bc.
"""

from __future__ import annotations

import argparse
import re
import time
from pathlib import Path

import numpy as np

from moving_bogie.api import closed_form_response, induced_frequencies
from moving_bogie.kernels.bound import bind
from moving_bogie.model.cases import TABLE1_CASES, table1_case
from moving_bogie.response.branch_cut import BranchCut
from moving_bogie.response.bromwich import bromwich_response
from moving_bogie.response.cut_policy import branch_cut_extent, s_min_for
from moving_bogie.response.residues import residue_expansion

DOC = Path(__file__).resolve().parents[1] / "docs" / "vibrations.md"
TAUS = (0.0, 20.0, 100.0)


def size_table() -> str:
    head = (
        "| case | eta_f | q_c | B | I_bc w_rear, tau=0 | tau=20 | tau=100 | max over w,u,theta, tau=0 "
        "| tau=20 | tau=100 | auto keeps I_bc for |\n"
    )
    head += "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n"
    rows = []
    for case in TABLE1_CASES:
        params = table1_case(case)
        result = induced_frequencies(params, dps=30)
        expansion = residue_expansion(bind(params), result, shapes=False)
        bc = BranchCut(bind(params))
        s_min = s_min_for(bc, expansion)
        values = bc.responses(np.array(TAUS), s_min=s_min)
        bound = max(bc.l1_bound(s_min=s_min).values())
        scale = max(abs(expansion.steady["w_rear"]), abs(expansion.steady["w_front"]))
        until, _ = branch_cut_extent(bc, 1e4, tol=1e-6 * scale, s_min=s_min)
        worst = np.max(np.abs(np.stack(list(values.values()))), axis=0)
        cells = [f"{case}", f"{float(params.eta_f):g}", f"{bc.q_c:.4f}", f"{bound:.1e}"]
        cells += [f"{v:.2e}" for v in values["w_rear"]] + [f"{v:.1e}" for v in worst]
        cells.append(f"tau <= {until:g}")
        rows.append("| " + " | ".join(cells) + " |")
    return head + "\n".join(rows) + "\n"


def agreement_table() -> str:
    head = (
        "| case | tau | w_rear (closed form) | rel. diff with I_bc (max over w,u,theta) "
        "| rel. diff without I_bc | Bromwich time [s] |\n|---:|---:|---:|---:|---:|---:|\n"
    )
    rows = []
    for case in (7, 2, 1, 5, 13):
        params = table1_case(case)
        result = induced_frequencies(params, dps=30)
        for tau in (20.0, 100.0):
            start = time.perf_counter()
            ref = bromwich_response(bind(params), [tau], a=0.02)
            elapsed = time.perf_counter() - start
            on = closed_form_response(params, [tau], frequencies=result, branch_cut=True)
            off = closed_form_response(params, [tau], frequencies=result, branch_cut=False)

            def rel(ts, ref=ref):
                return max(
                    abs(ts[n][0] - ref[n][0]) / max(abs(ref[n][0]), 1e-300)
                    for n in ("w_rear", "w_front", "u", "theta")
                )

            rows.append(
                f"| {case} | {tau:g} | {on['w_rear'][0]:.10f} | {rel(on):.1e} | {rel(off):.1e} "
                f"| {elapsed:.1f} |"
            )
    return head + "\n".join(rows) + "\n"


def replace_block(text: str, name: str, table: str) -> str:
    pattern = re.compile(rf"(<!-- BEGIN generated: {name} -->\n).*?(<!-- END generated: {name} -->)", re.S)
    if not pattern.search(text):
        raise SystemExit(f"marker for {name!r} not found in {DOC}")
    return pattern.sub(lambda m: m.group(1) + table + m.group(2), text)


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--write", action="store_true", help="update docs/vibrations.md in place")
    args = parser.parse_args()
    sizes = size_table()
    print(sizes)
    agreement = agreement_table()
    print(agreement)
    if args.write:
        text = DOC.read_text()
        text = replace_block(text, "branch-cut-sizes", sizes)
        text = replace_block(text, "bromwich-agreement", agreement)
        DOC.write_text(text)
        print(f"updated {DOC}")


if __name__ == "__main__":
    main()
