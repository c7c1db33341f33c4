"""The zarr store of a sweep, written block by block, read back as an :class:`xarray.Dataset`.

Layout: one dimension per varied parameter (coordinate values as float64 with ``units`` and the exact
decimal values in ``exact``), or one dimension ``point`` on a quasi-random design (each parameter a
coordinate along it). A sweep in SI units (a ``[physical]`` input) names its dimensions by the SI
parameters (``v`` in m/s, ``M`` in kg, ... with their ``units``) and keeps each group as a further
coordinate along the same dimension (``alpha``, ``eta_M``; ``d_dimensionless`` where the names clash).
The attribute ``operating_point`` holds the base point by the store's names. Then come the data variables of
:data:`~moving_bogie.sweep.evaluate.VARIABLES` (``margin`` and ``margin_bound`` only when the margin is
asked for; the unstable roots ``roots_re``, ``roots_im`` along a last dimension ``root`` when asked),
chunked exactly like the blocks of the sweep, so that writing one block writes one chunk file per variable.

Safety. The store is created under a temporary name and renamed into place (a store never exists half
made). Chunk files are written atomically by zarr (temporary file, then rename), and ``computed`` is
written last: a block whose ``computed`` chunk is there is complete, anything else is computed again by
a resumed run. An interrupted store is therefore never corrupt, and a resumed one holds the same bytes
as an uninterrupted one (the work of a block does not depend on the order of the blocks).
"""

from __future__ import annotations

import json
import os
import shutil
from collections.abc import Iterable
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal, TypeAlias, cast

import numpy as np

from moving_bogie.errors import MovingBogieError, ParameterError
from moving_bogie.model.bar import BAR_RULES, bar_note
from moving_bogie.model.exact import fraction_to_text
from moving_bogie.sweep.design import (
    Block,
    SweepSpec,
    group_coordinate,
    parameter_attributes,
    si_attributes,
)
from moving_bogie.sweep.evaluate import MARGIN_VARIABLES, VARIABLES

if TYPE_CHECKING:
    import xarray
    import zarr

    from moving_bogie.sweep.plan import SweepPlan

#: Where a store is: a folder's path.
StorePath: TypeAlias = str | os.PathLike[str]
#: A data variable of a store: (name, dtype, fill value, description).
Variable: TypeAlias = tuple[str, str, Any, str]

__all__ = [
    "RENAMED",
    "VARIABLE_NAMES",
    "consolidate",
    "create_store",
    "missing_blocks",
    "missing_points",
    "open_sweep",
    "package_version",
    "prepare_store",
    "read_store",
    "store_array",
    "store_group",
    "write_block",
    "write_coordinate",
]

#: CF ``long_name`` and ``units`` of each data variable (``ds.plot()`` labels its axes from them); the
#: margin's unit is "1/s" in a sweep in SI units.
VARIABLE_NAMES = {
    "stable": ("stable (no induced frequency with Im q < 0)", "1"),
    "n_unstable": ("number of unstable induced frequencies", "1"),
    "degree_of_instability": ("degree of instability, most negative Im q", "1"),
    "margin": ("stability margin, smallest Im q (decay rate; < 0: growth rate)", "1"),
    "margin_bound": ("the margin is a lower bound", "1"),
    "certain": ("the count is certified", "1"),
    "settled": ("verdict from a full count", "1"),
    "checked": ("verified by a full count (1 agreed, -1 disagreed, 0 not checked)", "1"),
    "computed": ("the block has been computed", "1"),
    "roots_re": ("Re q of the unstable induced frequencies", "1"),
    "roots_im": ("Im q of the unstable induced frequencies", "1"),
    "alpha_cr": ("critical velocity of the track, alpha_cr", "1"),
    "supercritical": ("the point moves above the critical velocity", "1"),
}

#: Variables renamed since older stores (old name: new name), renamed again when such a store is opened:
#: ``count`` shadowed :meth:`xarray.Dataset.count` (``ds.count`` is the method, not the variable).
RENAMED = {"count": "n_roots"}

#: The margin of a sweep in SI units: Im omega = Im q / t_scale.
SI_MARGIN = ("stability margin, smallest Im omega (decay rate; < 0: growth rate)", "1/s")


