"""What a run of ``reproduce`` produced: one :class:`Outcome` per artefact, gathered in a :class:`Report`."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from moving_bogie.paper.recipe import Built
from moving_bogie.paper.registry import Artifact

__all__ = ["STATUSES", "Outcome", "Report"]

#: The status of an artefact after a run.
STATUSES = ("covered", "not covered", "failed", "not built")


@dataclass
class Outcome:
    """The result of one artefact.

    Attributes
    ----------
    artifact : Artifact
    status : str
        One of :data:`STATUSES`: ``"covered"`` (rebuilt), ``"not covered"`` (no recipe: not a computed
        result), ``"failed"`` (the recipe raised; ``built.files`` holds the traceback file) or
        ``"not built"`` (not selected in this run).
    built : Built
        What the recipe returned.
    reason : str
        Why the artefact is not covered, failed or not built.
    seconds : float
        Wall time of the recipe.
    """

    artifact: Artifact
    status: str
    built: Built = field(default_factory=Built)
    reason: str = ""
    seconds: float = 0.0

    @property
    def ok(self) -> bool:
        """False when the recipe failed or its result disagrees with the paper."""
        return self.status != "failed" and self.built.ok


@dataclass
class Report:
    """All outcomes of a run, in the paper's order."""

    out: Path
    quick: bool
    outcomes: list[Outcome]
    seconds: float

    @property
    def ok(self) -> bool:
        """True when no artefact failed or disagrees with the paper."""
        return all(o.ok for o in self.outcomes)

    def count(self, status: str) -> int:
        """Number of artefacts with `status`."""
        return sum(o.status == status for o in self.outcomes)
