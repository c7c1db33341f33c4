"""The test suite's time: the whole suite and the fast subset on two pytest-xdist workers, of this checkout
and of another one side by side.

Run: ``python benchmarks/bench_suite.py [--before DIR] [--only whole|fast] [--record]``

Each run is the README's test command, ``python -m pytest -q -n 2`` (with ``-m "not slow"`` for the fast
subset), in the checkout's folder with its own package first on PYTHONPATH and without pytest's cache
(``-p no:cacheprovider``: as on a fresh clone, the derivation test regenerates every kernel). CPU seconds are
user + system of pytest and of everything it starts (workers, command lines, kernels, browsers). The
checkouts run one after the other, whole suite first; on a machine whose load changes, run it twice.

The notebook tests check the documentation build's runs of the notebooks where a checkout has current ones
(``docs/tutorials/``, ``tests/test_notebooks.py``), as in ``.ci/run``, which builds the site first; otherwise
they run the notebooks, about 80 s of CPU more. The column ``notebooks`` says which. A script, not a test:
nothing is asserted, the table is printed.
"""

from __future__ import annotations

import argparse
import importlib.util
import os
import resource
import subprocess
import sys
import time
from pathlib import Path

from records import add_record_option, row, source_revision, write_record

HERE = Path(__file__).resolve().parent.parent
#: The subsets: name -> (what is run, the pytest arguments after ``-q -n 2``, the target in seconds).
SUBSETS = {
    "whole": ("whole suite, pytest -q -n 2", [], 300.0),
    "fast": ('fast subset, pytest -q -n 2 -m "not slow"', ["-m", "not slow"], 60.0),
}


def notebooks_reused(root: Path) -> str:
    """Whether the notebook tests of the checkout ``root`` check current runs of the documentation build
    ("reused") or run the notebooks ("run"): the checkout's own runner decides, as its tests do."""
    runner_path = root / "notebooks" / "run.py"
    spec = importlib.util.spec_from_file_location("suite_runner", runner_path)
    if spec is None or spec.loader is None:
        return "run"
    runner = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(runner)
    if not hasattr(runner, "check_executed"):
        return "run"
    newest = runner.newest_package_file(root / "src" / "moving_bogie")  # that checkout's package, not ours
    for source in sorted((root / "notebooks").glob("[0-9][0-9]-*.py")):
        built = root / "docs" / "tutorials" / f"{source.stem}.ipynb"
        if not runner.is_current(source, built, newest) or runner.check_executed(source, built, quick=True):
            return "run"
    return "reused"


def run_suite(root: Path, extra: list[str]) -> tuple[float, float, str]:
    """(wall seconds, CPU seconds, pytest's summary line) of one run of the suite of ``root``."""
    env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
    env["PYTHONPATH"] = os.pathsep.join(p for p in (str(root / "src"), env.get("PYTHONPATH")) if p)
    argv = [sys.executable, "-m", "pytest", "-q", "-n", "2", "-p", "no:cacheprovider", *extra]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    proc = subprocess.run(argv, cwd=root, env=env, capture_output=True, text=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    lines = [line for line in proc.stdout.splitlines() if line.strip()]
    summary = lines[-1].strip("= ") if lines else f"exit {proc.returncode}"
    return wall, cpu, summary


def _counts(summary: str) -> str:
    """pytest's counts without its time (``1109 passed, 5 skipped`` of ``1109 passed, 5 skipped in 315s``)."""
    return summary.split(" in ")[0]


def _row(name: str, measured: dict, reused: dict) -> dict:
    """The record's row of one subset: this checkout measured, the other one the alternative."""
    work, _, target = SUBSETS[name]
    wall, cpu, summary = measured[(name, "this")]
    text = f"{wall:.0f} s wall, {cpu:.0f} s CPU; {_counts(summary)}"
    other = measured.get((name, "before"))
    alternative = "-"
    if other is not None:
        alternative = f"the code before: {other[0]:.0f} s wall, {other[1]:.0f} s CPU; {_counts(other[2])}"
    if name == "whole":
        work += f" (notebooks: {reused['this']}" + (f"; before: {reused['before']})" if other else ")")
    return row(work, text, alternative, f"{target:.0f} s")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--before", type=Path, default=None, help="another checkout (its root folder)")
    parser.add_argument("--only", choices=sorted(SUBSETS), action="append", help="one subset (repeatable)")
    add_record_option(parser)
    args = parser.parse_args()
    checkouts = [("this", HERE)] + ([("before", args.before.resolve())] if args.before else [])
    names = args.only or list(SUBSETS)
    measured: dict[tuple[str, str], tuple[float, float, str]] = {}
    reused = {label: notebooks_reused(root) for label, root in checkouts}
    for name in names:
        for label, root in checkouts:
            print(f"  {name} suite of {label}: running", file=sys.stderr, flush=True)
            measured[(name, label)] = run_suite(root, SUBSETS[name][1])
    print(f"{'subset':<8}{'code':<8}{'wall s':>8}{'CPU s':>8}  {'notebooks':<10}{'target s':>9}  pytest")
    rows = []
    for name in names:
        target = SUBSETS[name][2]
        for label, _ in checkouts:
            wall, cpu, summary = measured[(name, label)]
            print(f"{name:<8}{label:<8}{wall:>8.1f}{cpu:>8.1f}  {reused[label]:<10}{target:>9.0f}  {summary}")
        rows.append(_row(name, measured, reused))
    if args.record:
        placeholders = {str(args.before): "DIR"} if args.before else None
        title = "Test suite (two workers, no pytest cache)"
        if args.before:
            title += f"; before: {source_revision(args.before)}"
        write_record(__file__, title, rows, placeholders)


if __name__ == "__main__":
    main()
