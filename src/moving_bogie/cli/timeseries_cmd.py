"""``moving-bogie timeseries`` and ``moving-bogie shape``: closed-form vibrations, Eqs. (35)-(47); on periodic
supports the steady response over a bay and the free vibrations (docs/sleepers.md, "The time series on
sleepers"), from :func:`moving_bogie.response.sleeper_series.sleeper_series`. The output is
:mod:`.timeseries_output`'s."""

from __future__ import annotations

import argparse
import sys
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import numpy as np

    from moving_bogie.kernels.bound import BoundModel
    from moving_bogie.model.params import DimensionlessParams
    from moving_bogie.model.physical import PhysicalParams
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
from .timeseries_output import (
    format_series,
    format_sleeper_series,
    not_converged,
    print_shape,
    write_csv_series,
    write_shape_csv,
    write_sleeper_csv,
)

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
    from moving_bogie.errors import MovingBogieError
    from moving_bogie.response.cut_integral import branch_cut_for
    from moving_bogie.roots.frequencies import induced_frequencies

    from .progress import progress_bar

    if branch_cut is True:
        branch_cut_for(bound)  # refuses a supercritical velocity before the long frequency search

    with progress_bar("induced frequencies", enabled=not json_mode) as update:
        result = induced_frequencies(bound, dps=dps, progress=update)
    if not result.count_ok:
        detail = "; ".join(result.warnings) or f"{result.found} of {result.count} roots confirmed"
        raise MovingBogieError(f"induced frequencies incomplete ({detail}); no closed-form response")
    return result


def run_timeseries(args: argparse.Namespace) -> int:
    """Compute and print (or write) the closed-form time series; on periodic supports the steady response
    over a bay and the free vibrations (:func:`run_on_supports`)."""
    from moving_bogie.errors import ParameterError

    params, physical = params_from_args(args)  # every input checked before the heavy imports
    if params.model.periodic:
        return run_on_supports(args, params, physical)
    if args.bays is not None:
        raise ParameterError("bays", "--bays applies to a sleeper track only")
    _check(args)
    tau = _times(args)

    from moving_bogie.kernels.bound import bind
    from moving_bogie.response.closed_form import closed_form_response

    bound = bind(params)  # bound once: the frequency search and the closed form share it
    result = _frequencies_or_fail(bound, args.dps, args.json, _branch_cut(args))
    ts = closed_form_response(
        bound,
        tau,
        scales=physical.scales() if physical is not None else None,
        frequencies=result,
        branch_cut=_branch_cut(args),
    )
    if args.csv:
        write_csv_series(ts, args.csv)
    if args.plot or args.plot_long:
        from moving_bogie.response.plots import long_time_figure, save_figure, time_series_figure

        label = series_label(args, ts)
        if args.plot:
            save_figure(time_series_figure(ts, title=f"{label}: closed-form time series"), args.plot)
        if args.plot_long:
            save_figure(long_time_figure(ts, title=f"{label}: closed form at long times"), args.plot_long)
    if args.json:
        print_json(ts.to_dict())
    else:
        files = args.csv or args.plot or args.plot_long
        plots = [str(f) for f in (args.plot, args.plot_long) if f]
        print(format_series(ts, rows=args.rows or not files, csv=args.csv, plots=plots))
    return 0


# --- on periodic supports -----------------------------------------------------------------------------

#: the options of the continuous-track time series that a sleeper file does not take, and what to do instead
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


def check_sleeper_options(args: argparse.Namespace) -> None:
    """Refuse, naming it, the first option that does not apply to a sleeper file; check --bays, --points."""
    from moving_bogie.errors import ParameterError

    from .common import refuse_for_sleepers

    # --no-branch-cut sets False: refused too
    refuse_for_sleepers(args, _NOT_FOR_SLEEPERS, unset=(None,))
    bays = 1 if args.bays is None else args.bays
    if not 1 <= bays <= _MAX_BAYS:
        raise ParameterError("bays", f"--bays must be between 1 and {_MAX_BAYS} (got {bays})")
    points = SLEEPER_POINTS * bays if args.points is None else args.points
    if not 2 <= points <= _MAX_SLEEPER_POINTS:
        raise ParameterError("points", f"--points must be between 2 and {_MAX_SLEEPER_POINTS} (got {points})")
    args.bays, args.points = bays, points


def run_on_supports(
    args: argparse.Namespace, params: DimensionlessParams, physical: PhysicalParams | None
) -> int:
    """Print (or write) the steady response over ``--bays`` bays and the free vibrations in SI of a model on
    periodic supports (the file's parameters, ``--set`` applied)."""
    check_sleeper_options(args)
    from moving_bogie.api import sleeper_series

    series = sleeper_series(params if physical is None else physical, bays=args.bays, points=args.points)
    if args.csv:
        write_sleeper_csv(series, args.csv)
    if args.plot:
        from moving_bogie.response.plots import save_figure
        from moving_bogie.response.sleeper_plots import sleeper_series_figure

        save_figure(sleeper_series_figure(series, title=f"{args.file.name} ({series.model})"), args.plot)
    if args.json:
        print_json(series.to_dict())
    else:
        files = [str(f) for f in (args.csv, args.plot) if f]
        print(format_sleeper_series(series, rows=args.rows or not files, files=files))
    warnings = [] if series.converged else [not_converged(series)]
    warnings += list(series.free_notes)
    for text in warnings:
        print(f"warning: {text}", file=sys.stderr)
    from moving_bogie.roots.verdict import UNDETERMINED

    return 0 if series.converged and series.free_verdict != UNDETERMINED else 1


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
