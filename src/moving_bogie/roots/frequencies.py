"""Induced frequencies: every root of E_chr(q) = 0 (Eq. (48)) in a window, found with no starting guesses.

1. Count: the window (Re q >= 0 half, pairs q, -conj(q) are reported once) is tiled into rectangles that
   never meet the cut of K (:mod:`search_regions`); the argument principle counts the roots in each
   (:mod:`contour`), in double precision.
2. Locate: rectangles holding roots are bisected (each half counted) until a cell holds one root and is
   small enough for Newton's method to stay inside it.
3. Polish and confirm at high precision (:mod:`polish`): digits are those that agree at two precisions.
4. Check: the roots found must add up to the count, or the result says so (``count_ok``) and the CLI
   exits non-zero. The window is also compared with a window twice as large: a root outside the default
   window is reported, never silently dropped. When the window holds the lower half-disc of the far-field
   radius R, roots found there lie beyond R, so Im q >= 0 (``decaying_outside``): they are reported and do
   not change the verdict or the count (the Timoshenko-Rayleigh sequence along the real axis beyond
   sqrt(S)/r); otherwise they fail the count.

Stability: the motion is unstable when some induced frequency has Im q < 0 (Eq. (35) with e^{i q tau}).
The default window contains the lower half-disc of the radius R beyond which E_chr has no root with
Im q < 0 (:mod:`far_field`), so the verdict (:mod:`verdict`) speaks about every root, or says UNDETERMINED.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import mpmath
import numpy as np

from moving_bogie.kernels.bound import bind
from moving_bogie.kernels.characteristic import Characteristic, CharacteristicArray
from moving_bogie.kernels.cut import CutLocus, arms_y_at, cut_loci
from moving_bogie.roots.count.contour import Rectangle
from moving_bogie.roots.count.far_field import FarField, far_field_radius
from moving_bogie.roots.count.outcomes import Note, Reason, Unlocated, count_mismatch, notes_with
from moving_bogie.roots.count.strip import StripCount, strip_below_cut
from moving_bogie.roots.count.window import default_window, far_field_window  # noqa: F401  (public here too)
from moving_bogie.roots.refine.locate import locate
from moving_bogie.roots.refine.polish import PolishError, fixed_text, polish_and_confirm, split_cluster
from moving_bogie.roots.search.continuation import ContinuedRegion
from moving_bogie.roots.search.counting import count_tiling, frame
from moving_bogie.roots.verdict import Verdict, judge

if TYPE_CHECKING:
    from moving_bogie.model.params import DimensionlessParams
    from moving_bogie.roots.proof.certify import Certificate


@dataclass(frozen=True)
class InducedFrequency:
    """One induced frequency (the member of its pair with Re q >= 0).

    ``side`` tells where q lies with respect to the cut of K: "below" or "above" every cut curve over its
    Re q, or "between" two of them (layered tracks, the Timoshenko-Rayleigh lens) (for eta_f = 0 a real root
    in the gap is a limit from below). ``digits``/``decimals`` are confirmed by recomputation at higher
    precision; ``residual`` is |E_chr/E_chr'| at q, the distance to the exact root at working precision.
    """

    q: mpmath.mpc
    side: str
    multiplicity: int
    residual: mpmath.mpf
    digits: int
    decimals: int

    @property
    def re_text(self) -> str:
        return fixed_text(mpmath.re(self.q), self.decimals)

    @property
    def im_text(self) -> str:
        return fixed_text(mpmath.im(self.q), self.decimals)

    @property
    def unstable(self) -> bool:
        """Im q < 0, confirmed: |Im q| exceeds the confirmed resolution."""
        return mpmath.im(self.q) < 0 and abs(mpmath.im(self.q)) > mpmath.mpf(10) ** (-self.decimals)

    @property
    def marginal(self) -> bool:
        """|Im q| below the confirmed resolution (a real induced frequency: constant amplitude)."""
        return abs(mpmath.im(self.q)) <= mpmath.mpf(10) ** (-self.decimals)

    def to_dict(self) -> dict:
        return {
            "re": self.re_text,
            "im": self.im_text,
            "side": self.side,
            "multiplicity": self.multiplicity,
            "digits": self.digits,
            "residual": mpmath.nstr(self.residual, 3),
        }


@dataclass(frozen=True)
class FrequencyResult:
    """All induced frequencies in a window, the argument-principle count and the verdict."""

    params: DimensionlessParams  # (bind() gives its bound model)
    model: str  # the vehicle's name, for output only
    dps: int
    window: Rectangle
    roots: tuple
    count: int  # roots with Re q >= 0 by the argument principle (with multiplicity, pairs once)
    unsearched: tuple  # slivers around the cut that no contour can enter
    evaluations: int  # E_chr evaluations (double precision + high precision)
    notes: tuple[Note, ...] = field(default=())
    far_field: FarField | None = None
    certificate: Certificate | None = None  # when asked for (certify=True)
    strip: StripCount | None = None  # the sliver below the real axis, counted (roots/count/strip.py)
    unlocated: tuple[Unlocated, ...] = ()  # roots counted in a cell but not located
    decaying_outside: int = 0  # roots with Im q >= 0 in the window twice as large, outside this one

    @property
    def found(self) -> int:
        return sum(r.multiplicity for r in self.roots)

    @property
    def warnings(self) -> tuple[str, ...]:
        """The notes as printed (rendered from their reasons)."""
        return tuple(note.text for note in self.notes)

    @property
    def count_ok(self) -> bool:
        return self.found == self.count and not notes_with(self.notes, Reason.WINDOW)

    @property
    def unstable_roots(self) -> tuple:
        return tuple(r for r in self.roots if r.unstable)

    @property
    def stable(self) -> bool:
        """No confirmed root with Im q < 0 among those found (:attr:`verdict` is the complete statement)."""
        return not self.unstable_roots

    @property
    def strip_unstable(self) -> int:
        """Roots with Im q < 0 counted in the sliver below the cut (not located; 0 if none or not counted)."""
        return self.strip.count if self.strip is not None and self.strip.decided else 0

    @property
    def verdict(self) -> Verdict:
        """STABLE/UNSTABLE when the lower half-plane was searched completely, else UNDETERMINED."""
        return judge(self)

    @property
    def degree_of_instability(self):
        """Most negative Im q among the unstable roots (0 when stable)."""
        return min((mpmath.im(r.q) for r in self.unstable_roots), default=mpmath.mpf(0))

    @property
    def growth_time(self):
        """1/|Im q| of the fastest-growing root (dimensionless time for amplitude x e), or None."""
        return 1 / abs(self.degree_of_instability) if self.unstable_roots else None

    def _repr_html_(self) -> str:
        """Jupyter: the verdict first, then the count and the roots (:mod:`moving_bogie.html_repr`)."""
        from moving_bogie.html_repr import html_table

        params = self.params.to_dict()
        rows = [
            ("model", f"{params.get('beam')} beam, {params.get('track')} track, {self.model}"),
            ("roots counted / found", f"{self.count} / {self.found} (Re q >= 0, pairs q, -conj(q) once)"),
            ("degree of instability", mpmath.nstr(self.degree_of_instability, 6)),
            (
                "window",
                f"Re q {self.window.x0:g}..{self.window.x1:g}, Im q {self.window.y0:g}..{self.window.y1:g}",
            ),
        ]
        roots = [(r.re_text, r.im_text, r.side, r.multiplicity, r.digits) for r in self.roots]
        header = ("Re q", "Im q (< 0: grows)", "side of the cut", "multiplicity", "digits")
        reasons = [note.text for note in self.verdict.reasons] + list(self.warnings)
        return html_table(
            "induced frequencies", self.verdict.state.upper(), rows, reasons=reasons, items=(header, roots)
        )

    def to_dict(self) -> dict:
        return {
            "params": self.params.to_dict(),
            "model": self.model,
            "dps": self.dps,
            "window": {"re": [self.window.x0, self.window.x1], "im": [self.window.y0, self.window.y1]},
            "roots": [r.to_dict() for r in self.roots],
            "count": self.count,
            "found": self.found,
            "count_ok": self.count_ok,
            "verdict": self.verdict.to_dict(),
            "stable": self.stable if self.verdict.determined else None,
            "degree_of_instability": mpmath.nstr(self.degree_of_instability, 6),
            "growth_time": None if self.growth_time is None else mpmath.nstr(self.growth_time, 6),
            "evaluations": self.evaluations,
            "unsearched": [
                {"re": [u.x0, u.x1], "im": [u.y0, u.y1], "height": u.height} for u in self.unsearched
            ],
            "far_field": None if self.far_field is None else self.far_field.to_dict(),
            "warnings": list(self.warnings),
            "decaying_outside": self.decaying_outside,
            "strip": None if self.strip is None else self.strip.to_dict(),
        } | (self.certificate.to_dict_for(self) if self.certificate is not None else {})


def induced_frequencies(
    params,
    *,
    dps: int = 30,
    extra_dps: int | None = None,
    window: Rectangle | None = None,
    check_window: bool = True,
    eps: float = 2e-11,
    eps_branch: float = 1e-9,
    newton_cell: float = 0.25,
    progress: Callable[[float], None] | None = None,
    certify: bool = False,
    foundation=None,
) -> FrequencyResult:
    """Every induced frequency of ``params`` in ``window`` (default :func:`default_window`).

    Parameters
    ----------
    params : DimensionlessParams or BoundModel
        The parameters and, through their model, the vehicle and the track
        (:func:`~moving_bogie.kernels.bound.bind`; another vehicle: ``params.replace(vehicle=...)``).
    dps : int
        Working precision (decimal digits) of the polished roots.
    extra_dps : int, optional
        Extra digits of the confirming recomputation (default max(10, dps // 2)).
    window : Rectangle, optional
        Search window in the q-plane (Re q >= 0 half); default :func:`far_field_window`. A window that does
        not contain the lower half-disc of the far-field radius makes the verdict UNDETERMINED.
    check_window : bool
        Also count roots in a window twice as large; more roots there make the result fail loudly.
    eps : float
        Distance kept from the cut of K by the contours that follow it: the unsearched sliver around the
        cut is 2 eps high, at most 5 eps where two cut curves meet (default: at most 1e-10).
    eps_branch : float
        Half-width of the box left out around a branch point of K (where K is infinite like the inverse
        square root of the distance; the contours next to it are refined down to that scale).
    newton_cell : float
        Side of a single-root cell below which Newton's method is tried from its centre.
    progress : callable, optional
        Called with the fraction of work done (0..1).
    certify : bool
        Also prove every root, the count and the verdict in ball arithmetic (:mod:`certify`).
    foundation : module or Foundation, optional
        The track model (default that of the parameters' model, see
        :func:`moving_bogie.kernels.track.resolve_foundation`).
    """
    bound = bind(params)
    params = bound.params
    if extra_dps is None:
        extra_dps = max(10, dps // 2)
    if window is None:
        window, far = far_field_window(bound)
    else:
        far = far_field_radius(bound, default_window(bound).x1)
    fast = CharacteristicArray(bound, foundation=foundation)
    precise = Characteristic(bound, foundation=foundation)
    notes: list[Note] = []

    def report(x):
        if progress is not None:
            progress(min(1.0, x))

    big = Rectangle(window.x0, window.x0 + 2 * window.width, 2 * window.y0, 2 * window.y1)
    parts = frame(window, big) if check_window else ()
    # the cut is traced once, over the p-range of the window twice as large, for the window and the frame
    cuts = cut_loci(params, [(r.x0, r.x1) for r in (window, *parts)], foundation=fast.kernel.foundation)
    counted = count_tiling(fast, params, window, eps, eps_branch, cuts[0], newton_cell)
    cut, tiling, counts = counted.cut, counted.tiling, counted.counts
    notes += counted.notes
    total = sum(counts)
    report(0.1)
    decaying_outside = 0
    if check_window:
        more, lost, below = 0, 0, 0
        for k, (part, part_cut) in enumerate(zip(parts, cuts[1:])):
            part_count = count_tiling(fast, params, part, eps, eps_branch, part_cut)
            more += sum(part_count.counts)
            lost += len(part_count.notes)
            below += sum(part_count.counts) if k == 0 else 0  # the strip Im q <= window.y0 < 0
        if lost:
            notes.append(
                Note(
                    Reason.WINDOW,
                    f"{lost} cell(s) of the window twice as large could not be counted "
                    f"(Re q <= {big.x1:g}, {big.y0:g} <= Im q <= {big.y1:g})",
                )
            )
        if more and not below and _holds_far_disc(window, far):
            # The frame lies outside the half-disc |q| < R of the far-field check: its roots have Im q >= 0.
            decaying_outside = more
            notes.append(
                Note(
                    Reason.BEYOND_WINDOW,
                    f"{more} root(s) in the window twice as large (Re q <= {big.x1:g}, "
                    f"{big.y0:g} <= Im q <= {big.y1:g}), all with Im q >= 0 (no root with Im q < 0 beyond "
                    f"|q| = {far.radius:g}, the far-field check): they decay and do not change the verdict; "
                    "a time series adds them from strips along the real axis when the cut runs along it, "
                    "and refuses otherwise (pass a larger window to list them)",
                )
            )
        elif more:
            notes.append(
                Note(
                    Reason.WINDOW,
                    f"{more} more root(s) in the window twice as large "
                    f"(Re q <= {big.x1:g}, {big.y0:g} <= Im q <= {big.y1:g}); pass a larger window",
                )
            )
    report(0.2)
    cells, unlocated = [], []
    for rect, n in zip(tiling.regions, counts):
        if isinstance(rect, ContinuedRegion):  # counted through the cut, its roots located already
            cells += rect.cells
        elif n:
            found_cells, missing = locate(fast, rect, n, newton_cell)
            cells += found_cells
            if missing is not None:
                notes.append(missing.note)
                unlocated.append(missing)
    report(0.6)
    roots = []
    for k, (q0, mult, rect) in enumerate(cells):
        try:
            confirmed = [
                (polish_and_confirm(precise, q0, dps=dps, extra_dps=extra_dps, multiplicity=mult), mult)
            ]
        except PolishError as exc:
            confirmed = (
                split_cluster(precise, q0, mult, rect, dps=dps, extra_dps=extra_dps) if mult > 1 else []
            )
            if not confirmed:
                notes.append(Note(Reason.POLISH, str(exc)))
                continue
        for conf, m in confirmed:
            if not rect.contains(complex(conf.q), margin=1e-9 * max(1.0, abs(complex(conf.q)))):
                notes.append(
                    Note(Reason.POLISH, f"Newton left its cell {rect} (ended at {mpmath.nstr(conf.q, 8)})")
                )
                continue
            side = _side(conf.q, conf.decimals, cut, params)
            roots.append(InducedFrequency(conf.q, side, m, conf.step, conf.digits, conf.decimals))
        report(0.6 + 0.4 * (k + 1) / len(cells))
    roots, pair_notes = _fold_pairs(roots)
    notes += pair_notes
    roots.sort(key=lambda r: -float(mpmath.re(r.q)))
    count = total - _mirrors_counted(cells)
    found = sum(r.multiplicity for r in roots)
    if found != count:
        notes.append(count_mismatch(count, found))
    result = FrequencyResult(
        params,
        params.vehicle,
        dps,
        window,
        tuple(roots),
        count,
        tiling.unsearched,
        fast.evaluations + precise.evaluations,
        tuple(notes),
        far,
        strip=strip_below_cut(
            bound,
            window,
            [u for u in tiling.unsearched if not u.reason],
            foundation=foundation,
        ),
        unlocated=tuple(unlocated),
        decaying_outside=decaying_outside,
    )
    if certify:
        from moving_bogie.roots.proof.certify import certify as prove

        result = dataclasses.replace(result, certificate=prove(result))
    report(1.0)
    return result


def _holds_far_disc(window: Rectangle, far: FarField | None) -> bool:
    """The window contains the lower half-disc of the far-field radius R (every root with Im q < 0)."""
    return far is not None and far.radius is not None and window.x1 >= far.radius and window.y0 <= -far.radius


def _side(q, decimals, cut: CutLocus, params) -> str:
    """Position relative to the cut: "below" or "above" every cut curve over Re q, or "between" two of them
    (a layered track's curves, the lens of the Timoshenko-Rayleigh cut); a root on a curve within the
    confirmed digits counts as below it (a limit from below)."""
    y = float(mpmath.im(q))
    x = float(mpmath.re(q))
    tol = 10.0 ** (-decimals)
    arms = [arm for arm in cut.arms if arm.x_lo <= x <= arm.x_hi]
    if arms:
        above = int(np.sum(y - arms_y_at(arms, np.array([x]))[:, 0] > tol))
        return "below" if above == 0 else "above" if above == len(arms) else "between"
    threshold = float(params.eta_f)
    if cut.points.size and x >= cut.x_start:
        near = cut.points[np.argmin(np.abs(cut.points.real - x))]
        threshold = float(near.imag)
    return "above" if y - threshold > tol else "below"


def _fold_pairs(roots):
    """Keep one member of each pair q, -conj(q): drop a root with Re q < 0 whose mirror was found."""
    keep, notes = [], []
    for r in roots:
        if mpmath.re(r.q) < 0 and abs(mpmath.re(r.q)) > mpmath.mpf(10) ** (-r.decimals):
            mirror = -mpmath.conj(r.q)
            if any(abs(o.q - mirror) < 1e-8 for o in roots if o is not r):
                continue
            notes.append(Note(Reason.PAIR, f"root {mpmath.nstr(r.q, 8)} found without its mirror -conj(q)"))
        keep.append(r)
    return keep, notes


def _mirrors_counted(cells):
    """Roots counted in the strip Re q < 0 of the window (mirrors of roots with Re q > 0)."""
    return sum(m for q, m, _ in cells if mpmath.re(q) < -1e-9)
