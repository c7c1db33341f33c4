"""Benchmark the induced frequencies of the car (four contacts) side by side with one of its bogies.

Run: ``OPENBLAS_NUM_THREADS=1 python benchmarks/bench_car.py [--dps 30]``. A script, not a test: nothing is
asserted, the numbers are printed.

In the same run and the same process, for ``examples/car.toml`` (a passenger car per rail, SI):

* ``car``: :func:`moving_bogie.roots.frequencies.induced_frequencies` on the car (the block system of
  ``kernels/vehicle.py``, 10 x 10, four contacts);
* ``bogie``: the same search on one bogie of that car alone (its wheels, frame and primary suspension, the
  car's load per wheel), the paper's vehicle (the block system, 4 x 4, two contacts).

Times are CPU seconds of this process (``time.process_time``), so a busy machine does not inflate them.
"""

from __future__ import annotations

import argparse
import platform
import time
from pathlib import Path

from moving_bogie.model.files import load_params_file
from moving_bogie.roots.frequencies import induced_frequencies

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
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--dps", type=int, default=30)
    ns = parser.parse_args()
    car, _ = load_params_file(EXAMPLE)
    values = car.to_exact_dict()
    bogie = car.replace(vehicle="bogie", **{k: values[k] for k in BOGIE})
    print(f"python {platform.python_version()}, {platform.machine()}, dps {ns.dps}")
    print(f"{'vehicle':<8} {'CPU s':>7} {'roots':>6} {'count':>6} {'verdict':>10} {'R':>6} {'E evals':>9}")
    for name, params in (("bogie", bogie), ("car", car)):
        row = run(params, ns.dps)
        print(
            f"{name:<8} {row['seconds']:7.2f} {row['roots']:6d} {str(row['count_ok']):>6} "
            f"{row['verdict']:>10} {row['radius'] or float('nan'):6.3g} {row['evaluations']:9d}"
        )


if __name__ == "__main__":
    main()
