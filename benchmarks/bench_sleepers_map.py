"""Benchmark a 100 x 100 (v, M) stability map of a rail on sleepers beside the continuous track of the same
smeared support, in one run.

Run: ``OPENBLAS_NUM_THREADS=1 python benchmarks/bench_sleepers_map.py [--file examples/sleepers_zones.toml]
[--n 100] [--workers 2] [--range-v 20:400] [--range-M 3000] [--record]``. A script, not a test: nothing
is asserted, the table is printed. The sleeper map is the D-decomposition in M at each velocity
(``floquet/sleeper_map.py``, its floquet_frequencies checks included); the continuous map is
``stability/maps/map.py`` on the one-layer track with k_f = k_sup / l + k_f, c_f = c_sup / l + c_f, on the
same grid. Both run in this process with the same number of workers, one after the other; the table gives
the wall-clock seconds, the unstable cells and the uncertain ones.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

from moving_bogie.floquet.sleeper_map import sleeper_map
from moving_bogie.kernels.bound import bind
from moving_bogie.model.sleeper_input import load_sleeper_file
from moving_bogie.model.smeared import smeared_track
from moving_bogie.stability.maps.map import stability_map

HERE = Path(__file__).resolve().parent.parent


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--file", type=Path, default=HERE / "examples" / "sleepers_zones.toml")
    parser.add_argument("--n", type=int, default=100)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--range-v", default="20:400", help="m/s")
    parser.add_argument("--range-M", type=float, default=3000.0, help="largest M, kg")
    from records import add_record_option

    add_record_option(parser)
    args = parser.parse_args()
    data = load_sleeper_file(args.file)
    v0, v1 = (float(x) for x in args.range_v.split(":"))
    vs = np.linspace(v0, v1, args.n)
    ms = np.linspace(args.range_M / args.n, args.range_M, args.n)
    rows = []
    start = time.perf_counter()
    smap = sleeper_map(data, vs, ms, workers=args.workers)
    rows.append(("sleepers (D-decomposition)", time.perf_counter() - start, smap.count, smap.uncertain))
    physical = smeared_track(data)
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
        f"{args.workers} workers"
    )
    print(f"{'track':34s} {'wall [s]':>9s} {'unstable':>9s} {'uncertain':>9s}")
    for name, wall, count, unc in rows:
        print(f"{name:34s} {wall:9.1f} {int((count > 0).sum()):9d} {int(np.sum(unc)):9d}")
    checks = ", ".join(f"{c.map_count}/{c.search_count}" for c in smap.checks)
    print(f"sleeper map: {len(smap.lines())} crossings; checks map/floquet_frequencies: {checks}")
    if args.record:
        record(args, rows)


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
    rows_out = [row(work, measured, alternative, "< 3 min")]
    write_record(__file__, "A (v, M) stability map on sleepers", rows_out)


if __name__ == "__main__":
    main()
