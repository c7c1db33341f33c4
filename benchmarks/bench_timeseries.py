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

``--before SRC`` (a ``src`` folder of another checkout of the package, e.g. ``git worktree add /tmp/before
main``) adds the commands users wait for, run side by side in one go by this checkout and by that one
(subprocesses with ``PYTHONPATH`` set to each ``src``; wall and CPU seconds of the child, best of
``--repeat``): the Timoshenko-Rayleigh time series of Case 7's vehicle (S = 10, r = 0.09) to tau = 40 and
its validation, and whether the two printed the same numbers. ``--only-commands`` skips the rows above.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import resource
import subprocess
import sys
import time
from pathlib import Path

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
    parser.add_argument("--before", metavar="SRC", help="src folder of the code to compare with")
    parser.add_argument("--repeat", type=int, default=1, help="runs per command and code (best kept)")
    parser.add_argument("--only-commands", action="store_true", help="only the side-by-side commands")
    args = parser.parse_args()
    print(f"python {platform.python_version()}, numpy {np.__version__}, {platform.machine()}")
    if args.before:
        side_by_side(Path(args.before), args.repeat)
    if args.only_commands:
        return
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


#: The commands users wait for (issue: a Timoshenko-Rayleigh time series in seconds).
TR = ["--case", "7", "--beam", "tr", "--S", "10", "--r", "0.09"]
COMMANDS = {
    "timeseries TR, tau <= 40": ["timeseries", *TR, "--tmax", "40", "--json"],
    "validate TR": ["validate", *TR, "--json"],
}
HERE = Path(__file__).resolve().parent.parent / "src"


def run_command(src: Path, argv: list[str]) -> tuple[float, float, str]:
    """(wall s, CPU s of the child, stdout) of ``moving-bogie argv`` with the package from ``src``."""
    env = dict(os.environ, PYTHONPATH=str(src), OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    code = "import sys; from moving_bogie.cli import main; sys.exit(main(sys.argv[1:]))"
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    out = subprocess.run([sys.executable, "-c", code, *argv], env=env, capture_output=True, text=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu, out.stdout


def _numbers(text: str) -> dict:
    """Every number of a --json output by its path (timings left out), or {} when it is not one."""
    try:
        data = json.loads(text)
    except json.JSONDecodeError:
        return {}
    out: dict = {}

    def walk(value: object, path: str) -> None:
        if isinstance(value, dict):
            for key, item in value.items():
                if key not in ("timings", "elapsed", "seconds", "evaluations"):
                    walk(item, f"{path}/{key}")
        elif isinstance(value, list) and value and all(isinstance(v, (int, float)) for v in value):
            out[path] = np.asarray(value, dtype=float)
        elif isinstance(value, list):
            for k, item in enumerate(value):
                walk(item, f"{path}[{k}]")
        elif isinstance(value, (int, float)) and not isinstance(value, bool):
            out[path] = np.asarray([value], dtype=float)

    walk(data, "")
    return out


def side_by_side(before: Path, repeat: int) -> None:
    """Each command by this checkout and by ``before``, alternating, and the largest difference."""
    rows = [("command", "code", "wall s", "CPU s", "max |difference|")]
    for label, argv in COMMANDS.items():
        best: dict[str, tuple[float, float, str]] = {}
        for _ in range(repeat):
            for who, src in (("before", before), ("this", HERE)):
                wall, cpu, out = run_command(src, argv)
                if who not in best or cpu < best[who][1]:
                    best[who] = (wall, cpu, out)
        a, b = _numbers(best["before"][2]), _numbers(best["this"][2])
        diffs = [float(np.max(np.abs(a[k] - b[k]))) for k in a if k in b and a[k].shape == b[k].shape]
        same = f"{max(diffs):.1e}" if diffs else "(no numbers)"
        for who in ("before", "this"):
            wall, cpu, _ = best[who]
            rows.append((label, who, f"{wall:.1f}", f"{cpu:.1f}", same if who == "this" else ""))
    _print(rows)


def _print(rows: list[tuple[str, ...]]) -> None:
    widths = [max(len(r[k]) for r in rows) for k in range(len(rows[0]))]
    for k, row in enumerate(rows):
        print("  ".join(cell.ljust(w) for cell, w in zip(row, widths)))
        if k == 0:
            print("  ".join("-" * w for w in widths))
    print()


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
