"""Benchmark ``frequencies`` on a rail on sleepers (every root of the strip down to the free waves, the
verdict and a stable result's margin) beside the continuous track of the same smeared stiffness, in one run.

Run: ``OPENBLAS_NUM_THREADS=1 python benchmarks/bench_sleepers.py [--repeat 3] [--against DIR] [--record]``.
A script, not a test: nothing is asserted, the table is printed.

Two cases: ``examples/sleepers.toml`` (stable: its margin, the least-damped vibration's decay rate) and
``examples/sleepers_zones.toml`` at ``v = 97.2881`` m/s, ``M = 1416`` kg (unstable: inside the principal
parametric zone). The continuous track of each is its ``l -> 0`` limit (docs/sleepers.md): the paper's
one-layer track with ``k_f = k_sup / l + k_f`` and ``c_f = c_sup / l + c_f``, the same rail, vehicle and
speed; both are written to temporary files. Each command runs as a fresh child process (``python -m
moving_bogie frequencies --file ... --json``); the table gives the least of ``--repeat`` runs of its CPU
seconds (user + system of the child) and of its wall-clock seconds, the verdict, the roots counted (each
search in its own window) and the margin [1/s] of a stable result. The tracks (and, with ``--against``,
the same commands with the package of another checkout, ``DIR/src``) are timed alternately, so that all see
the same load.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
import tomllib
from pathlib import Path

HERE = Path(__file__).resolve().parent.parent


#: (name, file, [physical] values set) of the cases timed
CASES = [
    ("stable", "sleepers.toml", {}),
    ("unstable", "sleepers_zones.toml", {"v": 97.2881, "M": 1416.0}),
]


def _write(model: dict, si: dict, out: Path) -> Path:
    lines = ["[model]"] + [f'{k} = "{v}"' for k, v in model.items()] + ["", "[physical]"]
    lines += [f"{k} = {float(v)!r}" for k, v in si.items()]
    out.write_text("\n".join(lines) + "\n")
    return out


def sleeper_file(sleepers: Path, values: dict, out: Path) -> Path:
    """The sleeper file with ``values`` set in its ``[physical]`` table."""
    data = tomllib.loads(sleepers.read_text())
    return _write(data["model"], dict(data["physical"]) | values, out)


def continuous_file(sleepers: Path, out: Path) -> Path:
    """The one-layer track of the same smeared stiffness and damping as the sleeper file (l -> 0)."""
    data = tomllib.loads(sleepers.read_text())
    si = dict(data["physical"])
    if data["model"]["track"] != "sleepers":
        raise SystemExit("--file: the continuous counterpart is written for track = 'sleepers'")
    bay = si.pop("l")
    si["k_f"] = si.pop("k_sup") / bay + si.get("k_f", 0.0)
    si["c_f"] = si.pop("c_sup", 0.0) / bay + si.get("c_f", 0.0)
    model = {k: v for k, v in data["model"].items() if k != "track"}
    return _write(model, si, out)


def run(src: Path, path: Path) -> tuple[float, float, dict]:
    """(CPU seconds of the child, wall-clock seconds, its JSON output) of one ``frequencies --file``."""
    env = dict(os.environ, PYTHONPATH=f"{src}{os.pathsep}{src.parent}", OPENBLAS_NUM_THREADS="1")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    out = subprocess.run(
        [sys.executable, "-m", "moving_bogie", "frequencies", "--file", str(path), "--json"],
        env=env,
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return cpu, wall, json.loads(out)


def margin(out: dict) -> str:
    """The margin [1/s] of a stable result: the sleeper track's ``margin_1_s``, on the continuous track the
    decay rate Im omega of its least-damped root; "-" for an unstable result."""
    if "margin_1_s" in out:
        return "-" if out["margin_1_s"] is None else f"{out['margin_1_s']:.4g}"
    rates = [float(r["omega"]["im"]) for r in out.get("roots", []) if "omega" in r]
    return f"{min(rates):.4g}" if rates and min(rates) > 0 else "-"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--against", type=Path, default=None, help="another checkout, timed alternately")
    from records import add_record_option

    add_record_option(parser)
    args = parser.parse_args()
    checkouts = [("this", HERE / "src")] + (
        [(args.against.name, args.against / "src")] if args.against else []
    )
    best: dict[tuple[str, str, str], list] = {}
    with tempfile.TemporaryDirectory() as tmp:
        runs = []
        for case, name, values in CASES:
            path = sleeper_file(HERE / "examples" / name, values, Path(tmp) / f"{case}.toml")
            runs += [
                (case, "sleepers", path),
                (case, "one-layer", continuous_file(path, Path(tmp) / f"c{case}.toml")),
            ]
        for _ in range(args.repeat):
            for label, src in checkouts:
                for case, track, path in runs:
                    cpu, wall, out = run(src, path)
                    old = best.get((label, case, track))
                    best[(label, case, track)] = [
                        min(cpu, old[0]) if old else cpu,
                        min(wall, old[1]) if old else wall,
                        out,
                    ]
    print(f"frequencies --file (least of {args.repeat} runs, fresh processes)")
    width = max(len("checkout"), *(len(label) for label, _ in checkouts)) + 2
    head = f"{'checkout':<{width}}{'case':<10}{'track':<12}{'CPU s':>8}{'wall s':>9}"
    print(head + f"  {'verdict':<13}{'roots':>6}{'margin 1/s':>12}  harmonics")
    for (label, case, track), (cpu, wall, out) in best.items():
        harmonics = out.get("harmonics") or (out.get("region") or {}).get("harmonics")
        span = f"{harmonics[0]}..{harmonics[-1]}" if harmonics else "-"
        verdict = out["verdict"] if isinstance(out["verdict"], str) else out["verdict"]["state"].upper()
        print(
            f"{label:<{width}}{case:<10}{track:<12}{cpu:>8.2f}{wall:>9.2f}  {verdict:<13}{out['count']:>6}"
            f"{margin(out):>12}  {span}"
        )
    if args.record:
        record(best)


def record(best: dict) -> None:
    """benchmarks/results/bench_sleepers.json: this checkout's sleeper track, the continuous one beside it."""
    from records import row, write_record

    def cost(key: tuple[str, str, str]) -> str:
        cpu, wall, out = best[key]
        verdict = out["verdict"] if isinstance(out["verdict"], str) else out["verdict"]["state"].upper()
        return f"{cpu:.2f} s CPU ({wall:.2f} s wall), {verdict}, margin {margin(out)} 1/s"

    rows = []
    for (case, name, values), target in zip(CASES, ("< 3 s", "< 5 s")):
        sets = "".join(f" --set {k}={v:g}" for k, v in values.items())
        work = f"frequencies --file {name}{sets} (every root of the strip to the free waves, the margin)"
        continuous = cost(("this", case, "one-layer"))
        alternative = f"the continuous one-layer track of the same smeared stiffness: {continuous}"
        rows.append(row(work, cost(("this", case, "sleepers")), alternative, target))
    write_record(
        __file__,
        "A rail on sleepers beside the continuous track",
        rows,
        entries=("moving_bogie.__main__", "moving_bogie.cli.frequencies_cmd"),
    )


if __name__ == "__main__":
    main()
