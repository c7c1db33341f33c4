"""The benchmark gate: the commands users wait for, timed against a fixed calibration, must not slow down 2x.

    python benchmarks/bench_gate.py            # the gate (exit 1 when it fails); CI runs it before the tests
    python benchmarks/bench_gate.py --record   # record the ratios of this code as the gate's baseline

Each command of :data:`COMMANDS` (Table 2, a sweep of 3,200 points, the induced frequencies of a rail on
sleepers, a 30 x 30 stability map) runs as a child process with this checkout's package (one BLAS thread);
its CPU seconds (user + system of the child and its own children) are divided by those of
:func:`calibration`, a fixed pure-numpy and pure-Python workload timed in the same run, so that the ratio
depends little on the machine or on its load. A ratio more than :data:`LIMIT` times its recorded value
(``benchmarks/gate_baseline.json``) fails the gate; a command over the limit is run once more and its
better run kept, so a single disturbed run does not fail it. A command that fails, or has no recorded
ratio, fails the gate too. The table is printed either way, then the records of ``docs/performance.md``
whose code changed since they were made.

The sweep runs its blocks in the child's own process (``IN_PROCESS_POINTS`` raised above its size): a
cluster's start-up costs seconds of CPU of its own, which would hide a slowdown of the points' work.

A deliberate change of a command's work (more roots, a new quantity) changes its ratio: record the baseline
again with ``--record`` on the code that is to be the reference, and commit ``benchmarks/gate_baseline.json``.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path

import numpy as np
from bench_commands import Run, run_child
from performance_page import load_records
from records import machine, stale_sources

ROOT = Path(__file__).resolve().parent.parent
HERE = ROOT / "src"
BASELINE = Path(__file__).resolve().parent / "gate_baseline.json"
#: A ratio more than this many times its recorded value fails the gate.
LIMIT = 2.0
IN_PROCESS = "import moving_bogie.sweep.engine as engine; engine.IN_PROCESS_POINTS = 10**9; "
SWEEP = ["sweep", "--case", "7", "--vary", "alpha=0.3:0.95:40", "--vary", "eta_M=5:60:40"]
SWEEP += ["--vary", "eta_f=0.05,0.15", "--out", "{out}/s.zarr", "--json"]
SLEEPERS = ["frequencies", "--file", str(ROOT / "examples" / "sleepers.toml"), "--json"]
MAP = ["stability-map", "--case", "1", "--n", "30", "--workers", "1", "--json"]
#: label -> (arguments of moving-bogie, Python statements run before it in the child).
COMMANDS = {
    "table2": (["table2", "--json"], ""),
    "sweep of Case 7, 3200 points": (SWEEP, IN_PROCESS),
    "frequencies on sleepers": (SLEEPERS, ""),
    "stability-map, Case 1, 30 x 30": (MAP, ""),
}


def calibration(repeat: int = 3) -> float:
    """CPU seconds of a fixed workload, the least of ``repeat`` runs: numpy on small complex arrays (as the
    kernels evaluate E_chr on a contour) and a pure-Python loop of float and dictionary work."""
    rng = np.random.default_rng(0)
    z = rng.standard_normal(1024) + 1j * rng.standard_normal(1024)
    coefficients = rng.standard_normal(9)
    best = np.inf
    for _ in range(repeat):
        start = time.process_time()
        total = 0.0
        for k in range(4000):
            w = np.sqrt(z * z + (k + 1.0))
            e = np.polyval(coefficients, w) / (1.0 + np.exp(-np.abs(w)))
            total += float(np.sum(np.abs(e) > 1.0)) + float(np.sort(e.real)[512])
        table: dict[int, float] = {}
        for i in range(600_000):
            x = (i * 0.618033988749895) % 1.0
            table[i % 997] = table.get(i % 997, 0.0) + x * x
        total += sum(table.values())
        best = min(best, time.process_time() - start)
    return float(best)


def measure(label: str, unit: float) -> tuple[Run, float]:
    """One run of the command ``label``: the run and its CPU seconds in units of the calibration."""
    argv, setup = COMMANDS[label]
    run = run_child(HERE, argv, setup)
    return run, run.cpu / unit


def judge(ratio: float, recorded: float | None) -> str:
    """ "ok", "SLOWER" (over :data:`LIMIT` times its recorded ratio) or "NO RECORD"."""
    if recorded is None:
        return "NO RECORD"
    return "SLOWER" if ratio > LIMIT * recorded else "ok"


def gate(recorded: dict[str, float]) -> tuple[list[tuple[str, Run, float, str]], float]:
    """(label, run, ratio, verdict) per command, and the calibration's CPU seconds (taken again after the
    commands, the smaller kept: the load may have changed meanwhile)."""
    unit = calibration()
    rows = []
    for label in COMMANDS:
        run, ratio = measure(label, unit)
        if run.code == 0 and judge(ratio, recorded.get(label)) == "SLOWER":
            again, ratio_again = measure(label, unit)  # a second chance for a disturbed run
            if again.code == 0 and ratio_again < ratio:
                run, ratio = again, ratio_again
        verdict = f"FAILED (exit {run.code})" if run.code != 0 else judge(ratio, recorded.get(label))
        rows.append((label, run, ratio, verdict))
        print(f"  {label}: {verdict}", file=sys.stderr)
    return rows, unit


def print_table(rows: list[tuple[str, Run, float, str]], unit: float, recorded: dict[str, float]) -> None:
    print(
        f"calibration: {unit:.3f} s CPU; load average {os.getloadavg()[0]:.1f}; limit {LIMIT:g}x the record"
    )
    table = [("command", "CPU s", "wall s", "ratio", "recorded", "limit", "verdict")]
    for label, run, ratio, verdict in rows:
        old = recorded.get(label)
        limit = "-" if old is None else f"{LIMIT * old:.2f}"
        table.append((label, f"{run.cpu:.2f}", f"{run.wall:.1f}", f"{ratio:.2f}", "-" if old is None else
                      f"{old:.2f}", limit, verdict))  # fmt: skip
    widths = [max(len(r[k]) for r in table) for k in range(len(table[0]))]
    for k, line in enumerate(table):
        print("  ".join(cell.ljust(w) for cell, w in zip(line, widths)))
        if k == 0:
            print("  ".join("-" * w for w in widths))


def stale_records() -> list[str]:
    """The titles of the records of ``docs/performance.md`` whose measured code changed since."""
    return [r["title"] for r in load_records() if stale_sources(r)]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--record", action="store_true", help=f"write {BASELINE.name} from this run")
    args = parser.parse_args(argv)
    baseline = json.loads(BASELINE.read_text()) if BASELINE.exists() else {"ratios": {}}
    recorded: dict[str, float] = {} if args.record else baseline["ratios"]
    start = time.perf_counter()
    rows, unit = gate(recorded)
    print_table(rows, unit, recorded)
    print(f"the gate took {time.perf_counter() - start:.0f} s")
    stale = stale_records()
    if stale:
        print(f"docs/performance.md: {len(stale)} record(s) older than their code: {'; '.join(stale)}")
    if args.record:
        if any(run.code != 0 for _, run, _, _ in rows):
            print("not recorded: a command failed")
            return 1
        ratios = {label: round(ratio, 3) for label, _, ratio, _ in rows}
        record = {"date": time.strftime("%Y-%m-%d"), "machine": machine(), "calibration_s": round(unit, 4)}
        BASELINE.write_text(json.dumps(record | {"ratios": ratios}, indent=2) + "\n")
        print(f"recorded {BASELINE.relative_to(ROOT)}")
        return 0
    failed = [label for label, _, _, verdict in rows if verdict != "ok"]
    if failed:
        print(f"the benchmark gate FAILED: {', '.join(failed)}")
        return 1
    print("the benchmark gate passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