def package_version() -> str:
    """The version of moving-bogie that writes a store (its attribute ``package_version``)."""
    from moving_bogie import __version__

    return __version__


def prepare_store(
    path: StorePath, spec: SweepSpec | SweepPlan, *, resume: bool = False, overwrite: bool = False
) -> Path:
    """Check the ``--out`` path before any computation; create the store unless resuming one.

    Raises
    ------
    ParameterError
        Naming ``--out``: the path exists without ``--resume``/``--overwrite``, holds no sweep, or holds a
        different sweep than the one asked to resume.
    """
    path = Path(path)
    if resume and overwrite:
        raise ParameterError("--resume", "give either --resume or --overwrite, not both")
    if path.exists():
        if resume:
            try:
                text = cast(str, store_group(path, "r").attrs["sweep"])  # JSON text (create_store)
                stored = json.loads(text)
            except (KeyError, ValueError, OSError, MovingBogieError, FileNotFoundError):
                raise ParameterError(
                    "--out", f"--out {path}: not a sweep store, cannot --resume it"
                ) from None
            if stored != spec.describe():
                raise ParameterError(
                    "--resume", f"--resume: {path} holds a different sweep (parameters, values or options)"
                )
            return path
        if not overwrite:
            raise ParameterError(
                "--out", f"--out {path} exists: pass --resume to complete it or --overwrite to replace it"
            )
    if not path.parent.exists():
        raise ParameterError("--out", f"--out {path}: folder {path.parent} does not exist")
    if not os.access(path.parent, os.W_OK):
        raise ParameterError("--out", f"--out {path}: folder {path.parent} is not writable")
    if isinstance(spec, SweepSpec):
        create_store(path, spec)
    else:
        spec.create_store(path)
    return path


def store_group(path: StorePath, mode: Literal["r", "r+"]) -> zarr.Group:
    """The zarr group of the store at ``path`` (``mode`` "r" or "r+"); not a store: MovingBogieError."""
    import zarr

    try:
        return zarr.open_group(str(path), mode=mode)
    except (FileNotFoundError, ValueError, KeyError) as exc:
        raise MovingBogieError(f"{path}: not a zarr store ({exc})") from None


def store_array(g: zarr.Group, name: str) -> zarr.Array:
    """The array ``name`` of the store ``g``."""
    import zarr

    member = g[name]
    if not isinstance(member, zarr.Array):
        raise MovingBogieError(f"{name} in {g.store}: a group where a sweep store has an array")
    return member


