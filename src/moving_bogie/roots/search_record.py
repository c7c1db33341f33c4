"""What the verdict and the proof read of a finished search: two structural types.

:class:`~moving_bogie.roots.frequency_result.FrequencyResult` is built from the verdict
(:func:`~moving_bogie.roots.verdict.judge`) and may carry a proof
(:class:`~moving_bogie.roots.proof.certify.Certificate`); both read the result back. They read it through
:class:`SearchRecord`, the fields a search of Eq. (48) leaves behind, so that neither imports the result.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, Protocol

from moving_bogie.kernels.bound import BoundModel
from moving_bogie.kernels.track_model import SearchRegion
from moving_bogie.roots.count.contour import Rectangle
from moving_bogie.roots.count.far_field import FarField
from moving_bogie.roots.count.outcomes import Note, Unlocated
from moving_bogie.roots.count.strip import StripCount
from moving_bogie.roots.search.cut_cells import Sliver
from moving_bogie.typing import Mpc

__all__ = ["LocatedRoot", "SearchRecord"]


class LocatedRoot(Protocol):
    """One induced frequency found by the search (an :class:`InducedFrequency`)."""

    @property
    def q(self) -> Mpc: ...

    @property
    def multiplicity(self) -> int: ...

    @property
    def unstable(self) -> bool: ...

    def to_dict(self) -> dict[str, Any]: ...


class SearchRecord(Protocol):
    """A finished search of one window: its roots beside the argument-principle count, and what it left
    out (the far field, unsearched slivers, unlocated roots, the strip below the real axis)."""

    @property
    def bound(self) -> BoundModel: ...

    @property
    def window(self) -> Rectangle: ...

    @property
    def roots(self) -> Sequence[LocatedRoot]: ...

    @property
    def count(self) -> int: ...

    @property
    def found(self) -> int: ...

    @property
    def far_field(self) -> FarField | None: ...

    @property
    def region(self) -> SearchRegion | None: ...

    @property
    def notes(self) -> tuple[Note, ...]: ...

    @property
    def unsearched(self) -> Sequence[Sliver]: ...

    @property
    def unlocated(self) -> Sequence[Unlocated]: ...

    @property
    def strip(self) -> StripCount | None: ...

    @property
    def unstable_roots(self) -> Sequence[LocatedRoot]: ...

    @property
    def strip_unstable(self) -> int: ...
