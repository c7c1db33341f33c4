"""Results as xarray Datasets and pandas DataFrames, every variable with its CF-style ``units`` attribute.

A result lists its variables as :class:`Variable` (dimensions, values, unit, long name) and its coordinates
the same way; :func:`to_dataset` builds the Dataset, :func:`to_dataframe` the DataFrame (its ``attrs``
carry ``units``: column -> unit). Units are UDUNITS strings as CF asks (``m``, ``rad``, ``s``, ``1/s``,
``rad/s``, ``Hz``, ``kg``, ``m/s``); a dimensionless quantity has the unit ``1`` and, when it is a multiple
of a reference scale of Eqs. (15)-(16), that scale's name in the attribute ``scale`` (``w_st``).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from moving_bogie.presentation import GroupUnits, json_clean

if TYPE_CHECKING:
    import pandas
    import xarray

    from moving_bogie.response.closed_form import TimeSeries
    from moving_bogie.roots.frequency_result import FrequencyResult
    from moving_bogie.stability.maps.map import StabilityMap

__all__ = [
    "Variable",
    "cf_unit",
    "frequencies_dataset",
    "map_dataset",
    "series_dataset",
    "to_dataframe",
    "to_dataset",
]

#: Units of the dimensionless results that are multiples of a reference scale: unit -> that scale.
SCALED_UNITS = {"w_st": "w_st", "w_st chi": "w_st chi"}


def cf_unit(unit: str) -> tuple[str, str | None]:
    """(the CF ``units`` text, the reference scale or None) of a unit as the results write it."""
    if unit in SCALED_UNITS:
        return "1", SCALED_UNITS[unit]
    return (unit or "1"), None


@dataclass(frozen=True)
class Variable:
    """One variable or coordinate: its dimensions, values, unit (as the results write it) and long name."""

    dims: tuple[str, ...]
    values: Any
    unit: str | None  # None: not a quantity (a text, a flag); no units attribute
    long_name: str

    def attrs(self) -> dict[str, str]:
        if self.unit is None:
            return {"long_name": self.long_name}
        units, scale = cf_unit(self.unit)
        out = {"units": units, "long_name": self.long_name}
        return out | ({"scale": scale} if scale else {})


def to_dataset(
    variables: Mapping[str, Variable],
    coords: Mapping[str, Variable],
    attrs: Mapping[str, Any] | None = None,
) -> xarray.Dataset:
    """An xarray Dataset of ``variables`` over ``coords``, every one with its ``units`` and ``long_name``.

    ``attrs`` (JSON values, e.g. the parameters) are stored as text where they are not numbers or strings,
    so that the Dataset can be written to netCDF or zarr as it is.
    """
    import json

    import xarray

    def array(v: Variable) -> xarray.Variable:
        return xarray.Variable(v.dims, np.asarray(v.values), attrs=v.attrs())

    kept: dict[str, Any] = {}
    for key, value in (attrs or {}).items():
        plain = isinstance(value, str | int | float) and not isinstance(value, bool)
        kept[key] = value if plain else json.dumps(json_clean(value))
    return xarray.Dataset(
        {name: array(v) for name, v in variables.items()},
        coords={name: array(v) for name, v in coords.items()},
        attrs=kept,
    )


def to_dataframe(dataset: xarray.Dataset, order: Sequence[str] | None = None) -> pandas.DataFrame:
    """The Dataset as a DataFrame indexed by its dimensions (``order``: their order), the units of every
    column and index level in ``attrs["units"]`` and the Dataset's attributes beside them."""
    frame = dataset.to_dataframe(dim_order=list(order) if order is not None else None)
    units = {str(n): v.attrs["units"] for n, v in dataset.variables.items() if "units" in v.attrs}
    frame.attrs = dict(dataset.attrs) | {"units": units}
    return frame