def create_store(path: StorePath, spec: SweepSpec) -> None:
    """Write the metadata and coordinates of an empty store at ``path`` (replacing what is there)."""
    import zarr

    path = Path(path)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    shutil.rmtree(tmp, ignore_errors=True)
    g = zarr.open_group(str(tmp), mode="w")
    dims, shape, chunks = spec.dims, spec.shape, spec.chunks
    if spec.design == "sobol":
        point = g.create_array("point", shape=shape, chunks=shape, dtype="int64", dimension_names=("point",))
        point[:] = np.arange(shape[0])
        point.attrs.update(long_name="point of the quasi-random design", units="1")
    extra_coordinates: list[str] = []
    for axis in spec.axes:
        own = ("point",) if spec.design == "sobol" else (axis.label,)
        if spec.si:
            si_name = axis.label  # the SI name of an axis given in SI units
            write_coordinate(
                g, si_name, own, axis.si_floats, si_attributes(spec.params, axis.name), axis.si_values
            )
            group = group_coordinate(axis, {a.label for a in spec.axes})
            attrs = parameter_attributes(spec.params, axis.name) | {"si": si_name}
            write_coordinate(g, group, own, axis.floats, attrs, axis.values)
            extra_coordinates += [si_name, group] if spec.design == "sobol" else [group]
        else:
            exact = axis.values if spec.design == "grid" else None
            write_coordinate(
                g, axis.name, own, axis.floats, parameter_attributes(spec.params, axis.name), exact
            )
    for name, dtype, fill, text in _variables(spec):
        extra = (spec.max_roots,) if name.startswith("roots_") else ()
        arr = g.create_array(
            name,
            shape=shape + extra,
            chunks=chunks + extra,
            dtype=dtype,
            fill_value=fill,
            dimension_names=dims + (("root",) if extra else ()),
        )
        arr.attrs["description"] = text
        long_name, units = SI_MARGIN if name == "margin" and spec.si else VARIABLE_NAMES[name]
        arr.attrs.update(long_name=long_name, units=units)
        if name == "degree_of_instability":
            if spec.physical is not None:  # the growth rate in SI: -Im omega = -Im q / t_scale [1/s]
                arr.attrs["t_scale_s"] = spec.physical.scales().t_scale
                arr.attrs["si"] = "growth rate [1/s] = -degree_of_instability / t_scale_s"
        if extra_coordinates:  # the groups of an SI sweep, read back by xarray as coordinates
            arr.attrs["coordinates"] = " ".join(extra_coordinates)
    g.attrs.update(
        title="moving-bogie parameter sweep",
        model=spec.model,
        params=json.dumps(spec.params.to_dict()),
        sweep=json.dumps(spec.describe()),
        search_window=(
            "column counts: the lower half of roots.count.window.default_window "
            "(the largest over each column); "
            "full counts (settled, checked points): induced_frequencies' far-field window"
        ),
        package_version=package_version(),
        degree_convention=(
            "most negative Im q over the induced frequencies; 0 where stable; NaN where not certain"
        ),
        units="si" if spec.si else "dimensionless",
        operating_point=json.dumps(spec.operating_point()),
    )
    if spec.physical is not None:
        g.attrs["physical"] = json.dumps(spec.physical.to_dict())
    if bar_note(spec.params, spec.bar, spec.params.model.wheel_mass) is not None:
        g.attrs["bar"] = json.dumps({"rule": spec.bar, "meaning": BAR_RULES[spec.bar]})
    _write_speed(g, spec)
    consolidate(tmp)
    if path.exists():
        shutil.rmtree(path)
    os.replace(tmp, path)


def consolidate(path: StorePath) -> None:
    """Gather the metadata of every array into the store's root (xarray then opens it in one read).

    zarr warns that consolidated metadata is not part of the zarr 3 specification: xarray, the reader of
    these stores, reads it, so the warning is not passed on.
    """
    import warnings

    import zarr

    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message="Consolidated metadata", category=UserWarning)
        zarr.consolidate_metadata(str(path))


def _write_speed(g: zarr.Group, spec: SweepSpec) -> None:
    """``supercritical`` and ``alpha_cr`` at every point (:mod:`moving_bogie.sweep.speed`), or a note."""
    from moving_bogie.stability.velocity.supercritical import SUPERCRITICAL_MEANING
    from moving_bogie.sweep.speed import MAX_TRACKS, speed_arrays

    arrays = speed_arrays(spec)
    if arrays is None:
        g.attrs["supercritical"] = (
            f"not computed: more than {MAX_TRACKS} distinct tracks, or a track without a critical velocity"
        )
        return
    texts = {
        "alpha_cr": "critical velocity of the point's track, Eqs. (65)-(66) (alpha units)",
        "supercritical": "alpha > alpha_cr: " + SUPERCRITICAL_MEANING,
    }
    for name, values in arrays.items():
        arr = g.create_array(name, shape=spec.shape, dtype=values.dtype, dimension_names=spec.dims)
        arr[...] = values
        arr.attrs["description"] = texts[name]
        long_name, units = VARIABLE_NAMES[name]
        arr.attrs.update(long_name=long_name, units=units)
    if spec.physical is not None:
        v_ref = spec.physical.scales().v_ref
        v_cr = sorted({float(a) * v_ref for a in np.unique(arrays["alpha_cr"])})
        g.attrs["v_cr"] = json.dumps({"values": v_cr, "unit": "m/s"})


def write_coordinate(
    g: zarr.Group,
    name: str,
    dims: tuple[str, ...],
    floats: np.ndarray,
    attrs: dict[str, str],
    exact: Iterable[Fraction] | None,
) -> None:
    """One coordinate array: float64 values, attributes, the exact decimal values (None: not kept)."""
    coord = g.create_array(name, shape=(len(floats),), dtype="float64", dimension_names=dims)
    coord[:] = floats
    coord.attrs.update(attrs)
    if exact is not None:
        coord.attrs["exact"] = [fraction_to_text(v) for v in exact]


