"""Benchmark a (v, M) stability map of a rail on sleepers beside the continuous track of the same smeared
support, or beside the code before, in one run.

Run: ``OPENBLAS_NUM_THREADS=1 python benchmarks/bench_sleepers_map.py [--file examples/sleepers_zones.toml]
[--n 200] [--workers 2] [--range-v 20:400] [--range-M 3000] [--before REV [--repeat R]] [--record]``. A
script, not a test: nothing is asserted, the table is printed.

Without ``--before``: the sleeper map is the D-decomposition in M at each velocity
(``stability/maps/sleeper_map.py``, its floquet_frequencies checks included); the continuous map is
``stability/maps/map.py`` on the one-layer track with k_f = k_sup / l + k_f, c_f = c_sup / l + c_f, on the
same grid. Both run in this process with the same number of workers, one after the other; the table gives
the wall-clock seconds, the unstable cells and the uncertain ones.

With ``--before REV`` (a commit of this repository, checked out into a temporary worktree for the run, or
the ``src`` folder of another checkout): the sleeper map of the code before and of this code, each
``moving_bogie.sleeper_map`` in a child process with ``PYTHONPATH`` set to the ``src`` folder of its code,
alternating ``--repeat`` times (the least wall kept). Per run: wall seconds, CPU seconds of the child and
its workers, the load average (1 min) at its start and end, the unstable and uncertain cells, the
crossings and the checks. The maps are then compared: the counts and the uncertain columns cell by cell,
the crossings (their number, their changes, and the largest relative difference of their wheel masses
and frequencies) and the checks. The machine may be shared: CPU seconds depend much less on the load
than wall seconds.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile
import time
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from bench_sweep import Run

HERE = Path(__file__).resolve().parent.parent
SRC = HERE / "src"
#: Where the map's child processes and workers start (records.py: a record is stale once a file of their
#: import closure, or of the modules loaded here, changes).
ENTRIES = ("moving_bogie.stability.maps.sleeper_map",)

#: The child's program: the sleeper map of the file on the grid through the public API, its JSON written
#: to the path given (argv: file, v0, v1, n, M top, workers, out).
CHILD = """
import json, sys
import numpy as np
import moving_bogie as mb
file, v0, v1, n, top, workers, out = sys.argv[1:]
n = int(n)
_, physical = mb.load_parameters(file)
vs = np.linspace(float(v0), float(v1), n)
ms = np.linspace(float(top) / n, float(top), n)
smap = mb.sleeper_map(physical, vs, ms, workers=int(workers))
with open(out, "w") as f:
    json.dump(smap.to_dict(), f)
