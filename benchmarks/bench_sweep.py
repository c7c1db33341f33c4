"""Parameter sweeps on Dask beside the code before: points/s per worker, the margin's cost, 10^6 points.

    python benchmarks/bench_sweep.py --before REV [--repeat N] [--million] [--record]

REV is a commit of this repository (checked out for the run with ``git worktree add`` into a temporary
folder, removed afterwards) or the ``src`` folder of another checkout.

1. The 6,400-point sweep of Case 7 (40 alpha x 40 eta_M x 4 eta_f, :data:`CASE7`) on a LocalCluster of 1
   and of 2 worker processes, one table per worker count: the code before, this code, and this code with
   ``--margin`` (the stability margin of every point), alternating, each ``moving-bogie sweep`` a child
   process with ``PYTHONPATH`` set to the ``src`` folder of its code. Per run: the command's wall seconds,
   the sweep's own seconds (what ``--json`` prints: cluster start-up and the blocks), the CPU seconds of
   the child and its workers, points/s per worker (from the sweep's seconds) and the ratio to the code
   before; the least wall of ``--repeat`` runs is kept. The margin's cost is the ratio of the sweep with
   ``--margin`` to the one without. Targets: at least 900 points/s per worker, as fast as the code before.
2. The stores of the last runs compared variable by variable: every variable that two stores both hold
   must be identical (NaN equal to NaN), so the same work done faster stores the same numbers.
3. A 3-D sweep of 100 alpha x 1000 eta_M x 10 eta_f = 10^6 points of Case 1 on 2 workers (target < 5 min),
   this code only. Without --million, 10 consecutive alpha values from the middle of the 100 (10^5 points,
   the same columns) are run and the time multiplied by 10; the table says which was done.

Wall time depends on what else runs on the machine; the load average is printed beside every run, and CPU
time (which depends much less on it) beside the wall time.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
HERE = ROOT / "src"
CASE7 = ["--case", "7", "--vary", "alpha=0.3:0.95:40", "--vary", "eta_M=5:60:40"]
CASE7 += ["--vary", "eta_f=0.05,0.1,0.15,0.2"]
POINTS = 40 * 40 * 4
#: Where the sweep's child processes and workers start (records.py: a record is stale once a file of their
#: import closure changes).
ENTRIES = ("moving_bogie.__main__", "moving_bogie.cli.sweep_cmd")


@dataclass(frozen=True)
class Run:
    """One sweep: the command's wall seconds, the sweep's own seconds, CPU seconds, the load average (1 min)
    at its start and at its end, and the store it wrote."""

    wall: float
    seconds: float
    cpu: float
    loads: tuple[float, float]
    store: Path

    @property
    def load(self) -> str:
        return f"{self.loads[0]:.1f}-{self.loads[1]:.1f}"

    def per_worker(self, points: int, workers: int) -> float:
        return points / self.seconds / workers


def timed_child(
    src: Path, code: str, argv: list[str], what: str
) -> tuple[str, float, float, tuple[float, float]]:
    """``python -c code argv`` in a child with the package of ``src`` (one BLAS thread): its output, wall
    seconds, CPU seconds (the child and its own children) and the load average at its start and end."""
    env = dict(os.environ, PYTHONPATH=str(src), OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start, load = time.perf_counter(), os.getloadavg()[0]
    done = subprocess.run([sys.executable, "-c", code, *argv], env=env, capture_output=True, text=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode != 0:
        raise SystemExit(f"{what} failed with {src}:\n{done.stderr[-3000:]}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return done.stdout, wall, cpu, (load, os.getloadavg()[0])


def sweep(src: Path, args: list[str], workers: int, store: Path) -> Run:
    """``moving-bogie sweep args`` on ``workers`` local workers, in a child with the package of ``src``."""
    code = "import sys; from moving_bogie.cli import main; sys.exit(main(sys.argv[1:]))"
    argv = ["sweep", *args, "--workers", str(workers), "--out", str(store), "--overwrite", "--json"]
    out, wall, cpu, loads = timed_child(src, code, argv, "moving-bogie sweep")
    return Run(wall, float(json.loads(out)["seconds"]), cpu, loads, store)


def differences(a: Path, b: Path) -> dict[str, int]:
    """Per variable that both stores hold: the number of entries that differ (NaN equals NaN)."""
    import zarr

    ga, gb = zarr.open_group(str(a), mode="r"), zarr.open_group(str(b), mode="r")
    out = {}
    for name in sorted(set(ga.array_keys()) & set(gb.array_keys())):
        x, y = np.asarray(ga[name][...]), np.asarray(gb[name][...])
        if x.shape != y.shape:
            out[name] = max(x.size, y.size)
            continue
        same = x == y
        if x.dtype.kind == "f":
            same |= np.isnan(x) & np.isnan(y)
        out[name] = int(np.sum(~same))
    return out


@contextmanager
def checkout(before: str) -> Iterator[tuple[Path, str]]:
    """(the ``src`` folder of ``before``, how to name it): a folder as it is, a commit checked out into a
    temporary worktree for the run."""
    folder = Path(before)
    for src in (folder, folder / "src"):
        if (src / "moving_bogie").is_dir():
            yield src, "SRC"
            return
    temporary = Path(tempfile.mkdtemp(prefix="bench-sweep-"))
    tree = temporary / "before"
    git = ["git", "-C", str(ROOT)]
    made = subprocess.run([*git, "worktree", "add", "--detach", str(tree), before], capture_output=True)
    if made.returncode != 0:
        shutil.rmtree(temporary, ignore_errors=True)
        raise SystemExit(
            f"--before {before}: neither a checkout's src folder nor a commit of this repository"
        )
    try:
        yield tree / "src", before
    finally:
        subprocess.run([*git, "worktree", "remove", "--force", str(tree)], capture_output=True)
        shutil.rmtree(temporary, ignore_errors=True)


CODES = ("before", "this", "this --margin")


def compare_case7(before: Path, repeat: int, folder: Path) -> dict[int, dict[str, Run]]:
    """Per worker count: the best (least wall) run of each code of :data:`CODES`, alternating."""
    out: dict[int, dict[str, Run]] = {}
    for workers in (1, 2):
        best: dict[str, Run] = {}
        for _ in range(repeat):
            for code in CODES:
                src = before if code == "before" else HERE
                extra = ["--margin"] if code.endswith("--margin") else []
                store = folder / f"{code.replace(' --', '-')}-{workers}.zarr"
                run = sweep(src, CASE7 + extra, workers, store)
                if code not in best or run.wall < best[code].wall:
                    best[code] = run
        out[workers] = best
        print(f"  {workers} worker(s): done", file=sys.stderr)
    return out


def print_case7(results: dict[int, dict[str, Run]], name: str) -> None:
    header = f"{'code':22s} {'wall s':>7s} {'sweep s':>8s} {'CPU s':>7s} {'points/s/worker':>15s}"
    header += f" {'vs before':>10s} {'load':>9s}"
    for workers, runs in results.items():
        print(f"\n{POINTS}-point sweep of Case 7, {workers} worker(s)")
        print(header)
        print("-" * len(header))
        old = runs["before"]
        for code, run in runs.items():
            label = name if code == "before" else code
            ratio = run.seconds / old.seconds
            print(
                f"{label:22s} {run.wall:7.1f} {run.seconds:8.1f} {run.cpu:7.1f} "
                f"{run.per_worker(POINTS, workers):15.0f} {ratio:9.2f}x {run.load:>9s}"
            )
        cost = runs["this --margin"].seconds / runs["this"].seconds - 1
        print(f"the margin's cost: +{100 * cost:.0f} % of the sweep's seconds (CPU: "
              f"+{100 * (runs['this --margin'].cpu / runs['this'].cpu - 1):.0f} %)")  # fmt: skip


def print_stores(results: dict[int, dict[str, Run]]) -> list[str]:
    """Print the differences between the stores, one line per pair; return those lines."""
    lines = []
    for workers, runs in results.items():
        for a, b in (("before", "this"), ("this", "this --margin"), ("before", "this --margin")):
            diff = differences(runs[a].store, runs[b].store)
            differing = {k: n for k, n in diff.items() if n}
            what = "identical" if not differing else f"DIFFERENT: {differing}"
            lines.append(f"{workers} worker(s), {a} / {b}: {len(diff)} variables in both, {what}")
    print("\nstores compared (every variable both hold):")
    for line in lines:
        print(f"  {line}")
    return lines


def million(full: bool, folder: Path) -> tuple[str, Run, float]:
    """The 10^6-point sweep of Case 1 on 2 workers (or a tenth of it): (label, run, factor to 10^6)."""
    alphas = _values(0.3, 1.1, 100)
    if not full:
        alphas = alphas[45:55]
    args = ["--case", "1", "--vary", "alpha=" + ",".join(alphas), "--vary", "eta_M=1:200:1000"]
    args += ["--vary", "eta_f=" + ",".join(_values(0.02, 0.2, 10))]
    run = sweep(HERE, args, 2, folder / "million.zarr")
    shutil.rmtree(run.store, ignore_errors=True)
    return f"{len(alphas)} x 1000 x 10 sweep of Case 1, 2 workers", run, 100 / len(alphas)


def _values(lo: float, hi: float, n: int) -> list[str]:
    from fractions import Fraction

    a, b = Fraction(str(lo)), Fraction(str(hi))
    return [str(float(a + (b - a) * k / (n - 1))) for k in range(n)]


def record(
    results: dict[int, dict[str, Run]], stores: list[str], big: tuple[str, Run, float], name: str
) -> None:
    from records import row, write_record

    rows = []
    for workers, runs in results.items():
        this, old, margin = runs["this"], runs["before"], runs["this --margin"]
        rows.append(
            row(
                f"`moving-bogie sweep {' '.join(CASE7)}`, {POINTS} points, {workers} worker(s)",
                f"{this.wall:.1f} s wall, the sweep {this.seconds:.1f} s: "
                f"{this.per_worker(POINTS, workers):.0f} points/s per worker, {this.cpu:.1f} s CPU "
                f"(load {this.load}); with `--margin`: {margin.seconds:.1f} s, the margin's cost "
                f"+{100 * (margin.seconds / this.seconds - 1):.0f} %",
                f"{name}: {old.wall:.1f} s wall, the sweep {old.seconds:.1f} s: "
                f"{old.per_worker(POINTS, workers):.0f} points/s per worker, {old.cpu:.1f} s CPU",
                ">= 900 points/s per worker, as fast as the code before",
            )
        )
    rows.append(row("the stores of the runs above, compared", "; ".join(stores), "-", "identical"))
    label, run, scale = big
    how = "measured" if scale == 1 else f"{scale:g} x a measured {10**6 / scale:.0f}-point run"
    rows.append(
        row(
            "`moving-bogie sweep`, 10^6 points (100 alpha x 1000 eta_M x 10 eta_f, Case 1), 2 workers",
            f"{run.wall * scale:.0f} s wall, {run.cpu * scale:.0f} s CPU ({how}; load average {run.load})",
            "-",
            "< 5 min",
        )
    )
    argv = sys.argv
    where = {argv[k + 1]: name for k, arg in enumerate(argv[:-1]) if arg == "--before"}
    write_record(__file__, "Parameter sweeps on Dask", rows, placeholders=where, entries=ENTRIES)


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--before", required=True, metavar="REV", help="a commit, or another checkout's src")
    parser.add_argument(
        "--repeat", type=int, default=1, help="runs per code and worker count (least wall kept)"
    )
    parser.add_argument("--million", action="store_true", help="run the full 10^6-point sweep")
    from records import add_record_option

    add_record_option(parser)
    args = parser.parse_args()
    print(f"machine: {os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f} at start")
    with tempfile.TemporaryDirectory() as tmp, checkout(args.before) as (before, name):
        name = args.before if name != "SRC" else "before"
        results = compare_case7(before, args.repeat, Path(tmp))
        print_case7(results, name)
        stores = print_stores(results)
        big = million(args.million, Path(tmp))
        label, run, scale = big
        print(f"\n{label}: {run.wall:.1f} s wall, {run.cpu:.1f} s CPU, load average {run.load}")
        what = "measured" if scale == 1 else f"x{scale:g} the run above"
        print(f"10^6-point 3-D sweep, 2 workers ({what}): {run.wall * scale:.0f} s wall (target < 300 s)")
        if args.record:
            record(results, stores, big, name)


if __name__ == "__main__":
    main()
