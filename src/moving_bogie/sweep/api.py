"""``sweep()``: the Python counterpart of ``moving-bogie sweep``."""

from __future__ import annotations

from collections.abc import Mapping

from moving_bogie.errors import ParameterError
from moving_bogie.sweep.design import Axis, SweepSpec, parse_vary, sobol_axes, sweep_parameters
from moving_bogie.sweep.engine import run_sweep
from moving_bogie.sweep.store import open_sweep

__all__ = ["make_spec", "sweep"]


def _axis(known, name, spec, needs_count: bool):
    if isinstance(spec, str):
        return parse_vary(f"{name}={spec}", known, needs_count=needs_count)
    values = tuple(spec)
    text = ",".join(repr(v) if isinstance(v, float) else str(v) for v in values)
    if not needs_count:
        text = ":".join(text.split(","))
    return parse_vary(f"{name}={text}", known, needs_count=needs_count)


def make_spec(
    params, vary: Mapping, *, model: str | None = None, sample: int | None = None, **options
) -> SweepSpec:
    """A :class:`~moving_bogie.sweep.design.SweepSpec` from ``vary`` = {name: values}.

    Each value is text as on the command line (``"0.3:0.95:200"``, ``"0.01,0.05,0.1"``) or a sequence of
    numbers (floats are read by their shortest decimal text, as on the command line). With ``sample=N``
    the values are ranges (``"0.3:0.95"`` or ``(lo, hi)``) and N Sobol points are drawn.
    """
    if not vary:
        raise ParameterError("vary", "give at least one parameter to vary")
    model = model or params.vehicle
    known = sweep_parameters(params)
    if sample is None:
        axes = tuple(Axis(*_axis(known, name, spec, True)) for name, spec in vary.items())
        return SweepSpec(params, model, axes, **options)
    ranges = dict(_axis(known, name, spec, False) for name, spec in vary.items())
    extra = {"ranges": {k: [str(v) for v in r] for k, r in ranges.items()}, "n": sample, "seed": 0}
    return SweepSpec(params, model, sobol_axes(ranges, sample), design="sobol", extra=extra, **options)


def sweep(
    params,
    vary: Mapping,
    out,
    *,
    model: str | None = None,
    sample: int | None = None,
    resume=False,
    overwrite=False,
    client=None,
    workers=None,
    scheduler=None,
    processes=True,
    progress=None,
    **options,
):
    """Run a sweep into the zarr store ``out`` and return it as an :class:`xarray.Dataset`.

    Parameters
    ----------
    params : DimensionlessParams
        The base point; the varied parameters replace its values (:meth:`DimensionlessParams.replace`:
        varying eta_M or d keeps cf1, cf2 fixed).
    vary : mapping
        {name: values}, see :func:`make_spec`.
    out : path
        Zarr store; ``resume`` completes an interrupted one, ``overwrite`` replaces one.
    model : {"bogie", "masses"}
    sample : int, optional
        Number of Sobol points (``vary`` then gives ranges).
    client, workers, scheduler, processes, progress
        See :func:`~moving_bogie.sweep.engine.run_sweep`.
    **options
        ``roots`` (keep the unstable roots), ``check`` (points per block verified by a full count),
        ``block_points`` (points per block, about).

    Examples
    --------
    >>> from moving_bogie import table1_case
    >>> ds = sweep(table1_case(1), {"alpha": "0.5:1:24", "eta_M": "5:100:24"}, "s.zarr")  # doctest: +SKIP
    >>> ds.stable.sel(alpha=0.75, method="nearest").values  # doctest: +SKIP
    """
    spec = make_spec(params, vary, model=model, sample=sample, **options)
    run_sweep(
        spec,
        out,
        resume=resume,
        overwrite=overwrite,
        client=client,
        workers=workers,
        scheduler=scheduler,
        processes=processes,
        progress=progress,
    )
    return open_sweep(out)
