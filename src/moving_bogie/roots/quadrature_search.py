"""The search of a track whose receptance is a quadrature (on the soil): the window's roots with Im q <= 0 and
the decaying roots of the band above it.

The window is counted and its roots located as :mod:`moving_bogie.roots.quadrature_window` says; on a track
that says where its kernel stays analytic above the real axis, the band of decaying roots under its singular
lines is searched too (:mod:`moving_bogie.roots.decaying_band`), for the margin.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

import mpmath

from moving_bogie.kernels.track_model import BandTrack
from moving_bogie.roots.count.contour import EdgeZeroError, Rectangle
from moving_bogie.roots.count.far_field import MARGIN, FarField
from moving_bogie.roots.count.outcomes import Note, Reason
from moving_bogie.roots.decaying_band import STEPS, decaying_band
from moving_bogie.roots.frequency_result import FrequencyResult
from moving_bogie.roots.quadrature_window import (
    QuadratureCharacteristic,
    count_rectangle,
    far_check,
    grown_radius,
    induced,
    locate,
)

if TYPE_CHECKING:
    from moving_bogie.kernels.bound import BoundModel

__all__ = ["window_frequencies"]


def window_frequencies(
    bound: BoundModel,
    *,
    radius: float,
    far_field: FarField | None = None,
    progress: Callable[[float], None] | None = None,
    decaying: bool = True,
    band_steps: int | None = None,
) -> FrequencyResult:
    """Every root with Im q <= 0 in the window of size ``radius`` of a track whose receptance is a
    quadrature (module docstring), with the count beside them and the notes of the verdict.

    Parameters
    ----------
    bound : BoundModel
        The parameters bound to such a track.
    radius : float
        S: the window's size (the far-field radius, or larger).
    far_field : FarField, optional
        The far-field check of the track's continuous equivalent that gave ``radius`` (None: not checked).
    decaying : bool
        On a track that says where its kernel stays analytic above the real axis (a
        :class:`~moving_bogie.kernels.track_model.BandTrack`: the soil), also search the band of decaying
        roots under the singular lines
        (:mod:`~moving_bogie.roots.decaying_band`) for the margin; ``band_steps`` rectangles in its
        staircase (None: :data:`~moving_bogie.roots.decaying_band.STEPS`).
    """
    E = QuadratureCharacteristic(bound)
    if far_field is not None and far_field.radius is not None:
        radius = grown_radius(E, radius)
    rect = Rectangle(-1e-3 * radius, radius, -radius, 0.0)
    notes: list[Note] = []
    try:
        count, stands = count_rectangle(E, rect)
    except EdgeZeroError:
        rect = Rectangle(rect.x0, rect.x1, rect.y0, -1e-3 * radius)
        notes.append(Note(Reason.QUADRATURE, f"a root lies within {1e-3 * radius:.3g} of the real axis"))
        count, stands = count_rectangle(E, rect)
    if not stands:
        text = "the count rests on values of E_chr on the window's edge within twice their error of 0"
        notes.append(Note(Reason.QUADRATURE, text))
    if progress is not None:
        progress(0.5)
    roots = [induced(E, q, slope, step) for q, slope, step in locate(E, rect, count)]
    for root in roots:
        if root.marginal:
            text = f"Im q of the root at Re q = {root.re_text} is within its error of 0"
            notes.append(Note(Reason.QUADRATURE, text))
    band = None
    if decaying and isinstance(bound.track, BandTrack):
        band = decaying_band(E, radius, STEPS if band_steps is None else band_steps)
        notes.append(Note(Reason.BEYOND_WINDOW, band.statement()))
    else:
        notes.append(Note(Reason.BEYOND_WINDOW, "Im q > 0 is not searched: roots there decay"))
    far = far_field
    if far is not None and far.radius is not None:
        worst = far_check(E, radius)
        far = FarField(radius, worst, far.start)  # the track's own rho on the far edges
        if worst > MARGIN:
            reason = f"|E_chr - E_lead| / |E_lead| = {worst:.3g} > {MARGIN} on the window's far edges"
            far = FarField(None, worst, far.start, reason)
    if progress is not None:
        progress(1.0)
    return FrequencyResult(
        bound=bound,
        model=bound.model.vehicle,
        dps=15,
        window=rect,
        roots=tuple(sorted(roots, key=lambda r: float(mpmath.re(r.q)))),
        count=count,
        unsearched=(),
        evaluations=len(E.samples),
        notes=tuple(notes),
        far_field=far,
        band=band,
    )
