"""Time the command line's errors that need no computation, beside ``moving-bogie --help``.

Run: ``python benchmarks/bench_cli_errors.py [--repeat 5]``. A script, not a test: nothing is asserted, the
table is printed (markdown): for each error, its exit status, its first line and its wall time, the least of
``--repeat`` runs of a fresh ``python -m moving_bogie`` process (interpreter start and imports included, as
a user sees them). ``--help`` is the floor: every error here comes before the numerical modules are imported,
so it should cost about as much. Each run happens in an empty temporary folder, which is checked to be
empty afterwards (no output file or folder created).
"""

from __future__ import annotations

import argparse
import os
import platform
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
EXAMPLE = ROOT / "examples" / "uic60-bogie.toml"

#: (what, arguments); "{bad}" is a copy of examples/dimensionless_eb.toml with the key alpha misspelt.
CASES = [
    ("--help", ["--help"]),
    ("--plot out.xyz (timeseries)", ["timeseries", "--case", "1", "--tmax", "100", "--plot", "out.xyz"]),
    ("--plot out.xyz (stability-map)", ["stability-map", "--case", "1", "--plot", "out.xyz"]),
    ("--plot into a missing folder", ["timeseries", "--case", "1", "--tmax", "10", "--plot", "no/dir/x.png"]),
    (
        "--out store in a missing folder",
        ["sweep", "--case", "1", "--vary", "alpha=0:1:3", "--out", "no/s.zarr"],
    ),
    ("--npz without .npz", ["stability-map", "--case", "1", "--npz", "map.np"]),
    ("missing --file", ["frequencies", "--file", "nosuch.toml"]),
    ("unknown TOML key", ["frequencies", "--file", "{bad}"]),
    ("unknown --vehicle", ["frequencies", "--case", "1", "--vehicle", "bogy"]),
    ("unknown option", ["params", "--case", "1", "--alpah", "0.3"]),
    ("unknown case", ["frequencies", "--case", "14"]),
    ("bad --set name", ["timeseries", "--file", str(EXAMPLE), "--set", "vv=3", "--tmax", "1"]),
    ("bad group value", ["validate", "--case", "7", "--eta-M", "-3"]),
]


def run_once(args: list[str], folder: Path) -> tuple[float, int, str]:
    """(wall seconds, exit status, first line of stderr or stdout) of one fresh process in ``folder``."""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT / "src"), os.environ.get("PYTHONPATH", "")]))
    start = time.perf_counter()
    done = subprocess.run(
        [sys.executable, "-m", "moving_bogie", *args], cwd=folder, capture_output=True, text=True, env=env
    )
    seconds = time.perf_counter() - start
    text = (done.stderr or done.stdout).strip().splitlines()
    return seconds, done.returncode, text[0] if text else ""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5, help="runs per row; the least time is shown")
    options = parser.parse_args()
    bad = (ROOT / "examples" / "dimensionless_eb.toml").read_text().replace("alpha =", "alpah =", 1)
    print(f"{platform.node()}, {os.cpu_count()} CPUs, Python {platform.python_version()}, {time.ctime()}")
    print(f"wall time, least of {options.repeat} fresh processes\n")
    print("| error | exit | time [s] | first line |")
    print("|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        bad_file = Path(tmp) / "bad.toml"
        bad_file.write_text(bad)
        for what, args in CASES:
            folder = Path(tempfile.mkdtemp(dir=tmp))
            args = [a.format(bad=bad_file) for a in args]
            runs = [run_once(args, folder) for _ in range(options.repeat)]
            seconds = min(r[0] for r in runs)
            _, status, line = runs[0]
            created = " (CREATED FILES)" if any(folder.iterdir()) else ""
            shown = line.replace("|", "\\|").replace(str(Path(tmp)), "TMP")
            print(f"| {what} | {status} | {seconds:.2f} | {shown[:110]}{created} |")


if __name__ == "__main__":
    main()
