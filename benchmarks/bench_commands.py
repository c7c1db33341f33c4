"""The commands users wait for, each run by this checkout and by another one side by side, and their targets.

Run: ``python benchmarks/bench_commands.py --before SRC`` (SRC: the ``src`` folder of another checkout of
the package, e.g. ``git worktree add /tmp/before <commit>`` then ``/tmp/before/src``). Each command is run
as a child process with ``PYTHONPATH`` set to each ``src`` in turn, alternating, one BLAS thread; the table
gives the CPU seconds (user + system of the child and its own children) and the wall seconds of the best of
``--repeat`` runs, the exit status, and the largest difference between every number the two printed with
``--json`` (timing fields left out): the same work, done faster, must print the same numbers.

The rows are those of "speed where users wait": Table 2 from scratch (30 digits, counted and confirmed),
the certified Table 2, the Timoshenko-Rayleigh time series of Case 7's vehicle (S = 10, r = 0.09) and its
finite-beam validation, and a small sweep of the car (6 points, in-process).
"""

from __future__ import annotations

import argparse
import json
import os
import re
import resource
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent.parent / "src"
EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
TR = ["--case", "7", "--beam", "tr", "--S", "10", "--r", "0.09"]
#: label -> (arguments of moving-bogie, target); ``{out}`` is a fresh temporary folder per run.
COMMANDS = {
    "table2": (["table2", "--json"], "1 s CPU"),
    "table2 --certify": (["table2", "--certify", "--json"], "15 s CPU"),
    "timeseries TR, tau <= 40": (["timeseries", *TR, "--tmax", "40", "--json"], "3 s CPU"),
    "validate TR": (["validate", *TR, "--json"], "5 s CPU"),
    "sweep of the car, 6 points": (
        ["sweep", "--file", str(EXAMPLES / "car.toml"), "--vary", "v=40:120:6", "--out", "{out}/s.zarr",
         "--json"],
        "1 s CPU",
    ),
}  # fmt: skip


@dataclass(frozen=True)
class Run:
    """One run of a command: wall and CPU seconds, what it printed, its exit status."""

    wall: float
    cpu: float
    stdout: str
    code: int


