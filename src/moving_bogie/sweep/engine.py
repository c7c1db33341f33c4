"""Running a sweep: blocks out to the workers, arrays back, chunks into the store.

A sweep of fewer than :data:`IN_PROCESS_POINTS` points to compute, given neither ``workers``, ``scheduler``
nor ``client``, runs its blocks one after the other in this process: starting a cluster costs seconds,
more than such a sweep computes. Otherwise it runs on Dask distributed: by default a
:class:`distributed.LocalCluster` with one single-threaded worker process per core (or ``workers``) is
started and closed again; ``scheduler="tcp://HOST:8786"`` uses an existing cluster
(``dask scheduler`` on one machine, ``dask worker tcp://HOST:8786`` on each of the others, every one with
moving-bogie installed); ``client`` uses a client you already have. Each block is one task returning
plain numpy arrays; the calling process writes each finished block into the store at once, so an
interruption (Ctrl-C, a lost cluster, a killed process) keeps every finished block and ``resume=True``
computes only the others. A worker lost mid-task is replaced by the scheduler, which runs its task again.

Quiet by design: the local workers are started with SIGINT ignored (Ctrl-C in a terminal reaches the whole
process group; only this process handles it, cancels the tasks and closes the cluster), and Dask's own
log messages below CRITICAL are silenced for the life of the cluster (a worker that outlives the
scheduler by a heartbeat logs an ERROR; a task's failure still reaches the caller as an exception).
"""

from __future__ import annotations

import logging
import os
import signal
import threading
import time
from collections.abc import Callable, Iterable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from moving_bogie.errors import ParameterError
from moving_bogie.model.bar import bar_note
from moving_bogie.sweep.design import Block, SweepSpec
from moving_bogie.sweep.evaluate import BlockTask
from moving_bogie.sweep.plan import SweepPlan, evaluate_work
from moving_bogie.sweep.store import (
    StorePath,
    create_store,
    missing_blocks,
    prepare_store,
    read_store,
    write_block,
)

if TYPE_CHECKING:
    from distributed import Client, Future

__all__ = ["ContinuousPlan", "IN_PROCESS_POINTS", "SweepRun", "block_task", "make_client", "run_sweep"]

#: A sweep with fewer points than this to compute runs in this process unless a cluster is asked for.
IN_PROCESS_POINTS = 1000


@dataclass(frozen=True)
class SweepRun:
    """What a run did: blocks and points computed now, already in the store, the wall time, and where it
    ran (``scheduler``: "in-process", "local cluster", or the address of the cluster used)."""

    path: Path
    blocks_total: int
    blocks_computed: int
    points_computed: int
    seconds: float
    workers: int
    scheduler: str = "in-process"

    @property
    def points_per_second(self) -> float:
        return self.points_computed / self.seconds if self.seconds > 0 else float("nan")


def block_task(spec: SweepSpec, block: Block) -> BlockTask:
    """The worker's task for ``block``: only that block's values travel."""
    if spec.design == "sobol":
        values = tuple(a.values[block.slices[0]] for a in spec.axes)
    else:
        values = tuple(a.values[s] for a, s in zip(spec.axes, block.slices))
    return BlockTask(
        block.index,
        spec.bound,
        tuple(a.name for a in spec.axes),
        values,
        spec.design,
        spec.column_parameter,
        spec.roots,
        spec.max_roots,
        spec.check,
        fixed=spec.fixed,
        held=spec.held,
        margin=spec.margin,
    )


@dataclass(frozen=True)
class ContinuousPlan:
    """A :class:`~moving_bogie.sweep.design.SweepSpec` as a :class:`~moving_bogie.sweep.plan.SweepPlan`:
    its tasks are :func:`block_task`, its store that of :mod:`moving_bogie.sweep.store`."""

    spec: SweepSpec

    @property
    def size(self) -> int:
        return self.spec.size

    def blocks(self) -> list[Block]:
        return self.spec.blocks()

    def describe(self) -> dict[str, Any]:
        return self.spec.describe()

    def task(self, block: Block) -> BlockTask:
        return block_task(self.spec, block)

    def create_store(self, path: Path) -> None:
        create_store(path, self.spec)

    def write_block(self, path: Path, slices: tuple[slice, ...], arrays: dict[str, np.ndarray]) -> None:
        write_block(path, self.spec, slices, arrays)

    def summary(self, path: Path) -> dict[str, Any]:
        return continuous_summary(self.spec, path)


def continuous_summary(spec: SweepSpec, path: Path) -> dict[str, Any]:
    """The verdicts of a finished sweep of a continuous track at ``path``, for the summary (opening with
    :data:`~moving_bogie.sweep.plan.SWEEP_KEYS`)."""
    store = read_store(path, ("n_unstable", "certain", "settled", "checked", "supercritical"))
    a = store.arrays
    out = {
        "unstable_fraction": float((a["n_unstable"] > 0).mean()),
        "uncertain_points": int((~a["certain"]).sum()),
        "settled_points": int(a["settled"].sum()),
        "check_disagreements": int((a["checked"] < 0).sum()),
        "units": {axis.label: store.units.get(axis.label, "1") for axis in spec.axes},
    }
    varied = [axis.name for axis in spec.axes]
    note = next(
        (bar_note(spec.params, spec.bar, name) for name in varied if bar_note(spec.params, spec.bar, name)),
        None,
    )
    if note is not None:  # what the bar did along a varied wheel mass
        out["bar"] = note
    if "supercritical" in a:  # the points above the critical velocity of their track
        out["supercritical_points"] = int(a["supercritical"].sum())
    return out


