"""What a recipe of the paper's artefacts is given and what it returns.

A *recipe* rebuilds one table or figure: a callable ``recipe(ctx: BuildContext) -> Built``. It takes the
output folder, the mode and the shared results from :class:`BuildContext`, writes its files through it,
and returns a :class:`Built` (files written, the table as HTML and Markdown, notes for the index page).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

__all__ = ["BuildContext", "Built", "Recipe"]


@dataclass
class Built:
    """What a recipe returns: files written (relative to the output folder), a table, notes."""

    files: list[str] = field(default_factory=list)
    html: str = ""
    markdown: str = ""
    notes: list[str] = field(default_factory=list)
    ok: bool = True  # False: built, but the result disagrees with the paper (e.g. Table 2 mismatch)


class BuildContext:
    """Passed to every recipe: the output folder, the mode, shared results and a progress callback.

    Parameters
    ----------
    out : Path
        Output folder; recipes write below it.
    quick : bool
        Reduced grids and time windows.
    dps : int
        Working precision (decimal digits) of the induced frequencies.
    progress : callable, optional
        Called with the fraction (0..1) of the current artefact done.
    """

    def __init__(
        self, out: Path, *, quick: bool, dps: int, progress: Callable[[float], None] | None = None
    ) -> None:
        self.out = out
        self.quick = quick
        self.dps = dps
        self._progress = progress
        self._frequencies: dict[int, Any] = {}
        self._series: dict[tuple[int, float, int], Any] = {}
        #: The :class:`~moving_bogie.roots.table2.Table2` of this run, once the Table 2 recipe has run.
        self.table2: Any = None

    def progress(self, fraction: float) -> None:
        """Report the fraction of the current artefact done (0..1)."""
        if self._progress is not None:
            self._progress(max(0.0, min(1.0, fraction)))

    def save_figure(self, fig: Any, name: str, *, dpi: int = 110) -> str:
        """Save a matplotlib Figure as ``figures/<name>.png``, close it, return the relative path.

        A figure with a layout engine (constrained layout, as every recipe's) already fits its canvas and is
        saved as laid out; any other is cropped to its content (``bbox_inches="tight"``, an extra pass
        measuring every artist).
        """
        rel = f"figures/{name}.png"
        path = self.out / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        fig.savefig(path, dpi=dpi, bbox_inches=None if fig.get_layout_engine() is not None else "tight")
        _close_figure(fig)
        return rel

    def frequencies(self, case: int) -> Any:
        """Induced frequencies of Table 1 case `case` (bogie), from Table 2 when it was built in this run."""
        if case not in self._frequencies:
            row = next((r for r in self.table2.rows if r.case == case), None) if self.table2 else None
            if row is not None:
                self._frequencies[case] = row.result
            else:
                from moving_bogie.api import induced_frequencies
                from moving_bogie.model.cases import table1_case

                self._frequencies[case] = induced_frequencies(table1_case(case), dps=self.dps)
        return self._frequencies[case]

    def closed_form(self, case: int, tau_max: float, points: int) -> Any:
        """Closed-form response (Eqs. (35)-(43)) of Table 1 case `case` at ``points + 1`` times in
        [0, tau_max], computed once per run (figures sharing a case and a window share it)."""
        key = (case, float(tau_max), int(points))
        if key not in self._series:
            import numpy as np

            from moving_bogie.api import closed_form_response
            from moving_bogie.model.cases import table1_case

            tau = np.linspace(0.0, tau_max, points + 1)
            self._series[key] = closed_form_response(
                table1_case(case), tau, frequencies=self.frequencies(case)
            )
        return self._series[key]


#: A recipe: rebuilds one artefact into the context's output folder.
Recipe = Callable[[BuildContext], Built]


def _close_figure(fig: Any) -> None:
    """Release a matplotlib figure whether or not pyplot manages it."""
    import sys

    if "matplotlib.pyplot" in sys.modules:
        sys.modules["matplotlib.pyplot"].close(fig)
