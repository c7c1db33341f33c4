"""A small sweep from the command line: in this process beside a local Dask cluster, side by side.

    python benchmarks/bench_small_sweep.py [--repeat N] [--record]

The command ``moving-bogie sweep --file examples/car.toml --vary v=40:120:6`` (6 points, one block, one
point of it checked by a full count) is run as a user runs it, in a fresh interpreter, twice: as it is
(under 1000 points: in this process) and with ``--workers 2`` (a LocalCluster of two worker processes,
the path of large sweeps). Wall time and CPU time (the command and every process it started) are the
medians of ``--repeat`` runs; the stores of the two are compared point by point. Target: under 1 s.
"""

from __future__ import annotations

import argparse
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
COMMAND = ["sweep", "--file", str(ROOT / "examples" / "car.toml"), "--vary", "v=40:120:6"]
VARIABLES = ("stable", "n_unstable", "degree_of_instability", "margin", "certain", "settled", "checked")


def _children_cpu() -> float:
    use = resource.getrusage(resource.RUSAGE_CHILDREN)
    return use.ru_utime + use.ru_stime


def _run(extra: list[str], out: Path) -> tuple[float, float, str]:
    """One run of the command in a fresh interpreter: wall [s], CPU [s], and where it ran."""
    argv = [sys.executable, "-m", "moving_bogie", *COMMAND, *extra, "--out", str(out), "--overwrite"]
    c0, w0 = _children_cpu(), time.perf_counter()
    done = subprocess.run(argv, capture_output=True, text=True, check=True)
    wall, cpu = time.perf_counter() - w0, _children_cpu() - c0
    where = next(line.split(None, 1)[1] for line in done.stdout.splitlines() if line.startswith("scheduler"))
    return wall, cpu, where


def _same_stores(a: Path, b: Path) -> bool:
    from moving_bogie.sweep import open_sweep

    x, y = open_sweep(a).compute(), open_sweep(b).compute()
    return all(np.array_equal(x[v].values, y[v].values, equal_nan=True) for v in VARIABLES)


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--repeat", type=int, default=3, metavar="N", help="runs of each (default 3)")
    from records import add_record_option

    add_record_option(parser)
    args = parser.parse_args()
    print(f"machine: {os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f} at start")
    label = "moving-bogie " + " ".join(COMMAND[:2] + ["examples/car.toml"] + COMMAND[3:])
    runs = {"default": [], "--workers 2": []}
    with tempfile.TemporaryDirectory() as folder:
        stores = {key: Path(folder) / f"{k}.zarr" for k, key in enumerate(runs)}
        for _ in range(args.repeat):  # interleaved: a change of load reaches both alike
            for key, timings in runs.items():
                timings.append(_run([] if key == "default" else key.split(), stores[key]))
        same = _same_stores(*stores.values())
        shutil.rmtree(folder, ignore_errors=True)
    print(f"{'run':38s} {'where':>14s} {'wall [s]':>9s} {'CPU [s]':>9s}")
    summary = {}
    for key, timings in runs.items():
        wall = statistics.median(t[0] for t in timings)
        cpu = statistics.median(t[1] for t in timings)
        summary[key] = (wall, cpu, timings[0][2])
        print(f"{label.split()[1] + ' ' + key:38s} {timings[0][2]:>14s} {wall:9.2f} {cpu:9.2f}")
    print(f"stores of the two identical: {same}")
    if args.record:
        from records import row, write_record

        (wall, cpu, where), (wall2, cpu2, where2) = summary.values()
        rows = [
            row(
                f"`{label}` (6 points; stores identical: {same})",
                f"{wall:.2f} s wall, {cpu:.2f} s CPU ({where})",
                f"{wall2:.2f} s wall, {cpu2:.2f} s CPU (`--workers 2`, {where2})",
                "under 1 s",
            )
        ]
        write_record(__file__, "Small sweeps", rows)


if __name__ == "__main__":
    main()
