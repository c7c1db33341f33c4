"""moving-bogie: stability and vibrations of a bogie moving on an infinite beam on a viscoelastic foundation.

Reference: Z. Dimitrovová, *Instability of a Moving Bogie: Analysis of Vibrations and Possibility of
Instability in Subcritical Velocity Range*, preprint 10.20944/preprints202501.1517.v1 (2025).

A parameter file (``examples/*.toml``) loads with :func:`load_parameters`::

    params, physical = moving_bogie.load_parameters("examples/uic60-bogie.toml")
    result = moving_bogie.induced_frequencies(params)

The runtime never imports SymPy: formulas come from the generated kernels in
:mod:`moving_bogie.generated`, written by ``python -m derivations``.
"""

from importlib.metadata import PackageNotFoundError, version
from typing import Any

from moving_bogie.errors import MovingBogieError, MovingBogieWarning, ParameterError
from moving_bogie.model.cases import TABLE1_CASES, table1_case, table2_printed
from moving_bogie.model.files import load_parameters, load_params_file
from moving_bogie.model.params import DimensionlessParams
from moving_bogie.model.physical import PhysicalParams, Scales

#: Main entry points, imported on first use so that ``import moving_bogie`` (and the CLI) stays light: the
#: module of each name (``module:attribute`` when the attribute has another name there).
_LAZY = {
    "bind": "api",
    "BoundModel": "kernels.bound",
    "induced_frequencies": "api",
    "FrequencyResult": "roots.frequencies",
    "compute_table2": "roots.table2",
    "closed_form_response": "api",
    "deflection_shape": "api",
    "deflection_shape_details": "api",
    "simulate_finite_beam": "validation.finite_beam",
    "validate": "api",
    "critical_velocity": "stability.velocity.critical_velocity",
    "frequency_lines": "api",
    "instability_lines": "api",
    "instability_lines_many": "api",
    "d_decomposition": "api",
    "critical_stiffness": "api",
    "stability_map": "api",
    "speed_regime": "api",
    "smeared_track": "api",
    "sleeper_series": "api",
    "time_series": "api",
    "sleeper_map": "api",
    "sleeper_map_figure": "stability.figures.sleeper_map_figure",
    "sleeper_series_figure": "response.sleeper_plots",
    # a track on the soil (docs/soil.md)
    "load_soil_file": "soil.file",
    "load_soil_vehicle": "api",
    "soil_modes": "soil.rayleigh",
    "soil_critical_velocity": "soil.critical:critical_velocity",
    "moving_load": "soil.moving_load",
    "threshold_mass": "api",
    "dispersion_figure": "soil.plots",
    "moving_load_figure": "soil.plots",
}


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        import importlib

        module, _, attribute = _LAZY[name].partition(":")  # "module:attribute" when the names differ
        return getattr(importlib.import_module(f".{module}", __name__), attribute or name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


try:
    __version__ = version("moving-bogie")
except PackageNotFoundError:  # running from a source tree that is not installed
    __version__ = "0+unknown"

__all__ = [
    "TABLE1_CASES",
    "DimensionlessParams",
    "MovingBogieError",
    "MovingBogieWarning",
    "ParameterError",
    "PhysicalParams",
    "Scales",
    "__version__",
    "load_parameters",
    "load_params_file",
    "table1_case",
    "table2_printed",
    *_LAZY,
]
