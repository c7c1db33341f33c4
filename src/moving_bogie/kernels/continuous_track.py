"""The rail on a continuous foundation as a :class:`~moving_bogie.kernels.track_model.Track`.

Its receptance between the contacts is the kernel matrix G_ij = K(xi_i - xi_j, q) of Eq. (29), K by
residues at the roots in p of N(p, q) (:class:`~moving_bogie.kernels.track.TrackKernelArray`), at the one
harmonic 0; its characteristic function is even in Re q, so the search covers the window Re q >= 0 up to
the radius of the far field (G = O(|q|^-gamma), gamma the generated ``KERNEL_DECAY``); K has a cut in q
(``kernels/cut.py``); its free waves are its own (the critical velocity of ``stability/velocity/``).
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from moving_bogie.kernels.arithmetic import Batched
from moving_bogie.kernels.coupling import kernel_matrix
from moving_bogie.kernels.track import TrackKernelArray
from moving_bogie.kernels.track_model import WINDOW, RailReceptance, SearchRegion

if TYPE_CHECKING:
    from moving_bogie.kernels.bound import BoundModel

__all__ = ["ContinuousTrack"]


class ContinuousTrack:
    """The track of ``bound`` when it is a generated foundation module (``bound.foundation_model``).

    Parameters
    ----------
    bound : BoundModel
        The parameters bound to their model.

    Examples
    --------
    >>> from moving_bogie import bind, table1_case
    >>> track = bind(table1_case(1)).track
    >>> track.name, track.search_region().kind, track.receptance(0.3 + 0.1j).matrix.shape
    ('one-layer', 'window', (2, 2))
    """

    def __init__(self, bound: BoundModel) -> None:
        self._bound = bound
        self._system = bound.float_system
        self._index = np.array(self._system.index)

    @property
    def name(self) -> str:
        """The track's name in the catalogue."""
        return self._bound.model.track

    def receptance(
        self, q: ArrayLike, harmonics: Sequence[int] = (0,), *, derivative: bool = False
    ) -> RailReceptance:
        """The kernel matrix K(xi_i - xi_j, q) (Eq. (29)) at q (a number or an array), dK/dq if asked.

        Raises
        ------
        ValueError
            For harmonics other than (0,): a continuous track couples none.
        """
        if tuple(harmonics) != (0,):
            raise ValueError(f"harmonics: a continuous track has the one harmonic 0 (got {harmonics})")
        kernel = TrackKernelArray(self._bound)
        values = kernel(np.asarray(q, dtype=complex), self._system.offsets, derivative=derivative)
        G = kernel_matrix(values.K, self._index, Batched)
        dG = None if values.dK is None else kernel_matrix(values.dK, self._index, Batched)
        return RailReceptance(G, dG)

    def search_region(self) -> SearchRegion:
        """The window Re q >= 0 (the roots come in pairs q, -conj(q)) at the one harmonic 0."""
        return SearchRegion(WINDOW)

    @property
    def kernel_decay(self) -> Fraction | None:
        """gamma of K = O(|q|^-gamma) (``KERNEL_DECAY`` of the generated module; None if absent)."""
        return self._bound.kernel_decay

    @property
    def has_cut(self) -> bool:
        """K has a cut in q where N(p, q) has a real root p (``kernels/cut.py``)."""
        return True

    @property
    def smeared(self) -> ContinuousTrack:
        """The track itself: its free waves give the critical velocity."""
        return self
