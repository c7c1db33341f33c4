"""``moving-bogie timeseries`` and ``moving-bogie shape``: closed-form vibrations, Eqs. (35)-(47); on periodic
supports the steady response over a bay and the free vibrations (docs/sleepers.md, "The time series on
sleepers"). One path on every track: :func:`moving_bogie.api.time_series` gives a
:class:`~moving_bogie.response.closed_form.TimeSeries`, printed and written by :mod:`.timeseries_output`."""

from __future__ import annotations

import argparse
import sys
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import numpy as np

    from moving_bogie.kernels.bound import BoundModel
    from moving_bogie.response.closed_form import TimeSeries
    from moving_bogie.roots.frequency_result import FrequencyResult

from .checks import count, number
from .common import (
    MODEL_FROM_THE_FILE,
    add_json_option,
    add_output_option,
    add_parameter_options,
    continuous_track_only,
    params_from_args,
    print_json,
)
from .outputs import add_figure_option
from .timeseries_output import format_series, print_shape, write_csv_series, write_shape_csv

_MAX_POINTS = 10_000_000


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``timeseries`` and ``shape`` subcommands."""
    parser = subparsers.add_parser(
        "timeseries",
        help="closed-form time series w(0,tau), w(d,tau), u, theta (Eqs. (35)-(43))",
        description=(
            "Closed-form vibrations at the wheels and of the bogie bar: steady part (Eq. (39)), residues at\n"
            "every induced frequency (Eqs. (40)-(43)) and the branch-cut part I_bc of Eq. (35) where it\n"
            "matters (any beam and track). Times are dimensionless tau, or seconds with a [physical]\n"
            "parameter file (results then in m and rad). Exit status 2 on bad input or when the induced\n"
            "frequencies could not all be confirmed.\n"
            "A sleeper-track file (docs/sleepers.md) gives instead, in SI, the steady response over a bay\n"
            "under the constant loads (contact force and rail deflection under each wheel, their mean and\n"
            "peak-to-peak, the harmonics and whether they converged) and the free vibrations (each Floquet\n"
            "root's frequency, growth rate and doubling time, and the verdict); exit status 1 when the\n"
            "response has not converged or the verdict is UNDETERMINED."
        ),
        epilog=(
            "examples:\n  moving-bogie timeseries --case 7 --tau 20,50,100\n"
            "  moving-bogie timeseries --case 1 --tmax 100 --points 2001 --plot case1.png\n"
            "  moving-bogie timeseries --case 5 --tmax 2000 --points 20001 --plot-long case5_long.png\n"
            "  moving-bogie timeseries --case 2 --tmax 50 --json --no-branch-cut\n"
            "  moving-bogie timeseries --file examples/sleepers.toml --bays 2 --plot bay.png"
        ),
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    add_parameter_options(parser)
    _add_common(parser)
    _add_times(parser)
    out = parser.add_argument_group("output")
    add_json_option(out)
    add_output_option(out, "--csv", metavar="F.csv", help="write the series as CSV")
    add_figure_option(out, "--plot", help="three panels: w(0,tau), u, theta (paper's Figure 5 style)")
    add_figure_option(out, "--plot-long", help="two panels: w(0,tau), u (paper's Figure 6 style)")
    out.add_argument(
        "--rows",
        action="store_true",
        help="print the rows even when --csv, --plot or --plot-long writes them to a file",
    )
    parser.set_defaults(handler=run_timeseries)

    shape = subparsers.add_parser(
        "shape",
        help="beam deflection w(xi) around the bogie at one time (Eqs. (44)-(47))",
        description=(
            "Closed-form beam deflection shape w(xi, tau) at one time for xi around the bogie (rear wheel\n"
            "at xi = 0, front wheel at xi = d), with the branch-cut part where it matters. xi and tau are\n"
            "dimensionless, or metres and seconds with a [physical] parameter file (result in m)."
        ),
        epilog=(
            "examples:\n  moving-bogie shape --case 7 --tau 20\n"
            "  moving-bogie shape --case 1 --tau 100 --xi-min -30 --xi-max 30 --plot shape.png"
        ),
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    add_parameter_options(shape)
    _add_common(shape)
    shape.add_argument("--tau", type=number, required=True, metavar="T", help="the time")
    shape.add_argument("--xi-min", type=number, default=None, metavar="X", help="default -10 (or -10/chi m)")
    shape.add_argument(
        "--xi-max", type=number, default=None, metavar="X", help="default d + 10 (or (d+10)/chi m)"
    )
    shape.add_argument(
        "--points", type=count(2, 1_000_000), default=401, metavar="K", help="points in xi (default 401)"
    )
    sout = shape.add_argument_group("output")
    add_json_option(sout)
    add_output_option(sout, "--csv", metavar="F.csv", help="write xi, w as CSV")
    add_figure_option(sout, "--plot", help="plot w(xi)")
    shape.set_defaults(handler=run_shape)


def _add_times(parser: argparse.ArgumentParser) -> None:
    times = parser.add_argument_group("times")
    times.add_argument("--tau", metavar="T1,T2,...", help="comma-separated times")
    times.add_argument("--tmax", type=number, metavar="T", help="uniform times 0..T")
    times.add_argument(
        "--points",
        type=int,
        metavar="K",
        help="points with --tmax (default 2001); a sleeper file: points over the bays (default 201 per bay)",
    )
    times.add_argument(
        "--bays",
        type=int,
        metavar="n",
        help="a sleeper-track file only: bays shown of the steady response (default 1)",
    )


def _add_common(parser: argparse._ActionsContainer) -> None:
    parser.add_argument(
        "--branch-cut",
        action=argparse.BooleanOptionalAction,
        default=None,
        help="force the branch-cut part on or off (default: automatic, where it exceeds 1e-6 of the steady "
        "deflection)",
    )
    parser.add_argument(
        "--dps", type=count(15, 1000, "digits"), help="working precision in decimal digits (default 30)"
    )


def _branch_cut(args: argparse.Namespace) -> bool | str:
    """``branch_cut`` of the closed form: "auto", or the forced choice of ``--branch-cut``."""
    return "auto" if args.branch_cut is None else bool(args.branch_cut)


def _check(args: argparse.Namespace, points: int = 2001) -> None:
    """Check --dps and --points, filling in their defaults (30 digits, ``points``)."""
    from moving_bogie.errors import ParameterError

    args.dps = 30 if args.dps is None else args.dps
    args.points = points if args.points is None else args.points
    if not 15 <= args.dps <= 1000:
        raise ParameterError("dps", f"dps must be between 15 and 1000 (got {args.dps})")
    if not 2 <= args.points <= _MAX_POINTS:
        raise ParameterError("points", f"points must be between 2 and {_MAX_POINTS} (got {args.points})")


def _times(args: argparse.Namespace) -> np.ndarray:
    import numpy as np

    from moving_bogie.errors import ParameterError

    if (args.tau is None) == (args.tmax is None):
        raise ParameterError("tau", "give either --tau T1,T2,... or --tmax T")
    if args.tau is not None:
        try:
            values = [float(v) for v in args.tau.split(",") if v.strip()]
        except ValueError:
            raise ParameterError("tau", f"tau must be comma-separated numbers (got {args.tau!r})") from None
        if not values:
            raise ParameterError("tau", "tau: no times given")
        tau = np.array(values)
    else:
        if not (np.isfinite(args.tmax) and args.tmax > 0):
            raise ParameterError("tmax", f"tmax must be a positive number (got {args.tmax})")
        tau = np.linspace(0.0, args.tmax, args.points)
    if not np.all(np.isfinite(tau)) or np.any(tau < 0):
        raise ParameterError("tau", "tau must be finite and >= 0")
    return tau


def _frequencies_or_fail(
    bound: BoundModel, dps: int, json_mode: bool, branch_cut: bool | str
) -> FrequencyResult:
    from moving_bogie.response.residues import complete_frequencies

    from .progress import progress_bar

    with progress_bar("induced frequencies", enabled=not json_mode) as update:
        return complete_frequencies(bound, dps, branch_cut, update)


def run_timeseries(args: argparse.Namespace) -> int:
    """Compute and print (or write) the time series of the parameters on their track
    (:func:`moving_bogie.api.time_series`: the closed form, or on periodic supports the steady response over
    a bay and the free vibrations), with the options of that track (:data:`_SERIES_OPTIONS`)."""
    params, physical = params_from_args(args)  # every input checked before the heavy imports
    options = _SERIES_OPTIONS[params.model.periodic](args)

    from moving_bogie.api import time_series

    from .progress import progress_bar

    with progress_bar("time series", enabled=not args.json) as update:
        ts = time_series(physical if physical is not None else params, progress=update, **options)
    if args.csv:
        write_csv_series(ts, args.csv)
    if args.plot or args.plot_long:
        from moving_bogie.response.plots import long_time_figure, save_figure, series_figure

        label = series_label(args, ts)
        if args.plot:
            save_figure(series_figure(ts, label), args.plot)
        if args.plot_long:
            save_figure(long_time_figure(ts, title=f"{label}: closed form at long times"), args.plot_long)
    if args.json:
        print_json(ts.to_dict())
    else:
        plots = [str(f) for f in (args.plot, args.plot_long) if f]
        print(format_series(ts, rows=args.rows or not (args.csv or plots), csv=args.csv, plots=plots))
    for text in ts.warnings:
        print(f"warning: {text}", file=sys.stderr)
    return 0 if ts.complete else 1


#: the options of the closed form that a file on periodic supports does not take, and what to do instead
_NOT_FOR_SLEEPERS = {
    **MODEL_FROM_THE_FILE,
    "tau": "the steady response spans --bays bays on --points points",
    "tmax": "the steady response spans --bays bays on --points points",
    "branch_cut": "the steady response over a bay is a sum of harmonics, without a branch cut",
    "plot_long": "--plot draws the steady response over the bays",
    "dps": "the Floquet runtime works in double precision",
}
_MAX_SLEEPER_POINTS = 1_000_000
_MAX_BAYS = 10_000
SLEEPER_POINTS = 201


def _bay_options(args: argparse.Namespace) -> dict[str, Any]:
    """On periodic supports: the bays and the points over them, checked, and the closed form's options
    refused by name (one message, before any work)."""
    from moving_bogie.errors import ParameterError

    from .common import refuse_for_sleepers

    refuse_for_sleepers(args, _NOT_FOR_SLEEPERS, unset=(None,))  # --no-branch-cut sets False: refused too
    bays = 1 if args.bays is None else args.bays
    if not 1 <= bays <= _MAX_BAYS:
        raise ParameterError("bays", f"--bays must be between 1 and {_MAX_BAYS} (got {bays})")
    points = SLEEPER_POINTS * bays if args.points is None else args.points
    if not 2 <= points <= _MAX_SLEEPER_POINTS:
        raise ParameterError("points", f"--points must be between 2 and {_MAX_SLEEPER_POINTS} (got {points})")
    return {"bays": bays, "points": points}


def _closed_form_options(args: argparse.Namespace) -> dict[str, Any]:
    """The times, the precision and the branch cut of the closed form, checked (``--bays`` refused)."""
    from moving_bogie.errors import ParameterError

    if args.bays is not None:
        raise ParameterError("bays", "--bays applies to a sleeper track only")
    _check(args)
    return {"tau": _times(args), "dps": args.dps, "branch_cut": _branch_cut(args)}


#: The options each kind of track takes (by ``params.model.periodic``), read and checked from the command
#: line: what :func:`moving_bogie.api.time_series` passes on to the series of that track.
_SERIES_OPTIONS = {False: _closed_form_options, True: _bay_options}


def series_label(args: argparse.Namespace, ts: TimeSeries) -> str:
    """What a figure's title names: the Table 1 case, else the parameter file, else the model."""
    if args.case is not None:
        return f"Case {args.case}"
    if args.file is not None:
        return f"{args.file.name} ({ts.model})"
    return str(ts.model)


