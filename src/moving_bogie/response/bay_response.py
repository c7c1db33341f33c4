"""What periodic supports add to a time series (:class:`~moving_bogie.response.closed_form.TimeSeries`, its
``bay``): the steady response over the bays and the free vibrations in SI (:class:`BayResponse`, from
:func:`~moving_bogie.response.sleeper_series.sleeper_series`), each free vibration a Floquet root
(:class:`FreeVibration`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

__all__ = ["SLEEPER_UNITS", "BayResponse", "FreeVibration", "not_converged"]

#: The units of the series by kind (the continuous tracks' ``units`` in SI, with the contact force's).
SLEEPER_UNITS = {"tau": "s", "w": "m", "xi": "m", "force": "N"}


@dataclass(frozen=True)
class FreeVibration:
    """One Floquet root ``Omega`` [rad/s] (time dependence ``e^{i Omega t}``), its copy in the strip."""

    Omega: complex

    @property
    def frequency_rad_s(self) -> float:
        """Re Omega [rad/s] (modulo the sleeper-passing frequency Omega_0)."""
        return self.Omega.real

    @property
    def frequency_hz(self) -> float:
        return self.Omega.real / (2 * math.pi)

    @property
    def growth_rate(self) -> float:
        """-Im Omega [1/s]: positive grows, negative decays."""
        return -self.Omega.imag

    @property
    def doubling_time(self) -> float | None:
        """ln 2 / growth rate [s] for a growing vibration, else None."""
        return math.log(2) / self.growth_rate if self.growth_rate > 0 else None

    @property
    def halving_time(self) -> float | None:
        """ln 2 / decay rate [s] for a decaying vibration, else None."""
        return math.log(2) / -self.growth_rate if self.growth_rate < 0 else None

    @property
    def state(self) -> str:
        return "growing" if self.growth_rate > 0 else ("decaying" if self.growth_rate < 0 else "neutral")

    def to_dict(self) -> dict[str, Any]:
        return {
            "Omega_rad_s": [self.Omega.real, self.Omega.imag],
            "frequency_rad_s": self.frequency_rad_s,
            "frequency_Hz": self.frequency_hz,
            "growth_rate_1_s": self.growth_rate,
            "doubling_time_s": self.doubling_time,
            "halving_time_s": self.halving_time,
            "state": self.state,
        }


@dataclass(frozen=True)
class BayResponse:
    """What periodic supports add to a :class:`~moving_bogie.response.closed_form.TimeSeries` (its
    ``bay``): the steady response over ``bays`` bays and the free vibrations, in SI.

    ``time`` [s] and ``position`` [m] (the rear wheel's distance from the support behind it at t = 0) share
    the axis; ``contact_force`` [N] and ``deflection`` [m] have shape (wheels, points); ``wheel_positions``
    [m] are the wheels' distances ahead of the rear one, ``bay`` is l [m]. The means are the harmonic
    n = 0, the peak-to-peak values are taken on ``sleeper_series.PEAK_POINTS`` points of one bay.
    ``harmonics`` is N (the harmonics -N..N), ``change`` the series' relative change when N last doubled.
    ``continuous_deflection`` [m] is the steady deflection of the continuous track with the same smeared
    supports (None: no such track), under which each wheel's force is its static load ``static_force``
    [N]. ``free`` are the Floquet roots with ``Im Omega <= free_window[1]`` in the strip ``free_strip``,
    ``free_count`` the argument principle's count, ``free_verdict`` and ``free_notes`` its verdict and
    reasons.
    """

    model: str
    v: float
    bay: float
    Omega0: float
    time: np.ndarray
    position: np.ndarray
    wheel_positions: np.ndarray
    contact_force: np.ndarray
    deflection: np.ndarray
    force_mean: np.ndarray
    force_peak_to_peak: np.ndarray
    deflection_mean: np.ndarray
    deflection_peak_to_peak: np.ndarray
    static_force: np.ndarray
    continuous_deflection: np.ndarray | None
    continuous_model: str | None
    harmonics: int
    change: float
    tol: float
    converged: bool
    free: tuple[FreeVibration, ...]
    free_count: int
    free_verdict: str
    free_strip: tuple[float, float]
    free_window: tuple[float, float]
    free_notes: tuple[str, ...]
    names: tuple[str, ...] = ()

    @property
    def wheels(self) -> int:
        return int(self.contact_force.shape[0])

    def _repr_html_(self) -> str:
        """Jupyter: the free vibrations' verdict first, then the steady response per wheel and the roots."""
        from moving_bogie.html_repr import html_table

        rows = [
            ("model", self.model),
            ("v, bay", f"{self.v:.6g} m/s, {self.bay:.6g} m (Omega_0 = {self.Omega0:.6g} rad/s)"),
            (
                "harmonics",
                f"-{self.harmonics}..{self.harmonics}" + ("" if self.converged else " (NOT converged)"),
            ),
            ("contact force mean [N]", ", ".join(f"{x:.6g}" for x in self.force_mean)),
            ("contact force peak-to-peak [N]", ", ".join(f"{x:.6g}" for x in self.force_peak_to_peak)),
            ("deflection peak-to-peak [m]", ", ".join(f"{x:.3e}" for x in self.deflection_peak_to_peak)),
        ]
        items = [(f"{f.Omega.real:.6g}", f"{f.Omega.imag:.6g}", f"{f.frequency_hz:.6g}") for f in self.free]
        header = ("Re Omega [rad/s]", "Im Omega [rad/s] (< 0: grows)", "f [Hz]")
        return html_table(
            "steady response over a bay and free vibrations",
            self.free_verdict.upper(),
            rows,
            reasons=list(self.free_notes),
            items=(header, items),
        )

    @property
    def period(self) -> float:
        """The bay-passing period l / v [s]."""
        return self.bay / self.v

    @property
    def wheel_names(self) -> tuple[str, ...]:
        """The rail's deflection under each wheel by its DOF name (the vehicle's ``DOFS``, wheels first)."""
        return self.names[: self.wheels] or tuple(f"w_{j}" for j in range(self.wheels))

    @property
    def complete(self) -> bool:
        """Whether the steady response converged and the free vibrations' verdict is not UNDETERMINED."""
        from moving_bogie.roots.verdict import UNDETERMINED

        return self.converged and self.free_verdict != UNDETERMINED

    @property
    def warnings(self) -> tuple[str, ...]:
        """A steady response not converged in the harmonics, then the notes of the strip search."""
        told = () if self.converged else (not_converged(self),)
        return told + self.free_notes

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: the model, the bay, Omega_0, the steady response over the bay per wheel
        (``steady_bay``) and the free vibrations (units in the key names), beside the keys every time
        series has (:meth:`~moving_bogie.response.closed_form.TimeSeries.to_dict`)."""
        cont = self.continuous_deflection
        wheels = [
            {
                "position_m": float(self.wheel_positions[j]),
                "force_mean_N": float(self.force_mean[j]),
                "force_peak_to_peak_N": float(self.force_peak_to_peak[j]),
                "deflection_mean_m": float(self.deflection_mean[j]),
                "deflection_peak_to_peak_m": float(self.deflection_peak_to_peak[j]),
                "static_force_N": float(self.static_force[j]),
                "continuous_deflection_m": None if cont is None else float(cont[j]),
            }
            for j in range(self.wheels)
        ]
        return {
            "model": self.model,
            "v_m_s": self.v,
            "l_m": self.bay,
            "Omega0_rad_s": self.Omega0,
            "Omega0_Hz": self.Omega0 / (2 * math.pi),
            "period_s": self.period,
            "steady_bay": {
                "harmonics": [-self.harmonics, self.harmonics],
                "change": self.change,
                "tol": self.tol,
                "converged": self.converged,
                "continuous_model": self.continuous_model,
                "wheels": wheels,
                "time_s": self.time.tolist(),
                "position_m": self.position.tolist(),
                "contact_force_N": self.contact_force.tolist(),
                "deflection_m": self.deflection.tolist(),
            },
            "free": {
                "strip_rad_s": list(self.free_strip),
                "window_im_rad_s": list(self.free_window),
                "count": self.free_count,
                "roots": [r.to_dict() for r in self.free],
                "verdict": self.free_verdict,
                "notes": list(self.free_notes),
            },
        }


def not_converged(bay: BayResponse) -> str:
    """The warning of a steady response that has not converged in the harmonics."""
    return (
        f"the steady response has NOT converged: it changed by {bay.change:.3g} (relative) at "
        f"N = {bay.harmonics}, tolerance {bay.tol:g}"
    )
