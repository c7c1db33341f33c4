"""Layered tracks against the one-layer track: time the same jobs side by side and print a table.

    python benchmarks/bench_layered.py [--quick] [--size N]

Targets (issue 12): induced frequencies of a two-layer case under 1 s; a 200 x 200 two-layer stability map
under 60 s. Each job runs on the one-layer track (k_f = k_1, c_f = c_1, the same vehicle) and on the
two-layer track of examples/two-layer.toml in the same run; the induced frequencies of
examples/three-layer.toml close the table. Wall time depends on what else runs on the
machine; CPU time (this process and its workers) does not, and is printed next to it.
"""

from __future__ import annotations

import argparse
import resource
import time
from pathlib import Path

import numpy as np

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "two-layer.toml"


def _cpu() -> float:
    own = resource.getrusage(resource.RUSAGE_SELF)
    kids = resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + kids.ru_utime + kids.ru_stime


def _timed(func):
    w0, c0 = time.perf_counter(), _cpu()
    out = func()
    return time.perf_counter() - w0, _cpu() - c0, out


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--quick", action="store_true", help="a 20 x 20 map instead of 200 x 200")
    parser.add_argument("--size", type=int, default=None, help="map size N (N x N)")
    args = parser.parse_args()

    from moving_bogie.api import induced_frequencies, stability_map
    from moving_bogie.model.files import load_params_file
    from moving_bogie.stability.velocity.critical_velocity import critical_velocity

    layered, _ = load_params_file(EXAMPLE)
    one = layered.replace(track="one-layer")
    size = args.size or (20 if args.quick else 200)
    width = 44
    print(f"{'job':<{width}}  {'wall [s]':>9}  {'cpu [s]':>9}  {'target [s]':>10}  result", flush=True)

    def row(label, wall, cpu, target, note):
        t = "-" if target is None else f"{target:g}"
        print(f"{label:<{width}}  {wall:9.2f}  {cpu:9.2f}  {t:>10}  {note}", flush=True)

    alphas = np.linspace(0.0, 1.2, size)
    thetas = np.linspace(1.0, 200.0, size)
    for label, params in (("one-layer", one), ("two-layer", layered)):
        wall, cpu, res = _timed(lambda p=params: critical_velocity(p))
        row(
            f"critical velocity, 30 digits ({label})", wall, cpu, None, f"alpha_cr {float(res.alpha_cr):.10f}"
        )
        wall, cpu, res = _timed(lambda p=params: induced_frequencies(p, dps=30))
        note = f"{res.count} roots, count {'certified' if res.count_ok else 'NOT certified'}"
        row(f"induced frequencies, 30 digits ({label})", wall, cpu, 1.0, note)
        wall, cpu, res = _timed(lambda p=params: stability_map(p, alphas=alphas, thetas=thetas))
        unstable = int(np.count_nonzero(res.count > 0))
        settled = int(res.settled_cells.sum())
        note = f"{unstable} unstable, {int(res.uncertain.sum())} uncertain, {settled} settled"
        row(f"stability map {size} x {size} ({label})", wall, cpu, 60.0, note)
    three, _ = load_params_file(EXAMPLE.with_name("three-layer.toml"))
    wall, cpu, res = _timed(lambda: induced_frequencies(three, dps=30))
    note = f"{res.count} roots, count {'certified' if res.count_ok else 'NOT certified'}"
    note += f", sliver <= {max(u.height for u in res.unsearched):.1e}"
    row("induced frequencies, 30 digits (three-layer)", wall, cpu, None, note)


if __name__ == "__main__":
    main()
