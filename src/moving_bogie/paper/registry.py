"""The registry of the paper's artefacts: every table and figure, its caption and its recipe.

:data:`ARTIFACTS` lists the artefacts in the paper's order (that of :data:`~moving_bogie.paper.captions.
CAPTIONS`). Each has a recipe (:mod:`moving_bogie.paper.tables`, :mod:`moving_bogie.paper.figures`), or,
for an artefact that is not a computed result, the reason it is not rebuilt (:data:`NOT_COMPUTED`).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from moving_bogie.paper.captions import CAPTIONS, Caption
from moving_bogie.paper.figures import SERIES, STABILITY_FIGURES, StabilityFigure, TimeSeriesFigure
from moving_bogie.paper.recipe import Recipe
from moving_bogie.paper.tables import build_table1, build_table2

__all__ = ["ARTIFACTS", "NOT_COMPUTED", "RECIPES", "Artifact", "select"]


@dataclass(frozen=True)
class Artifact:
    """One table or figure of the paper and how to rebuild it.

    Attributes
    ----------
    caption : Caption
        The paper's caption, verbatim.
    kind : str
        ``"figure"`` or ``"table"``.
    recipe : callable or None
        Rebuilds the artefact (``recipe(ctx) -> Built``); None for an artefact the software does not
        compute, `reason` then says why.
    reason : str
        Why there is no recipe (empty when there is one).
    """

    caption: Caption
    kind: str
    recipe: Recipe | None
    reason: str = ""

    @property
    def id(self) -> str:
        """Stable identifier, also the file name: ``"table2"``, ``"figure5"``, ``"figureA3"``."""
        return self.caption.id

    @property
    def label(self) -> str:
        """How the paper's text cites it: ``"Figure 5"``."""
        return self.caption.label


#: The recipe of every artefact the software computes, by artefact id.
RECIPES: dict[str, Recipe] = {
    "table1": build_table1,
    "table2": build_table2,
    **{f"figure{number}": StabilityFigure(number) for number in STABILITY_FIGURES},
    **{fig_id: TimeSeriesFigure(fig_id) for fig_id in SERIES},
}

#: Why the artefacts without a recipe are not rebuilt, by artefact id.
NOT_COMPUTED: dict[str, str] = {
    "figure1": "a schematic drawing of the model, not a computed result; README.md carries the same "
    "sketch in text form",
}


def _artifact(caption: Caption) -> Artifact:
    kind = "table" if caption.id.startswith("table") else "figure"
    if caption.id in RECIPES:
        return Artifact(caption, kind, RECIPES[caption.id])
    return Artifact(caption, kind, None, NOT_COMPUTED[caption.id])  # KeyError: a caption nobody handles


#: Every table and figure of the paper, in the paper's order.
ARTIFACTS: tuple[Artifact, ...] = tuple(_artifact(caption) for caption in CAPTIONS)


def select(names: Sequence[str]) -> tuple[list[Artifact], list[str]]:
    """The artefacts named by id (``"figure5"``) or label (``"Figure 5"``), in the paper's order.

    Returns
    -------
    selected : list of Artifact
    unknown : list of str
        The names that match no artefact, sorted.
    """
    wanted = {name.strip() for name in names}
    selected = [a for a in ARTIFACTS if a.id in wanted or a.label in wanted]
    unknown = sorted(wanted - {a.id for a in selected} - {a.label for a in selected})
    return selected, unknown
