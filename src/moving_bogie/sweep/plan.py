"""What :func:`~moving_bogie.sweep.engine.run_sweep` needs of a sweep: its blocks, their tasks and its store.

Two kinds of sweep share the engine (in-process or Dask, resume, progress): the continuous tracks'
:class:`~moving_bogie.sweep.design.SweepSpec` and the sleeper tracks'
:class:`~moving_bogie.sweep.sleepers.SleeperSweepSpec`. Each cuts its points into blocks (one chunk of
the store each), makes one picklable task per block whose ``evaluate()`` returns the block's arrays, and
writes its own store layout; a block is complete once its ``computed`` chunk is written.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Protocol

import numpy as np

from moving_bogie.sweep.design import Block

__all__ = ["SWEEP_KEYS", "BlockWork", "SweepPlan"]

#: The keys every sweep's summary has, with the same meaning on every track: the fraction of points with an
#: unstable root, the points whose verdict is not certain, the unit of every varied parameter.
SWEEP_KEYS = ("unstable_fraction", "uncertain_points", "units")


class BlockWork(Protocol):
    """The work of one block, sent to a worker: plain data and one method."""

    def evaluate(self) -> dict[str, np.ndarray]:
        """The block's arrays, one per data variable of the store (shape of the block)."""
        ...


class SweepPlan(Protocol):
    """A sweep as the engine and the store see it."""

    @property
    def size(self) -> int:
        """The number of points."""
        ...

    def blocks(self) -> list[Block]:
        """Every block, in a fixed order."""
        ...

    def describe(self) -> dict[str, Any]:
        """JSON-ready description kept in the store (a resumed sweep must match it)."""
        ...

    def task(self, block: Block) -> BlockWork:
        """The worker's task for ``block``."""
        ...

    def create_store(self, path: Path) -> None:
        """Write the metadata and coordinates of an empty store at ``path``."""
        ...

    def write_block(self, path: Path, slices: tuple[slice, ...], arrays: dict[str, np.ndarray]) -> None:
        """Write one block's arrays into its chunk of every variable, ``computed`` last."""
        ...

    def summary(self, path: Path) -> dict[str, Any]:
        """The verdicts of the finished sweep at ``path`` (:data:`SWEEP_KEYS` and the sweep's own)."""
        ...


def evaluate_work(work: BlockWork) -> dict[str, np.ndarray]:
    """``work.evaluate()``: the function a Dask worker runs for a block."""
    return work.evaluate()
