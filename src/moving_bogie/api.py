"""The public Python API: each function binds its parameters once and calls the runtime with the bound model.

Every function here accepts :class:`~moving_bogie.model.params.DimensionlessParams`,
:class:`~moving_bogie.model.physical.PhysicalParams` (made dimensionless, its scales kept where the result
has units) or a :class:`~moving_bogie.kernels.bound.BoundModel`, calls :func:`bind` once (the bound model
with the track of its model's kind, :data:`TRACK_KINDS`) and passes the bound model down; below this module
nothing binds again (``kernels/``, ``roots/``, ``response/``, ``validation/``, ``stability/`` and ``sweep/``
take ``bound: BoundModel``). The options are those of the function each one calls, documented there.

A vehicle on a track on the soil (docs/soil.md) is read by :func:`load_soil_vehicle`
(:mod:`moving_bogie.soil_vehicle`) and bound to the soil's own track.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import replace
from typing import TYPE_CHECKING, Any

from moving_bogie.errors import ParameterError
from moving_bogie.kernels.bound import BoundModel, TrackFactory
from moving_bogie.kernels.continuous_track import ContinuousTrack
from moving_bogie.kernels.periodic_track import PeriodicTrack
from moving_bogie.model.periodic import PERIODIC
from moving_bogie.model.physical import PhysicalParams
from moving_bogie.soil_vehicle import SoilVehicle, load_soil_vehicle, soil_vehicle, threshold_mass

if TYPE_CHECKING:
    import numpy as np
    from numpy.typing import ArrayLike

    from moving_bogie.model.params import DimensionlessParams
    from moving_bogie.model.physical import Scales
    from moving_bogie.response.closed_form import TimeSeries
    from moving_bogie.roots.frequencies import FrequencyResult
    from moving_bogie.stability.lines.frequency_lines import FrequencyLines
    from moving_bogie.stability.lines.line_results import InstabilityLines
    from moving_bogie.stability.maps.map import StabilityMap
    from moving_bogie.stability.maps.sleeper_map import SleeperMap
    from moving_bogie.stability.stiffness.critical_stiffness import CriticalStiffness
    from moving_bogie.stability.stiffness.d_decomposition import DDecomposition
    from moving_bogie.stability.velocity.supercritical import SpeedRegime
    from moving_bogie.validation.verdict import ValidationResult

__all__ = [
    "TRACK_KINDS",
    "SoilVehicle",
    "bind",
    "bind_with_scales",
    "closed_form_response",
    "critical_stiffness",
    "d_decomposition",
    "deflection_shape",
    "deflection_shape_details",
    "frequency_lines",
    "induced_frequencies",
    "load_soil_vehicle",
    "instability_lines",
    "instability_lines_many",
    "sleeper_map",
    "sleeper_series",
    "time_series",
    "smeared_track",
    "soil_vehicle",
    "speed_regime",
    "validate_on_supports",
    "stability_map",
    "threshold_mass",
    "validate",
]


#: The track of each kind of foundation (its ``TRACK_KIND``; a generated foundation module without one is a
#: continuous track, :class:`~moving_bogie.kernels.continuous_track.ContinuousTrack`). A new kind of track
#: adds its class here (kernels/track_model.py says what the class provides).
TRACK_KINDS: dict[str, TrackFactory] = {PERIODIC: PeriodicTrack}


def bind(params: DimensionlessParams | PhysicalParams | BoundModel | SoilVehicle) -> BoundModel:
    """The bound model of ``params`` on the track of its model's kind (a :class:`BoundModel` as it is).

    Called once by each entry point; SI parameters are made dimensionless first (``to_dimensionless()``).
    A vehicle on the soil (:class:`~moving_bogie.soil.vehicle.SoilVehicle`, ``load_soil_vehicle``) is bound
    to its track on the soil (:class:`~moving_bogie.soil.rail_track.SoilRail`).

    Examples
    --------
    >>> from moving_bogie import load_parameters
    >>> params, _ = load_parameters("examples/sleepers.toml")
    >>> bound = bind(params)
    >>> bound.name, bound.track.search_region().kind
    ('eb/sleepers/mass', 'strip')
    """
    if isinstance(params, BoundModel):
        return params
    if isinstance(params, SoilVehicle):
        return BoundModel(params.physical.to_dimensionless(), track=params.rail)
    dimensionless = params.to_dimensionless() if isinstance(params, PhysicalParams) else params
    kind = getattr(dimensionless.model.foundation, "TRACK_KIND", None)
    return BoundModel(dimensionless, track=TRACK_KINDS.get(kind) if kind is not None else None)


def speed_regime(params: DimensionlessParams, physical: PhysicalParams | None = None) -> SpeedRegime:
    """The speed against the track's critical velocity
    (:func:`~moving_bogie.stability.velocity.supercritical.speed_regime`; on periodic supports that of the
    smeared track, :func:`~moving_bogie.stability.velocity.smeared_regime.smeared_regime`)."""
    if params.model.periodic:
        from moving_bogie.stability.velocity.smeared_regime import smeared_regime

        return smeared_regime(params, physical)
    from moving_bogie.stability.velocity.supercritical import speed_regime as continuous

    return continuous(params, physical)


def bind_with_scales(
    params: DimensionlessParams | PhysicalParams | BoundModel | SoilVehicle,
) -> tuple[BoundModel, Scales | None]:
    """The bound model of ``params`` and, for SI parameters, their scales (Eqs. (15)-(16)), else None."""
    if isinstance(params, PhysicalParams):
        return bind(params.to_dimensionless()), params.scales()
    if isinstance(params, SoilVehicle):
        return bind(params), params.physical.scales()
    return bind(params), None


def induced_frequencies(
    params: DimensionlessParams | PhysicalParams | BoundModel | SoilVehicle, **options: Any
) -> FrequencyResult:
    """Every induced frequency of ``params`` in the search region of its track (the window, or one strip of
    a periodic track): :func:`moving_bogie.roots.frequencies.induced_frequencies`; for a track whose
    receptance is a quadrature (on the soil) :func:`moving_bogie.roots.quadrature_search.window_frequencies`
    in the window of the far-field radius of its Winkler equivalent (the same parameters on their
    continuous track, :func:`~moving_bogie.roots.quadrature_window.window_radius`).

    For SI parameters the result keeps their scales and shows itself in SI (rad/s, Hz, s).
    """
    from moving_bogie.roots.frequencies import induced_frequencies as run

    bound, scales = bind_with_scales(params)
    if isinstance(bound.track, ContinuousTrack) or bound.track.search_region().periodic:
        result = run(bound, **options)
    else:
        from moving_bogie.roots.quadrature_search import window_frequencies
        from moving_bogie.roots.quadrature_window import window_radius

        radius, far = window_radius(BoundModel(bound.params))
        result = window_frequencies(bound, radius=radius, far_field=far, **options)
    return result if scales is None else replace(result, scales=scales)


def closed_form_response(
    params: DimensionlessParams | PhysicalParams | BoundModel, tau: ArrayLike, **options: Any
) -> TimeSeries:
    """Closed-form time series, Eqs. (35)-(43).

    :func:`moving_bogie.response.closed_form.closed_form_response`.

    With physical parameters, ``tau`` is the time t in seconds and the results are in m and rad.
    """
    from moving_bogie.response.closed_form import closed_form_response as run

    bound, scales = bind_with_scales(params)
    _closed_form_track(bound, "time_series gives the steady response over a bay and the free vibrations")
    return run(bound, tau, scales=scales, **options)


def _closed_form_track(bound: BoundModel, instead: str) -> None:
    """A ParameterError naming ``params`` on periodic supports, where no closed form exists (``instead``)."""
    if bound.track.search_region().periodic:
        raise ParameterError("params", f"{bound.name}: no closed form on periodic supports; {instead}")


def _continuous(bound: BoundModel, what: str) -> BoundModel:
    """``bound`` when its track is continuous (the closed-form kernels that ``what`` traces), else a
    ParameterError naming ``params`` and what serves its track."""
    if isinstance(bound.track, ContinuousTrack):
        return bound
    if bound.track.search_region().periodic:
        instead = "sleeper_map (the (v, M) map by D-decomposition along real Omega) and induced_frequencies"
    else:
        instead = "threshold_mass (the D-decomposition in the wheel mass) and induced_frequencies"
    raise ParameterError("params", f"{bound.name}: {what} follow a continuous track's kernels; use {instead}")


def time_series(
    params: DimensionlessParams | PhysicalParams | BoundModel,
    tau: ArrayLike | None = None,
    *,
    progress: Callable[[float], None] | None = None,
    **options: Any,
) -> TimeSeries:
    """The time series of ``params`` on its track, one type on every track (:class:`~moving_bogie.response.
    closed_form.TimeSeries`): the closed form at the times ``tau`` (:func:`closed_form_response`, after a
    complete search of the induced frequencies: else a :class:`~moving_bogie.errors.MovingBogieError`);
    on periodic supports the steady response over ``bays`` bays on ``points`` points and the free
    vibrations (:func:`sleeper_series`, ``tau`` not given).

    ``options`` are those of the track's series (``branch_cut``, ``dps``, ... on a continuous track;
    ``bays``, ``points``, ``free``, ``tol`` on periodic supports).
    """
    bound, scales = bind_with_scales(params)
    if bound.track.search_region().periodic:
        if tau is not None:
            why = "a series on periodic supports spans its bays (bays=, points=), not given times"
            raise ParameterError("tau", why)
        return sleeper_series(params, progress=progress, **options)
    from moving_bogie.response.closed_form import closed_form_response as run
    from moving_bogie.response.residues import complete_frequencies

    if tau is None:
        raise ParameterError("tau", "give the times of the series")
    frequencies = complete_frequencies(bound, options.get("dps", 30), options.get("branch_cut"), progress)
    return run(bound, tau, scales=scales, frequencies=frequencies, **options)


def deflection_shape(
    params: DimensionlessParams | PhysicalParams | BoundModel, xi: ArrayLike, tau: float, **options: Any
) -> np.ndarray:
    """Beam deflection w(xi, tau), Eqs. (44)-(47): :func:`moving_bogie.response.closed_form.deflection_shape`.

    With physical parameters xi is in metres, tau in seconds and the result in metres.
    """
    return deflection_shape_details(params, xi, tau, **options)[0]


def deflection_shape_details(
    params: DimensionlessParams | PhysicalParams | BoundModel, xi: ArrayLike, tau: float, **options: Any
) -> tuple[np.ndarray, bool, tuple]:
    """(w, branch_cut, notes): :func:`moving_bogie.response.closed_form.deflection_shape_details`."""
    from moving_bogie.response.closed_form import deflection_shape_details as run

    bound, scales = bind_with_scales(params)
    _closed_form_track(bound, "time_series gives the rail's deflection under the wheels over a bay")
    return run(bound, xi, tau, scales=scales, **options)


def validate(params: DimensionlessParams | PhysicalParams | BoundModel, **options: Any) -> ValidationResult:
    """Finite beam against closed form (Section 3.2): :func:`~moving_bogie.validation.compare.validate`; on
    periodic supports the finite rail against the Floquet theory (:func:`validate_on_supports`), the same
    result type (its ``supports`` holds what that check adds).

    Physical parameters are made dimensionless: the comparison runs in dimensionless tau and w / w_st.
    """
    from moving_bogie.validation.compare import validate as run

    bound = bind(params)
    if bound.track.search_region().periodic:
        return validate_on_supports(params, **options)
    return run(bound, **options)


def validate_on_supports(
    params: DimensionlessParams | PhysicalParams | BoundModel,
    *,
    tol: float = 0.01,
    progress: Callable[[float], None] | None = None,
) -> ValidationResult:
    """The finite rail on sleepers against the Floquet theory (docs/sleepers.md):
    :func:`~moving_bogie.validation.on_supports.check_on_supports` of the bound model, its values in SI
    too for SI parameters."""
    from moving_bogie.validation.on_supports import check_on_supports

    bound, scales = bind_with_scales(params)
    return check_on_supports(bound, scales, tol=tol, progress=progress)


def smeared_track(params: PhysicalParams) -> PhysicalParams:
    """The continuous track with the same smeared supports as SI parameters on periodic supports (the
    limit l -> 0, docs/sleepers.md (S2)): :func:`~moving_bogie.model.smeared.smeared_physical`.

    Raises
    ------
    ParameterError
        Naming ``track`` when the track has no such limit.
    """
    from moving_bogie.model.smeared import smeared_physical

    smeared = smeared_physical(params)
    if smeared is None:
        raise ParameterError("track", f"{params.model.name} has no smeared continuous track")
    return smeared


def sleeper_series(params: DimensionlessParams | PhysicalParams | BoundModel, **options: Any) -> TimeSeries:
    """The steady response over a bay and the free vibrations on sleepers (in SI for SI parameters, with
    the steady deflection of the smeared continuous track beside), as a time series whose ``bay`` holds
    the contact forces and the harmonics: :func:`~moving_bogie.response.sleeper_series.sleeper_series`
    (``bays``, ``points``, ``free``, ``progress``)."""
    from moving_bogie.model.smeared import smeared_physical
    from moving_bogie.response.sleeper_series import sleeper_series as run

    bound, scales = bind_with_scales(params)
    smeared = smeared_physical(params) if isinstance(params, PhysicalParams) else None
    return run(bound, scales, smeared=None if smeared is None else bind_with_scales(smeared), **options)


def sleeper_map(
    params: DimensionlessParams | PhysicalParams | BoundModel,
    velocities: Sequence[float] | np.ndarray,
    masses: Sequence[float] | np.ndarray,
    margin: bool = False,
    progress: Callable[[float], None] | None = None,
    **options: Any,
) -> SleeperMap:
    """Unstable counts over velocities [m/s] x wheel masses [kg] on sleepers (the D-decomposition of
    (S19)-(S22)): :func:`~moving_bogie.stability.maps.sleeper_map.sleeper_map` (``verify``, ``workers``,
    ``progress``, ``checkpoint``, ``resume``); ``margin``: with every cell's margin, a strip search each
    (:func:`~moving_bogie.stability.maps.sleeper_margin.with_margins`, most of the time then)."""
    from moving_bogie.stability.maps.sleeper_map import sleeper_map as run

    bound, scales = bind_with_scales(params)
    if scales is None:
        raise ParameterError(
            "params", "a sleeper map is in SI units (v in m/s, M in kg): give PhysicalParams"
        )
    if not margin:
        return run(bound, scales, velocities, masses, progress=progress, **options)
    from moving_bogie.stability.maps.sleeper_margin import with_margins

    first, rest = (
        (None, None) if progress is None else (lambda x: progress(0.1 * x), lambda x: progress(0.1 + 0.9 * x))
    )
    smap = run(bound, scales, velocities, masses, progress=first, **options)
    kept = {k: options[k] for k in ("workers", "checkpoint", "resume") if k in options}
    return with_margins(smap, bound, scales, progress=rest, **kept)


def frequency_lines(
    params: DimensionlessParams | PhysicalParams | BoundModel, **options: Any
) -> FrequencyLines:
    """Induced frequencies over alpha (Figure 2): :func:`moving_bogie.stability.lines.frequency_lines`."""
    from moving_bogie.stability.lines.frequency_lines import frequency_lines as run

    return run(_continuous(bind(params), "frequency lines"), **options)


def instability_lines(
    params: DimensionlessParams | PhysicalParams | BoundModel, **options: Any
) -> InstabilityLines:
    """Instability lines (Section 3.5): :func:`moving_bogie.stability.lines.instability_lines`."""
    from moving_bogie.stability.lines.instability_lines import instability_lines as run

    return run(_continuous(bind(params), "instability lines"), **options)


def instability_lines_many(
    requests: Sequence[tuple[DimensionlessParams | PhysicalParams | BoundModel, dict[str, Any]]],
) -> list[InstabilityLines]:
    """Instability lines of several parameter sets, each ``(params, options)``, traced together (the panels
    of a figure): :func:`moving_bogie.stability.lines.instability_lines.instability_lines_many`."""
    from moving_bogie.stability.lines.instability_lines import instability_lines_many as run

    return run([(_continuous(bind(params), "instability lines"), options) for params, options in requests])


def d_decomposition(
    params: DimensionlessParams | PhysicalParams | BoundModel, *args: Any, **options: Any
) -> DDecomposition:
    """D-decomposition at one velocity: :func:`moving_bogie.stability.stiffness.d_decomposition`."""
    from moving_bogie.stability.stiffness.d_decomposition import d_decomposition as run

    return run(_continuous(bind(params), "the D-decomposition curves in the suspension"), *args, **options)


def critical_stiffness(
    params: DimensionlessParams | PhysicalParams | BoundModel, *args: Any, **options: Any
) -> CriticalStiffness:
    """Critical suspension stiffness kappa_v over alpha (Figure 16).

    :func:`moving_bogie.stability.stiffness.critical_stiffness.critical_stiffness`.
    """
    from moving_bogie.stability.stiffness.critical_stiffness import critical_stiffness as run

    return run(_continuous(bind(params), "critical stiffnesses"), *args, **options)


def stability_map(params: DimensionlessParams | PhysicalParams | BoundModel, **options: Any) -> StabilityMap:
    """Degree of instability over a grid: :func:`moving_bogie.stability.maps.map.stability_map`.

    For SI parameters the map keeps their units and shows itself in SI (v [m/s], M [kg], rates [1/s]).
    """
    from moving_bogie.stability.maps.map import stability_map as run

    result = run(_continuous(bind(params), "the map's columns"), **options)
    if not isinstance(params, PhysicalParams):
        return result
    from moving_bogie.stability.figures.plot_units import PlaneUnits

    return replace(result, units=PlaneUnits.of(result.params, params, operating=True))
