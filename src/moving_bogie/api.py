"""The public Python API: each function binds its parameters once and calls the runtime with the bound model.

Every function here accepts :class:`~moving_bogie.model.params.DimensionlessParams`,
:class:`~moving_bogie.model.physical.PhysicalParams` (made dimensionless, its scales kept where the result
has units) or a :class:`~moving_bogie.kernels.bound.BoundModel`, calls
:func:`~moving_bogie.kernels.bound.bind` once and passes the bound model down; below this module nothing
binds again (``kernels/``, ``roots/``, ``response/``, ``validation/``, ``stability/`` and ``sweep/`` take
``bound: BoundModel``). The options are those of the function each one calls, documented there.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace
from typing import TYPE_CHECKING, Any

from moving_bogie.kernels.bound import BoundModel, bind
from moving_bogie.model.physical import PhysicalParams

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
    from moving_bogie.stability.stiffness.critical_stiffness import CriticalStiffness
    from moving_bogie.stability.stiffness.d_decomposition import DDecomposition
    from moving_bogie.validation.verdict import ValidationResult

__all__ = [
    "bind_with_scales",
    "closed_form_response",
    "critical_stiffness",
    "d_decomposition",
    "deflection_shape",
    "deflection_shape_details",
    "frequency_lines",
    "induced_frequencies",
    "instability_lines",
    "instability_lines_many",
    "stability_map",
    "validate",
]


def bind_with_scales(
    params: DimensionlessParams | PhysicalParams | BoundModel,
) -> tuple[BoundModel, Scales | None]:
    """The bound model of ``params`` and, for SI parameters, their scales (Eqs. (15)-(16)), else None."""
    if isinstance(params, PhysicalParams):
        return bind(params.to_dimensionless()), params.scales()
    return bind(params), None


def induced_frequencies(
    params: DimensionlessParams | PhysicalParams | BoundModel, **options: Any
) -> FrequencyResult:
    """Every induced frequency of ``params``: :func:`moving_bogie.roots.frequencies.induced_frequencies`.

    For SI parameters the result keeps their scales and shows itself in SI (rad/s, Hz, s).
    """
    from moving_bogie.roots.frequencies import induced_frequencies as run

    bound, scales = bind_with_scales(params)
    result = run(bound, **options)
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
    return run(bound, tau, scales=scales, **options)


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
    return run(bound, xi, tau, scales=scales, **options)


def validate(params: DimensionlessParams | PhysicalParams | BoundModel, **options: Any) -> ValidationResult:
    """Finite beam against closed form (Section 3.2): :func:`~moving_bogie.validation.compare.validate`.

    Physical parameters are made dimensionless: the comparison runs in dimensionless tau and w / w_st.
    """
    from moving_bogie.validation.compare import validate as run

    return run(bind(params), **options)


def frequency_lines(
    params: DimensionlessParams | PhysicalParams | BoundModel, **options: Any
) -> FrequencyLines:
    """Induced frequencies over alpha (Figure 2): :func:`moving_bogie.stability.lines.frequency_lines`."""
    from moving_bogie.stability.lines.frequency_lines import frequency_lines as run

    return run(bind(params), **options)


def instability_lines(
    params: DimensionlessParams | PhysicalParams | BoundModel, **options: Any
) -> InstabilityLines:
    """Instability lines (Section 3.5): :func:`moving_bogie.stability.lines.instability_lines`."""
    from moving_bogie.stability.lines.instability_lines import instability_lines as run

    return run(bind(params), **options)


def instability_lines_many(
    requests: Sequence[tuple[DimensionlessParams | PhysicalParams | BoundModel, dict[str, Any]]],
) -> list[InstabilityLines]:
    """Instability lines of several parameter sets, each ``(params, options)``, traced together (the panels
    of a figure): :func:`moving_bogie.stability.lines.instability_lines.instability_lines_many`."""
    from moving_bogie.stability.lines.instability_lines import instability_lines_many as run

    return run([(bind(params), options) for params, options in requests])


def d_decomposition(
    params: DimensionlessParams | PhysicalParams | BoundModel, *args: Any, **options: Any
) -> DDecomposition:
    """D-decomposition at one velocity: :func:`moving_bogie.stability.stiffness.d_decomposition`."""
    from moving_bogie.stability.stiffness.d_decomposition import d_decomposition as run

    return run(bind(params), *args, **options)


def critical_stiffness(
    params: DimensionlessParams | PhysicalParams | BoundModel, *args: Any, **options: Any
) -> CriticalStiffness:
    """Critical suspension stiffness kappa_v over alpha (Figure 16).

    :func:`moving_bogie.stability.stiffness.critical_stiffness.critical_stiffness`.
    """
    from moving_bogie.stability.stiffness.critical_stiffness import critical_stiffness as run

    return run(bind(params), *args, **options)


def stability_map(params: DimensionlessParams | PhysicalParams | BoundModel, **options: Any) -> StabilityMap:
    """Degree of instability over a grid: :func:`moving_bogie.stability.maps.map.stability_map`.

    For SI parameters the map keeps their units and shows itself in SI (v [m/s], M [kg], rates [1/s]).
    """
    from moving_bogie.stability.maps.map import stability_map as run

    result = run(bind(params), **options)
    if not isinstance(params, PhysicalParams):
        return result
    from moving_bogie.stability.figures.plot_units import PlaneUnits

    return replace(result, units=PlaneUnits.of(result.params, params, operating=True))
