"""The induced frequencies of a bound model on periodic supports, as the one result of every track.

:func:`strip_frequencies` runs the search of one strip of width Omega_0 (:mod:`moving_bogie.roots.strip`,
docs/sleepers.md, Eq. (S14)) on the track and vehicle of a bound model and returns the
:class:`~moving_bogie.roots.frequency_result.FrequencyResult` that a continuous track's search returns:
the roots, the argument-principle count beside them, the notes (with the reason
:attr:`~moving_bogie.roots.count.outcomes.Reason.STRIP`; the band above the window, which holds decaying
vibrations only, with the reason ``BEYOND_WINDOW``) and the verdict of :mod:`moving_bogie.roots.verdict`;
its ``region`` holds Omega_0, the harmonics and the free waves' lowest Im q, from which a stable result
has its margin (:attr:`~moving_bogie.roots.frequency_result.FrequencyResult.margin`).

The digits of each root are those the search confirmed by recomputation: the root moved by ``step`` when
the last harmonic was added, and is a zero of the Hill determinant to ``residual``; the decimals printed
are those that neither changes (double precision bounds them at about 15 significant digits).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import mpmath

from moving_bogie.kernels.hill import VehicleMatrices, harmonic_set
from moving_bogie.kernels.periodic_track import PeriodicTrack
from moving_bogie.kernels.track_model import STRIP, SearchRegion
from moving_bogie.roots.count.outcomes import Note, Reason
from moving_bogie.roots.frequency_result import FrequencyResult, InducedFrequency
from moving_bogie.roots.strip import FloquetRoot, floquet_frequencies

if TYPE_CHECKING:
    from moving_bogie.kernels.bound import BoundModel

__all__ = ["strip_frequencies"]

#: The relative resolution of double precision: no root is confirmed to more than this.
_DOUBLE = 1e-15


def strip_frequencies(
    bound: BoundModel, *, progress: Callable[[float], None] | None = None, **options: Any
) -> FrequencyResult:
    """Every root in one strip of width Omega_0 of the bound model's periodic track (Eq. (S14)).

    Parameters
    ----------
    bound : BoundModel
        Parameters of a model on periodic supports, bound to a
        :class:`~moving_bogie.kernels.periodic_track.PeriodicTrack`.
    progress : callable, optional
        Called with the fraction done (1 at the end).
    **options
        Those of :func:`~moving_bogie.roots.strip.floquet_frequencies` (``N0``, ``N_max``, ``tol``,
        ``depth``, ``top``, ``continued``).
    """
    track = bound.track
    if not isinstance(track, PeriodicTrack):
        raise TypeError(f"bound: the strip search needs a track on periodic supports (got {track.name!r})")
    vehicle = VehicleMatrices.from_module(bound.vehicle, vars(bound.floats))
    found = floquet_frequencies(track.sleepers, vehicle, **options)
    roots = tuple(_induced(root) for root in found.roots)
    notes = tuple(Note(Reason.STRIP, text) for text in found.notes)
    notes += tuple(Note(Reason.BEYOND_WINDOW, text) for text in found.unsearched())
    harmonics = tuple(int(n) for n in harmonic_set(found.harmonics))
    region = SearchRegion(STRIP, found.Omega0, harmonics, found.free_waves or None, found.continued_to)
    if progress is not None:
        progress(1.0)
    return FrequencyResult(
        bound=bound,
        model=bound.model.vehicle,
        dps=15,
        window=found.window,
        roots=roots,
        count=found.count,
        unsearched=(),
        evaluations=found.evaluations,
        notes=notes,
        region=region,
        strip_margin=None if found.margin is None else (found.margin, found.margin_source or ""),
    )


def _induced(root: FloquetRoot) -> InducedFrequency:
    """One root of the strip with the decimals its last harmonic and its residual leave unchanged."""
    q = root.q
    size = max(1.0, abs(q))
    resolution = max(root.step, root.residual, _DOUBLE * size)
    decimals = max(0, math.floor(-math.log10(2 * resolution))) if math.isfinite(resolution) else 0
    digits = max(0, decimals + math.floor(math.log10(size)) + 1)
    return InducedFrequency(
        q=mpmath.mpc(q.real, q.imag),
        side="strip",
        multiplicity=1,
        residual=mpmath.mpf(root.residual),
        digits=digits,
        decimals=decimals,
    )
