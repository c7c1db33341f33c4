"""``sweep`` and ``sweep-plot``: parameter sweeps on Dask into a zarr store, and slices of them; on periodic
supports one strip search per point (:mod:`moving_bogie.sweep.sleepers`), on the engine of every sweep."""

from __future__ import annotations

import argparse
import sys
import tomllib
from pathlib import Path
from typing import TYPE_CHECKING

from moving_bogie.errors import ParameterError
from moving_bogie.presentation import field_lines

from .checks import count, exact_number, named_values, workers
from .common import (
    MODEL_FROM_THE_FILE,
    add_bar_option,
    add_json_option,
    add_parameter_options,
    add_units_option,
    params_from_args,
    print_json,
    refuse_for_sleepers,
    si_input,
    soil_file_given,
    vary_texts,
)
from .job_size import check_points
from .outputs import add_figure_option, add_output_option
from .progress import counts_bar
from .reporting import PROG, fail

if TYPE_CHECKING:
    from moving_bogie.sweep.design import SweepSpec
    from moving_bogie.sweep.plan import SweepPlan
    from moving_bogie.sweep.sleepers import SleeperSweepSpec

_RAW = argparse.RawDescriptionHelpFormatter


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add ``sweep`` and ``sweep-plot``."""
    p = subparsers.add_parser(
        "sweep",
        help="stability verdict over a grid or a Sobol design of any parameters (Dask, zarr)",
        description=(
            "Stability at every point of a grid of any parameters (one --vary per dimension) or of a\n"
            "quasi-random design (--sample sobol:N), computed into a zarr store readable with xarray: in\n"
            "this process for under 1000 points, else on Dask (a local cluster, or --scheduler for an\n"
            "existing one; --workers N asks for the cluster at any size). Per point: stable,\n"
            "n_unstable, degree_of_instability (0 where stable), certain. An interrupted sweep keeps its\n"
            "finished chunks: run it again with --resume. With a [physical] parameter file the varied\n"
            "parameters are the SI ones (v in m/s, M in kg, ...; every other SI parameter fixed) and the\n"
            "store's coordinates are named and unitted so, the dimensionless groups kept beside them.\n"
            "A sleeper-track file (docs/sleepers.md) is swept over its [physical] names, each point one\n"
            "Floquet strip search: n_roots, stable, unstable, certain, Omega_im [1/s], Omega_re [rad/s],\n"
            "harmonics, Omega0 [rad/s]. A soil-track file (docs/soil.md) is swept over its track's\n"
            "[physical] keys and its layers' keys (c_s1, h2, ... numbered from 1 at the top), each point\n"
            "the critical velocity: v_cr, omega_cr, v_cr_uncoupled, omega_uncoupled, found."
        ),
        epilog=(
            "examples:\n"
            "  moving-bogie sweep --case 1 --vary alpha=0.3:1.1:200 --vary eta_M=1:200:200 --out s.zarr\n"
            "  moving-bogie sweep --case 7 --vary alpha=0.3:1:80 --vary eta_M=5:100:80 \\\n"
            "      --vary eta_f=0.01,0.05,0.1 --workers 2 --out s3.zarr\n"
            "  moving-bogie sweep --case 1 --vary alpha=0.3:1.1 --vary eta_f=0.01:0.2 --sample sobol:256 \\\n"
            "      --out sobol.zarr\n"
            "  moving-bogie sweep-plot s3.zarr --x alpha --y eta_M --sel eta_f=0.05 --out slice.png\n"
            "  moving-bogie sweep --file examples/uic60-bogie.toml --vary v=60:200:50 \\\n"
            "      --vary M=400:1600:40 --out si.zarr\n"
            "  moving-bogie sweep-plot si.zarr --x v --y M --out si.png\n"
            "  moving-bogie sweep --file examples/sleepers.toml --vary v=40:80:9 --out sl.zarr\n"
            "  moving-bogie sweep-plot sl.zarr --x v --out growth.png\n"
            "  moving-bogie sweep --file examples/soil-ballasted.toml --vary c_s1=40:120:9 --out soil.zarr\n"
            "  moving-bogie sweep-plot soil.zarr --x c_s1 --out vcr.png"
        ),
        formatter_class=_RAW,
    )
    add_parameter_options(p)
    add_units_option(p)
    p.add_argument(
        "--vary",
        action="append",
        default=[],
        metavar="NAME=SPEC",
        help="a varied parameter: NAME=START:STOP:COUNT or NAME=V1,V2,... (NAME=START:STOP with --sample)",
    )
    p.add_argument("--sample", metavar="sobol:N", help="N quasi-random (Sobol) points instead of a grid")
    add_output_option(p, "--out", folder=True, required=True, metavar="S.zarr", help="zarr store to write")
    p.add_argument("--resume", action="store_true", help="complete an interrupted store")
    p.add_argument("--overwrite", action="store_true", help="replace an existing store")
    p.add_argument(
        "--workers",
        type=workers,
        metavar="N",
        help="local worker processes (default: one per core; under 1000 points run in this process)",
    )
    p.add_argument("--scheduler", metavar="tcp://HOST:8786", help="use an existing Dask scheduler")
    add_bar_option(p)
    p.add_argument("--roots", action="store_true", help="store the unstable roots of every point")
    p.add_argument(
        "--margin",
        action="store_true",
        help="store the stability margin of every point (smallest Im q; about 4x the time of the sweep)",
    )
    p.add_argument(
        "--check",
        type=count(0, 1_000_000),
        metavar="K",
        help="points per chunk verified by a full count (default 1; not on a sleeper track)",
    )
    p.add_argument(
        "--chunk-points",
        type=count(1, 10_000_000),
        metavar="N",
        help="points per chunk, about (default 2048; on a sleeper track 1: a point costs seconds)",
    )
    add_json_option(p)
    p.set_defaults(handler=run_sweep_cmd)
    _register_plot(subparsers)


def _register_plot(subparsers: argparse._SubParsersAction) -> None:
    """Add ``sweep-plot``."""
    q = subparsers.add_parser(
        "sweep-plot",
        help="draw a 2-D slice of a sweep store with its instability boundary",
        description=(
            "Degree of instability over two varied parameters of a sweep store, the other dimensions\n"
            "fixed by --sel (nearest value); the stable/unstable boundary drawn, uncertain points hatched.\n"
            "A sleeper-track sweep: with --x alone the growth rate -Im Omega against it, with --x and --y\n"
            "the map of stable, unstable and undetermined points."
        ),
        epilog=(
            "example:\n  moving-bogie sweep-plot s.zarr --x alpha --y eta_M --sel eta_f=0.05 --out slice.png"
        ),
        formatter_class=_RAW,
    )
    q.add_argument("store", type=Path, metavar="S.zarr", help="the sweep store (written by sweep)")
    q.add_argument("--x", required=True, metavar="NAME", help="parameter on the horizontal axis")
    q.add_argument(
        "--y",
        metavar="NAME",
        help="parameter on the vertical axis (a sleeper-track sweep without it: the growth rate against --x)",
    )
    q.add_argument("--sel", action="append", default=[], metavar="NAME=X", help="fix another dimension")
    add_figure_option(q, "--out", required=True, help="the figure")
    q.set_defaults(handler=run_sweep_plot)


def _spec(args: argparse.Namespace) -> SweepSpec:
    if args.workers is not None and args.scheduler:  # their values: the argparse types of cli/checks.py
        raise ParameterError("--workers", "give either --workers or --scheduler, not both")
    check = 1 if args.check is None else args.check
    chunk_points = 2048 if args.chunk_points is None else args.chunk_points
    params, physical = params_from_args(args)
    physical = si_input(args, physical)
    vary = vary_texts(args.vary)
    options = dict(roots=args.roots, margin=args.margin, check=check, block_points=chunk_points)
    options["bar"] = args.bar

    from moving_bogie.sweep.api import make_spec
    from moving_bogie.sweep.design import parse_sample

    sample = parse_sample(args.sample) if args.sample else None
    if sample is not None:
        check_points(sample, "--sample")
    return make_spec(params, vary, sample=sample, physical=physical, **options)


def run_sweep_cmd(args: argparse.Namespace) -> int:
    from moving_bogie.sweep.api import discarded_if_empty
    from moving_bogie.sweep.engine import ContinuousPlan, run_sweep
    from moving_bogie.sweep.store import read_store

    spec: SweepPlan
    if soil_file_given(args):
        from .soil_sweep import soil_spec

        spec = soil_spec(args)
    elif args.file is not None and params_from_args(args)[0].model.periodic:
        spec = _sleeper_spec(args)
    else:
        spec = ContinuousPlan(_spec(args))
    check_points(spec.size)  # a sweep's size is bounded before its store is created
    # every option is checked (and the store created) before any computation
    try:
        with (
            discarded_if_empty(args.out, overwrite=args.overwrite),
            counts_bar("sweep", "points", enabled=not args.json) as bar,
        ):
            run = run_sweep(
                spec,
                args.out,
                resume=args.resume,
                overwrite=args.overwrite,
                workers=args.workers,
                scheduler=args.scheduler,
                progress=bar,
            )
    except KeyboardInterrupt:
        if not Path(args.out).exists():
            return fail("interrupted", json_mode=args.json, code=130)
        return fail(
            f"interrupted; {args.out} keeps every finished chunk: run the same command with --resume"
            + (" in place of --overwrite" if args.overwrite else "")
            + " to complete it",
            json_mode=args.json,
            code=130,
        )
    summary = {
        "out": str(args.out),
        "dims": read_store(args.out, ()).sizes,
        "points": spec.size,
        "points_computed": run.points_computed,
        "blocks": [run.blocks_computed, run.blocks_total],
        "workers": run.workers,
        "scheduler": run.scheduler,
        "seconds": round(run.seconds, 2),
        "points_per_second": round(run.points_per_second, 1) if run.points_computed else None,
    } | spec.summary(args.out)
    if args.json:
        print_json(summary)
    else:
        print("\n".join(field_lines(summary, width=20)))
    return 0


# --- on periodic supports -----------------------------------------------------------------------------

#: the options of a continuous-track sweep that a sleeper file does not take, and why
_NOT_FOR_SLEEPERS = {
    **MODEL_FROM_THE_FILE,
    "roots": "the store keeps the fastest-growing root of every point (Omega_re, Omega_im)",
    "check": "every point is a full strip search of its own",
    "margin": "a sleeper sweep stores the margin of every stable point (margin, in 1/s) without it",
}


def _refuse_options(args: argparse.Namespace) -> None:
    """Refuse, naming it, the first option that does not apply to a sleeper file."""
    refuse_for_sleepers(args, _NOT_FOR_SLEEPERS)
    if args.units == "dimensionless":
        raise ParameterError(
            "--units", "--units dimensionless does not apply to a sleeper-track file: it is swept in SI units"
        )


def _sleeper_spec(args: argparse.Namespace) -> SleeperSweepSpec:
    """The sweep of ``args.file``, every option and every axis's extreme values checked."""
    from moving_bogie.sweep.design import parse_sample
    from moving_bogie.sweep.sleepers import make_sleeper_spec

    _refuse_options(args)
    if args.workers is not None and args.scheduler:
        raise ParameterError("--workers", "give either --workers or --scheduler, not both")
    chunk_points = 1 if args.chunk_points is None else args.chunk_points
    vary = vary_texts(args.vary)
    sample = parse_sample(args.sample) if args.sample else None
    if sample is not None:
        check_points(sample, "--sample")
    data = tomllib.loads(args.file.read_text())
    settings = _sleeper_settings(args.set)
    return make_sleeper_spec(
        data, str(args.file), vary, settings=settings, sample=sample, block_points=chunk_points, bar=args.bar
    )


