"""Why a search, a count or a window falls short: typed reasons, and the notes rendered from them.

A note (:class:`Note`) carries its :class:`Reason` and the detail of the case; the text printed for it
(:meth:`Note.text`, ``"reason: detail"``) is rendered from the two and never read back: whatever decides on
a note (whether the count is complete, which part of the verdict is UNDETERMINED) reads its reason.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum

from moving_bogie.roots.count.contour import Region

__all__ = ["Note", "Reason", "Unlocated", "count_mismatch", "notes_with"]


class Reason(Enum):
    """What fell short; the value is the label the note is printed with."""

    #: No far-field radius R beyond which E_chr has no root with Im q < 0 (Eq. (48)).
    FAR_FIELD = "far field"
    #: WindowIncomplete: the window stops inside R, or the window twice as large could not be counted
    #: completely or holds more roots that may have Im q < 0.
    WINDOW = "window"
    #: CountMismatch: the roots found and confirmed do not add up to the argument-principle count.
    COUNT = "count"
    #: Unsearched: a region of the window left out because its count failed.
    UNSEARCHED = "unsearched"
    #: The unsearched band around the cut of K reaches below the real axis and was not counted there.
    SLIVER = "sliver"
    #: Roots with Im q >= 0 beyond the window (they decay; the verdict stands).
    BEYOND_WINDOW = "beyond the window"
    #: Roots counted in a cell that bisection and Newton's method could not locate.
    LOCATE = "locate"
    #: A root whose digits could not be confirmed, or whose Newton iteration left its cell.
    POLISH = "polish"
    #: A root with Re q < 0 found without its mirror -conj(q).
    PAIR = "pair"
    #: The search of one strip of a periodic track fell short (its depth, the harmonics, a band near the
    #: real axis; docs/sleepers.md).
    STRIP = "strip"
    #: The error of a receptance by quadrature may decide the case: a root whose Im q is within its error
    #: of 0, or a band next to the real axis left out (a track on the soil, docs/soil.md).
    QUADRATURE = "quadrature"


@dataclass(frozen=True)
class Note:
    """One shortfall: its ``reason`` and the ``detail`` of the case (numbers, cells, the remedy)."""

    reason: Reason
    detail: str

    @property
    def text(self) -> str:
        return f"{self.reason.value}: {self.detail}"

    def __str__(self) -> str:
        return self.text


@dataclass(frozen=True)
class Unlocated:
    """Roots counted in ``cell`` that were not located (``missing`` of them), with the note that says so."""

    cell: Region  # a Rectangle or a cut cell
    missing: int
    note: Note


def notes_with(notes: tuple[Note, ...] | list[Note], reason: Reason) -> list[Note]:
    """The notes of ``notes`` given for ``reason``."""
    return [note for note in notes if note.reason is reason]


def count_mismatch(count: int, found: int) -> Note:
    """CountMismatch: ``count`` roots with Re q >= 0 by the argument principle, ``found`` confirmed."""
    return Note(
        Reason.COUNT,
        f"the argument principle counts {count} root(s) with Re q >= 0, {found} were found and confirmed",
    )
