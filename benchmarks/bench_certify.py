"""Benchmark the certified Table 2 (ball arithmetic) side by side with the uncertified search.

Run: ``OPENBLAS_NUM_THREADS=1 python benchmarks/bench_certify.py [--cases 1,5,13] [--workers 2]``. A script,
not a test: nothing is asserted, the numbers are printed (~20 s of CPU for the 13 cases).

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

``--against DIR`` instead proves each case with this checkout's package and with that of another
(``DIR/src``, e.g. the code before a change), each in a fresh child process, case by case alternately so
that both see the same load; it prints the proof's CPU seconds of both side by side and whether the
certificates (counts, verdicts, reasons, proven roots; not the timing) are the same.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import subprocess
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

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
    proof = {k: v for k, v in cert.to_dict().items() if k != "seconds"}
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
        "certificate": json.dumps(proof | {"each": [e.certified for e in cert.roots]}, default=str),
    }


def run_elsewhere(directory: Path, case: int) -> dict:
    """:func:`run_case` with the package of ``directory`` (its ``src``), in a child process."""
    env = dict(os.environ, PYTHONPATH=f"{directory / 'src'}{os.pathsep}{directory}")
    command = [sys.executable, __file__, "--json-case", str(case)]
    out = subprocess.run(command, env=env, capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


def side_by_side(cases: list[int], against: Path) -> None:
    """Each case proven by this checkout and by ``against``, alternately in child processes."""
    here = Path(__file__).resolve().parent.parent
    label = against.name or str(against)
    print(f"{'case':>4} {'proof s':>8} {label[:10]:>10} {'segments':>9} {label[:10]:>10}  certificate")
    totals = [0.0, 0.0]
    for case in cases:
        mine, other = run_elsewhere(here, case), run_elsewhere(against, case)
        totals = [totals[0] + mine["proof"], totals[1] + other["proof"]]
        same = "same" if mine["certificate"] == other["certificate"] else "DIFFERS"
        print(
            f"{case:>4} {mine['proof']:>8.2f} {other['proof']:>10.2f} {mine['segments']:>9} "
            f"{other['segments']:>10}  {same} ({mine['verdict']})"
        )
    print(f" all {totals[0]:>8.2f} {totals[1]:>10.2f}   (CPU seconds of the proof: this checkout, {label})")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", default=",".join(map(str, TABLE1_CASES)))
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--against", type=Path, help="another checkout to prove alternately (DIR/src)")
    parser.add_argument("--json-case", type=int, help=argparse.SUPPRESS)
    from records import add_record_option

    add_record_option(parser)
    args = parser.parse_args()
    if args.json_case is not None:
        print(json.dumps(run_case(args.json_case), default=str))
        return
    cases = [int(c) for c in args.cases.split(",")]
    print(f"python {platform.python_version()}, {os.cpu_count()} cpu(s), load {os.getloadavg()[0]:.1f}")
    if args.against:
        side_by_side(cases, args.against)
        return
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
        write_record(__file__, "Certified verdicts", [row(work, measured, alternative, "< 15 s CPU")])


if __name__ == "__main__":
    main()