#: How far from the rear wheel (in beam lengths 1/chi) ``shape`` evaluates the deflection.
XI_REACH = 500.0


def run_shape(args: argparse.Namespace) -> int:
    """Compute and print (or write) the deflection shape at one time."""
    import numpy as np

    from moving_bogie.errors import ParameterError

    _check(args)
    params, physical = params_from_args(args)  # every input checked before the heavy imports
    continuous_track_only(params, "shape", "timeseries --file F gives the rail's deflection over a bay")
    if not (np.isfinite(args.tau) and args.tau >= 0):
        raise ParameterError("tau", f"tau must be finite and >= 0 (got {args.tau})")
    d = float(params.d)
    chi = physical.scales().chi if physical is not None else 1.0
    lo = args.xi_min if args.xi_min is not None else -10.0 / chi
    hi = args.xi_max if args.xi_max is not None else (d + 10.0) / chi
    if not (np.isfinite(lo) and np.isfinite(hi) and hi > lo):
        raise ParameterError("xi_max", f"need xi_min < xi_max (got {lo}, {hi})")
    reach = XI_REACH / chi  # the closed form's exponentials leave double precision farther out
    if max(abs(lo), abs(hi)) > reach:
        unit = " m" if physical is not None else ""
        raise ParameterError(
            "xi_min" if abs(lo) > reach else "xi_max",
            f"xi_min and xi_max (--xi-min, --xi-max) must lie within +-{reach:.6g}{unit} of the rear wheel "
            f"(got {lo:g}, {hi:g})",
        )
    xi = np.linspace(lo, hi, args.points)

    from moving_bogie.kernels.bound import bind
    from moving_bogie.response.closed_form import SI_UNITS, deflection_shape_details

    bound = bind(params)
    result = _frequencies_or_fail(bound, args.dps, args.json, _branch_cut(args))
    w, with_cut, notes = deflection_shape_details(
        bound,
        xi,
        args.tau,
        scales=physical.scales() if physical is not None else None,
        frequencies=result,
        branch_cut=_branch_cut(args),
    )
    units = (
        {"xi": SI_UNITS["xi"], "tau": SI_UNITS["tau"], "w": SI_UNITS["w"]}
        if physical is not None
        else {"xi": "1", "tau": "1", "w": "w_st"}
    )
    if args.csv:
        write_shape_csv(xi, w, units, args.csv)
    if args.plot:
        from moving_bogie.response.plots import save_figure, shape_figure

        fig = shape_figure(xi, w, tau=args.tau, d=d / chi, si=physical is not None)
        save_figure(fig, args.plot)
    print_shape(
        xi,
        w,
        tau=args.tau,
        model=args.model,
        units=units,
        with_cut=with_cut,
        notes=notes,
        json_mode=args.json,
    )
    return 0