def _variables(spec: SweepSpec) -> list[Variable]:
    out: list[Variable] = [v for v in VARIABLES if spec.margin or v[0] not in MARGIN_VARIABLES]
    if spec.roots:
        out += [
            (
                "roots_re",
                "float64",
                np.nan,
                "Re q of the unstable roots (Re q >= 0 member of each pair), NaN-padded",
            ),
            ("roots_im", "float64", np.nan, "Im q of the unstable roots, NaN-padded"),
        ]
    # computed last: a block is complete once its computed chunk exists
    return [v for v in out if v[0] != "computed"] + [v for v in out if v[0] == "computed"]


def write_block(
    path: StorePath, spec: SweepSpec, slices: tuple[slice, ...], arrays: dict[str, np.ndarray]
) -> None:
    """Write one block's arrays into its chunk of every variable (``computed`` last); the margin in 1/s in
    a sweep in SI units."""
    g = store_group(path, "r+")
    t_scale = spec.physical.scales().t_scale if spec.physical is not None else 1.0
    for name, *_ in _variables(spec):
        store_array(g, name)[slices] = arrays[name] / t_scale if name == "margin" else arrays[name]


def missing_blocks(path: StorePath, spec: SweepPlan) -> list[Block]:
    """Blocks of ``spec`` whose ``computed`` chunk is not in the store at ``path``."""
    computed = np.asarray(store_array(store_group(path, "r"), "computed")[...])
    return [b for b in spec.blocks() if not np.all(computed[b.slices])]


def missing_points(path: StorePath) -> tuple[int, int]:
    """(points not computed, points) of the store at ``path``: an interrupted sweep's is not complete."""
    computed = np.asarray(store_array(store_group(path, "r"), "computed")[...])
    return int((~computed).sum()), int(computed.size)


def read_store(path: StorePath, names: Iterable[str]) -> StoreSummary:
    """The dimensions of the store at ``path``, the units of its arrays and those arrays ``names`` that it
    holds, read whole with zarr: a summary without starting xarray and dask."""
    g = store_group(path, "r")
    out = StoreSummary({}, {}, {})
    for name in g.array_keys():
        array = store_array(g, name)
        dims = getattr(array.metadata, "dimension_names", None) or array.attrs.get("_ARRAY_DIMENSIONS", ())
        out.sizes.update({str(dim): n for dim, n in zip(cast(list, dims), array.shape) if dim})
        out.units[name] = str(array.attrs.get("units", "1"))
        if name in names:
            out.arrays[name] = np.asarray(array[...])
    return out


@dataclass(frozen=True)
class StoreSummary:
    """What :func:`read_store` read: dimension lengths, units of every array, and the arrays asked for."""

    sizes: dict[str, int]
    units: dict[str, str]
    arrays: dict[str, np.ndarray]


def open_sweep(path: StorePath, dask: bool = True) -> xarray.Dataset:
    """The sweep at ``path`` as an :class:`xarray.Dataset` (lazy, dask-backed; with ``dask=False`` lazy
    without dask, which a summary of the store reads faster than dask starts).

    A store has its metadata consolidated (:func:`consolidate`); one without (written by an earlier
    version) is read array by array, without the margin and the units of its variables. The variables of
    an older store named otherwise are given their names of :data:`RENAMED`.
    """
    import xarray as xr

    path = Path(path)
    if not path.exists():
        raise ParameterError("store", f"no sweep store at {path}")
    try:
        root = json.loads((path / "zarr.json").read_text()) if (path / "zarr.json").exists() else {}
        consolidated = "consolidated_metadata" in root
        if dask:
            ds = xr.open_zarr(str(path), consolidated=consolidated)
        else:
            ds = xr.open_zarr(str(path), consolidated=consolidated, chunks=None)
    except (FileNotFoundError, ValueError, KeyError) as exc:
        raise MovingBogieError(f"{path}: not a sweep store ({exc})") from None
    old = {name: new for name, new in RENAMED.items() if name in ds.variables and new not in ds.variables}
    return ds.rename_vars(old)
