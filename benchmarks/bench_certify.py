"""Benchmark the certified Table 2 (ball arithmetic) side by side with the uncertified search.

Run: ``OPENBLAS_NUM_THREADS=1 python benchmarks/bench_certify.py [--cases 1,5,13] [--workers 2]``. A script,
not a test: nothing is asserted, the numbers are printed (~25 s of CPU for the 13 cases).

For each case of Table 1, in the same run and the same process:

* ``search``: :func:`moving_bogie.roots.frequencies.induced_frequencies` with its defaults (double-precision
  argument principle in the window and in the window twice as large, bisection, 30 + 15 digit polish);
* ``proof``: :func:`moving_bogie.roots.proof.certify.certify` on that result (Krawczyk balls of radius 1e-26
  at
  200 bits, proven winding numbers on every tile at 96 bits; see docs/frequencies.md).

Times are CPU seconds of this process (``time.process_time``), so a busy machine does not inflate them;
the last line also gives the wall-clock time of the whole table run in ``--workers`` processes (2 by
default: the two cores), the way ``moving-bogie table2 --certify`` would run on an otherwise idle machine
if the cases were shared between two processes.
"""

from __future__ import annotations

import argparse
import os
import platform
import time
from concurrent.futures import ProcessPoolExecutor

from moving_bogie.api import induced_frequencies
from moving_bogie.model.cases import TABLE1_CASES, table1_case
from moving_bogie.roots.proof.certify import certify


def run_case(case: int) -> dict:
    """Time the search and the proof of one case; returns the row of the table."""
    t0 = time.process_time()
    result = induced_frequencies(table1_case(case))
    t1 = time.process_time()
    cert = certify(result)
    t2 = time.process_time()
    return {
        "case": case,
        "search": t1 - t0,
        "proof": t2 - t1,
        "roots": len(result.roots),
        "proven": cert.proven_roots,
        "count": result.count,
        "proven_count": cert.count,
        "segments": sum(pc.segments for pc in cert.tiles),
        "verdict": cert.verdict,
        "numerical": "stable" if result.stable else "unstable",
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", default=",".join(map(str, TABLE1_CASES)))
    parser.add_argument("--workers", type=int, default=2)
    from records import add_record_option

    add_record_option(parser)
    args = parser.parse_args()
    cases = [int(c) for c in args.cases.split(",")]
    print(f"python {platform.python_version()}, {os.cpu_count()} cpu(s), load {os.getloadavg()[0]:.1f}")
    head = (
        f"{'case':>4} {'search s':>9} {'proof s':>8} {'roots':>6} {'proven':>7} {'count':>6} {'proven':>7}"
        f" {'segments':>9}  {'numerical':<10} proven verdict"
    )
    print(head)
    rows = [run_case(c) for c in cases]
    for r in rows:
        print(
            f"{r['case']:>4} {r['search']:>9.2f} {r['proof']:>8.2f} {r['roots']:>6} {r['proven']:>7} "
            f"{r['count']:>6} {r['proven_count']!s:>7} {r['segments']:>9}  {r['numerical']:<10} "
            f"{r['verdict']}"
        )
    search = sum(r["search"] for r in rows)
    proof = sum(r["proof"] for r in rows)
    print(
        f" all {search:>9.2f} {proof:>8.2f} {sum(r['roots'] for r in rows):>6} "
        f"{sum(r['proven'] for r in rows):>7} {sum(r['count'] for r in rows):>6} "
        f"{sum(r['proven_count'] or 0 for r in rows):>7}   (CPU seconds, one process)"
    )
    start = time.perf_counter()
    with ProcessPoolExecutor(args.workers) as pool:
        list(pool.map(run_case, cases))
    wall = time.perf_counter() - start
    print(f"search + proof of the {len(cases)} cases in {args.workers} processes: {wall:.1f} s wall clock")
    if args.record:
        from records import row, write_record

        roots = sum(r["roots"] for r in rows)
        proven = sum(r["proven"] for r in rows)
        work = f"certified Table 2: {len(cases)} cases, {roots} roots, every count and verdict proven"
        measured = (
            f"{search + proof:.1f} s CPU ({proof:.1f} s of it the proof), {proven}/{roots} roots proven; "
            f"{wall:.1f} s wall in {args.workers} processes"
        )
        alternative = f"the search alone, uncertified: {search:.1f} s CPU"
        write_record(__file__, "Certified verdicts", [row(work, measured, alternative, "< 60 s CPU")])


if __name__ == "__main__":
    main()
