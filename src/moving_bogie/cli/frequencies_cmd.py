"""``moving-bogie frequencies`` and ``moving-bogie table2``: induced frequencies and the verdict."""

from __future__ import annotations

import argparse
from dataclasses import replace
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    pass

from .checks import count, exact_number
from .common import (
    add_json_option,
    add_parameter_options,
    add_units_option,
    params_from_args,
    print_json,
    si_input,
    soil_file_given,
)
from .frequencies_output import (
    report,
    with_regime,
)


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``frequencies`` and ``table2`` subcommands."""
    parser = subparsers.add_parser(
        "frequencies",
        help="all induced frequencies (roots of E_chr, Eq. (48)) and the stability verdict",
        description=(
            "Find every induced frequency q (root of E_chr, Eq. (48)) with Re q >= 0 in the search window,\n"
            "with no starting guesses: the roots are counted by the argument principle on contours that\n"
            "avoid the cut of K, located, polished at --dps digits and confirmed at higher precision.\n"
            "The motion is unstable when some root has Im q < 0. The default window holds every root with\n"
            "Im q < 0 (a radius R beyond which E_chr has none is checked first), so the verdict is about\n"
            "every root; when the search is incomplete the verdict is UNDETERMINED with the reason."
        ),
        epilog=(
            "exit status:\n"
            "  0  verdict STABLE or UNSTABLE, every root in the window found (also above the critical\n"
            "     velocity: the 'speed: SUPERCRITICAL' line, and \"supercritical\" in --json, say so)\n"
            "  1  verdict UNDETERMINED, the count and the roots found disagree (see the warnings),\n"
            "     or with --certify a root or the count is not proven\n"
            "  2  bad input (the message names the option)\n"
            "warnings and errors go to stderr; the table and the verdict to stdout. With --json an error\n"
            'is the JSON object {"error": ..., "option": ...} on stdout.\n\n'
            "examples:\n  moving-bogie frequencies --case 1\n"
            "  moving-bogie frequencies --case 7 --alpha 0.7 --json\n"
            "  moving-bogie frequencies --case 1 --beam tr --S 100 --r 0.03\n"
            "  moving-bogie frequencies --case 5 --model masses\n"
            "  moving-bogie frequencies --case 1 --certify"
        ),
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    add_parameter_options(parser)
    _add_search_options(parser)
    parser.add_argument(
        "--continued",
        action="store_true",
        help="on a rail on sleepers, also search beyond the rail's free waves: the receptance continued "
        "across them, to the depth the result states (docs/sleepers.md, 'Beyond the free waves'; about "
        "four times the time)",
    )
    add_units_option(parser)
    add_json_option(parser)
    parser.set_defaults(handler=run_frequencies)

    table = subparsers.add_parser(
        "table2",
        help="Table 2 of the paper: induced frequencies of the 13 cases of Table 1",
        description=(
            "Compute the induced frequencies of every Table 1 case and print them like the paper's Table 2\n"
            "(q^r with +-, q^i), with the printed value and the difference where the paper prints one.\n"
            "Exit status 1 on any difference beyond the print's rounding, any count mismatch or any\n"
            "UNDETERMINED verdict."
        ),
        epilog="examples:\n  moving-bogie table2\n  moving-bogie table2 --decimals 12\n"
        "  moving-bogie table2 --json\n  moving-bogie table2 --certify",
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    table.add_argument(
        "--decimals", type=count(0, 30), default=6, help="decimals shown in the text table (default 6)"
    )
    table.add_argument(
        "--dps",
        type=count(15, 1000, "digits"),
        default=30,
        help="working precision in decimal digits (default 30)",
    )
    _add_certify_option(table)
    add_json_option(table)
    table.set_defaults(handler=run_table2)


def _add_certify_option(parser: argparse._ActionsContainer) -> None:
    parser.add_argument(
        "--certify",
        action="store_true",
        help="prove every root (alone in a square of half-side 1e-26), the count and the verdict in ball "
        "arithmetic (exit status 1 if a root or a count is not proven; see docs/frequencies.md)",
    )


def _add_search_options(parser: argparse._ActionsContainer) -> None:
    parser.add_argument(
        "--dps",
        type=count(15, 1000, "digits"),
        default=30,
        help="working precision in decimal digits (default 30)",
    )
    parser.add_argument(
        "--window",
        metavar="X,Y",
        help="search window 0 <= Re q <= X, -Y <= Im q <= Y + eta_f (default: see docs/frequencies.md)",
    )
    _add_certify_option(parser)


def _check_dps(dps: int) -> None:
    from moving_bogie.errors import ParameterError

    if not 15 <= dps <= 1000:
        raise ParameterError("dps", f"dps must be between 15 and 1000 (got {dps})")


def run_frequencies(args: argparse.Namespace) -> int:
    from moving_bogie.errors import ParameterError

    if soil_file_given(args):
        from .soil_frequencies_cmd import run_soil_frequencies

        if args.continued:
            raise ParameterError(
                "continued", "--continued applies to a rail on sleepers, not a soil-track file"
            )
        return run_soil_frequencies(args)
    _check_dps(args.dps)
    params, physical = params_from_args(args)  # every input checked before the heavy imports
    periodic = params.model.periodic
    if periodic:
        _refuse_on_a_strip(args)
    elif args.continued:
        raise ParameterError("continued", "--continued applies to a rail on sleepers (periodic supports)")
    window = None
    if args.window:
        try:
            x, y = (float(exact_number(v)) for v in args.window.split(","))
        except ValueError as exc:
            reason = str(exc) if "range" in str(exc) else f"got {args.window!r}"
            raise ParameterError("window", f"window must be two numbers X,Y ({reason})") from None
        if not (x > 0 and y > 0):
            raise ParameterError("window", "window sizes must be positive")

    from moving_bogie.api import bind, induced_frequencies, speed_regime
    from moving_bogie.roots.count.contour import Rectangle
    from moving_bogie.roots.damping_limit import damping_limit

    from .progress import progress_bar

    if args.window:
        window = Rectangle(-1e-3 * x, x, -y, y + float(params.eta_f))
    if periodic:
        options: dict[str, Any] = {"continued": True} if args.continued else {}
    else:
        options = {"dps": args.dps, "window": window, "certify": args.certify}
    with progress_bar("induced frequencies", enabled=not args.json) as update:
        result = induced_frequencies(bind(params), progress=update, **options)
    physical = si_input(args, physical)  # the units shown: SI for a [physical] file unless --units says
    if physical is not None:
        result = replace(result, scales=physical.scales())
    limit = None if periodic else damping_limit(result)
    report(args, result, physical, speed_regime(params, physical), limit=limit)
    proven = result.certificate is None or result.certificate.all_proven
    return 0 if result.count_ok and result.verdict.determined and proven else 1


def _refuse_on_a_strip(args: argparse.Namespace) -> None:
    """--window and --certify do not apply to a track on periodic supports (one message, exit status 2)."""
    from moving_bogie.errors import ParameterError

    if args.window:
        raise ParameterError(
            "window",
            "--window does not apply to a sleeper track: it is searched in one strip of width Omega_0",
        )
    if args.certify:
        raise ParameterError("certify", "--certify is not available on a sleeper track (periodic supports)")


def run_table2(args: argparse.Namespace) -> int:
    from moving_bogie.roots.table2 import compute_table2, format_table2
    from moving_bogie.stability.velocity.supercritical import SUPERCRITICAL_MEANING, speed_regime

    from .progress import progress_bar

    _check_dps(args.dps)
    with progress_bar("Table 2", enabled=not args.json) as update:
        table = compute_table2(dps=args.dps, progress=update, certify=args.certify)
    regimes = [speed_regime(row.result.params) for row in table.rows]
    if args.json:
        data = table.to_dict()
        for entry, regime in zip(data["cases"], regimes):
            entry["verdict"] = with_regime(entry.get("verdict"), regime)
            entry |= {"alpha_cr": regime.alpha_cr, "supercritical": regime.supercritical}
        print_json(data)
    else:
        print(format_table2(table, decimals=args.decimals))
        above = [row.case for row, regime in zip(table.rows, regimes) if regime.supercritical]
        if above:
            print(f"speed: SUPERCRITICAL in case(s) {', '.join(map(str, above))}: {SUPERCRITICAL_MEANING}")
        else:
            known = [r.alpha / r.alpha_cr for r in regimes if r.alpha_cr is not None]
            unknown = [row.case for row, r in zip(table.rows, regimes) if r.alpha_cr is None]
            text = f"alpha / alpha_cr <= {max(known):.4g}" if known else "no critical velocity determined"
            if unknown:
                print(f"speed: critical velocity UNDETERMINED in case(s) {', '.join(map(str, unknown))}")
            else:
                print(f"speed: every case subcritical ({text}; v_cr of each track)")
    proven = all(row.result.certificate is None or row.result.certificate.all_proven for row in table.rows)
    decided = all(row.result.verdict.determined for row in table.rows)
    return 0 if table.ok and proven and decided else 1
