"""The result of the finite-rail check of the Floquet theory on sleepers (docs/sleepers.md): each quantity
compared (:class:`Comparison`) and the check (:class:`SleeperCheck`), which shows itself as the continuous
tracks' check does (:class:`~moving_bogie.validation.verdict.ValidationResult`: ``agrees``, ``notes``,
``to_dict()``, ``_repr_html_``), computed by :func:`~moving_bogie.validation.sleepers_check.check_sleepers`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from moving_bogie.validation.sleepers_beam import BeamRun
from moving_bogie.validation.sleepers_fit import FloquetFit, extrapolated
from moving_bogie.validation.sleepers_rail import SleeperRail

if TYPE_CHECKING:
    from moving_bogie.model.params import DimensionlessParams
    from moving_bogie.model.scales import Scales

__all__ = ["TOLERANCE_RULE", "Comparison", "SleeperCheck"]

#: What the check judges (the continuous tracks' ``tolerance_rule`` of the same JSON key).
TOLERANCE_RULE = (
    "|finite - Floquet| <= tol |Floquet| for the rate and the frequency; for the steady force "
    "max |difference| over the last bay <= tol x the Floquet force's peak-to-peak"
)


@dataclass(frozen=True)
class Comparison:
    """One quantity: the Floquet value, the finite rail's, their relative difference against ``tol``."""

    quantity: str
    floquet: float
    finite: float
    relative: float
    tolerance: float

    @property
    def within(self) -> bool:
        return bool(self.relative <= self.tolerance)

    def to_dict(self) -> dict[str, Any]:
        return {
            "quantity": self.quantity,
            "floquet": self.floquet,
            "finite_beam": self.finite,
            "relative_diff": self.relative,
            "tolerance": self.tolerance,
            "within": self.within,
        }


