"""A rail on discrete supports every l as a :class:`~moving_bogie.kernels.track_model.Track`.

The rail-side receptance between the (contact, harmonic) pairs is the Hill receptance H of Eq. (S9)
(:func:`~moving_bogie.kernels.periodic_receptance.receptance`, by residues and adaptive quadrature), in the
coupling's convention G = (pi / 2) H (:mod:`moving_bogie.kernels.coupling`: pi W = 2 G f); the
characteristic function is periodic in q with period Omega_0 = 2 pi alpha / lam, so the search covers one
strip of that width (docs/sleepers.md, Eq. (S14)); the free waves of the rail put singular lines of the
receptance near the real axis (Eq. (S15)); no power law bounds the far field (the strip is bounded in
Re q, its depth is searched until a band below it is empty).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from fractions import Fraction
from typing import TYPE_CHECKING, Any, cast

import numpy as np
from numpy.typing import ArrayLike

from moving_bogie.kernels.hill import harmonic_set
from moving_bogie.kernels.periodic_receptance import receptance
from moving_bogie.kernels.sleeper_track import SleeperTrack
from moving_bogie.kernels.track_model import STRIP, RailReceptance, SearchRegion

if TYPE_CHECKING:
    from moving_bogie.kernels.bound import BoundModel
    from moving_bogie.model.periodic import PeriodicFoundation

__all__ = ["PeriodicTrack"]


class PeriodicTrack:
    """The sleeper track of a bound model whose parameters carry the groups of ``generated/sleepers.py``.

    ``PeriodicTrack(bound)`` takes the generated functions of the beam on its supports from
    ``bound.foundation`` (the catalogue's :class:`~moving_bogie.model.periodic.PeriodicFoundation`) and the
    groups from ``bound.floats``; :meth:`on` makes one from a
    :class:`~moving_bogie.kernels.sleeper_track.SleeperTrack` and the contact positions directly.

    Parameters
    ----------
    bound : BoundModel
        The parameters bound to their model.
    offset : float
        The rear wheel's position relative to a support at tau = 0 (the roots do not depend on it).
    tol : float
        Relative tolerance of the receptance's quadrature.
    """

    def __init__(self, bound: BoundModel, *, offset: float = 0.0, tol: float = 1e-12) -> None:
        numbers = vars(bound.floats)
        groups = {k: v for k, v in numbers.items() if isinstance(v, float)}
        kernels = cast("PeriodicFoundation", bound.foundation)
        self._set(SleeperTrack(kernels, groups), bound.positions, offset, tol)

    @classmethod
    def on(
        cls,
        track: SleeperTrack,
        positions: ArrayLike = (0.0,),
        *,
        offset: float = 0.0,
        tol: float = 1e-12,
    ) -> PeriodicTrack:
        """The periodic track of a :class:`SleeperTrack` under contacts at ``positions`` (dimensionless)."""
        out = cls.__new__(cls)
        out._set(track, positions, offset, tol)
        return out

    def _set(self, track: SleeperTrack, positions: ArrayLike, offset: float, tol: float) -> None:
        self.sleepers = track
        self.positions = np.asarray(positions, dtype=float) + offset
        self.tol = tol

    @property
    def name(self) -> str:
        """The track's name in the catalogue (``"sleepers"``, ``"sleepers-two-layer"``)."""
        return self.sleepers.track

    @property
    def groups(self) -> Mapping[str, Any]:
        """The track's dimensionless groups (floats)."""
        return self.sleepers.groups

    def receptance(
        self, q: ArrayLike, harmonics: Sequence[int] = (0,), *, derivative: bool = False
    ) -> RailReceptance:
        """G = (pi / 2) H (Eq. (S9)) between the (contact, harmonic) pairs at one q (no derivative: None).

        Raises
        ------
        ValueError
            For an array of q (the quadrature evaluates one q at a time).
        """
        if np.ndim(q):
            raise ValueError("q: the receptance of a rail on supports is evaluated at one q at a time")
        rec = receptance(self.sleepers, complex(q), harmonics, self.positions, tol=self.tol)  # type: ignore[arg-type]
        return RailReceptance((np.pi / 2) * rec.matrix, None, (np.pi / 2) * rec.error)

    def search_region(self, N: int = 1) -> SearchRegion:
        """One strip of width Omega_0 with the harmonics -N-1..N (symmetric under n -> -n - 1)."""
        return SearchRegion(STRIP, self.sleepers.Omega0, tuple(int(n) for n in harmonic_set(N)))

    @property
    def kernel_decay(self) -> Fraction | None:
        """None: the strip is bounded in Re q and its depth is searched (no power law is used)."""
        return None

    @property
    def has_cut(self) -> bool:
        """The free waves of the rail put singular lines of the receptance near the real axis (Eq. (S15))."""
        return True

    @property
    def smeared(self) -> None:
        """The continuous track with the smeared supports (``model/smeared.py``), not bound here yet:
        None until the sleeper parameters are a model of the one catalogue."""
        return None