def make_client(workers: int | None = None, scheduler: str | None = None, processes: bool = True) -> Client:
    """A Dask client: on ``scheduler`` if given, else on a new LocalCluster of ``workers`` processes.

    Every worker runs one thread: the full counts use mpmath, whose working precision is global to a
    process, so two tasks must never share one (``processes=False``, threads in this process, is allowed
    for a single worker only).
    """
    from distributed import Client, LocalCluster

    if scheduler:
        return Client(scheduler)
    n = workers or os.cpu_count() or 1
    if not processes and n > 1:
        raise ParameterError("workers", "workers as threads (processes=False) must be a single worker")
    with _sigint_ignored():  # the worker processes inherit the disposition
        cluster = LocalCluster(
            n_workers=n,
            threads_per_worker=1,
            processes=processes,
            dashboard_address=":0",  # a free port: never clashes with another cluster
            silence_logs=logging.CRITICAL,
        )
    client = Client(cluster)
    client.wait_for_workers(n)
    return client


@contextmanager
def _sigint_ignored() -> Iterator[None]:
    """SIGINT ignored while child processes are started (main thread only; restored afterwards)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)


def run_sweep(
    spec: SweepSpec | SweepPlan,
    out: StorePath,
    *,
    resume: bool = False,
    overwrite: bool = False,
    client: Client | None = None,
    workers: int | None = None,
    scheduler: str | None = None,
    processes: bool = True,
    progress: Callable[[int, int], None] | None = None,
    on_block: Callable[[int], None] | None = None,
) -> SweepRun:
    """Compute every missing block of ``spec`` into the store ``out``.

    Parameters
    ----------
    spec : SweepPlan
        A :class:`~moving_bogie.sweep.design.SweepSpec` (continuous tracks) or a
        :class:`~moving_bogie.sweep.sleepers.SleeperSweepSpec` (sleeper tracks).
    out : path
        Zarr store (a folder). Must not exist unless ``resume`` (complete it) or ``overwrite``.
    client : distributed.Client, optional
        Use this client (not closed afterwards).
    workers : int, optional
        Worker processes of the LocalCluster (default: one per core). Given neither ``workers``,
        ``scheduler`` nor ``client``, fewer than :data:`IN_PROCESS_POINTS` points run in this process.
    scheduler : str, optional
        Address of an existing scheduler (``tcp://HOST:8786``).
    processes : bool
        LocalCluster workers as processes (default) or threads.
    progress : callable, optional
        Called as ``progress(points_done, points_total)`` after each block.
    on_block : callable, optional
        Called with the index of each block once it is in the store.
    """
    spec = ContinuousPlan(spec) if isinstance(spec, SweepSpec) else spec
    path = prepare_store(out, spec, resume=resume, overwrite=overwrite)
    blocks = spec.blocks()
    todo = missing_blocks(path, spec) if resume else blocks
    points = sum(_points(b) for b in todo)
    total, done = spec.size, spec.size - points
    if progress is not None:
        progress(done, total)
    start = time.perf_counter()
    in_process = client is None and workers is None and scheduler is None and points < IN_PROCESS_POINTS
    if in_process:
        finished = ((b, spec.task(b).evaluate()) for b in todo)
        n_workers, where = 1, "in-process"
        _store_blocks(path, spec, finished, done, total, progress, on_block)
    else:
        n_workers, where = _run_distributed(
            spec, path, todo, (done, total), client, (workers, scheduler, processes), progress, on_block
        )
    seconds = time.perf_counter() - start
    return SweepRun(path, len(blocks), len(todo), points, seconds, n_workers, where)


def _store_blocks(
    path: Path,
    spec: SweepPlan,
    finished: Iterable[tuple[Block, dict[str, np.ndarray]]],
    done: int,
    total: int,
    progress: Callable[[int, int], None] | None,
    on_block: Callable[[int], None] | None,
) -> None:
    """Write each (block, arrays) of ``finished`` into the store as it comes, reporting progress."""
    for b, arrays in finished:
        spec.write_block(path, b.slices, arrays)
        done += _points(b)
        if progress is not None:
            progress(done, total)
        if on_block is not None:
            on_block(b.index)


def _run_distributed(
    spec: SweepPlan,
    path: Path,
    todo: Sequence[Block],
    counts: tuple[int, int],
    client: Client | None,
    cluster: tuple[int | None, str | None, bool],
    progress: Callable[[int, int], None] | None,
    on_block: Callable[[int], None] | None,
) -> tuple[int, str]:
    """The blocks ``todo`` on Dask (``client``, or one made from ``cluster`` = (workers, scheduler,
    processes) and closed afterwards); the number of workers and where they ran."""
    from distributed import as_completed

    own = client is None
    if own and todo:
        client = make_client(*cluster)
    where = cluster[1] or ("local cluster" if own else "client")
    futures: dict[Future, Block] = {}
    try:
        n_workers = len(client.scheduler_info()["workers"]) if client is not None else 0
        if client is not None:  # None only when there is nothing to run
            for b in todo:
                futures[client.submit(evaluate_work, spec.task(b), pure=False)] = b

        def finished() -> Iterator[tuple[Block, dict[str, np.ndarray]]]:
            for future in as_completed(list(futures)):
                b = futures.pop(future)
                yield b, future.result()

        done, total = counts
        _store_blocks(path, spec, finished(), done, total, progress, on_block)
    finally:
        with _sigint_ignored():  # a second Ctrl-C must not interrupt the shutdown
            if futures and client is not None:
                client.cancel(list(futures))
            if own and client is not None:
                closing = client.cluster
                client.close()
                if closing is not None:
                    closing.close()
    return n_workers, where


def _points(block: Block) -> int:
    n = 1
    for s in block.slices:
        n *= s.stop - s.start
    return n