def series_dataset(series: TimeSeries) -> xarray.Dataset:
    """A :class:`~moving_bogie.response.closed_form.TimeSeries` over its times: ``t`` [s] in SI, else
    ``tau`` [1]; each response under its DOF name (m and rad in SI, multiples of w_st and w_st chi else)."""
    time_unit = series.units.get("tau", "1")
    time = "t" if time_unit == "s" else "tau"
    coords = {time: Variable((time,), series.tau, time_unit, "time" if time == "t" else "dimensionless time")}
    variables = {
        name: Variable((time,), values, series.response_units.get(name, "1"), f"{name}, Eqs. (35)-(43)")
        for name, values in series.responses.items()
    }
    steady = {f"{k} steady": json_clean(v) for k, v in series.steady.items()}
    attrs = {"model": series.model or "", "branch_cut_until": series.branch_cut_until} | steady
    return to_dataset(variables, coords, attrs | {"notes": list(series.notes)})


def frequencies_dataset(result: FrequencyResult) -> xarray.Dataset:
    """The induced frequencies of a :class:`~moving_bogie.roots.frequency_result.FrequencyResult`, one row
    per root (the member of each pair with Re >= 0), in double precision: ``omega_re`` [rad/s],
    ``omega_im`` [1/s] (< 0: grows) and ``frequency`` [Hz] for SI parameters, else ``q_re``, ``q_im`` [1]."""
    roots = result.roots
    index = {"root": Variable(("root",), np.arange(1, len(roots) + 1), "1", "induced frequency number")}
    q = np.array([complex(r.q) for r in roots], dtype=complex)
    if result.scales is not None:
        omega = q / result.scales.t_scale
        variables = {
            "omega_re": Variable(("root",), omega.real, "rad/s", "Re omega, angular frequency"),
            "omega_im": Variable(("root",), omega.imag, "1/s", "Im omega, decay rate (< 0: grows)"),
            "frequency": Variable(("root",), omega.real / (2 * np.pi), "Hz", "frequency Re omega / 2 pi"),
        }
    else:
        variables = {
            "q_re": Variable(("root",), q.real, "1", "Re q, induced frequency, Eq. (48)"),
            "q_im": Variable(("root",), q.imag, "1", "Im q (< 0: grows)"),
        }
    variables |= {
        "side": Variable(("root",), [r.side for r in roots], None, "side of the cut of K"),
        "multiplicity": Variable(("root",), [r.multiplicity for r in roots], "1", "multiplicity"),
        "digits": Variable(("root",), [r.digits for r in roots], "1", "digits confirmed at higher precision"),
    }
    attrs = {"model": result.model, "verdict": result.verdict.state, "count": result.count}
    return to_dataset(variables, index, attrs | {"params": result.params.to_dict()})


def map_dataset(smap: StabilityMap) -> xarray.Dataset:
    """A :class:`~moving_bogie.stability.maps.map.StabilityMap` over its two axes, in SI (v [m/s], M [kg],
    rates [1/s]) when it has SI units, with the groups (alpha, eta_M) as coordinates beside them."""
    units = smap.units or GroupUnits()
    x, y = units.name("alpha"), units.name(smap.parameter)
    coords = {
        x: Variable((x,), units.value("alpha", smap.alphas), units.unit("alpha"), "velocity"),
        y: Variable((y,), units.value(smap.parameter, smap.thetas), units.unit(smap.parameter), y),
    }
    if units.si:
        coords |= {
            "alpha": Variable((x,), smap.alphas, "1", "velocity alpha, Eq. (17)"),
            smap.parameter: Variable((y,), smap.thetas, "1", smap.parameter),
        }
    rate, im = ("1/s", "Im omega") if units.si else ("1", "Im q")
    dims = (y, x)
    variables = {
        "degree": Variable(dims, units.frequency(smap.degree), rate, f"degree of instability, min {im}"),
        "unstable_count": Variable(dims, smap.count, "1", "induced frequencies with Im q < 0"),
        "uncertain": Variable(dims, smap.uncertain, None, "cell not certified"),
        "settled": Variable(dims, smap.settled_cells, None, "cell settled by a full count"),
    }
    if smap.margin is not None:
        variables["margin"] = Variable(dims, units.frequency(smap.margin), rate, f"margin, smallest {im}")
    attrs = {"model": smap.model, "parameter": smap.parameter, "params": smap.params.to_dict()}
    return to_dataset(variables, coords, attrs)
