"""Benchmark the notebooks in quick mode, as the tests and the documentation site run them, each in a fresh
process, beside the same notebooks of another checkout.

Run: ``OPENBLAS_NUM_THREADS=1 python benchmarks/bench_notebooks.py [NN ...] [--repeat 2] [--against DIR]``
(``NN`` the numbers of the notebooks, default all). A script, not a test: nothing is asserted, the table is
printed. Each run is ``python notebooks/run.py --quick NOTEBOOK.py`` of its checkout (its runner, its
notebook, its package on PYTHONPATH); its CPU seconds are user + system of the child and of the kernel it
starts and waits for. The checkouts are timed alternately, notebook by notebook, so that both see the same
load; the table gives the least of ``--repeat`` runs.
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent.parent


def run(root: Path, notebook: Path) -> tuple[float, float]:
    """(CPU seconds of the runner and its kernel, wall-clock seconds) of one quick run of ``notebook``."""
    env = dict(os.environ, PYTHONPATH=str(root / "src"), OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    argv = [sys.executable, str(root / "notebooks" / "run.py"), "--quick", str(notebook)]
    subprocess.run(argv, env=env, capture_output=True, text=True, check=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime), wall


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("numbers", nargs="*", metavar="NN", help="notebooks by number (default: all)")
    parser.add_argument("--repeat", type=int, default=2)
    parser.add_argument("--against", type=Path, default=None, help="another checkout, timed alternately")
    args = parser.parse_args()
    checkouts = [("this", HERE)] + ([(args.against.name, args.against.resolve())] if args.against else [])
    names = [p.name for p in sorted((HERE / "notebooks").glob("[0-9][0-9]-*.py"))]
    names = [n for n in names if not args.numbers or n[:2] in args.numbers]
    best: dict[tuple[str, str], tuple[float, float]] = {}
    for name in names:
        for _ in range(args.repeat):
            for label, root in checkouts:
                cpu, wall = run(root, root / "notebooks" / name)
                old = best.get((name, label), (cpu, wall))
                best[(name, label)] = (min(cpu, old[0]), min(wall, old[1]))
    print(f"notebooks/run.py --quick (least of {args.repeat} runs, fresh processes; CPU s, wall s)")
    print(f"{'notebook':<36}" + "".join(f"{label:>16}" for label, _ in checkouts))
    for name in names:
        cells = "".join(f"{best[(name, lb)][0]:>8.2f}{best[(name, lb)][1]:>8.1f}" for lb, _ in checkouts)
        print(f"{name:<36}{cells}")
    totals = "".join(f"{sum(best[(n, lb)][0] for n in names):>8.2f}{'':>8}" for lb, _ in checkouts)
    print(f"{'total CPU':<36}{totals}")


if __name__ == "__main__":
    main()