@dataclass(frozen=True)
class SleeperCheck:
    """The comparisons, the Floquet verdict, the two runs (for plots) and the wall times.

    ``model`` names the model checked (``beam/track/vehicle``, for output), ``scales`` are the SI scales of
    its parameters (None: dimensionless), with which :meth:`to_dict` gives every compared value in SI
    beside the dimensionless one (rates in 1/s, frequencies in rad/s, forces in N: the static load 2 is P)
    and ``time_scale`` the seconds per unit of tau.
    """

    comparisons: tuple[Comparison, ...]
    floquet_verdict: str
    root: complex | None
    Omega0: float
    free: BeamRun
    loaded: BeamRun | None
    steady_tau: np.ndarray | None
    steady_force: np.ndarray | None
    fit: FloquetFit
    coarse: FloquetFit | None
    rate_spread: float
    rail: SleeperRail
    floquet_s: float
    finite_s: float
    notes: tuple[str, ...] = field(default=())
    time_scale: float | None = None
    limit_force: np.ndarray | None = None
    model: str | None = None
    scales: Scales | None = None
    params: DimensionlessParams | None = None

    @property
    def rate(self) -> float:
        """The finite rail's growth rate ``ln |mu| / T0`` (per unit tau), extrapolated to a zero time step
        when the run at twice the step was made (:func:`extrapolated`)."""
        return self.fit.rate if self.coarse is None else extrapolated(self.fit, self.coarse)[0]

    @property
    def frequency(self) -> float:
        """The finite rail's dominant frequency, extrapolated as :attr:`rate`."""
        return self.fit.frequency if self.coarse is None else extrapolated(self.fit, self.coarse)[1]

    @property
    def fit_start(self) -> float:
        return self.fit.window[0]

    @property
    def agrees(self) -> bool:
        return bool(self.comparisons) and all(c.within for c in self.comparisons)

    def _repr_html_(self) -> str:
        """Jupyter: whether the finite rail agrees first, then every quantity compared (as the continuous
        tracks' check shows itself)."""
        from moving_bogie.html_repr import html_table

        rows = [
            ("Floquet verdict", self.floquet_verdict.upper()),
            ("finite rail", f"{self.rail.bays} bays, {self.rail.elements} elements per bay"),
            ("wall times [s]", f"Floquet {self.floquet_s:.3g}, finite rail {self.finite_s:.3g}"),
        ]
        items = [
            (
                c.quantity,
                f"{c.floquet:.6g}",
                f"{c.finite:.6g}",
                f"{c.relative:.3g}",
                "yes" if c.within else "no",
            )
            for c in self.comparisons
        ]
        header = ("quantity", "Floquet", "finite rail", "relative difference", "within")
        verdict = "AGREES" if self.agrees else "DISAGREES"
        return html_table(
            "finite rail on sleepers against the Floquet theory",
            verdict,
            rows,
            reasons=list(self.notes),
            items=(header, items),
        )

    @property
    def tolerance(self) -> float | None:
        """The relative tolerance of the comparisons (None when nothing was compared)."""
        return self.comparisons[0].tolerance if self.comparisons else None

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: the keys of the continuous tracks' check
        (:data:`~moving_bogie.validation.verdict.VERDICT_KEYS`: the model and its parameters, the verdict,
        the tolerance and its rule, each quantity's relative difference and comparison, the wall times, the
        notes), then the Floquet verdict, every comparison in order (in SI too when ``scales`` are known)
        and the finite rail's run and fit."""
        params = self.params
        out: dict[str, Any] = {
            "model": self.model,
            "beam": None if params is None else params.beam,
            "track": None if params is None else params.track,
            "params": None if params is None else params.to_dict(),
            "tolerance": self.tolerance,
            "tolerance_rule": TOLERANCE_RULE,
            "relative_diff": {c.quantity: c.relative for c in self.comparisons},
            **self._summary(),
        }
        if self.scales is not None:
            _add_si(out, self.scales)
        out["quantities"] = {c["quantity"]: c for c in out["comparisons"]}
        return out

    def _summary(self) -> dict[str, Any]:
        return {
            "agrees": self.agrees,
            "floquet_verdict": self.floquet_verdict,
            "root_q": None if self.root is None else [self.root.real, self.root.imag],
            "Omega0": self.Omega0,
            "comparisons": [c.to_dict() for c in self.comparisons],
            "finite_beam": {
                "bays": self.rail.bays,
                "elements_per_bay": self.rail.elements,
                "length": self.rail.length,
                "unknowns": self.rail.size,
                "dt": self.free.dt,
                "free_run_tau": float(self.free.tau[-1]),
                "fit_start": self.fit_start,
                "fit_end": self.fit.window[1],
                "fitted_periods": self.fit.samples,
                "free_vibration_rate": self.rate,
                "rate_at_dt": self.fit.rate,
                "rate_at_2dt": None if self.coarse is None else self.coarse.rate,
                "rate_spread": self.rate_spread,
                "multipliers": [[m.real, m.imag] for m in self.fit.multipliers.tolist()],
                "dominant_multiplier": [self.fit.multiplier.real, self.fit.multiplier.imag],
                "dominant_harmonic": self.fit.harmonic,
            },
            "timings": {"floquet_s": self.floquet_s, "finite_beam_s": self.finite_s},
            "notes": list(self.notes),
        }


def _add_si(out: dict[str, Any], scales: Scales) -> None:
    """Every compared value of a :meth:`SleeperCheck.to_dict` also in SI (``floquet_si``,
    ``finite_beam_si``, ``unit_si``) and the finite rail's time step in s (``dt_s``)."""
    per_tau = 1 / scales.t_scale
    for item in out["comparisons"]:
        quantity = item["quantity"]
        steady = quantity.startswith("steady")
        scale = scales.load if steady else per_tau
        item["unit_si"] = "N" if steady else ("1/s" if "rate" in quantity else "rad/s")
        item["floquet_si"], item["finite_beam_si"] = item["floquet"] * scale, item["finite_beam"] * scale
    out["finite_beam"]["dt_s"] = out["finite_beam"]["dt"] * scales.t_scale
