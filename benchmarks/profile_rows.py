"""Where the time goes in the commands users wait for: a CPU profile of each, its top functions printed.

    python benchmarks/profile_rows.py [--row NAME ...] [--top N]

Each row is one command of the command line, run in this process under :mod:`cProfile` with CPU time as
its clock (the load of the machine then counts little); the package is imported before the profile
starts, so what is printed is the command's own work. For each row: the CPU time, the parts of its work
named in ``PARTS`` (cumulative CPU of the functions that do them, so the reader sees at once which part to
attack), then the ``--top``
functions by cumulative time (where the work sits in the call tree) and by own time (where the
interpreter spends it), the package's functions and numpy's or mpmath's alike. A sweep writes a
temporary store, deleted afterwards.
"""

from __future__ import annotations

import argparse
import contextlib
import cProfile
import io
import pstats
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

#: The Timoshenko-Rayleigh beam of Case 7 (the time series and validation rows).
TR = ["--case", "7", "--beam", "tr", "--S", "10", "--r", "0.09"]
#: The rows: name -> the command's arguments ({out} is a temporary folder).
ROWS = {
    "table2": ["table2"],
    "timeseries-tr": ["timeseries", *TR, "--tmax", "40"],
    "validate-tr": ["validate", *TR],
    "table2-certify": ["table2", "--certify"],
    "small-sweep": ["sweep", "--file", str(ROOT / "examples" / "car.toml"), "--vary", "v=40:120:6",
                    "--out", "{out}/s.zarr"],
}  # fmt: skip

#: The parts of a row's work: label -> (module path suffix, function name); cumulative CPU seconds each.
#: Parts may nest (the indented labels are inside the one above them).
PARTS = {
    "timeseries-tr": {
        "induced frequencies of the default window": ("response/residues.py", "frequencies_for"),
        "real-axis sequence beyond the window": ("response/axis_sequence.py", "axis_sequence"),
        "  count per strip (argument principle; the window's too)": ("roots/frequencies.py", "_count"),
        "  locate by bisection (the window's too)": ("roots/frequencies.py", "_locate_counted"),
        "  Newton from the asymptotic law": ("response/axis_law.py", "law_roots"),
        "  polish and confirm (mpmath; the window's too)": ("roots/frequencies.py", "_polish_located"),
        "  residue coefficients (mpmath; the window's too)": ("response/residues.py", "residue_expansion"),
        "branch cut, where it matters (auto rule)": ("response/cut_policy.py", "branch_cut_extent"),
        "  L1 bound of the jump": ("response/cut_integral.py", "l1_bound"),
        "  adaptive panels of the jump": ("response/quadrature.py", "adapt_panels_with_values"),
        "branch cut I_bc over the time series": ("response/closed_form.py", "_add_branch_cut"),
        "  jump across the cut (all calls)": ("response/cut_integral.py", "_jump"),
        "  sum over nodes x times (fourier_sum)": ("response/quadrature.py", "fourier_sum"),
        "    e^{i x} of nodes x times (cis)": ("response/quadrature.py", "cis"),
    },
}
PARTS["validate-tr"] = PARTS["timeseries-tr"]


def parts_table(stats: pstats.Stats, parts: dict[str, tuple[str, str]]) -> str:
    """The cumulative CPU seconds of each part (the largest over functions of that name and module)."""
    table = stats.stats  # type: ignore[attr-defined]  # pstats keeps its table in this attribute
    lines = []
    for label, (suffix, name) in parts.items():
        hits = [v[3] for (path, _, func), v in table.items() if path.endswith(suffix) and func == name]
        seconds = f"{max(hits):8.2f}" if hits else "       -"
        lines.append(f"{seconds}  {label}")
    return "\n".join(lines)


def profile_row(argv: list[str]) -> tuple[float, pstats.Stats]:
    """Run one command under cProfile (CPU clock): its CPU seconds and the statistics."""
    from moving_bogie.cli import main

    profile = cProfile.Profile(time.process_time)
    start = time.process_time()
    with contextlib.redirect_stdout(io.StringIO()):
        profile.enable()
        try:
            code = main(argv)
        finally:
            profile.disable()
    if code:
        raise SystemExit(f"{' '.join(argv)} exited {code}")
    return time.process_time() - start, pstats.Stats(profile)


def _top(stats: pstats.Stats, key: str, n: int) -> str:
    out = io.StringIO()
    stats.stream = out
    stats.sort_stats(key).print_stats(n)
    lines = out.getvalue().splitlines()
    first = next(i for i, line in enumerate(lines) if line.lstrip().startswith("ncalls"))
    return "\n".join(line.replace(str(ROOT) + "/", "") for line in lines[first:] if line.strip())


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--row", action="append", choices=list(ROWS), help="only these rows (default all)")
    parser.add_argument("--top", type=int, default=25, metavar="N", help="functions per list (default 25)")
    args = parser.parse_args()
    import moving_bogie.cli  # noqa: F401  (imported before any profile starts)

    for name in args.row or list(ROWS):
        with tempfile.TemporaryDirectory() as folder:
            argv = [a.replace("{out}", folder) for a in ROWS[name]]
            cpu, stats = profile_row(argv)
        print(f"=== {name}: moving-bogie {' '.join(ROWS[name]).replace(str(ROOT) + '/', '')}")
        print(f"CPU {cpu:.2f} s under the profiler (its overhead included)\n")
        if name in PARTS:
            print(
                f"by part (cumulative CPU seconds; indented parts are inside the one above):\n"
                f"{parts_table(stats, PARTS[name])}\n"
            )
        print(f"by cumulative time:\n{_top(stats, 'cumulative', args.top)}\n")
        print(f"by own time:\n{_top(stats, 'tottime', args.top)}\n")


if __name__ == "__main__":
    main()
