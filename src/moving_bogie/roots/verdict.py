"""The stability verdict: STABLE, UNSTABLE, or UNDETERMINED with the reasons.

The motion is unstable when some induced frequency has Im q < 0 (Eq. (35) with e^{i q tau}). A verdict is a
statement about *every* root of E_chr (Eq. (48)) with Im q < 0, so it is given only when the search was
complete there:

- the far-field check found a radius R beyond which E_chr has no root with Im q < 0 (:mod:`far_field`),
- the search window contains the lower half-disc of radius R (0 <= Re q <= R, -R <= Im q <= 0),
- the roots found add up to the argument-principle count (roots counted in a cell that lies in Im q > 0 but
  could not be located are stable whatever they are: they are named in the warnings, not in the verdict),
- no unsearched sliver around the cut of K reaches below Im q = 0, or the part below it was counted
  (:mod:`strip`: with eta_f = 0 the cut lies on the real axis and K there is the limit from below),
- no search cell reaching below Im q = 0 was left out because its count failed (``Sliver.reason``),
- on a track whose receptance is a quadrature, no root lies within the quadrature's error of the real axis
  and no band next to it was left out (notes of reason ``QUADRATURE``).

Otherwise the verdict is UNDETERMINED and lists what is missing; roots with Im q > 0 outside the window
(a stated choice, checked against a window twice as large) do not affect it.
"""

from __future__ import annotations

from dataclasses import dataclass

from moving_bogie.roots.count.outcomes import Note, Reason, count_mismatch, notes_with
from moving_bogie.roots.search_record import SearchRecord

STABLE, UNSTABLE, UNDETERMINED = "stable", "unstable", "undetermined"


@dataclass(frozen=True)
class Verdict:
    """``state`` is one of STABLE, UNSTABLE, UNDETERMINED; ``reasons`` say why it is UNDETERMINED."""

    state: str
    reasons: tuple[Note, ...] = ()

    @property
    def determined(self) -> bool:
        return self.state != UNDETERMINED

    def to_dict(self) -> dict:
        return {"state": self.state, "reasons": [note.text for note in self.reasons]}


def incompleteness(result: SearchRecord) -> list[Note]:
    """Why the search of ``result`` (a FrequencyResult) may have missed a root with Im q < 0.

    On a periodic track (one strip of width Omega_0, docs/sleepers.md) the strip's own notes (its depth,
    the harmonics, a band near the real axis) stand where the far field and the window do.
    """
    quadrature = notes_with(result.notes, Reason.QUADRATURE)
    if result.region is not None and result.region.periodic:
        reasons = notes_with(result.notes, Reason.STRIP) + quadrature
        if result.found != result.count:
            reasons.append(count_mismatch(result.count, result.found))
        return reasons
    reasons = quadrature
    far = result.far_field
    if far is None:
        reasons.append(
            Note(Reason.FAR_FIELD, "not checked (no radius beyond which E_chr has no root with Im q < 0)")
        )
    elif far.radius is None:
        reasons.append(Note(Reason.FAR_FIELD, far.reason))
    else:
        w = result.window
        if w.x1 < far.radius or w.y0 > -far.radius:
            reasons.append(
                Note(
                    Reason.WINDOW,
                    f"it stops at Re q = {w.x1:g}, Im q = {w.y0:g}, inside the radius R = {far.radius:g} "
                    "beyond which E_chr has no root with Im q < 0; widen it or drop --window",
                )
            )
    upper = sum(u.missing for u in result.unlocated if u.cell.y0 > 0)
    if result.found != result.count and result.count - result.found != upper:
        reasons.append(count_mismatch(result.count, result.found))
    lost = [u for u in result.unsearched if u.reason and u.y0 < 0]
    for u in lost:
        reasons.append(
            Note(
                Reason.UNSEARCHED,
                f"the cell {u.x0:.6g} <= Re q <= {u.x1:.6g}, {u.y0:.6g} <= Im q <= {u.y1:.6g} "
                f"({u.x1 - u.x0:.1e} x {u.height:.1e}) could not be counted: {u.reason}",
            )
        )
    low = min((u.y0 for u in result.unsearched if not u.reason), default=0.0)
    strip = result.strip
    if low < 0 and strip is not None and not strip.decided:
        reasons.append(
            Note(
                Reason.SLIVER,
                f"the unsearched band around the cut of K reaches Im q = {low:.1e} < 0 and "
                f"could not be counted there ({strip.reason})",
            )
        )
    elif low < 0 and strip is None:
        reasons.append(
            Note(
                Reason.SLIVER,
                f"the unsearched band around the cut of K reaches Im q = {low:.1e} < 0, "
                "so a root just below the real axis there cannot be excluded",
            )
        )
    return reasons


def judge(result: SearchRecord) -> Verdict:
    """The verdict of a FrequencyResult: complete search -> STABLE/UNSTABLE, else UNDETERMINED."""
    reasons = incompleteness(result)
    if reasons:
        return Verdict(UNDETERMINED, tuple(reasons))
    unstable = result.unstable_roots or result.strip_unstable
    return Verdict(UNSTABLE if unstable else STABLE)
