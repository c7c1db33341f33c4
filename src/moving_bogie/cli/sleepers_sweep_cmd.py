"""``moving-bogie sweep --file F`` for a file on a sleeper track: one Floquet strip search per point
(:mod:`moving_bogie.sweep.sleepers`), on the engine of every sweep."""

from __future__ import annotations

import argparse
import tomllib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import xarray

    from moving_bogie.sweep.sleepers import SleeperSweepSpec

#: the options of a continuous-track sweep that a sleeper file does not take, and why
_MODEL = (
    "the file's [model] and [physical] tables set the model and its SI values (--set NAME=VALUE changes one)"
)
_NOT_FOR_SLEEPERS = {
    "case": _MODEL,
    "beam": _MODEL,
    "track": _MODEL,
    "vehicle": _MODEL,
    "roots": "the store keeps the fastest-growing root of every point (Omega_re, Omega_im)",
    "check": "every point is a full strip search of its own",
    "margin": "a sleeper sweep stores the margin of every stable point (margin, in 1/s) without it",
}


def _refuse_options(args: argparse.Namespace) -> None:
    """Refuse, naming it, the first option that does not apply to a sleeper file."""
    from moving_bogie.errors import ParameterError

    from .common import refuse_for_sleepers

    refuse_for_sleepers(args, _NOT_FOR_SLEEPERS)
    if args.units == "dimensionless":
        raise ParameterError(
            "--units", "--units dimensionless does not apply to a sleeper-track file: it is swept in SI units"
        )


def sleeper_spec(args: argparse.Namespace) -> SleeperSweepSpec:
    """The sweep of ``args.file``, every option and every axis's extreme values checked."""
    from moving_bogie.errors import ParameterError
    from moving_bogie.sweep.design import parse_sample
    from moving_bogie.sweep.sleepers import make_sleeper_spec

    from .common import vary_texts

    _refuse_options(args)
    if args.workers is not None and args.scheduler:
        raise ParameterError("--workers", "give either --workers or --scheduler, not both")
    chunk_points = 1 if args.chunk_points is None else args.chunk_points
    vary = vary_texts(args.vary)
    sample = parse_sample(args.sample) if args.sample else None
    if sample is not None:
        from .job_size import check_points

        check_points(sample, "--sample")
    data = tomllib.loads(args.file.read_text())
    settings = sleeper_settings(args.set)
    return make_sleeper_spec(
        data, str(args.file), vary, settings=settings, sample=sample, block_points=chunk_points
    )


def sleeper_summary(spec: SleeperSweepSpec, ds: xarray.Dataset) -> dict[str, Any]:
    """The verdicts of a sleeper sweep for the summary: the counts of points and the fastest growth."""
    import numpy as np

    ds = ds.compute()
    growth = np.where(ds.unstable.values, -ds.Omega_im.values, np.nan)
    fastest = None
    if np.isfinite(growth).any():
        at = np.unravel_index(int(np.nanargmax(growth)), growth.shape)
        dims = list(ds.unstable.dims)
        fastest = {"growth_rate_1_s": float(growth[at])} | {
            name: float(ds[name].values[at[dims.index(ds[name].dims[0])]]) for name in spec.units
        }
    return {
        "model": spec.model,
        "stable_points": int(ds.stable.sum()),
        "unstable_points": int(ds.unstable.sum()),
        "undetermined_points": int((~ds.stable & ~ds.unstable).sum()),
        "uncertain_points": int((~ds.certain).sum()),
        "fastest_growth": fastest,
        "units": spec.units,
    }


def sleeper_settings(texts: list[str] | None) -> dict[str, float]:
    """``--set NAME=VALUE`` as SI floats, the overrides of a sleeper file's ``[physical]`` values."""
    from moving_bogie.errors import ParameterError

    out: dict[str, float] = {}
    for text in texts or ():
        name, eq, value = text.partition("=")
        try:
            out[name.strip()] = float(value)
        except ValueError:
            raise ParameterError("set", f"--set {text!r}: expected NAME=NUMBER") from None
        if not eq or not name.strip():
            raise ParameterError("set", f"--set {text!r}: expected NAME=NUMBER")
    return out
