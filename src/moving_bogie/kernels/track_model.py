"""The track of a bound model: what the vehicle-rail coupling and the searches ask of the rail.

A bound model (:class:`~moving_bogie.kernels.bound.BoundModel`) holds one track object
(:attr:`~moving_bogie.kernels.bound.BoundModel.track`). Whatever the track (a rail on a continuous
foundation, a rail on sleepers, a rail on layered soil), the computations above ask it the same questions:

- :meth:`Track.receptance`: the rail-side receptance G between the (contact, harmonic) pairs at a frequency
  q, in the convention of :mod:`moving_bogie.kernels.coupling` (the rail's deflection at the contacts is
  pi W = 2 G f); :func:`~moving_bogie.kernels.coupling.coupled_system` couples it to the vehicle. On a
  continuous track G is the kernel matrix G_ij = K(xi_i - xi_j, q) of Eq. (29) and there is one harmonic
  (0); on sleepers G = (pi / 2) H, H the Hill receptance over the harmonics q + n Omega_0
  (docs/sleepers.md, Eq. (S9));
- :meth:`Track.search_region`: where every root lies once: the window 0 <= Re q <= R of a track whose
  characteristic function is even in Re q (a :data:`WINDOW`), or one strip of width Omega_0 of a track
  periodic in q (a :data:`STRIP`), with the harmonics the receptance needs there;
- :attr:`Track.kernel_decay`: the far field, gamma of G = O(|q|^-gamma) (None when not known: the search
  region must then bound the roots another way, as the strip does);
- :attr:`Track.has_cut`: whether G has branch cuts in q (the continuous track's cut of K,
  ``kernels/cut.py``; the singular lines of the free waves of a rail on sleepers, Eq. (S15)), which the
  search must tile around or continue across;
- :attr:`Track.smeared`: the continuous track whose free waves give the critical velocity (itself on a
  continuous track; the smeared supports on sleepers).

**How a new track plugs in.** Write a class with these members (it need not inherit from :class:`Track`:
the protocol is structural) whose constructor takes the bound model, ``MyTrack(bound)``, and reads what it
needs from it (``bound.floats``: every group as a float; ``bound.positions``: the contacts xi_j). Bind
parameters to it with ``BoundModel(params, track=MyTrack)``: the bound model calls ``MyTrack(bound)`` once,
keeps the class when it is copied (``bound.replace(alpha=...)`` binds the new parameters to a new
``MyTrack``) and pickles it by reference for the workers of a map or sweep. Nothing else changes: the
receptance may be rational (residues, as :class:`~moving_bogie.kernels.continuous_track.ContinuousTrack`)
or evaluated by quadrature, as the sleepers' (:mod:`moving_bogie.kernels.periodic_track`) and a layered
soil's are: :class:`RailReceptance` carries the estimated ``error`` of a quadrature beside the matrix.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any, Protocol, runtime_checkable

from numpy.typing import ArrayLike

__all__ = ["STRIP", "WINDOW", "BandTrack", "RailReceptance", "SearchRegion", "Track"]

#: The kinds of search region: a window of the right half-plane, or one strip of the period in Re q.
WINDOW, STRIP = "window", "strip"


@dataclass(frozen=True)
class SearchRegion:
    """Where a search finds every root once.

    Attributes
    ----------
    kind : {"window", "strip"}
        :data:`WINDOW`: the roots come in pairs q, -conj(q) and the search covers Re q >= 0 up to the far
        field's radius. :data:`STRIP`: the characteristic function is periodic in q with period
        ``period`` and the search covers one strip x0 <= Re q < x0 + period.
    period : float or None
        Omega_0 (dimensionless, in the track's time scale) of a strip; None for a window.
    harmonics : tuple of int
        The harmonics n of q + n Omega_0 the receptance couples at the start of the search ((0,) for a
        window); a strip search adds harmonics until its roots converge.
    free_waves : float or None
        The lowest Im q of the rail's free waves, where the singular lines of the receptance begin above
        the real axis (None when not known or not used).
    continued_to : float or None
        The Im q up to which a strip's search continued the receptance across the free waves' singular
        lines (docs/sleepers.md, "Beyond the free waves"); None when it stopped below them.
    """

    kind: str
    period: float | None = None
    harmonics: tuple[int, ...] = (0,)
    free_waves: float | None = None
    continued_to: float | None = None

    @property
    def periodic(self) -> bool:
        """Whether the region is one strip of a periodic characteristic function."""
        return self.kind == STRIP

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: ``kind``, ``Omega_0`` (the period, dimensionless), ``harmonics``, ``free_waves_im``,
        ``continued_to_im``."""
        return {
            "kind": self.kind,
            "Omega_0": self.period,
            "harmonics": list(self.harmonics),
            "free_waves_im": self.free_waves,
            "continued_to_im": self.continued_to,
        }


@dataclass(frozen=True)
class RailReceptance:
    """The rail-side receptance G at q between (contact, harmonic) pairs, and what came with it.

    Attributes
    ----------
    matrix : array
        G, shape ``q.shape + (P, P)`` with P = contacts x harmonics, the row and column of the pair
        (contact c, harmonic index h) at ``h * contacts + c``; pi W = 2 G f (Eq. (28)).
    derivative : array or None
        dG/dq when asked for and available.
    error : float
        Estimated absolute error of the entries (0 for a closed form; a quadrature's estimate otherwise).
    """

    matrix: Any
    derivative: Any = None
    error: float = 0.0


@runtime_checkable
class Track(Protocol):
    """The track of a bound model (module docstring): the members the runtime reads."""

    @property
    def name(self) -> str:
        """The track's name in the catalogue (``"one-layer"``, ``"sleepers"``), for output only."""

    def receptance(
        self, q: ArrayLike, harmonics: Sequence[int] = (0,), *, derivative: bool = False
    ) -> RailReceptance:
        """G at q (a number, or an array for a track that evaluates batches) between the bound model's
        contacts at the given harmonics."""

    def search_region(self) -> SearchRegion:
        """The region that holds every root once."""

    @property
    def kernel_decay(self) -> Fraction | None:
        """gamma of G = O(|q|^-gamma) for large |q| (None: not known)."""

    @property
    def has_cut(self) -> bool:
        """Whether G has branch cuts or singular lines in q that a search must avoid or cross."""

    @property
    def smeared(self) -> Any:
        """The continuous track whose free waves give the critical velocity (a :class:`Track`)."""


@runtime_checkable
class BandTrack(Protocol):
    """A track whose kernel, a quadrature along real wavenumbers, stays analytic in a band above the real
    axis of q (its decaying roots there are searched, :mod:`moving_bogie.roots.decaying_band`)."""

    @property
    def band_scale(self) -> float:
        """rad/s per unit of q, for output."""

    @property
    def band_caveat(self) -> str:
        """What :meth:`waves_clear` is (a bound, or a scan), for the notes of a result ("" for a bound)."""

    def band_depth(self, x: float) -> float:
        """The depth in Im q under which no singular line of the kernel lies at Re q >= ``x`` > 0 (0:
        none)."""

    def waves_clear(self, x0: float, x1: float, y0: float, y1: float) -> bool:
        """Whether no other singular line of the kernel crosses the rectangle [x0, x1] x [y0, y1] of q."""
