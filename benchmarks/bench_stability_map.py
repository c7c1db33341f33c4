"""Time stability maps (verdict, degree and margin of every cell) of this checkout against another one, side
by side, and compare what they computed.

Run: ``OPENBLAS_NUM_THREADS=1 python benchmarks/bench_stability_map.py --against DIR [--repeat 2]``.
A script, not a test: nothing is asserted, the table is printed. Each map is computed on one worker in a
fresh child process with ``PYTHONPATH`` set to the ``src`` folder of the checkout timed (its CPU seconds,
user + system, minus those of a child that only imports the package); the checkouts alternate, map by map,
so that both see the same load, and the table keeps the least of ``--repeat`` runs. The last columns
compare the two maps: the cells whose count, degree, bound flag or certainty differ, and the largest
difference of the margins.
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent.parent

#: map -> the code that computes it (``smap``), run with the package of the checkout timed.
MAPS = {
    "Case 1, 30 alphas x 60 wheel masses": (
        "from moving_bogie.model.cases import table1_case\n"
        "smap = stability_map(table1_case(1), alphas=np.linspace(0.005, 1.2, 30), "
        "thetas=np.linspace(0.5, 200, 60), workers=1)"
    ),
    "Case 5, 12 alphas x 30 wheel masses": (
        "from moving_bogie.model.cases import table1_case\n"
        "smap = stability_map(table1_case(5), alphas=np.linspace(0.3, 1.1, 12), "
        "thetas=np.linspace(2, 120, 30), workers=1)"
    ),
    "two-layer track, 6 x 10": (
        "from moving_bogie.model.files import load_params_file\n"
        f"p = load_params_file({str(HERE / 'examples' / 'two-layer.toml')!r})[0]\n"
        "smap = stability_map(p, alphas=np.linspace(0.1, 0.9, 6), thetas=np.linspace(5, 60, 10), workers=1)"
    ),
}
PRELUDE = "import numpy as np\nfrom moving_bogie.api import stability_map\n"
SAVE = (
    "\nnp.savez({out!r}, **{{k: np.asarray(getattr(smap, k)) "
    "for k in ('count', 'degree', 'margin', 'margin_bound', 'uncertain')}})\n"
)


def run(src: Path, code: str) -> float:
    """CPU seconds (user + system) of a child running ``code`` with the package of ``src``."""
    env = dict(os.environ, PYTHONPATH=str(src), OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([sys.executable, "-c", PRELUDE + code], env=env, check=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def compare(a: Path, b: Path) -> str:
    """Cells that differ in count, degree, bound or certainty; the largest margin difference."""
    x, y = np.load(a), np.load(b)
    cells = sum(
        int(np.sum(~((x[k] == y[k]) | (np.isnan(x[k]) & np.isnan(y[k]))))) if x[k].dtype.kind == "f" else
        int(np.sum(x[k] != y[k]))
        for k in ("count", "degree", "margin_bound", "uncertain")
    )  # fmt: skip
    margin = float(np.nanmax(np.abs(x["margin"] - y["margin"]), initial=0.0))
    return f"{cells:6d} {margin:13.1e}"


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--against", type=Path, required=True, help="another checkout, timed alternately")
    parser.add_argument("--repeat", type=int, default=1)
    args = parser.parse_args()
    sources = {"this": HERE / "src", "against": args.against.resolve() / "src"}
    best: dict[tuple[str, str], float] = {}
    with tempfile.TemporaryDirectory() as tmp:
        saved = {(job, name): Path(tmp) / f"{k}-{name}.npz" for k, job in enumerate(MAPS) for name in sources}
        for _ in range(args.repeat):
            for name, src in sources.items():
                best["import", name] = min(run(src, ""), best.get(("import", name), float("inf")))
            for job, code in MAPS.items():
                for name, src in sources.items():
                    cpu = run(src, code + SAVE.format(out=str(saved[job, name])))
                    best[job, name] = min(cpu, best.get((job, name), float("inf")))
        print(f"{'map (1 worker)':40s} {'this [s CPU]':>13s} {'against':>8s} {'speed-up':>9s} {'cells':>6s} "
              f"{'margin diff':>13s}")  # fmt: skip
        for job in MAPS:
            this, other = (best[job, name] - best["import", name] for name in sources)
            print(f"{job:40s} {this:13.2f} {other:8.2f} {other / this:8.1f}x "
                  f"{compare(saved[job, 'this'], saved[job, 'against'])}")  # fmt: skip


if __name__ == "__main__":
    main()
