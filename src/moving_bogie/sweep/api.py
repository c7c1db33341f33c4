"""``sweep()``: the Python counterpart of ``moving-bogie sweep``.

Worker processes (a LocalCluster of Dask) import the calling script again: a script calls ``sweep()``
under ``if __name__ == "__main__":``, and :func:`sweep` says so, before anything starts, when the guard
is missing.
"""

from __future__ import annotations

import shutil
from collections.abc import Callable, Collection, Iterable, Iterator, Mapping
from contextlib import contextmanager
from fractions import Fraction
from pathlib import Path
from typing import TYPE_CHECKING, Any

from moving_bogie.errors import MovingBogieError, ParameterError
from moving_bogie.kernels.bound import BoundModel, bind
from moving_bogie.model.params import DimensionlessParams
from moving_bogie.model.physical import PhysicalParams
from moving_bogie.processes import require_main_guard
from moving_bogie.sweep.design import Axis, SweepSpec, parse_vary, sobol_axes, sweep_parameters
from moving_bogie.sweep.engine import IN_PROCESS_POINTS, run_sweep
from moving_bogie.sweep.store import StorePath, missing_points, open_sweep

if TYPE_CHECKING:
    import xarray
    from distributed import Client

__all__ = ["discarded_if_empty", "make_spec", "sweep"]


def _axis(
    known: Collection[str], name: str, spec: str | Iterable[Any], needs_count: bool
) -> tuple[str, tuple[Fraction, ...]]:
    """One ``vary`` entry as the command line reads it: text, or numbers written as text."""
    if isinstance(spec, str):
        return parse_vary(f"{name}={spec}", known, needs_count=needs_count)
    values = tuple(spec)
    text = ",".join(repr(v) if isinstance(v, float) else str(v) for v in values)
    if not needs_count:
        text = ":".join(text.split(","))
    return parse_vary(f"{name}={text}", known, needs_count=needs_count)


def make_spec(
    params: DimensionlessParams | BoundModel,
    vary: Mapping[str, str | Iterable[Any]],
    *,
    sample: int | None = None,
    physical: PhysicalParams | None = None,
    **options: Any,
) -> SweepSpec:
    """A :class:`~moving_bogie.sweep.design.SweepSpec` from ``vary`` = {name: values}.

    Each value is text as on the command line (``"0.3:0.95:200"``, ``"0.01,0.05,0.1"``) or a sequence of
    numbers (floats are read by their shortest decimal text, as on the command line). With ``sample=N``
    the values are ranges (``"0.3:0.95"`` or ``(lo, hi)``) and N Sobol points are drawn.

    With ``physical`` (the :class:`~moving_bogie.model.physical.PhysicalParams` of ``params``, a
    ``[physical]`` input) the names are the SI parameters of the model's metadata (``v`` [m/s], ``M``
    [kg], ...) and the values are in their units; each is converted to its group exactly as
    :meth:`~moving_bogie.model.physical.PhysicalParams.to_dimensionless` does, every other SI parameter
    fixed but the bar's M_b, J_b, which follow the wheel mass unless ``bar="fixed"``
    (:mod:`~moving_bogie.model.bar`).
    """
    if not vary:
        raise ParameterError("vary", "give at least one parameter to vary")
    bound = bind(params)  # the sweep's entry binds once; every point is bound.replace(...) of it
    params = bound.params
    si = physical is not None
    known = sweep_parameters(params, si=si)
    for name in vary:
        _check_units(params, name.strip(), si)
    if sample is None:
        axes = tuple(Axis(*_axis(known, name, spec, True)) for name, spec in vary.items())
        extra: dict[str, Any] = {}
    else:
        ranges = dict(_axis(known, name, spec, False) for name, spec in vary.items())
        extra = {"ranges": {k: [str(v) for v in r] for k, r in ranges.items()}, "n": sample, "seed": 0}
        axes = sobol_axes(ranges, sample)
    if physical is not None:
        axes = tuple(_to_group(physical, a) for a in axes)
        if sample is not None:
            extra["si_ranges"] = extra.pop("ranges")
            extra["ranges"] = {a.name: [str(min(a.values)), str(max(a.values))] for a in axes}
    design = "grid" if sample is None else "sobol"
    return SweepSpec(bound, params.vehicle, axes, design=design, extra=extra, physical=physical, **options)


