"""Progress bars for long CLI work (rich, on stderr); core functions only take a ``progress`` callback."""

from __future__ import annotations

import sys
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from rich.progress import Progress


@contextmanager
def progress_bar(description: str, *, enabled: bool = True) -> Iterator[Callable[[float], None]]:
    """Yield a callback ``update(fraction)``; shows a rich bar on an interactive stderr, nothing otherwise."""
    if not enabled or not sys.stderr.isatty():
        yield lambda fraction: None
        return
    with _rich_bars() as bar:
        task = bar.add_task(description, total=1.0)
        yield lambda fraction: bar.update(task, completed=max(0.0, min(1.0, fraction)))


@contextmanager
def two_level_bar(
    description: str, *, enabled: bool = True
) -> Iterator[tuple[Callable[[float], None], Callable[[str, float], None]]]:
    """Yield ``(overall, part)``: ``overall(fraction)`` moves a bar for the whole job, ``part(label,
    fraction)`` a second bar for the step under way (named ``label``); rich on an interactive stderr,
    no-ops otherwise."""
    if not enabled or not sys.stderr.isatty():
        yield (lambda fraction: None), (lambda label, fraction: None)
        return
    with _rich_bars() as bar:
        whole = bar.add_task(description, total=1.0)
        step = bar.add_task("", total=1.0)
        seen: dict[Any, Any] = {}

        def part(label: str, fraction: float) -> None:
            if seen.get("label") != label:
                seen["label"] = label
                bar.reset(step, total=1.0, description=f"  {label}")
            bar.update(step, completed=max(0.0, min(1.0, fraction)))

        yield (lambda fraction: bar.update(whole, completed=max(0.0, min(1.0, fraction)))), part


def _rich_bars() -> Progress:
    """The rich Progress both bars use: description, bar, percentage, elapsed time; on stderr, transient."""
    from rich.console import Console
    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

    return Progress(
        TextColumn("{task.description}"),
        BarColumn(),
        TextColumn("{task.percentage:>3.0f}%"),
        TimeElapsedColumn(),
        console=Console(stderr=True),
        transient=True,
    )