"""


def child_map(src: Path, args: argparse.Namespace, out: Path) -> tuple[Run, dict]:
    """The sleeper map of ``args`` computed by the package of ``src`` in a child process: its run (wall and
    CPU seconds, the load average at its start and end) and its ``SleeperMap.to_dict()``."""
    from bench_sweep import Run, timed_child

    v0, v1 = args.range_v.split(":")
    argv = [str(args.file), v0, v1, str(args.n), str(args.range_M), str(args.workers), str(out)]
    _, wall, cpu, loads = timed_child(src, CHILD, argv, "the sleeper map")
    return Run(wall, wall, cpu, loads, out), json.loads(out.read_text())


def _relative(a: list[float], b: list[float]) -> float:
    x, y = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return float(np.max(np.abs(x - y) / np.maximum(np.abs(y), 1e-300), initial=0.0))


def compare(a: dict, b: dict) -> list[str]:
    """How the maps ``a`` and ``b`` (``SleeperMap.to_dict()``) differ, one line per item compared."""
    ca, cb = np.asarray(a["count"]), np.asarray(b["count"])
    ua, ub = np.asarray(a["uncertain"]), np.asarray(b["uncertain"])
    out = [
        f"counts: {'identical' if np.array_equal(ca, cb) else f'{int(np.sum(ca != cb))} cells DIFFER'}",
        f"uncertain columns: {'identical' if np.array_equal(ua, ub) else f'{int(np.sum(ua != ub))} DIFFER'}",
    ]
    la, lb = a["lines"], b["lines"]
    key = [(p["v"], p["change"]) for p in la], [(p["v"], p["change"]) for p in lb]
    if key[0] == key[1]:
        dm = _relative([p["M"] for p in la], [p["M"] for p in lb])
        dq = _relative([p["Omega_rad_s"] for p in la], [p["Omega_rad_s"] for p in lb])
        out.append(
            f"crossings: the same {len(la)} (velocity, change); largest relative difference "
            f"M {dm:.1e}, Omega {dq:.1e}"
        )
    else:
        out.append(f"crossings: {len(la)} against {len(lb)}, DIFFERENT velocities or changes")
    same = [(c["v"], c["M"], c["map_count"], c["search_count"]) for c in a["checks"]]
    other = [(c["v"], c["M"], c["map_count"], c["search_count"]) for c in b["checks"]]
    out.append(f"checks: {len(same)} against {len(other)}, {'identical' if same == other else 'DIFFERENT'}")
    return out


def before_and_this(args: argparse.Namespace) -> None:
    """The map of the code before and of this code side by side (module docstring); --record writes it."""
    from bench_sweep import checkout

    runs: dict[str, tuple[Run, dict]] = {}
    with tempfile.TemporaryDirectory() as tmp, checkout(args.before) as (before, name):
        name = args.before if name != "SRC" else "before"
        for k in range(args.repeat):
            for code, src in ((name, before), ("this", SRC)):
                run, result = child_map(src, args, Path(tmp) / f"{k}-{code}.json")
                print(
                    f"  {code}: {run.wall:.1f} s wall, {run.cpu:.1f} s CPU, load {run.load}", file=sys.stderr
                )
                if code not in runs or run.wall < runs[code][0].wall:
                    runs[code] = run, result
    v0, v1 = args.range_v.split(":")
    print(
        f"{args.file.name}: {args.n} x {args.n} cells, v {v0}..{v1} m/s, M up to {args.range_M:g} kg, "
        f"{args.workers} workers, least wall of {args.repeat} run(s) each, {os.cpu_count()} cores"
    )
    header = f"{'code':10s} {'wall s':>7s} {'CPU s':>7s} {'load':>9s} {'unstable':>9s} {'uncertain':>9s}"
    header += f" {'crossings':>9s} {'checks':>7s}"
    print(header)
    print("-" * len(header))
    for code, (run, r) in runs.items():
        print(
            f"{code:10s} {run.wall:7.1f} {run.cpu:7.1f} {run.load:>9s} {r['unstable_cells']:9d} "
            f"{int(np.sum(r['uncertain'])) * args.n:9d} {r['crossings']:9d} {len(r['checks']):7d}"
        )
    lines = compare(runs["this"][1], runs[name][1])
    print(f"this map against {name}:")
    for line in lines:
        print(f"  {line}")
    if args.record:
        record_before(args, runs, name, lines)


def beside_continuous(args: argparse.Namespace) -> None:
    """The sleeper map and the continuous track's map on the same grid, in this process."""
    from moving_bogie import load_parameters, sleeper_map
    from moving_bogie.kernels.bound import bind
    from moving_bogie.model.smeared import smeared_physical
    from moving_bogie.stability.maps.map import stability_map

    _, data = load_parameters(args.file)
    v0, v1 = (float(x) for x in args.range_v.split(":"))
    vs = np.linspace(v0, v1, args.n)
    ms = np.linspace(args.range_M / args.n, args.range_M, args.n)
    rows = []
    start = time.perf_counter()
    smap = sleeper_map(data, vs, ms, workers=args.workers)
    rows.append(("sleepers (D-decomposition)", time.perf_counter() - start, smap.count, smap.uncertain))
    physical = smeared_physical(data)
    assert physical is not None, "the benchmark compares with the smeared continuous track"
    start = time.perf_counter()
    cont = stability_map(
        bind(physical.to_dimensionless()),
        parameter="eta_M",
        alphas=(vs / physical.si_factor("alpha")).tolist(),
        thetas=(ms / physical.si_factor("eta_M")).tolist(),
        workers=args.workers,
    )
    rows.append(("one-layer, same smeared support", time.perf_counter() - start, cont.count, cont.uncertain))
    print(
        f"{args.file.name}: {args.n} x {args.n} cells, v {v0:g}..{v1:g} m/s, M up to {args.range_M:g} kg, "
        f"{args.workers} workers, load average {os.getloadavg()[0]:.1f} at the end"
    )
    print(f"{'track':34s} {'wall [s]':>9s} {'unstable':>9s} {'uncertain':>9s}")
    for name, wall, count, unc in rows:
        print(f"{name:34s} {wall:9.1f} {int((count > 0).sum()):9d} {int(np.sum(unc)):9d}")
    checks = ", ".join(f"{c.map_count}/{c.search_count}" for c in smap.checks)
    print(f"sleeper map: {len(smap.lines())} crossings; checks map/floquet_frequencies: {checks}")
    if args.record:
        record(args, rows)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--file", type=Path, default=HERE / "examples" / "sleepers_zones.toml")
    parser.add_argument("--n", type=int, default=200)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--range-v", default="20:400", help="m/s")
    parser.add_argument("--range-M", type=float, default=3000.0, help="largest M, kg")
    parser.add_argument("--before", metavar="REV", help="a commit, or another checkout's src: side by side")
    parser.add_argument(
        "--repeat", type=int, default=1, help="with --before: runs per code (least wall kept)"
    )
    from records import add_record_option

    add_record_option(parser)
    args = parser.parse_args()
    if args.before:
        before_and_this(args)
    else:
        beside_continuous(args)


