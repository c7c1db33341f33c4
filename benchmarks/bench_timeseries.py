"""Time the closed-form time series (Eqs. (35)-(43)) and print a table.

Run: ``python benchmarks/bench_timeseries.py``. Rows, for Cases 7 (damped), 2 (undamped) and 5 (unstable)
of Table 1, once the induced frequencies are known:

* residue coefficients (mpmath, at the roots' 30 digits), computed once;
* the steady + harmonic part for 10^3, 10^4, 10^5 points up to tau = 10^2, 10^3, 10^4: the cost depends
  on the number of points only, not on tau (target: 10^5 points to tau = 10^4 under 1 s);
* the full ``closed_form_response`` with ``branch_cut="auto"`` for 10^5 points to tau = 10^4, and the
  branch-cut part alone on 2001 points to tau = 100, by the half-line integral and, side by side, by the
  traced-cut integral of any model (``CurveBranchCut``, the same numbers to 1e-10);
* the same branch-cut part for the Timoshenko-Rayleigh beam (Case 7's vehicle, S = 10, r = 0.09), which
  only the traced-cut integral can do, and its ``closed_form_response`` on 2001 points to tau = 100.

The machine is shared: each timing is the best of three runs.

The commands ``timeseries`` and ``validate`` of that Timoshenko-Rayleigh case as a whole, side by side with
another checkout: ``bench_commands.py``.
"""

from __future__ import annotations

import argparse
import platform
import time

import numpy as np

from moving_bogie.api import closed_form_response, induced_frequencies
from moving_bogie.kernels.bound import bind
from moving_bogie.model.cases import table1_case
from moving_bogie.response.branch_cut import BranchCut
from moving_bogie.response.cut_integral import CurveBranchCut
from moving_bogie.response.residues import residue_expansion


def best(func, repeat: int = 3) -> float:
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        func()
        times.append(time.perf_counter() - start)
    return min(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    from records import add_record_option

    add_record_option(parser)
    args = parser.parse_args()
    print(f"python {platform.python_version()}, numpy {np.__version__}, {platform.machine()}")
    rows = [("case", "job", "points", "tau max", "seconds")]
    for case in (7, 2, 5):
        params = table1_case(case)
        start = time.perf_counter()
        result = induced_frequencies(params, dps=30)
        rows.append(
            (f"{case}", "induced frequencies (30 digits)", "-", "-", f"{time.perf_counter() - start:.2f}")
        )
        t = best(lambda params=params, result=result: residue_expansion(bind(params), result, shapes=False))
        rows.append((f"{case}", "residue coefficients (mpmath)", "-", "-", f"{t:.3f}"))
        expansion = residue_expansion(bind(params), result, shapes=False)
        for n in (10**3, 10**4, 10**5):
            for tmax in (1e2, 1e3, 1e4):
                tau = np.linspace(0.0, tmax, n)
                t = best(lambda tau=tau, e=expansion: e.totals(tau))
                rows.append(
                    (f"{case}", "steady + harmonic, 4 responses", f"{n:.0e}", f"{tmax:.0e}", f"{t:.3f}")
                )
        tau = np.linspace(0.0, 1e4, 10**5)
        t = best(lambda tau=tau, p=params, r=result: closed_form_response(p, tau, frequencies=r), repeat=1)
        rows.append((f"{case}", "closed_form_response, branch_cut='auto'", "1e+05", "1e+04", f"{t:.2f}"))
        bc = BranchCut(bind(params))
        tau = np.linspace(0.0, 100.0, 2001)
        t = best(lambda tau=tau, bc=bc: bc.responses(tau), repeat=1)
        rows.append((f"{case}", "branch-cut part alone (half-line)", "2001", "1e+02", f"{t:.2f}"))
        curve = CurveBranchCut(bind(params))
        t = best(lambda tau=tau, bc=curve: bc.responses(tau), repeat=1)
        rows.append((f"{case}", "branch-cut part alone (traced cut)", "2001", "1e+02", f"{t:.2f}"))
    params = table1_case(7).replace(beam="tr", S=10, r="0.09")
    result = induced_frequencies(params, dps=30)
    tau = np.linspace(0.0, 100.0, 2001)
    curve = CurveBranchCut(bind(params))
    t = best(lambda tau=tau, bc=curve: bc.responses(tau), repeat=1)
    rows.append(("7 TR", "branch-cut part alone (traced cut)", "2001", "1e+02", f"{t:.2f}"))
    t = best(lambda tau=tau, p=params, r=result: closed_form_response(p, tau, frequencies=r), repeat=1)
    rows.append(("7 TR", "closed_form_response, branch_cut='auto'", "2001", "1e+02", f"{t:.2f}"))
    widths = [max(len(r[k]) for r in rows) for k in range(len(rows[0]))]
    for k, row in enumerate(rows):
        print(
            "  ".join(
                cell.rjust(w) if j != 1 else cell.ljust(w) for j, (cell, w) in enumerate(zip(row, widths))
            )
        )
        if k == 0:
            print("  ".join("-" * w for w in widths))
    if args.record:
        record_rows(rows[1:])


def record_rows(rows) -> None:
    """benchmarks/results/bench_timeseries.json: the rows the performance page shows."""
    from records import row, write_record

    def seconds(case: str, job: str, points: str = "-", tmax: str = "-") -> str:
        (hit,) = [r[4] for r in rows if r[0] == case and r[1] == job and r[2] == points and r[3] == tmax]
        return hit

    steady = [seconds(c, "steady + harmonic, 4 responses", "1e+05", "1e+04") for c in ("7", "2", "5")]
    full = [seconds(c, "closed_form_response, branch_cut='auto'", "1e+05", "1e+04") for c in ("7", "2", "5")]
    half = [seconds(c, "branch-cut part alone (half-line)", "2001", "1e+02") for c in ("7", "2", "5")]
    traced = [seconds(c, "branch-cut part alone (traced cut)", "2001", "1e+02") for c in ("7", "2", "5")]
    tr = seconds("7 TR", "closed_form_response, branch_cut='auto'", "2001", "1e+02")
    out = [
        row(
            "10^5 time points to tau = 10^4, roots known (Cases 7, 2, 5)",
            "steady + harmonic part "
            + " / ".join(steady)
            + " s; with the branch-cut part "
            + " / ".join(full)
            + " s",
            "-",
            "< 1 s",
        ),
        row(
            "branch-cut part I_bc alone, 2001 times to tau = 100 (Cases 7, 2, 5)",
            "half-line integral " + " / ".join(half) + " s",
            "traced-cut integral of any model: " + " / ".join(traced) + " s",
        ),
        row(
            "Timoshenko-Rayleigh time series, Case 7's vehicle, S = 10, r = 0.09, 2001 times to tau = 100",
            f"{tr} s",
        ),
    ]
    write_record(__file__, "Closed-form time series", out)


if __name__ == "__main__":
    main()
