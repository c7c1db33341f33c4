"""A two-layer sweep in SI units (speed x wheel mass): the column path and the per-point path side by side.

    python benchmarks/bench_sweep_layered.py [--quick] [--no-old] [--points K]

The sweep of the issue, ``moving-bogie sweep --file examples/two-layer.toml --vary v=40:400:50 --vary
M=500:3000:40 --bar fixed`` (2000 points, the default ``--check 1``), computed

* by the column path: the whole column of 40 wheel masses counted at once at each speed (mu_v, J_b held,
  E_chr of degree 2 in eta_M), the default;
* by the per-point path the sweep took before (each point a column of one value, a continuation in v per
  wheel mass), the same verdicts point by point;

each on a LocalCluster of 1 and of 2 worker processes, and the column path once more cut into two blocks
(``--chunk-points 1024``: both workers busy, one more full count for the check). Then a grid with unstable
points (v = 400..900 m/s, M = 3000..30000 kg, 50 x 40) by the column path on 2 workers. For every run: wall
time (``run`` = what the command reports as points/s: the cluster's start and the blocks; ``total`` =
from the start of the run including the store and the critical velocity), CPU time of this process and its
worker processes, the points decided by a full count (``settled``) and left undecided (``uncertain``).

Checks printed at the end: the two paths' stores agree at every point (count equal, degree of instability
within 1e-8), and K points drawn at random (seed 24; on the unstable grid half of them unstable) agree with
``induced_frequencies`` (the full search over the far-field window).
"""

from __future__ import annotations

import argparse
import os
import resource
import shutil
import tempfile
import time
from pathlib import Path

import numpy as np

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "two-layer.toml"
ISSUE = {"v": "40:400:50", "M": "500:3000:40"}
UNSTABLE = {"v": "400:900:50", "M": "3000:30000:40"}


def _cpu() -> float:
    own = resource.getrusage(resource.RUSAGE_SELF)
    kids = resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + kids.ru_utime + kids.ru_stime


def _per_point(spec):
    """The same sweep by the per-point path: no column, mu_v and J_b following each point's own eta_M."""
    from dataclasses import dataclass

    from moving_bogie.sweep.design import SweepSpec

    @dataclass(frozen=True)
    class PerPoint(SweepSpec):
        @property
        def column_parameter(self):
            return None

        @property
        def held(self):
            return ()

    return PerPoint(**{f: getattr(spec, f) for f in spec.__dataclass_fields__})


def _run(spec, workers, out):
    from moving_bogie.sweep.engine import run_sweep
    from moving_bogie.sweep.store import open_sweep

    w0, c0 = time.perf_counter(), _cpu()
    run = run_sweep(spec, out, workers=workers, overwrite=True)
    wall, cpu = time.perf_counter() - w0, _cpu() - c0
    ds = open_sweep(out).compute()
    return {"run": run.seconds, "total": wall, "cpu": cpu, "blocks": run.blocks_computed, "ds": ds}


def _row(label, size, r):
    ds = r["ds"]
    print(
        f"{label:44s} {r['blocks']:6d} {r['run']:8.1f} {r['total']:8.1f} {r['cpu']:8.1f} "
        f"{size / r['run']:9.1f} {size / r['total']:9.1f} {int(ds.settled.sum()):7d} "
        f"{int((~ds.certain).sum()):9d}"
    )


def _full_search_check(spec, ds, k, rng) -> tuple[int, int]:
    """k random points (half unstable where there are any) against induced_frequencies."""
    from moving_bogie.api import induced_frequencies

    n = ds.n_unstable.values
    pools = [np.argwhere(n > 0), np.argwhere(n == 0)] if (n > 0).any() else [np.argwhere(n == 0)]
    drawn = []
    for pool, m in zip(pools, [k - k // len(pools)] + [k // len(pools)] * (len(pools) - 1)):
        drawn += [tuple(pool[i]) for i in rng.choice(len(pool), size=min(m, len(pool)), replace=False)]
    agree = 0
    for i, j in drawn:
        point = spec.params.replace(
            **(
                spec.fixed
                | {spec.axes[0].name: spec.axes[0].values[i], spec.axes[1].name: spec.axes[1].values[j]}
            )
        )
        ref = induced_frequencies(point, dps=15)
        unstable = [complex(r.q) for r in ref.unstable_roots]
        lowest = min([0.0, *(q.imag for q in unstable)])
        ok = (
            ref.count_ok
            and ref.verdict.determined
            and len(unstable) == n[i, j]
            and abs(lowest - float(ds.degree_of_instability.values[i, j])) <= 1e-8
        )
        agree += ok
        print(
            f"    v = {float(ds.v[i]):7.1f} m/s, M = {float(ds.M[j]):8.1f} kg: sweep {n[i, j]}, full search "
            f"{len(unstable)} ({'agree' if ok else 'DISAGREE'})"
        )
    return agree, len(drawn)


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--quick", action="store_true", help="the per-point path on 2 workers only")
    parser.add_argument("--no-old", action="store_true", help="skip the per-point path")
    parser.add_argument("--points", type=int, default=4, help="random points checked by a full search")
    args = parser.parse_args()

    from moving_bogie.model.files import load_params_file
    from moving_bogie.sweep import make_spec

    params, physical = load_params_file(EXAMPLE)
    held = dict(bar="fixed")  # the frame's M_b, J_b held along M (--bar fixed): the column of degree 2
    issue = make_spec(params, ISSUE, physical=physical, **held)
    halves = make_spec(params, ISSUE, physical=physical, block_points=1024, **held)
    unstable = make_spec(params, UNSTABLE, physical=physical, **held)
    print(f"machine: {os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f} at start")
    print(
        f"{'job':44s} {'blocks':>6s} {'run [s]':>8s} {'total':>8s} {'CPU [s]':>8s} {'pts/s run':>9s} "
        f"{'pts/s tot':>9s} {'settled':>7s} {'uncertain':>9s}"
    )
    rng = np.random.default_rng(24)
    results = {}
    with tempfile.TemporaryDirectory() as folder:
        jobs = []
        if not args.no_old:
            for w in (2,) if args.quick else (1, 2):
                jobs.append((f"per-point path (before), {w} worker(s)", _per_point(issue), w, "old"))
        jobs += [(f"column path, {w} worker(s)", issue, w, "new") for w in (1, 2)]
        jobs.append(("column path, 2 blocks, 2 workers", halves, 2, "halves"))
        jobs.append(("unstable grid (v 400-900, M 3-30 t), 2 workers", unstable, 2, "unstable"))
        for label, spec, w, key in jobs:
            r = _run(spec, w, Path(folder) / f"{key}{w}.zarr")
            _row(label, spec.size, r)
            results[key] = r
            shutil.rmtree(Path(folder) / f"{key}{w}.zarr", ignore_errors=True)
        if "old" in results:
            a, b = results["new"]["ds"], results["old"]["ds"]
            same = bool((a.n_unstable.values == b.n_unstable.values).all())
            gap = float(np.nanmax(np.abs(a.degree_of_instability.values - b.degree_of_instability.values)))
            print(
                f"column vs per-point path: counts {'equal' if same else 'DIFFER'} at every point, "
                f"largest degree difference {gap:.1e}"
            )
        for key in ("new", "unstable"):
            spec = issue if key == "new" else unstable
            ds = results[key]["ds"]
            print(f"{key} grid: {int((ds.n_unstable > 0).sum())} unstable of {spec.size}; random points:")
            agree, total = _full_search_check(spec, ds, args.points, rng)
            print(f"    {agree} of {total} agree with the full search")


if __name__ == "__main__":
    main()
