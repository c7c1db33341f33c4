"""Long jobs on the command line: progress bars (rich, on stderr) with the fraction done, the elapsed time
and an estimate of the time left, and ``--resume``.

Core functions only take a ``progress`` callback; the bars are drawn here, on an interactive stderr only
(nothing in ``--json`` runs, on a pipe or in a log file). A job that keeps its finished parts (a map:
:mod:`moving_bogie.checkpoint`) keeps them in the cache folder; ``--resume`` reads them back.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import TYPE_CHECKING, Any

from .reporting import PROG

if TYPE_CHECKING:
    from rich.console import Console
    from rich.progress import Progress, ProgressColumn

__all__ = [
    "add_resume_option",
    "checkpoint_options",
    "counts_bar",
    "progress_bar",
    "shown",
    "two_level_bar",
]


def add_resume_option(parser: argparse.ArgumentParser) -> None:
    """``--resume``: complete the interrupted job of the same command (its kept parts read back)."""
    parser.add_argument(
        "--resume",
        action="store_true",
        help="compute only what an interrupted run of the same command left missing",
    )


def checkpoint_options(args: argparse.Namespace) -> dict[str, Any]:
    """The ``checkpoint`` and ``resume`` arguments of a long job run by a command: its finished parts kept
    in the cache folder (:func:`~moving_bogie.checkpoint.cache_root`), read back with ``--resume``; none
    (and a warning) when that folder cannot be written."""
    import os

    from moving_bogie.checkpoint import cache_root

    root = cache_root()
    try:
        root.mkdir(parents=True, exist_ok=True)
        writable = os.access(root, os.W_OK)
    except OSError:
        writable = False
    if not writable:  # the job runs all the same, without keeping its parts
        print(f"{PROG}: warning: {root} is not writable: an interrupted run is not kept", file=sys.stderr)
        return {"checkpoint": None, "resume": False}
    return {"checkpoint": root, "resume": bool(getattr(args, "resume", False))}


def shown(enabled: bool, console: Console | None) -> bool:
    """Whether to draw: ``enabled`` and a terminal (``console`` given: its own judgement, which a test
    forces; else whether stderr is interactive)."""
    if not enabled:
        return False
    return console.is_terminal if console is not None else sys.stderr.isatty()


@contextmanager
def progress_bar(
    description: str, *, enabled: bool = True, console: Console | None = None
) -> Iterator[Callable[[float], None]]:
    """Yield a callback ``update(fraction)``: a bar with the time left on a terminal, a no-op otherwise."""
    if not shown(enabled, console):
        yield lambda fraction: None
        return
    with _rich_bars(console) as bar:
        task = bar.add_task(description, total=1.0)
        yield lambda fraction: bar.update(task, completed=_clip(fraction))


@contextmanager
def counts_bar(
    description: str, unit: str, *, enabled: bool = True, console: Console | None = None
) -> Iterator[Callable[[int, int], None]]:
    """Yield a callback ``update(done, total)``: a bar with done/total, the rate in ``unit``/s of the work
    done since the first call (a resumed job's earlier work not counted) and the time left."""
    if not shown(enabled, console):
        yield lambda done, total: None
        return
    from rich.progress import MofNCompleteColumn, TextColumn

    rate = TextColumn("{task.fields[rate]} " + unit + "/s")
    with _rich_bars(console, MofNCompleteColumn(), rate) as bar:
        task = bar.add_task(description, total=None, rate="-")
        first: dict[str, float] = {}

        def update(done: int, total: int) -> None:
            import time

            now = time.perf_counter()
            t0, done0 = first.setdefault("t", now), first.setdefault("done", done)
            speed = (done - done0) / (now - t0) if now > t0 else 0.0
            bar.update(task, completed=done, total=total, rate=f"{speed:.3g}")

        yield update


@contextmanager
def two_level_bar(
    description: str, *, enabled: bool = True, console: Console | None = None
) -> Iterator[tuple[Callable[[float], None], Callable[[str, float], None]]]:
    """Yield ``(overall, part)``: ``overall(fraction)`` moves a bar for the whole job, ``part(label,
    fraction)`` a second bar for the step under way (named ``label``); rich on a terminal, no-ops
    otherwise."""
    if not shown(enabled, console):
        yield (lambda fraction: None), (lambda label, fraction: None)
        return
    with _rich_bars(console) as bar:
        whole = bar.add_task(description, total=1.0)
        step = bar.add_task("", total=1.0)
        seen: dict[Any, Any] = {}

        def part(label: str, fraction: float) -> None:
            if seen.get("label") != label:
                seen["label"] = label
                bar.reset(step, total=1.0, description=f"  {label}")
            bar.update(step, completed=_clip(fraction))

        yield (lambda fraction: bar.update(whole, completed=_clip(fraction))), part


def _clip(fraction: float) -> float:
    return max(0.0, min(1.0, fraction))


def _rich_bars(console: Console | None, *middle: ProgressColumn) -> Progress:
    """The rich Progress every bar uses: description, bar, ``middle`` (default the percentage), elapsed
    time, time left; on stderr (or ``console``), removed when done."""
    from rich.console import Console
    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn, TimeRemainingColumn

    return Progress(
        TextColumn("{task.description}"),
        BarColumn(),
        *(middle or (TextColumn("{task.percentage:>3.0f}%"),)),
        TimeElapsedColumn(),
        TextColumn("ETA"),
        TimeRemainingColumn(),
        console=console if console is not None else Console(stderr=True),
        transient=True,
    )
