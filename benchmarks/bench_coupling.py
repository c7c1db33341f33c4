"""Benchmark the one vehicle-rail coupling (``kernels/coupling.py``) per number type, and ``table2``.

Run: ``OPENBLAS_NUM_THREADS=1 python benchmarks/bench_coupling.py [--repeat 3] [--against DIR]``. A script,
not a test: nothing is asserted, the numbers are printed.

* ``coupling``: one evaluation of the block system A, its q-derivative dA and the load vector b for each
  shipped vehicle, in mpmath (30 digits), gmpy2 (113 bits), Arb (128 bits) and numpy (a batch of 1,000
  points, per point), from made-up kernel values: the least of ``--repeat`` timings of a loop;
* ``table2``: ``moving-bogie table2`` as a fresh child process (CPU seconds of the child, user + system),
  the least of ``--repeat`` runs. ``--against DIR`` runs the same command with the package of another
  checkout (``DIR/src``) alternately with this one, so that both see the same load, and says whether the
  two outputs are identical.
"""

from __future__ import annotations

import argparse
import importlib
import os
import resource
import subprocess
import sys
import time
from pathlib import Path

import gmpy2
import mpmath
import numpy as np
from flint import acb, arb, ctx

from moving_bogie.kernels.arithmetic import Batched, Rows
from moving_bogie.kernels.coupling import coupled_system, dynamic_stiffness

HERE = Path(__file__).resolve().parent.parent
VEHICLES = ("mass", "oscillator", "masses", "bogie", "car")


def _inputs(name: str):
    module = importlib.import_module(f"moving_bogie.generated.vehicle_{name}")
    rng = np.random.default_rng(1)
    params = {k: float(10 ** rng.uniform(-1, 1)) for k in module.MATRIX_ARGUMENTS}
    n = module.CONTACTS
    G = rng.normal(size=(2, n, n)) + 1j * rng.normal(size=(2, n, n))
    return module, params, G


def _one(module, params, G, ops, convert, q) -> None:
    values = {k: convert(v) for k, v in params.items()}
    matrices = [
        [[x if isinstance(x, int) and x == 0 else convert(x) for x in row] for row in f(**values)]
        for f in (module.mass_matrix, module.damping_matrix, module.stiffness_matrix)
    ]
    loads = module.static_loads(**values)
    Gq = [[convert(x) for x in row] for row in G[0]]
    dG = [[convert(x) for x in row] for row in G[1]]

    def evaluate() -> None:
        D, dD = dynamic_stiffness(q, matrices, ops, derivative=True)
        coupled_system(D, Gq, ops, loads=loads, dD=dD, dG=dG)

    return evaluate


def _batched(module, params, G):
    """(one batched evaluation at 1,000 points, the number of points)."""
    q = np.linspace(0.1, 2.0, 1000) + 0.2j
    functions = (module.mass_matrix, module.damping_matrix, module.stiffness_matrix)
    matrices = [np.array(f(**params), dtype=float) for f in functions]
    Gq = np.broadcast_to(G[0], q.shape + G[0].shape)
    loads = module.static_loads(**params)

    def evaluate() -> None:
        D, dD = dynamic_stiffness(q, matrices, Batched, derivative=True)
        coupled_system(D, Gq, Batched, loads=loads, dD=dD, dG=Gq)

    return evaluate, q.size


def _best(run, repeat: int, loops: int) -> float:
    best = float("inf")
    for _ in range(repeat):
        start = time.perf_counter()
        for _ in range(loops):
            run()
        best = min(best, (time.perf_counter() - start) / loops)
    return best


def coupling_rows(repeat: int) -> None:
    print(f"{'vehicle':<11}{'mpmath':>12}{'gmpy2':>12}{'Arb':>12}{'numpy/point':>14}   (one A, dA, b)")
    for name in VEHICLES:
        module, params, G = _inputs(name)
        times = []
        with mpmath.workdps(30):
            ops = Rows(mpmath.pi, mpmath.mpc(0, 1))
            times.append(
                _best(_one(module, params, G, ops, mpmath.mpmathify, mpmath.mpc(0.7, 0.2)), repeat, 200)
            )
        with gmpy2.context(gmpy2.get_context(), precision=113):
            ops = Rows(gmpy2.const_pi(), gmpy2.mpc(0, 1))
            times.append(_best(_one(module, params, G, ops, gmpy2.mpc, gmpy2.mpc(0.7, 0.2)), repeat, 200))
        with ctx.workprec(128):
            ops = Rows(acb(arb.pi()), acb(0, 1))
            times.append(_best(_one(module, params, G, ops, acb, acb(0.7, 0.2)), repeat, 200))
        batched, points = _batched(module, params, G)
        times.append(_best(batched, repeat, 20) / points)
        print(
            f"{name:<11}" + "".join(f"{t * 1e6:>10.1f}us" for t in times[:3]) + f"{times[3] * 1e6:>12.3f}us"
        )


def table2_seconds(src: Path) -> tuple[float, str]:
    """CPU seconds (user + system) of ``moving-bogie table2`` with the package in ``src``, and its output."""
    env = dict(os.environ, PYTHONPATH=f"{src}{os.pathsep}{src.parent}", OPENBLAS_NUM_THREADS="1")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    out = subprocess.run(
        [sys.executable, "-m", "moving_bogie", "table2"], env=env, capture_output=True, text=True, check=True
    ).stdout
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime), out


def table2_rows(repeat: int, against: Path | None) -> None:
    checkouts = [("this", HERE / "src")] + ([(against.name, against / "src")] if against else [])
    best = {label: float("inf") for label, _ in checkouts}
    outputs = {}
    for _ in range(repeat):
        for label, src in checkouts:
            seconds, outputs[label] = table2_seconds(src)
            best[label] = min(best[label], seconds)
    for label, seconds in best.items():
        print(f"table2 ({label}): {seconds:.2f} s CPU (least of {repeat})")
    if against:
        print("outputs identical:", len(set(outputs.values())) == 1)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--against", type=Path, default=None, help="another checkout, timed alternately")
    parser.add_argument("--no-table2", action="store_true", help="only the coupling rows")
    args = parser.parse_args()
    coupling_rows(args.repeat)
    if not args.no_table2:
        table2_rows(args.repeat, args.against)


if __name__ == "__main__":
    main()
