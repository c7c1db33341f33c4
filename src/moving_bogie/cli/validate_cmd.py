"""``moving-bogie validate``: the finite beam against the closed form, side by side (Section 3.2); on periodic
supports the finite rail against the Floquet theory (docs/sleepers.md, "The finite rail on sleepers")."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from moving_bogie.model.params import DimensionlessParams
    from moving_bogie.model.physical import PhysicalParams
    from moving_bogie.validation.verdict import ValidationResult

from .checks import count, number
from .common import add_json_option, add_parameter_options, params_from_args, print_json, refuse_for_sleepers
from .outputs import add_figure_option
from .validate_output import format_result


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``validate`` subcommand."""
    parser = subparsers.add_parser(
        "validate",
        help="finite-beam validation of the closed-form time series (paper, Section 3.2)",
        description=(
            "Run the finite-beam modal model (simply supported beam, --modes sine modes, with the\n"
            "quasi-static response of the truncated modes added back; on a layered track each mode of\n"
            "the rail coupled with the same mode of every mass layer) and the closed-form response on\n"
            "one tau grid, and compare the rear- and front-wheel deflections, the bar bounce and the bar\n"
            "pitch over the window before reflections from the supports can matter. They agree when\n"
            "every quantity's largest difference is within --tol (default 1 %) of its largest value\n"
            "over the window. A second run with twice the time step estimates the finite beam's own\n"
            "error, for information (see docs/finite_beam.md).\n"
            "Exit status 1 when some quantity differs by more than --tol, 2 on bad input."
        ),
        epilog=(
            "examples:\n  moving-bogie validate --case 7\n"
            "  moving-bogie validate --case 7 --beam tr --S 10 --r 0.09\n"
            "  moving-bogie validate --file examples/two-layer.toml\n"
            "  moving-bogie validate --case 1 --tmax 400 --plot case1.png\n"
            "  moving-bogie validate --case 2 --modes 1000 --json\n"
            "  moving-bogie validate --case 5 --model masses --plot masses5.png\n"
            "  moving-bogie validate --file examples/sleepers.toml --plot sleepers.png\n"
            "On a sleeper track (--file naming track = sleepers or sleepers-two-layer) the finite rail is\n"
            "compared with the Floquet theory instead: the growth rate and dominant frequency of the free\n"
            "vibration (unstable case) or the steady contact force over a bay (stable case); see\n"
            "docs/sleepers.md."
        ),
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    add_parameter_options(parser)
    parser.add_argument(
        "--modes",
        type=count(4, 20_000),
        default=500,
        metavar="N",
        help="sine modes of the finite beam (default 500)",
    )
    parser.add_argument(
        "--tmax",
        type=number,
        metavar="T",
        help="end of the run in dimensionless time (default 200 with foundation damping, 100 without)",
    )
    parser.add_argument(
        "--tol",
        type=number,
        default=0.01,
        metavar="X",
        help="relative tolerance per quantity, a fraction of its largest value (default 0.01)",
    )
    parser.add_argument(
        "--no-correction",
        action="store_true",
        help="plain N-mode finite beam, without the static correction of the truncated modes",
    )
    parser.add_argument(
        "--no-estimate",
        action="store_true",
        help="skip the second run (twice the time step) of the error estimate",
    )
    add_figure_option(parser, "--plot", help="write the paper-style figure (PNG, PDF, SVG, ...)")
    add_json_option(parser)
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """One call of :func:`moving_bogie.validate` (the finite beam against the closed form, or on periodic
    supports the finite rail against the Floquet theory: the library dispatches on the bound model, and
    gives one result type), with the options of that track (:data:`_CHECK_OPTIONS`); its figure, its JSON
    or its table."""
    params, physical = params_from_args(args) if args.file is not None else (None, None)
    periodic = params is not None and params.model.periodic
    options = _CHECK_OPTIONS[periodic](args)  # every option checked before the heavy imports
    if params is None:
        params, physical = params_from_args(args)
    from moving_bogie.api import validate

    from .progress import progress_bar

    target = physical if physical is not None else params  # SI parameters: the check in SI where it has it
    with progress_bar(_WHAT[periodic], enabled=not args.json) as update:
        result = validate(target, progress=update, **options)
    if args.plot:
        from moving_bogie.response.plots import save_figure

        save_figure(_figure(args, result, target), args.plot, dpi=150)
    data = result.to_dict()
    if args.case is not None:
        data["case"] = args.case
    if args.plot:
        data["plot"] = str(args.plot)
    if args.json:
        print_json(data)
    else:
        print(format_result(result))
        if args.plot:
            print(f"figure written to {args.plot}")
    return 0 if result.agrees else 1


def _tolerance(args: argparse.Namespace) -> None:
    from moving_bogie.errors import ParameterError

    if not (0 < args.tol < 1):
        raise ParameterError("tol", f"--tol must be a fraction between 0 and 1 (got {args.tol})")


def _beam_options(args: argparse.Namespace) -> dict[str, Any]:
    """The finite beam's options, checked (one message naming the first wrong)."""
    from moving_bogie.errors import ParameterError

    if args.modes < 4:
        raise ParameterError("modes", f"--modes must be at least 4 (got {args.modes})")
    if args.tmax is not None and not (args.tmax > 0 and args.tmax < float("inf")):
        raise ParameterError("tmax", f"--tmax must be a positive number (got {args.tmax})")
    _tolerance(args)
    return {
        "n_modes": args.modes,
        "tau_max": args.tmax,
        "tol": args.tol,
        "static_correction": not args.no_correction,
        "estimate": not args.no_estimate,
    }


def _rail_options(args: argparse.Namespace) -> dict[str, Any]:
    """On periodic supports ``--tol`` only: the finite beam's options refused by name."""
    _tolerance(args)
    _refuse_on_supports(args)
    return {"tol": args.tol}


#: The options each kind of track's check takes (by ``params.model.periodic``), and what its progress
#: bar names.
_CHECK_OPTIONS = {False: _beam_options, True: _rail_options}
_WHAT = {False: "finite beam + closed form", True: "Floquet theory + finite rail"}


def _figure(
    args: argparse.Namespace, result: ValidationResult, params: DimensionlessParams | PhysicalParams
) -> Figure:
    """The paper-style figure of the check (:func:`~moving_bogie.validation.plots.check_figure`: on sleepers
    the finite rail's, titled by the model and its speed)."""
    from moving_bogie.validation.plots import check_figure
    from moving_bogie.validation.verdict import beam_title

    name = f"Case {args.case}" if args.case is not None else "moving bogie"
    beam = f", {beam_title(params)}"
    track = getattr(params, "track", "one-layer")
    beam += "" if track == "one-layer" else f", {track} track"
    title = f"{name} ({args.model}{beam}): finite beam (solid) vs closed form (dashed)"
    return check_figure(result, params, title=title)


# --- on periodic supports -----------------------------------------------------------------------------

#: options of ``validate`` that the continuous tracks' check takes and a sleeper file does not, and why
_MODEL = "give the model in the file"
_NOT_HERE = {
    "case": _MODEL, "beam": _MODEL, "track": _MODEL, "vehicle": _MODEL,
    "tmax": "the check runs its own times (growth over periods, a steady bay)",
    "no_correction": "the rail on sleepers is meshed in beam elements, not in truncated sine modes",
    "no_estimate": "the rail on sleepers has no second run of the error estimate",
}  # fmt: skip


def _refuse_on_supports(args: argparse.Namespace) -> None:
    """One message naming the first option that does not apply to a sleeper file (before any work)."""
    from moving_bogie.errors import ParameterError

    refuse_for_sleepers(args, _NOT_HERE)
    if args.modes != 500:
        raise ParameterError(
            "modes", "--modes does not apply to a sleeper-track file: its rail is meshed in beam elements"
        )