def run_child(src: Path, argv: list[str], setup: str = "") -> Run:
    """``moving-bogie argv`` in a child process with the package from ``src`` (one BLAS thread), after the
    Python statements ``setup``."""
    env = dict(os.environ, PYTHONPATH=str(src), OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    code = setup + "import sys; from moving_bogie.cli import main; sys.exit(main(sys.argv[1:]))"
    with tempfile.TemporaryDirectory() as out:
        args = [a.replace("{out}", out) for a in argv]
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        done = subprocess.run([sys.executable, "-c", code, *args], env=env, capture_output=True, text=True)
        wall = time.perf_counter() - start
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return Run(wall, cpu, done.stdout, done.returncode)


#: A number printed as a string (the digits of a root): compared as the double it rounds to.
DECIMAL = re.compile(r"[-+]?\d+(\.\d*)?([eE][-+]?\d+)?")


def numbers(text: str) -> dict:
    """Every number of a --json output by its path (timings and a sweep's worker count left out: how it
    ran, not what it computed; strings of digits, such as the printed roots, as numbers too), or {} when
    it is not one."""
    try:
        data = json.loads(text)
    except json.JSONDecodeError:
        return {}
    out: dict = {}

    def walk(value: object, path: str) -> None:
        if isinstance(value, dict):
            for key, item in value.items():
                if key not in (
                    "timings",
                    "elapsed",
                    "seconds",
                    "points_per_second",
                    "evaluations",
                    "workers",
                ):
                    walk(item, f"{path}/{key}")
        elif isinstance(value, list) and value and all(isinstance(v, (int, float)) for v in value):
            out[path] = np.asarray(value, dtype=float)
        elif isinstance(value, list):
            for k, item in enumerate(value):
                walk(item, f"{path}[{k}]")
        elif isinstance(value, (int, float)) and not isinstance(value, bool):
            out[path] = np.asarray([value], dtype=float)
        elif isinstance(value, str) and DECIMAL.fullmatch(value):
            out[path] = np.asarray([float(value)], dtype=float)

    walk(data, "")
    return out


def largest_difference(a: str, b: str) -> str:
    """The largest difference between the numbers of two ``--json`` outputs, path by path, and where it is
    (the path, when it is not zero), over the paths both print with the same shape; the paths only one
    prints (an output that gained or lost a field between the two codes) are counted after it."""
    x, y = numbers(a), numbers(b)
    if not x or not y:
        return "(no numbers)"
    common = [k for k in x if k in y and x[k].shape == y[k].shape]
    apart = len(x.keys() | y.keys()) - len(common)
    extra = f"; {apart} field(s) printed by one code only" if apart else ""
    if not common:
        return "DIFFERENT FIELDS" + extra
    if any(not np.array_equal(np.isnan(x[k]), np.isnan(y[k])) for k in common):
        return "NaN MISMATCH" + extra
    diffs = {k: float(np.nanmax(np.abs(x[k] - y[k]), initial=0.0)) for k in common}
    where = max(diffs, key=lambda k: diffs[k])
    return f"{diffs[where]:.1e}" + (f" (at {where})" if diffs[where] else "") + extra


def compare(before: Path, repeat: int, only: list[str] | None = None) -> list[tuple[str, Run, Run, str]]:
    """(label, best run of ``before``, best run of this checkout, largest difference) per command (those
    whose label contains one of ``only``, when given)."""
    out = []
    for label, (argv, _) in COMMANDS.items():
        if only and not any(word in label for word in only):
            continue
        best: dict[str, Run] = {}
        for _ in range(repeat):
            for who, src in (("before", before), ("this", HERE)):
                run = run_child(src, argv)
                if who not in best or run.cpu < best[who].cpu:
                    best[who] = run
        out.append(
            (
                label,
                best["before"],
                best["this"],
                largest_difference(best["before"].stdout, best["this"].stdout),
            )
        )
        print(f"  {label}: done", file=sys.stderr)
    return out


def print_table(results: list[tuple[str, Run, Run, str]]) -> None:
    rows = [("command", "code", "CPU s", "wall s", "exit", "max |difference|", "target")]
    for label, old, new, diff in results:
        rows.append((label, "before", f"{old.cpu:.2f}", f"{old.wall:.1f}", str(old.code), "", ""))
        rows.append(
            ("", "this", f"{new.cpu:.2f}", f"{new.wall:.1f}", str(new.code), diff, COMMANDS[label][1])
        )
    widths = [max(len(r[k]) for r in rows) for k in range(len(rows[0]))]
    for k, row in enumerate(rows):
        print("  ".join(cell.ljust(w) for cell, w in zip(row, widths)))
        if k == 0:
            print("  ".join("-" * w for w in widths))


def record(results: list[tuple[str, Run, Run, str]], before: Path) -> None:
    """benchmarks/results/bench_commands.json for the performance page."""
    from records import row, source_revision, write_record

    rows = [
        row(
            f"`moving-bogie {' '.join(COMMANDS[label][0]).replace(str(EXAMPLES.parent) + '/', '')}`",
            f"{new.cpu:.2f} s CPU, {new.wall:.1f} s wall, exit {new.code}; "
            f"largest difference of the printed numbers from the code before: {diff}",
            f"the code before ({source_revision(before)}): {old.cpu:.2f} s CPU, {old.wall:.1f} s wall",
            COMMANDS[label][1],
        )
        for label, old, new, diff in results
    ]
    title = "The commands users wait for, side by side with the code before"
    argv = sys.argv
    where = {argv[k + 1]: "SRC" for k, arg in enumerate(argv[:-1]) if arg == "--before"}  # no local path
    write_record(__file__, title, rows, placeholders=where)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--before", metavar="SRC", type=Path, required=True, help="src folder of the other code"
    )
    parser.add_argument("--repeat", type=int, default=1, help="runs per command and code (best kept)")
    parser.add_argument(
        "--only",
        metavar="WORD",
        nargs="+",
        help="run only the commands whose label contains one of these words (e.g. --only TR)",
    )
    from records import add_record_option

    add_record_option(parser)
    args = parser.parse_args()
    if not (args.before / "moving_bogie").is_dir():
        parser.error(f"--before: {args.before} holds no moving_bogie package")
    if args.record and args.only:
        parser.error("--record writes the table of every command: leave out --only")
    results = compare(args.before, args.repeat, args.only)
    print_table(results)
    if args.record:
        record(results, args.before)


if __name__ == "__main__":
    main()
