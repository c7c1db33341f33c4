"""The threshold mass and the (v, M) map on the soil, side by side with the window search.

    python benchmarks/bench_soil_map.py [--n 8] [--workers 2] [--record]

In one run, wall time of, on ``examples/soil-unstable.toml`` (a heavy mass faster than the critical
velocity on a soft half-space):

- the D-decomposition in the wheel mass along real Omega at the file's speed (every crossing, the
  threshold mass; ``instability-lines --file``), beside the window search at the file's mass (one
  argument-principle count and its roots; ``frequencies --file``), which settles one mass only;
- the (v, M) map of ``--n`` x ``--n`` cells on ``--workers`` processes (``stability-map --file``; the
  issue's goal: 50 x 50 on 2 workers under 3 min), and the time per column, from which the 50 x 50 map's
  time follows (its columns are independent: the mass axis costs nothing);
- the machine's load average over the run (the timings scale with it on a shared machine).

Prints a table; nothing is asserted (tests/test_soil_threshold.py checks the values).
"""

from __future__ import annotations

import argparse
import math
import os
import time
from pathlib import Path

import numpy as np

from moving_bogie.api import bind, induced_frequencies, load_soil_vehicle, soil_vehicle
from moving_bogie.kernels.bound import BoundModel
from moving_bogie.stability.maps.real_axis import window_column
from moving_bogie.stability.maps.real_axis_map import real_axis_map

FILE = Path(__file__).resolve().parent.parent / "examples" / "soil-unstable.toml"


def _timed(func):
    start = time.perf_counter()
    out = func()
    return time.perf_counter() - start, out


def _at_speed(vehicle, v: float):
    import dataclasses

    values = tuple((k, v if k == "v" else x) for k, x in vehicle.input.vehicle_values)
    return soil_vehicle(dataclasses.replace(vehicle.input, vehicle_values=values))


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=8, help="cells per axis of the map timed (default 8)")
    parser.add_argument("--workers", type=int, default=2, help="processes of the map (default 2)")
    parser.add_argument("--record", action="store_true", help="write benchmarks/results/bench_soil_map.json")
    args = parser.parse_args()
    vehicle = load_soil_vehicle(FILE)
    bound = bind(vehicle)
    eta = float(bound.floats.eta_M)
    unit = vehicle.physical.si_factor("eta_M") / vehicle.input.rail_factor
    equivalent = BoundModel(bound.params)
    t_col, col = _timed(
        lambda: window_column(bound, equivalent=equivalent, eta_max=4 * eta, eta_min=eta / 16)
    )
    t_win, res = _timed(lambda: induced_frequencies(vehicle))
    threshold = col.threshold
    text = "none" if threshold is None else f"M* = {threshold.eta_M * unit:.6g} kg"
    rows = [
        (
            "D-decomposition at the file's speed (every mass)",
            f"{t_col:.1f} s ({text}, {col.samples} samples)",
            f"window search at one mass: {t_win:.1f} s (count {res.count}, {res.verdict.state})",
            "-",
        )
    ]
    v, n = float(vehicle.physical.v), args.n
    vs, ms = np.linspace(v / 2, 1.5 * v, n), np.linspace(4 * eta * unit / n, 4 * eta * unit, n)
    bounds = [bind(_at_speed(vehicle, float(x))) for x in vs]
    columns = [(b, BoundModel(b.params)) for b in bounds]
    scales = (vehicle.physical.scales().v_ref, unit, 1.0)
    t_map, smap = _timed(
        lambda: real_axis_map(
            columns, vs, ms, scales=scales, name="soil/mass", track="soil", identity="", workers=args.workers
        )
    )
    per_column = t_map * min(args.workers, n) / n
    full = per_column * math.ceil(50 / args.workers)
    rows.append(
        (
            f"(v, M) map {n} x {n} on {args.workers} workers",
            f"{t_map:.1f} s ({int((smap.count > 0).sum())} unstable cells)",
            f"{per_column:.1f} s per column: 50 x 50 about {full / 60:.1f} min",
            "50 x 50 < 3 min",
        )
    )
    rows.append(("load average of the machine (1 min, at the end)", f"{os.getloadavg()[0]:.1f}", "-", "-"))
    header = ("work", "measured", "alternative", "target")
    widths = [max(len(str(r[k])) for r in [*rows, header]) for k in range(4)]
    for r in [header, *rows]:
        print(" | ".join(str(x).ljust(w) for x, w in zip(r, widths, strict=True)))
    if args.record:
        from records import row, write_record

        write_record(
            __file__,
            "The threshold mass and the (v, M) map on the soil",
            [row(*r) for r in rows],
            entries=("moving_bogie.stability.maps.real_axis_map",),
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
