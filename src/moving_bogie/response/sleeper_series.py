"""The time series of a vehicle on a sleeper track: the steady response and the free vibrations.

:func:`sleeper_series` takes what the continuous tracks' closed form takes, the bound model (on its
:class:`~moving_bogie.kernels.periodic_track.PeriodicTrack`) and the SI scales of its parameters, and gives
what it gives, a :class:`~moving_bogie.response.closed_form.TimeSeries` (the rail's deflection under each
wheel by its DOF name, its steady part, the induced frequencies of the strip search), whose ``bay`` holds
what periodic supports add (:class:`BayResponse`: the contact forces, the bay, Omega_0, the harmonics).

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
from collections.abc import Callable
from dataclasses import replace
from typing import TYPE_CHECKING, Any, cast

import numpy as np

from moving_bogie.errors import ParameterError
from moving_bogie.kernels.bound import BoundModel
from moving_bogie.kernels.hill import VehicleMatrices
from moving_bogie.kernels.periodic_track import PeriodicTrack
from moving_bogie.response.bay_response import SLEEPER_UNITS, BayResponse, FreeVibration
from moving_bogie.response.smeared_deflection import continuous_steady_deflection
from moving_bogie.response.steady_bay import static_loads, steady_response

if TYPE_CHECKING:
    from moving_bogie.model.scales import Scales
    from moving_bogie.response.closed_form import TimeSeries
    from moving_bogie.roots.frequency_result import FrequencyResult

__all__ = ["sleeper_series"]

#: points over one bay on which the peak-to-peak values are taken (independent of the output's points)
PEAK_POINTS = 1025


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
    progress: Callable[[float], None] | None = None,
) -> TimeSeries:
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
        Also search the Floquet roots (the free vibrations, the series' ``frequencies``); False leaves
        ``frequencies`` None, ``bay.free`` empty and the verdict ``"not searched"``.
    progress : callable, optional
        Called with the fraction done (the strip search, then the steady response).

    Returns
    -------
    TimeSeries
        The rail's deflection under each wheel by DOF name (in m, times in s), its steady part the mean over
        a bay, and in ``bay`` the :class:`BayResponse`.

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
    found = _strip_search(bound, scales, progress) if free else None
    bay = _bay_response(bound, scales, smeared, bays, points, tol, found)
    if progress is not None:
        progress(1.0)
    return _time_series(bay, found)


def _bay_response(
    bound: BoundModel,
    scales: Scales,
    smeared: tuple[BoundModel, Scales | None] | None,
    bays: int,
    points: int,
    tol: float,
    found: FrequencyResult | None,
) -> BayResponse:
    """The steady response over ``bays`` bays (Eqs. (S16)-(S18)) in SI, with the roots ``found``."""
    sleepers = cast("PeriodicTrack", bound.track).sleepers
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
    return BayResponse(
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
        **(_NOT_SEARCHED if found is None else _free_vibrations(found, scales.t_scale)),
        names=bound.names,
    )


def _time_series(bay: BayResponse, found: FrequencyResult | None) -> TimeSeries:
    """The series every track gives: the rail's deflection under each wheel by its DOF name, its steady
    part (the mean over a bay, the harmonic n = 0), in s and m; the bay's own part in ``bay``."""
    from moving_bogie.response.closed_form import TimeSeries

    names = bay.wheel_names
    return TimeSeries(
        tau=bay.time,
        responses={name: bay.deflection[j] for j, name in enumerate(names)},
        steady={name: float(bay.deflection_mean[j]) for j, name in enumerate(names)},
        response_units=dict.fromkeys(names, "m"),
        branch_cut=False,
        frequencies=found,
        model=bay.model,
        units=dict(SLEEPER_UNITS),
        notes=bay.free_notes,
        contacts=bay.wheels,
        bay=bay,
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


def _strip_search(
    bound: BoundModel, scales: Scales, progress: Callable[[float], None] | None
) -> FrequencyResult:
    """The Floquet roots of Eq. (S14) in one strip (:func:`~moving_bogie.roots.strip_frequencies.
    strip_frequencies`, as ``frequencies`` gives them), shown in SI with ``scales``."""
    from moving_bogie.roots.strip_frequencies import strip_frequencies

    stage = None if progress is None else (lambda x: progress(0.9 * x))
    return replace(strip_frequencies(bound, progress=stage), scales=scales)


def _free_vibrations(found: FrequencyResult, t_scale: float) -> dict[str, Any]:
    """The roots of the strip search in rad/s, with its count, window, verdict and the notes of the search
    (the band above the window, which holds decaying vibrations only, is the window's top in
    ``free_window``)."""
    from moving_bogie.roots.count.outcomes import Reason

    window = found.window
    return {
        "free": tuple(FreeVibration(complex(r.q) / t_scale) for r in found.roots),
        "free_count": found.count,
        "free_verdict": found.verdict.state,
        "free_strip": (window.x0 / t_scale, window.x1 / t_scale),
        "free_window": (window.y0 / t_scale, window.y1 / t_scale),
        "free_notes": tuple(n.detail for n in found.notes if n.reason is not Reason.BEYOND_WINDOW),
    }