def record(args: argparse.Namespace, rows: list) -> None:
    """benchmarks/results/bench_sleepers_map.json: the sleeper map, the continuous map beside it."""
    from records import row, write_record

    (_, sleepers, count, unc), (_, continuous, c_count, _) = rows
    work = (
        f"stability-map --file {args.file.name}, {args.n} x {args.n} cells in (v, M), {args.workers} workers "
        f"(D-decomposition in M per velocity)"
    )
    measured = f"{sleepers:.1f} s wall, {int((count > 0).sum())} unstable cells, {int(np.sum(unc))} uncertain"
    alternative = (
        "the continuous one-layer track of the same smeared support on the same grid: "
        f"{continuous:.1f} s wall, {int((c_count > 0).sum())} unstable cells"
    )
    rows_out = [row(work, measured, alternative, "< 60 s")]
    write_record(__file__, "A (v, M) stability map on sleepers", rows_out, entries=ENTRIES)


def record_before(
    args: argparse.Namespace, runs: dict[str, tuple[Run, dict]], name: str, lines: list[str]
) -> None:
    """benchmarks/results/bench_sleepers_map.json: this map beside the code before, and how they compare."""
    from records import row, write_record

    work = (
        f"the sleeper map of stability-map --file {args.file.name}, {args.n} x {args.n} cells in (v, M), "
        f"{args.workers} workers"
    )

    def said(code: str) -> str:
        run, r = runs[code]
        return (
            f"{run.wall:.1f} s wall, {run.cpu:.1f} s CPU (load {run.load}), {r['unstable_cells']} unstable "
            f"cells, {int(np.sum(r['uncertain']))} uncertain columns, {r['crossings']} crossings"
        )

    rows_out = [
        row(work, said("this"), f"{name}: {said(name)}", "< 60 s"),
        row("the two maps compared", "; ".join(lines), "-", "identical counts"),
    ]
    where = {args.before: name}
    write_record(
        __file__, "A (v, M) stability map on sleepers", rows_out, placeholders=where, entries=ENTRIES
    )


if __name__ == "__main__":
    main()
