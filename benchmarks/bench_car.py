"""Benchmark the induced frequencies of the car (four contacts) side by side with one of its bogies.

Run: ``OPENBLAS_NUM_THREADS=1 python benchmarks/bench_car.py [--dps 30] [--repeat 3] [--against DIR]``. A
script, not a test: nothing is asserted, the numbers are printed.

In the same run and the same process, for ``examples/car.toml`` (a passenger car per rail, SI):

* ``car``: :func:`moving_bogie.roots.frequencies.induced_frequencies` on the car (the block system of
  ``kernels/vehicle.py``, 10 x 10, four contacts);
* ``bogie``: the same search on one bogie of that car alone (its wheels, frame and primary suspension, the
  car's load per wheel), the paper's vehicle (the block system, 4 x 4, two contacts).

Each run is a fresh child process (imports and first-call set-up included, as for one command).
``--against DIR`` measures the same rows with the package of another checkout (``DIR/src``, e.g. the code
before a change), run by run alternately with this one, so that both see the same load; its rows are marked
with the directory's name, and the roots of both are compared digit by digit.

Times are CPU seconds of the child process's search (``time.process_time``), the least of ``--repeat``
runs, so a busy machine does not inflate them.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import subprocess
import sys
import time
from pathlib import Path

from moving_bogie.api import induced_frequencies
from moving_bogie.model.files import load_params_file

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "car.toml"
BOGIE = ("alpha", "eta_f", "eta_s", "eta_M", "d", "mu_v", "J_b", "kappa_v", "eta_v")


def run(params, dps: int) -> dict:
    t0 = time.process_time()
    result = induced_frequencies(params, dps=dps)
    return {
        "seconds": time.process_time() - t0,
        "roots": len(result.roots),
        "count_ok": result.count_ok,
        "verdict": result.verdict.state,
        "radius": result.far_field.radius,
        "evaluations": result.evaluations,
        "digits": [f"{r.re_text} {r.im_text} {r.digits}" for r in result.roots],
    }


def measure(dps: int) -> dict:
    """One run of both rows in this process: {vehicle: row}."""
    car, _ = load_params_file(EXAMPLE)
    values = car.to_exact_dict()
    bogie = car.replace(vehicle="bogie", **{k: values[k] for k in BOGIE})
    return {name: run(params, dps) for name, params in (("bogie", bogie), ("car", car))}


def measure_elsewhere(directory: Path, dps: int) -> dict:
    """:func:`measure` with the package of ``directory`` (its ``src``), in a child process."""
    env = dict(os.environ, PYTHONPATH=f"{directory / 'src'}{os.pathsep}{directory}")
    out = subprocess.run(
        [sys.executable, __file__, "--dps", str(dps), "--json-once"],
        env=env,
        capture_output=True,
        text=True,
        check=True,
    )
    return json.loads(out.stdout)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--dps", type=int, default=30)
    parser.add_argument("--repeat", type=int, default=3, help="runs of each row; the least CPU time is shown")
    parser.add_argument("--against", type=Path, help="another checkout to measure alternately (DIR/src)")
    parser.add_argument("--json-once", action="store_true", help=argparse.SUPPRESS)
    ns = parser.parse_args()
    if ns.json_once:
        print(json.dumps(measure(ns.dps)))
        return
    here = Path(__file__).resolve().parent.parent
    trees = [("this", here)] + ([(ns.against.name or str(ns.against), ns.against)] if ns.against else [])
    best: dict = {}
    for _ in range(ns.repeat):
        for label, directory in trees:
            rows = measure_elsewhere(directory, ns.dps)
            for name, row in rows.items():
                key = (name, label)
                if key not in best or row["seconds"] < best[key]["seconds"]:
                    best[key] = row
    head = f"python {platform.python_version()}, {platform.machine()}, dps {ns.dps}"
    print(f"{head}, least of {ns.repeat} runs")
    print(
        f"{'vehicle':<8} {'code':<10} {'CPU s':>7} {'roots':>6} {'count':>6} {'verdict':>10} {'R':>6} "
        f"{'E evals':>9}"
    )
    for name in ("bogie", "car"):
        for label, _ in trees:
            row = best[(name, label)]
            print(
                f"{name:<8} {label:<10} {row['seconds']:7.2f} {row['roots']:6d} {str(row['count_ok']):>6} "
                f"{row['verdict']:>10} {row['radius'] or float('nan'):6.3g} {row['evaluations']:9d}"
            )
    if ns.against:
        for name in ("bogie", "car"):
            same = best[(name, "this")]["digits"] == best[(name, trees[1][0])]["digits"]
            verdict = "equal" if same else "DIFFERS"
            print(f"{name}: every confirmed digit of every root {verdict} in both codes")


if __name__ == "__main__":
    main()
