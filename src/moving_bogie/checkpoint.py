"""Long jobs of independent parts that keep their work: each finished part is written at once, and a
resumed job computes only the parts missing.

A job (a stability map: chunks of columns; a sleeper map: columns) is a fixed list of parts, each
computed by one call that depends on nothing but its own inputs. :func:`run_parts` runs the parts in this
process or in worker processes and writes each finished one into its :class:`Checkpoint`: a folder
``<root>/<kind>-<key>`` (the key a hash of the job's description, kept beside the parts in ``job.json``)
holding one ``part-<k>.npz`` per finished part, each written atomically (a temporary file, then a rename),
so an interrupted job leaves only whole parts. The same job resumed reads them back bit for bit and
computes the others: its result equals that of an uninterrupted run. A job that finishes removes its
folder; a changed input is another job (another key), computed anew.
"""

from __future__ import annotations

import hashlib
import io
import json
import multiprocessing
import os
import shutil
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import ProcessPoolExecutor, as_completed
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any, TypeVar

import numpy as np

from moving_bogie.errors import JobInterrupted
from moving_bogie.output import atomic_write
from moving_bogie.processes import ignore_interrupts, require_main_guard

__all__ = ["Checkpoint", "Part", "cache_root", "kept_until_done", "run_parts"]

#: A finished part: named arrays (numbers, booleans, text), as a .npz holds them.
Part = dict[str, np.ndarray]
T = TypeVar("T")


def cache_root() -> Path:
    """Where the commands keep interrupted jobs: ``$MOVING_BOGIE_CACHE``, else
    ``$XDG_CACHE_HOME/moving-bogie``, else ``~/.cache/moving-bogie``."""
    if os.environ.get("MOVING_BOGIE_CACHE"):
        return Path(os.environ["MOVING_BOGIE_CACHE"])
    base = os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache"
    return Path(base) / "moving-bogie"


@dataclass(frozen=True)
class Checkpoint:
    """The folder of one job's finished parts (module docstring)."""

    folder: Path
    job: str  # the job's description, JSON text

    @classmethod
    def open(
        cls, root: str | os.PathLike[str], kind: str, job: dict[str, Any], *, resume: bool
    ) -> Checkpoint:
        """The checkpoint of ``job`` (with the package's version) under ``root``: its kept parts when
        ``resume``, else emptied."""
        from moving_bogie import __version__

        text = json.dumps(job | {"version": __version__}, sort_keys=True, default=str)
        key = hashlib.sha256(text.encode()).hexdigest()[:16]
        folder = Path(root) / f"{kind}-{key}"
        same = (folder / "job.json").exists() and (folder / "job.json").read_text() == text
        if folder.exists() and not (resume and same):
            shutil.rmtree(folder)
        if not folder.exists():
            folder.mkdir(parents=True)
            atomic_write(folder / "job.json", text)
        return cls(folder, text)

    def _path(self, index: int) -> Path:
        return self.folder / f"part-{index:06d}.npz"

    def load(self, index: int) -> Part | None:
        """Part ``index`` when kept, else None."""
        path = self._path(index)
        if not path.exists():
            return None
        with np.load(path, allow_pickle=False) as data:
            return {name: data[name] for name in data.files}

    def save(self, index: int, part: Part) -> None:
        """Keep part ``index`` (atomically)."""
        buffer = io.BytesIO()
        arrays: dict[str, Any] = dict(part)
        np.savez(buffer, allow_pickle=False, **arrays)
        atomic_write(self._path(index), buffer.getvalue())

    def remove(self) -> None:
        """The job is done: its folder goes (inside :func:`kept_until_done`, when that block ends)."""
        if _DEFERRED:
            _DEFERRED[-1].append(self)
        else:
            shutil.rmtree(self.folder, ignore_errors=True)


#: The checkpoints of finished jobs kept until the blocks of :func:`kept_until_done` end (innermost last).
_DEFERRED: list[list[Checkpoint]] = []


@contextmanager
def kept_until_done() -> Iterator[None]:
    """Within the block, a finished job keeps its parts until the block ends without an error: a command
    that runs several jobs (a sleeper map, then the continuous map beside it) resumes after an
    interruption of the last one without computing the first again."""
    _DEFERRED.append([])
    try:
        yield
    except BaseException:
        _DEFERRED.pop()
        raise
    for done in _DEFERRED.pop():
        done.remove()


def run_parts(
    work: Callable[[T], Part],
    tasks: Sequence[T],
    *,
    workers: int | None = None,
    checkpoint: Checkpoint | None = None,
    progress: Callable[[float], None] | None = None,
    what: str = "parts",
) -> list[Part]:
    """``work(task)`` for every task not kept in ``checkpoint``, each kept as it finishes; all parts in
    the order of ``tasks``.

    ``workers``: processes (default the CPUs, at most one per task); 1 runs in this process. Worker
    processes ignore SIGINT: Ctrl-C reaches this process, which stops the workers and raises
    :class:`JobInterrupted` saying how many parts are kept. ``progress`` is called with the fraction of
    parts done (kept ones included); ``what`` names the parts in the message of an interruption.
    """
    parts: dict[int, Part] = {}
    if checkpoint is not None:
        parts = {k: p for k in range(len(tasks)) if (p := checkpoint.load(k)) is not None}
    todo = [k for k in range(len(tasks)) if k not in parts]

    def report() -> None:
        if progress is not None:
            progress(len(parts) / max(1, len(tasks)))

    try:
        report()
        for k, part in _finished(work, tasks, todo, workers):
            if checkpoint is not None:
                checkpoint.save(k, part)
            parts[k] = part
            report()
    except KeyboardInterrupt:
        folder = checkpoint.folder if checkpoint else None
        raise JobInterrupted(len(parts), len(tasks), folder, what) from None
    return [parts[k] for k in range(len(tasks))]


def _finished(
    work: Callable[[T], Part], tasks: Sequence[T], todo: list[int], workers: int | None
) -> Iterator[tuple[int, Part]]:
    """(index, part) of the tasks ``todo`` as they finish. A worker that dies (killed, out of memory)
    raises :class:`~concurrent.futures.process.BrokenProcessPool` instead of leaving its task waiting;
    when the caller stops early (Ctrl-C, an error) the workers are stopped at once."""
    n = min(len(todo), workers or os.cpu_count() or 1)
    if n <= 1:
        yield from ((k, work(tasks[k])) for k in todo)
        return
    if multiprocessing.get_start_method() != "fork":  # spawn, forkserver: the script is imported again
        require_main_guard(f"a job on {n} worker processes")
    pool = ProcessPoolExecutor(n, initializer=ignore_interrupts)
    done = False
    try:
        futures = {pool.submit(work, tasks[k]): k for k in todo}
        for future in as_completed(futures):
            yield futures[future], future.result()
        done = True
    finally:
        if not done:  # the running tasks are not waited for
            for process in list((getattr(pool, "_processes", None) or {}).values()):
                process.terminate()
        pool.shutdown(wait=done, cancel_futures=True)
