"""How long a job will take, said before it starts.

A grid job (a stability map, continuous or on sleepers) is timed on one of its columns before the others
start; the estimate is that time times the columns per worker. Over :data:`SAY` seconds the command says
so on stderr, with the job's size and how to make it shorter, and goes on; over :data:`ASK` seconds it
stops with exit status 2 unless ``--yes`` is given. A sweep keeps at most :data:`MAX_POINTS` points
(every variable of its store is held in memory once); over that it is refused before anything is written.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import time
from collections.abc import Callable

from moving_bogie.errors import ParameterError

from .reporting import PROG

__all__ = [
    "ASK",
    "MAX_POINTS",
    "SAY",
    "SHORTER",
    "add_yes_option",
    "check_points",
    "duration",
    "estimate_grid",
]

#: A job estimated to take longer than this (seconds) says so before it starts.
SAY = 120.0
#: A job estimated to take longer than this (seconds) runs only with --yes.
ASK = 3600.0
#: The most points of a sweep.
MAX_POINTS = 10_000_000
#: How to make a long map shorter.
SHORTER = "lower --n (the time grows as its square at least)"


def add_yes_option(parser: argparse.ArgumentParser) -> None:
    """Add ``--yes``: run a job estimated to take over an hour (:data:`ASK`) without asking."""
    parser.add_argument(
        "--yes",
        action="store_true",
        help="run even when the job is estimated to take over an hour (timed on one column first)",
    )


def duration(seconds: float) -> str:
    """``45 s``, ``12 min``, ``3.4 h``, ``2.1 days``."""
    if seconds < 100:
        return f"{seconds:.0f} s"
    if seconds < 6000:
        return f"{seconds / 60:.0f} min"
    if seconds < 2 * 86400:
        return f"{seconds / 3600:.1f} h"
    return f"{seconds / 86400:.3g} days"


def estimate_grid(
    what: str,
    shape: tuple[int, int],
    workers: int | None,
    time_column: Callable[[], object],
    *,
    yes: bool,
    shorter: str,
) -> float:
    """Time one column of a ``shape`` = (columns, rows) grid with ``time_column`` and say, before the other
    columns start, how long the whole grid will take on ``workers`` processes (default: the CPUs).

    Returns the estimate in seconds.

    Raises
    ------
    ParameterError
        Naming ``--yes`` when the estimate is over :data:`ASK` and ``yes`` is False; the message gives the
        size, the estimate and ``shorter`` (how to make the job shorter).
    """
    columns, rows = shape
    if rows > 400:  # a long column: say why nothing else shows yet
        print(f"{PROG}: {what}: timing one column of {rows} cells first", file=sys.stderr)
    start = time.perf_counter()
    time_column()
    per_column = time.perf_counter() - start
    parallel = max(1, min(workers or os.cpu_count() or 1, columns))
    seconds = per_column * math.ceil(columns / parallel)
    size = f"{columns} x {rows} = {columns * rows} cells"
    text = (
        f"{what}: {size}, about {duration(seconds)} on {parallel} worker(s) "
        f"(one column of {rows} cells took {per_column:.2g} s)"
    )
    if seconds > ASK and not yes:
        raise ParameterError("--yes", f"{text}: pass --yes to run it, or {shorter}")
    if seconds > SAY:
        print(f"{PROG}: {text}; {shorter} to make it shorter", file=sys.stderr)
    return seconds


def check_points(points: int, option: str = "--vary") -> None:
    """Refuse, naming ``option``, a sweep of more than :data:`MAX_POINTS` points."""
    if points > MAX_POINTS:
        how = (
            "draw fewer"
            if option == "--sample"
            else "split it into several stores (fewer values per --vary), or sample it"
        )
        raise ParameterError(
            option,
            f"{option}: {points} points is more than a sweep holds ({MAX_POINTS}): {how} "
            f"(--sample sobol:N, N <= {MAX_POINTS})",
        )
