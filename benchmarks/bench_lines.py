"""Time the instability lines (Figures 3, 4, 7, 8; one panel as the ``instability-lines`` command traces it)
and the frequency lines (Figure 2) of this checkout against another one, side by side, and print a table.

Run: ``OPENBLAS_NUM_THREADS=1 python benchmarks/bench_lines.py [--against DIR] [--full] [--repeat 2]``.
A script, not a test: nothing is asserted. Each job runs in a fresh child process with ``PYTHONPATH`` set to
the ``src`` folder of the checkout timed; the table gives the least of ``--repeat`` runs of the child's
CPU seconds (user + system; the import of the package is timed apart and subtracted), this checkout and
``--against`` alternately, so that the load of the machine weighs on both alike. The figures are drawn
in quick mode (the grids of ``reproduce --quick``) unless ``--full``.
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent.parent

#: job -> the Python code the child runs ({quick} is True or False).
JOBS = {
    "import only": "",
    "1 panel: bogie, eta_f = 0.05, 6 spacings": (
        "from moving_bogie.api import instability_lines\n"
        "from moving_bogie.paper.stability_figures import SPACINGS, _base, _grid\n"
        "instability_lines(_base('0.05'), spacings=SPACINGS, alpha_range=(0, 1), **_grid({quick}))"
    ),
    **{
        f"Figure {n} ({panels} sets of lines)": (
            f"from moving_bogie.paper.stability_figures import figure{n}\nfigure{n}(quick={{quick}})"
        )
        for n, panels in ((3, 6), (4, 12), (7, 4), (8, 3))
    },
    "Figure 2 (frequency lines of Case 1)": (
        "from moving_bogie.paper.stability_figures import figure2\nfigure2(quick={quick})"
    ),
}


def run(src: Path, code: str) -> float:
    """CPU seconds (user + system) of a child running ``code`` with the package of ``src``."""
    env = dict(
        os.environ, PYTHONPATH=str(src), OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1", MPLBACKEND="Agg"
    )
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    prelude = "import matplotlib\nimport moving_bogie.api\nimport moving_bogie.paper.stability_figures\n"
    subprocess.run([sys.executable, "-c", prelude + code], env=env, check=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--against", type=Path, default=None, help="another checkout, timed alternately")
    parser.add_argument("--full", action="store_true", help="the full grids (minutes per figure)")
    parser.add_argument("--repeat", type=int, default=1)
    args = parser.parse_args()
    sources = {"this": HERE / "src"}
    if args.against is not None:
        sources["against"] = args.against.resolve() / "src"
    best: dict[tuple[str, str], float] = {}
    for _ in range(args.repeat):
        for job, code in JOBS.items():
            for name, src in sources.items():
                cpu = run(src, code.format(quick=not args.full))
                best[job, name] = min(cpu, best.get((job, name), float("inf")))
    header = f"{'job (' + ('full' if args.full else 'quick') + ' grids)':44s} {'this [s CPU]':>13s}"
    if args.against is not None:
        header += f" {'against [s CPU]':>16s} {'speed-up':>9s}"
    print(header)
    for job in JOBS:
        start = {name: 0.0 if job == "import only" else best["import only", name] for name in sources}
        this = best[job, "this"] - start["this"]
        line = f"{job:44s} {this:13.2f}"
        if args.against is not None:
            other = best[job, "against"] - start["against"]
            ratio = "" if job == "import only" else f"{other / this:8.1f}x"
            line += f" {other:16.2f} {ratio:>9s}"
        print(line)


if __name__ == "__main__":
    main()