def _check_units(params: DimensionlessParams, name: str, si: bool) -> None:
    """A group named in an SI sweep, or an SI name in a dimensionless one: say which to use."""
    specs = params.model.specs
    by_si = {spec.si: spec for spec in specs.values()}
    if si and name in specs and name not in by_si:
        spec = specs[name]
        raise ParameterError(
            "--vary",
            f"--vary {name}: the input is in SI units ([physical]); vary {spec.si} [{spec.unit}] "
            "instead (or pass --units dimensionless)",
        )
    if not si and name in by_si and name not in specs:
        spec = by_si[name]
        raise ParameterError(
            "--vary",
            f"--vary {name}: {name} [{spec.unit}] is an SI parameter; it needs a [physical] parameter "
            f"file (--file F.toml) for the scales EI, m, k_f, or vary the group {spec.name} instead",
        )


def _to_group(physical: PhysicalParams, axis: Axis) -> Axis:
    """An axis of SI values -> the axis of their groups, keeping the SI values."""
    spec = next(s for s in physical.model.specs.values() if s.si == axis.name)
    values: list[Fraction] = []
    for v in axis.values:
        try:
            values.append(physical.group_value(axis.name, v)[1])
        except ParameterError as exc:
            raise ParameterError("--vary", f"--vary {axis.name}: {exc}") from None
    return Axis(spec.name, tuple(values), si=axis.name, unit=spec.unit, si_values=axis.values)


def sweep(
    params: DimensionlessParams | BoundModel,
    vary: Mapping[str, str | Iterable[Any]],
    out: StorePath,
    *,
    sample: int | None = None,
    physical: PhysicalParams | None = None,
    resume: bool = False,
    overwrite: bool = False,
    client: Client | None = None,
    workers: int | None = None,
    scheduler: str | None = None,
    processes: bool = True,
    progress: Callable[[int, int], None] | None = None,
    **options: Any,
) -> xarray.Dataset:
    """Run a sweep into the zarr store ``out`` and return it as an :class:`xarray.Dataset`.

    Parameters
    ----------
    params : DimensionlessParams or BoundModel
        The base point and, through its model, the vehicle; the varied parameters replace its values
        (:meth:`DimensionlessParams.replace`: varying eta_M or d keeps cf1, cf2 fixed).
    vary : mapping
        {name: values}, see :func:`make_spec`.
    out : path
        Zarr store; ``resume`` completes an interrupted one, ``overwrite`` replaces one.
    sample : int, optional
        Number of Sobol points (``vary`` then gives ranges).
    physical : PhysicalParams, optional
        The SI parameters of ``params``: ``vary`` then names SI parameters in their units and the store
        is in SI units (:func:`make_spec`).
    client, workers, scheduler, processes, progress
        See :func:`~moving_bogie.sweep.engine.run_sweep`.
    **options
        ``roots`` (keep the unstable roots), ``margin`` (measure the stability margin of every point:
        about four times the time), ``check`` (points per block verified by a full count),
        ``block_points`` (points per block, about), ``bar`` (``"follows"``, the default, or ``"fixed"``:
        what moves with the wheel mass, :mod:`~moving_bogie.model.bar`).

    Raises
    ------
    MovingBogieError
        When worker processes would start (``workers`` given, or :data:`IN_PROCESS_POINTS` points or
        more) from the top level of a script outside ``if __name__ == "__main__":``: each worker runs
        the script again (:func:`~moving_bogie.processes.require_main_guard`). Nothing is written then,
        and a run that fails before its first block is stored leaves no store behind.

    Examples
    --------
    In a script, under the guard that worker processes need:

    >>> from moving_bogie import table1_case
    >>> if __name__ == "__main__":
    ...     ds = sweep(table1_case(1), {"alpha": "0.5:1:24", "eta_M": "5:100:24"}, "s.zarr", workers=2)
    ...     print(ds.stable.sel(alpha=0.75, method="nearest").values)  # doctest: +SKIP
    """
    spec = make_spec(params, vary, sample=sample, physical=physical, **options)
    local = client is None and scheduler is None and processes
    if local and (workers is not None or spec.size >= IN_PROCESS_POINTS):  # a LocalCluster will start
        require_main_guard(f"sweep(workers={workers})")
    with discarded_if_empty(out, overwrite=overwrite):
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


@contextmanager
def discarded_if_empty(path: StorePath, *, overwrite: bool = False) -> Iterator[None]:
    """Around a run into the store at ``path``: when the run fails (an error, Ctrl-C) before any block is
    in the store, a store the run made goes (a failed start leaves none behind). A store that was there
    before stays, unless the run was to ``overwrite`` it."""
    made = overwrite or not Path(path).exists()
    try:
        yield
    except BaseException:
        if made and Path(path).exists():
            try:
                missing, total = missing_points(path)
            except (MovingBogieError, KeyError):
                missing, total = 0, 1  # not a sweep store: left alone
            if missing == total:
                shutil.rmtree(path, ignore_errors=True)
        raise
