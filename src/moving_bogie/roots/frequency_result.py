"""The result of the search for induced frequencies: each root found and the result as a whole (Eq. (48)).

:class:`InducedFrequency` is one root q of E_chr(q) = 0 with its confirmed digits and its side of the cut of
K; :class:`FrequencyResult` holds every root of a window with the argument-principle count beside them, the
notes that say where the search fell short and the verdict (:mod:`~moving_bogie.roots.verdict`), built by
:func:`~moving_bogie.roots.frequencies.induced_frequencies`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import mpmath

from moving_bogie.kernels.bound import BoundModel
from moving_bogie.kernels.track_model import SearchRegion
from moving_bogie.roots.count.contour import Rectangle
from moving_bogie.roots.count.far_field import FarField
from moving_bogie.roots.count.outcomes import Note, Reason, Unlocated, notes_with
from moving_bogie.roots.count.strip import StripCount
from moving_bogie.roots.refine.polish import fixed_text
from moving_bogie.roots.verdict import STABLE, Verdict, judge
from moving_bogie.typing import Mpf

if TYPE_CHECKING:
    import pandas
    import xarray

    from moving_bogie.model.params import DimensionlessParams
    from moving_bogie.model.scales import Scales
    from moving_bogie.roots.decaying_band import DecayingBand
    from moving_bogie.roots.proof.certify import Certificate
    from moving_bogie.roots.search.cut_cells import Sliver

__all__ = ["FrequencyResult", "InducedFrequency"]


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

    bound: BoundModel  # the parameters bound to their model
    model: str  # the vehicle's name, for output only
    dps: int
    window: Rectangle
    roots: tuple[InducedFrequency, ...]
    count: int  # roots with Re q >= 0 by the argument principle (with multiplicity, pairs once)
    unsearched: tuple[Sliver, ...]  # slivers around the cut that no contour can enter
    evaluations: int  # E_chr evaluations (double precision + high precision)
    notes: tuple[Note, ...] = field(default=())
    far_field: FarField | None = None
    certificate: Certificate | None = None  # when asked for (certify=True)
    strip: StripCount | None = None  # the sliver below the real axis, counted (roots/count/strip.py)
    unlocated: tuple[Unlocated, ...] = ()  # roots counted in a cell but not located
    decaying_outside: int = 0  # roots with Im q >= 0 in the window twice as large, outside this one
    region: SearchRegion | None = None  # one strip of width Omega_0 and its harmonics (None: the window)
    strip_margin: tuple[float, str] | None = None  # a stable strip's margin and what sets it
    scales: Scales | None = None  # the SI scales of a [physical] input: shown in SI (Eqs. (15)-(16))
    band: DecayingBand | None = None  # on the soil: the decaying roots under the singular lines

    @property
    def periodic(self) -> bool:
        """Whether the roots are those of one strip of a periodic track (no pairs q, -conj(q))."""
        return self.region is not None and self.region.periodic

    @property
    def params(self) -> DimensionlessParams:
        """The parameters of :attr:`bound`."""
        return self.bound.params

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
    def unstable_roots(self) -> tuple[InducedFrequency, ...]:
        return tuple(r for r in self.roots if r.unstable)

    @property
    def stable(self) -> bool:
        """No confirmed root with Im q < 0 among those found (:attr:`verdict` is the complete statement)."""
        return not self.unstable_roots

    @property
    def strip_unstable(self) -> int:
        """Roots with Im q < 0 counted in the sliver below the cut (not located; 0 if none or not counted)."""
        if self.strip is None or self.strip.count is None:
            return 0
        return self.strip.count

    @property
    def verdict(self) -> Verdict:
        """STABLE/UNSTABLE when the lower half-plane was searched completely, else UNDETERMINED."""
        return judge(self)

    @property
    def degree_of_instability(self) -> Mpf:
        """Most negative Im q among the unstable roots (0 when stable)."""
        return min((mpmath.im(r.q) for r in self.unstable_roots), default=mpmath.mpf(0))

    @property
    def growth_time(self) -> Mpf | None:
        """1/|Im q| of the fastest-growing root (dimensionless time for amplitude x e), or None."""
        return 1 / abs(self.degree_of_instability) if self.unstable_roots else None

    def _repr_html_(self) -> str:
        """Jupyter: the verdict first, then the count and the roots (in SI for SI parameters: ``scales``)."""
        from moving_bogie.html_repr import html_table
        from moving_bogie.model.si_results import frequency_rows, root_table

        params = self.params.to_dict()
        rows = [
            ("model", f"{params.get('beam')} beam, {params.get('track')} track, {self.model}"),
            ("roots counted / found", f"{self.count} / {self.found} ({self._counted_where})"),
        ]
        rows += frequency_rows(self)
        reasons = [note.text for note in self.verdict.reasons] + list(self.warnings)
        return html_table(
            "induced frequencies", self.verdict.state.upper(), rows, reasons=reasons, items=root_table(self)
        )

    @property
    def _counted_where(self) -> str:
        if self.region is not None and self.region.periodic:
            return f"one strip of width Omega_0 = {self.region.period:.6g}, harmonics {self._harmonics}"
        return "Re >= 0, each pair once"

    @property
    def _harmonics(self) -> str:
        h = self.region.harmonics if self.region is not None else (0,)
        return f"{h[0]}..{h[-1]}"

    def to_xarray(self) -> xarray.Dataset:
        """The roots as an xarray Dataset (one row per pair, double precision), with CF ``units``: omega
        [rad/s] and f [Hz] for SI parameters, else q: :func:`moving_bogie.export.frequencies_dataset`."""
        from moving_bogie.export import frequencies_dataset

        return frequencies_dataset(self)

    def to_dataframe(self) -> pandas.DataFrame:
        """The roots as a pandas DataFrame, the units in ``attrs["units"]``."""
        from moving_bogie.export import to_dataframe

        return to_dataframe(self.to_xarray())

    def to_dict(self) -> dict:
        return (
            {
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
            }
            | ({} if self.band is None else {"decaying": self.band.to_dict()})
            | (self.certificate.to_dict_for(self) if self.certificate is not None else {})
            | self._region_dict()
        )

    @property
    def margin(self) -> Mpf | None:
        """On a periodic track, a STABLE result's decay rate Im q of its least-damped vibration as the strip
        search states it (:attr:`~moving_bogie.roots.strip.FloquetResult.margin`: the least-damped root,
        or the rail's free waves, or the window's top as a lower bound); on the soil, the least Im q of the
        decaying roots found in the band under the singular lines (:mod:`~moving_bogie.roots.decaying_band`:
        roots outside the band are not searched, so a less damped one may lie there); None otherwise (on a
        window the roots themselves say it)."""
        if self.verdict.state != STABLE:
            return None
        if self.band is not None:
            band = self.band.margin
            return None if band is None else mpmath.mpf(band)
        if not self.periodic or self.strip_margin is None:
            return None
        return mpmath.mpf(self.strip_margin[0])

    @property
    def margin_source(self) -> str | None:
        """What sets :attr:`margin`: "a root", "the rail's free waves" or "the window's top"; on the soil
        "a root in the band under the singular lines"."""
        if self.margin is not None and self.band is not None:
            return "the least-damped root found in the band under the singular lines, physical sheet"
        return None if self.margin is None or self.strip_margin is None else self.strip_margin[1]

    def _region_dict(self) -> dict:
        """``region`` (the strip's ``Omega_0``, ``harmonics``, free waves) and ``margin`` on a periodic
        track, nothing on a window."""
        if self.region is None or not self.region.periodic:
            return {}
        margin = self.margin
        return {
            "region": self.region.to_dict(),
            "margin": None if margin is None else mpmath.nstr(margin, 6),
            "margin_source": self.margin_source,
        }
