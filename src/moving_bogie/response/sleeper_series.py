"""The time series of a vehicle on a sleeper track: the steady response and the free vibrations.

:func:`sleeper_series` takes what the continuous tracks' closed form takes, the bound model (on its
:class:`~moving_bogie.kernels.periodic_track.PeriodicTrack`) and the SI scales of its parameters.

The steady response under the constant loads (docs/sleepers.md, Eqs. (S16)-(S18),
:func:`moving_bogie.response.steady_bay.steady_response`) gives, per wheel, the contact force and the rail
deflection under the wheel as functions of the position in the bay; its mean over a bay is the harmonic
``n = 0`` and its harmonics are converged (the series change by less than ``tol`` of their largest value
when N doubles, else ``converged`` is False). The free vibrations are the Floquet roots in one strip
(Eq. (S14), :func:`moving_bogie.roots.strip.floquet_frequencies`): a root ``Omega`` (time dependence
``e^{i Omega t}``) oscillates at ``Re Omega`` (modulo ``Omega_0``) and grows at the rate ``-Im Omega``.

SI units from the scales (Eq. (16) of the paper with the smeared stiffness ``k_e`` for ``k_f``,
docs/sleepers.md (S2)): displacements times ``w_st = P chi / (2 k_e)``, forces times ``P / 2`` (the static
load is 2), times times ``t_scale``, lengths divided by ``chi``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from moving_bogie.errors import ParameterError
from moving_bogie.kernels.bound import BoundModel
from moving_bogie.kernels.hill import VehicleMatrices
from moving_bogie.kernels.periodic_track import PeriodicTrack
from moving_bogie.kernels.sleeper_track import SleeperTrack
from moving_bogie.response.smeared_deflection import continuous_steady_deflection
from moving_bogie.response.steady_bay import static_loads, steady_response

if TYPE_CHECKING:
    from moving_bogie.model.scales import Scales

__all__ = ["SLEEPER_UNITS", "FreeVibration", "SleeperSeries", "sleeper_series"]

#: The units of the series by kind (the continuous tracks' ``units`` in SI, with the contact force's).
SLEEPER_UNITS = {"tau": "s", "w": "m", "xi": "m", "force": "N"}

#: points over one bay on which the peak-to-peak values are taken (independent of the output's points)
PEAK_POINTS = 1025


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
class SleeperSeries:
    """The steady response over ``bays`` bays and the free vibrations of one sleeper-track file, in SI.

    ``time`` [s] and ``position`` [m] (the rear wheel's distance from the support behind it at t = 0) share
    the axis; ``contact_force`` [N] and ``deflection`` [m] have shape (wheels, points); ``wheel_positions``
    [m] are the wheels' distances ahead of the rear one, ``bay`` is l [m]. The means are the harmonic
    n = 0, the peak-to-peak values are taken on ``PEAK_POINTS`` points of one bay. ``harmonics`` is N (the
    harmonics -N..N), ``change`` the series' relative change when N last doubled.
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

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: the keys of the continuous tracks' series with the same meaning
        (:data:`~moving_bogie.response.closed_form.SERIES_KEYS`: the times, the units, the rail's deflection
        under each wheel by its DOF name, its steady part (here the mean over a bay, the harmonic n = 0),
        the notes), then the bay, Omega_0, the steady response over the bay per wheel (``steady_bay``) and
        the free vibrations (units in the key names)."""
        names = self.wheel_names
        return {
            "tau": self.time.tolist(),
            "units": dict(SLEEPER_UNITS),
            "responses": {name: self.deflection[j].tolist() for j, name in enumerate(names)},
            "steady": {name: float(self.deflection_mean[j]) for j, name in enumerate(names)},
            "response_units": {name: "m" for name in names},
            "notes": list(self.free_notes),
            **self._own(),
        }

    def _own(self) -> dict[str, Any]:
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


def _series(amplitudes: np.ndarray, harmonics: np.ndarray, Omega0: float, tau: np.ndarray) -> np.ndarray:
    """sum_n a_n e^{i n Omega_0 tau} (real part), shape (contacts, points): Eq. (S16)."""
    return np.real(np.exp(1j * Omega0 * np.outer(tau, harmonics)) @ amplitudes).T


def sleeper_series(
    bound: BoundModel,
    scales: Scales | None = None,
    *,
    smeared: tuple[BoundModel, Scales | None] | None = None,
    bays: int = 1,
    points: int = 201,
    tol: float = 1e-3,
    free: bool = True,
) -> SleeperSeries:
    """The steady response over ``bays`` bays on ``points`` points and the free vibrations.

    Parameters
    ----------
    bound : BoundModel
        Parameters on periodic supports bound to their track (``moving_bogie.bind``), ``alpha > 0``.
    scales : Scales
        Their SI scales (``PhysicalParams.scales()``): the series in s, m and N (required: None is refused).
    smeared : (BoundModel, Scales), optional
        The continuous track with the same smeared supports and its scales
        (:func:`~moving_bogie.model.smeared.smeared_physical`), whose steady deflection is given beside.
    bays, points : int
        Bays shown and points over them (both ends included).
    tol : float
        Largest change of the steady series when N doubles, relative to their largest value (Eq. (S18)).
    free : bool
        Also search the Floquet roots (the free vibrations); False leaves ``free`` empty and the verdict
        ``"not searched"``.

    Raises
    ------
    ParameterError
        Naming ``params`` without SI scales, ``track`` for a track without periodic supports, ``v`` for a
        vehicle that does not move.
    """
    track = bound.track
    if not isinstance(track, PeriodicTrack):
        raise ParameterError("track", f"{bound.name}: the steady response over a bay needs periodic supports")
    sleepers = track.sleepers
    if sleepers.alpha <= 0:
        raise ParameterError("v", "v must be positive: the steady response over a bay needs a moving vehicle")
    if scales is None:
        why = "the series on sleepers is in SI units (s, m, N): give SI parameters (PhysicalParams)"
        raise ParameterError("params", why)
    length = 1 / scales.chi
    vehicle = VehicleMatrices.of(bound)
    loads = static_loads(bound.vehicle, bound.vehicle_values(bound.floats))
    steady = steady_response(sleepers, vehicle, loads, tol=tol, points=129)
    h, F, U = steady.harmonics, steady.force_harmonics, steady.deflection_harmonics
    Omega0 = sleepers.Omega0
    tau = np.linspace(0.0, bays * 2 * np.pi / Omega0, points)
    one_bay = np.linspace(0.0, 2 * np.pi / Omega0, PEAK_POINTS)
    force, deflection = (_series(a, h, Omega0, tau) for a in (F, U))
    peak_f, peak_u = (_series(a, h, Omega0, one_bay) for a in (F, U))
    i0 = int(np.flatnonzero(h == 0)[0])
    free_part = _free_vibrations(sleepers, vehicle, scales.t_scale) if free else None
    return SleeperSeries(
        model=bound.name,
        v=sleepers.alpha * scales.v_ref,
        bay=sleepers.lam * length,
        Omega0=Omega0 / scales.t_scale,
        time=tau * scales.t_scale,
        position=sleepers.alpha * tau * length,
        wheel_positions=vehicle.positions * length,
        contact_force=force * scales.load,
        deflection=deflection * scales.w_st,
        force_mean=F[i0].real * scales.load,
        force_peak_to_peak=np.ptp(peak_f, axis=1) * scales.load,
        deflection_mean=U[i0].real * scales.w_st,
        deflection_peak_to_peak=np.ptp(peak_u, axis=1) * scales.w_st,
        static_force=loads * scales.load,
        **_smeared_part(smeared),
        harmonics=int(h[-1]),
        change=steady.change,
        tol=tol,
        converged=steady.converged,
        **(free_part or _NOT_SEARCHED),
        names=bound.names,
    )


def _smeared_part(smeared: tuple[BoundModel, Scales | None] | None) -> dict[str, Any]:
    """The steady deflection of the smeared continuous track (in m with its scales) and its name."""
    if smeared is None:
        return {"continuous_deflection": None, "continuous_model": None}
    bound, scales = smeared
    w_st = 1.0 if scales is None else scales.w_st
    return {
        "continuous_deflection": continuous_steady_deflection(bound) * w_st,
        "continuous_model": bound.name,
    }


_NOT_SEARCHED: dict[str, Any] = {
    "free": (),
    "free_count": 0,
    "free_verdict": "not searched",
    "free_strip": (math.nan, math.nan),
    "free_window": (math.nan, math.nan),
    "free_notes": (),
}


def _free_vibrations(track: SleeperTrack, vehicle: VehicleMatrices, t_scale: float) -> dict[str, Any]:
    """The Floquet roots of Eq. (S14) in rad/s, with the count, window and verdict of the strip search."""
    from moving_bogie.roots.strip import floquet_frequencies

    result = floquet_frequencies(track, vehicle)
    window = result.window
    return {
        "free": tuple(FreeVibration(r.q / t_scale) for r in result.roots),
        "free_count": result.count,
        "free_verdict": result.verdict.state,
        "free_strip": (window.x0 / t_scale, window.x1 / t_scale),
        "free_window": (window.y0 / t_scale, window.y1 / t_scale),
        "free_notes": result.notes,
    }
