"""Parameter sweeps on Dask: points/s per worker, 1 -> 2 worker scaling, a 10^6-point 3-D sweep.

    python benchmarks/bench_sweep.py [--quick] [--million]

1. The same 200 x 200 x 4 sweep (alpha x eta_M x eta_f, Case 1) on a LocalCluster of 1 and of 2 worker
   processes, side by side: wall time, points/s, points/s per worker, speed-up (target >= 1.5). An
   80 x 80 x 4 sweep takes about 16 s of CPU in one process, while starting a cluster and importing the
   package in each worker costs several seconds: too small to show the scaling.
2. A 3-D sweep of 100 alpha x 1000 eta_M x 10 eta_f = 10^6 points on 2 workers (target < 5 min): long
   columns of eta_M are what the column count shares its work over. Without --million, 10 consecutive
   alpha values from the middle of the 100 (10^5 points, the same columns) are run and the time is
   multiplied by 10: the chunks are independent, so the time is linear in their number if the alphas are
   alike; the table says which was done.

Wall time depends on what else runs on the machine; CPU time (this process and its worker processes,
counted when the cluster closes) does not, and is printed next to it. Each run starts its own cluster
(start-up included in the wall time).
"""

from __future__ import annotations

import argparse
import os
import resource
import shutil
import tempfile
import time
from pathlib import Path


def _cpu() -> float:
    own = resource.getrusage(resource.RUSAGE_SELF)
    kids = resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + kids.ru_utime + kids.ru_stime


def _run(spec, workers, folder):
    from moving_bogie.sweep.engine import run_sweep

    out = Path(folder) / f"s{workers}-{spec.size}.zarr"
    w0, c0 = time.perf_counter(), _cpu()
    run = run_sweep(spec, out, workers=workers, overwrite=True)
    wall, cpu = time.perf_counter() - w0, _cpu() - c0
    shutil.rmtree(out, ignore_errors=True)
    return wall, cpu, run


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--quick", action="store_true", help="a 40 x 40 x 4 scaling run and 10^4 points")
    parser.add_argument("--million", action="store_true", help="run the full 10^6-point sweep")
    parser.add_argument("--no-scaling", action="store_true", help="skip part 1")
    from records import add_record_option

    add_record_option(parser)
    args = parser.parse_args()

    from moving_bogie.model.cases import table1_case
    from moving_bogie.sweep import make_spec

    n = 40 if args.quick else 200
    base = table1_case(1)
    scaling = make_spec(base, {"alpha": f"0.3:1.1:{n}", "eta_M": f"1:200:{n}", "eta_f": "0.02,0.05,0.1,0.2"})
    print(f"machine: {os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f} at start")
    print(f"{'job':52s} {'wall [s]':>9s} {'CPU [s]':>9s} {'points/s':>9s} {'per worker':>10s}")
    rows, record = {}, []
    with tempfile.TemporaryDirectory() as folder:
        for workers in () if args.no_scaling else (1, 2):
            wall, cpu, run = _run(scaling, workers, folder)
            rows[workers] = wall
            rate = scaling.size / wall
            label = f"{n} x {n} x 4 sweep, {workers} worker(s)"
            print(f"{label:52s} {wall:9.1f} {cpu:9.1f} {rate:9.1f} {rate / workers:10.1f}")
        if rows:
            print(f"{'speed-up 1 -> 2 workers (target >= 1.5)':52s} {rows[1] / rows[2]:9.2f}")
            record.append(
                (
                    f"sweep of {scaling.size} points ({n} alpha x {n} eta_M x 4 eta_f, Case 1), 2 workers",
                    f"{rows[2]:.1f} s wall, {scaling.size / rows[2] / 2:.0f} points/s per worker",
                    f"1 worker: {rows[1]:.1f} s wall (speed-up {rows[1] / rows[2]:.2f})",
                    "speed-up >= 1.5",
                )
            )
        m, n_eta = (10, 100) if args.quick else (100, 1000)
        alphas = _values(0.3, 1.1, m)
        if not args.million:
            alphas = alphas[m // 2 - m // 20 : m // 2 + m // 20]
        big = make_spec(
            base,
            {"alpha": ",".join(alphas), "eta_M": f"1:200:{n_eta}", "eta_f": ",".join(_values(0.02, 0.2, 10))},
        )
        wall, cpu, run = _run(big, 2, folder)
        scale = m / len(alphas)
        label = f"{len(alphas)} x {n_eta} x 10 sweep, 2 workers"
        print(f"{label:52s} {wall:9.1f} {cpu:9.1f} {big.size / wall:9.1f} {big.size / wall / 2:10.1f}")
        what = "measured" if scale == 1 else f"x{scale:g} the row above"
        total = m * n_eta * 10
        print(
            f"{f'{total:.0e}-point 3-D sweep, 2 workers ({what})':52s} {wall * scale:9.1f} {cpu * scale:9.1f}"
        )
        how = "measured" if scale == 1 else f"{scale:g} x a measured {big.size}-point run ({wall:.1f} s wall)"
        record.append(
            (
                f"{total:.0e}-point 3-D sweep ({m} alpha x {n_eta} eta_M x 10 eta_f), 2 workers",
                f"{wall * scale:.0f} s wall, {cpu * scale:.0f} s CPU ({how})",
                "-",
                "< 5 min" if total == 10**6 else "-",
            )
        )
    if args.record:
        from records import row, write_record

        write_record(__file__, "Parameter sweeps on Dask", [row(*r) for r in record])


def _values(lo, hi, n):
    from fractions import Fraction

    lo, hi = Fraction(str(lo)), Fraction(str(hi))
    return [str(float(lo + (hi - lo) * k / (n - 1))) for k in range(n)]


if __name__ == "__main__":
    main()
