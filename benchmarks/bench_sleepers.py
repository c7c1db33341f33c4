"""Benchmark one ``frequencies`` call on a rail on sleepers beside the continuous track of the same smeared
stiffness, in one run.

Run: ``OPENBLAS_NUM_THREADS=1 python benchmarks/bench_sleepers.py [--file examples/sleepers.toml]
[--repeat 3] [--against DIR] [--record]``. A script, not a test: nothing is asserted, the table is printed.

The continuous track is the ``l -> 0`` limit of the file's (docs/sleepers.md): the paper's one-layer track
with ``k_f = k_sup / l + k_f`` and ``c_f = c_sup / l + c_f``, the same rail, vehicle and speed, written to a
temporary file. Each command runs as a fresh child process (``python -m moving_bogie frequencies --file
... --json``); the table gives the least of ``--repeat`` runs of its CPU seconds (user + system of the child)
and of its wall-clock seconds, the verdict and the roots counted (each search in its own window: the
strip's Im Omega <= 0 on sleepers, the paper's window on the continuous track). The two tracks (and, with
``--against``, the same commands with the package of another checkout, ``DIR/src``) are timed alternately,
so that all see the same load.
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
    lines = ["[model]"] + [f'{k} = "{v}"' for k, v in model.items()] + ["", "[physical]"]
    lines += [f"{k} = {float(v)!r}" for k, v in si.items()]
    out.write_text("\n".join(lines) + "\n")
    return out


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


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--file", type=Path, default=HERE / "examples" / "sleepers.toml")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--against", type=Path, default=None, help="another checkout, timed alternately")
    from records import add_record_option

    add_record_option(parser)
    args = parser.parse_args()
    checkouts = [("this", HERE / "src")] + (
        [(args.against.name, args.against / "src")] if args.against else []
    )
    with tempfile.TemporaryDirectory() as tmp:
        tracks = [("sleepers", args.file), ("one-layer", continuous_file(args.file, Path(tmp) / "c.toml"))]
        best: dict[tuple[str, str], list] = {}
        for _ in range(args.repeat):
            for label, src in checkouts:
                for track, path in tracks:
                    cpu, wall, out = run(src, path)
                    old = best.get((label, track))
                    best[(label, track)] = [
                        min(cpu, old[0]) if old else cpu,
                        min(wall, old[1]) if old else wall,
                        out,
                    ]
    print(f"frequencies --file {args.file.name} (least of {args.repeat} runs, fresh processes)")
    print(f"{'checkout':<12}{'track':<12}{'CPU s':>8}{'wall s':>9}  {'verdict':<13}{'roots':>6}  harmonics")
    for (label, track), (cpu, wall, out) in best.items():
        harmonics = out.get("harmonics")
        span = f"{harmonics[0]}..{harmonics[-1]}" if harmonics else "-"
        verdict = out["verdict"] if isinstance(out["verdict"], str) else out["verdict"]["state"].upper()
        print(f"{label:<12}{track:<12}{cpu:>8.2f}{wall:>9.2f}  {verdict:<13}{out['count']:>6}  {span}")
    if args.record:
        record(args.file, best)


def record(path: Path, best: dict) -> None:
    """benchmarks/results/bench_sleepers.json: this checkout's sleeper track, the continuous one beside it."""
    from records import row, write_record

    def cost(key: tuple[str, str]) -> str:
        cpu, wall, out = best[key]
        verdict = out["verdict"] if isinstance(out["verdict"], str) else out["verdict"]["state"].upper()
        return f"{wall:.2f} s wall, {cpu:.2f} s CPU, {verdict}"

    work = f"frequencies --file {path.name} (Floquet roots in one strip, converged in the harmonics)"
    continuous = cost(("this", "one-layer"))
    alternative = f"the continuous one-layer track of the same smeared stiffness: {continuous}"
    rows = [row(work, cost(("this", "sleepers")), alternative, "< 5 s")]
    write_record(__file__, "A rail on sleepers beside the continuous track", rows)


if __name__ == "__main__":
    main()