def _sleeper_settings(texts: list[str] | None) -> dict[str, float]:
    """``--set NAME=VALUE`` as SI floats, the overrides of a sleeper file's ``[physical]`` values."""
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


def run_sweep_plot(args: argparse.Namespace) -> int:
    from moving_bogie.sweep.plots import plot_sweep_slice
    from moving_bogie.sweep.store import missing_points, open_sweep

    from .stability_options import save_figure

    sel: dict[str, float] = {}
    for name, value in named_values(args.sel, "--sel", "NAME=NUMBER").items():
        try:
            sel[name] = float(exact_number(value))
        except ValueError as exc:
            raise ParameterError("--sel", f"--sel {name}={value}: {exc}") from None
    ds = open_sweep(args.store)
    missing, total = missing_points(args.store)
    if missing:
        print(
            f"{PROG}: warning: {args.store} is incomplete: {missing} of {total} points not computed (drawn "
            "blank); run the sweep again with --resume to complete it",
            file=sys.stderr,
        )
    if ds.attrs.get("kind") == "soil":
        from moving_bogie.sweep.soil_plots import plot_soil_sweep

        fig = plot_soil_sweep(ds, args.x, args.y, sel)
    elif ds.attrs.get("kind") == "sleepers":
        from moving_bogie.sweep.sleeper_plots import plot_sleeper_sweep

        fig = plot_sleeper_sweep(ds, args.x, args.y, sel)
    elif args.y is None:
        raise ParameterError("--y", "--y NAME is required (a 1-D view needs a sleeper-track sweep)")
    else:
        fig = plot_sweep_slice(ds, args.x, args.y, sel)
    save_figure(fig, args.out)
    print(args.out)
    return 0
