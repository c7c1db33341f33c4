"""``moving-bogie reproduce``: rebuild the paper's tables and figures into a folder with an index."""

from __future__ import annotations

import argparse
import sys

from .checks import count
from .outputs import add_output_option


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``reproduce`` subcommand."""
    parser = subparsers.add_parser(
        "reproduce",
        help="rebuild Table 2 and the paper's figures into a folder with index.html and index.md",
        description=(
            "Rebuild every table and figure of the paper that the software covers into DIR, and write\n"
            "DIR/index.html and DIR/index.md showing each one under the paper's caption (verbatim).\n"
            "Figure 1, a drawing rather than a computed result, is listed as 'not covered' with the reason.\n"
            "--quick (or MOVING_BOGIE_QUICK=1) uses reduced grids, short time windows and no finite-beam\n"
            "runs: a check that everything builds, in a couple of minutes. Exit status 1 when an\n"
            "artifact fails or Table 2 differs from the print, 2 on bad input."
        ),
        epilog=(
            "examples:\n  moving-bogie reproduce --out paper-figures\n"
            "  moving-bogie reproduce --out /tmp/quick --quick\n"
            "  moving-bogie reproduce --out figs --only table2 figure5 figureA3\n"
            "  moving-bogie reproduce --list"
        ),
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    add_output_option(
        parser, "--out", folder=True, metavar="DIR", help="output folder (created in a folder that exists)"
    )
    parser.add_argument(
        "--quick",
        action="store_true",
        default=None,
        help="reduced grids and time windows (default: on when MOVING_BOGIE_QUICK=1)",
    )
    parser.add_argument(
        "--only", nargs="+", metavar="ID", help="build only these artifacts (ids as listed by --list)"
    )
    parser.add_argument(
        "--dps",
        type=count(15, 1000, "digits"),
        help="working precision of the induced frequencies (default 30; quick 20)",
    )
    parser.add_argument("--list", action="store_true", help="list the artifacts and exit")
    parser.add_argument("--no-progress", action="store_true", help="no progress bar")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from moving_bogie.errors import ParameterError
    from moving_bogie.paper.registry import ARTIFACTS
    from moving_bogie.paper.reproduce import quick_from_env, reproduce

    from .progress import two_level_bar

    if args.list:
        for a in ARTIFACTS:
            note = f"  (not computed: {a.reason})" if a.recipe is None else ""
            print(f"{a.id:<10} {a.label}{note}")
        return 0
    if args.out is None:
        raise ParameterError("out", "give the output folder: --out DIR")
    if args.dps is not None and not 15 <= args.dps <= 1000:
        raise ParameterError("dps", f"dps must be between 15 and 1000 (got {args.dps})")
    quick = quick_from_env() if args.quick is None else True

    def log(line: str) -> None:
        print(line, file=sys.stderr, flush=True)

    with two_level_bar("reproducing the paper", enabled=not args.no_progress) as (update, part):
        report = reproduce(
            args.out,
            quick=quick,
            only=args.only,
            dps=args.dps,
            progress=update,
            log=log,
            artifact_progress=part,
        )
    print(
        f"wrote {report.out / 'index.html'} and index.md: {report.count('covered')} covered, "
        f"{report.count('not covered')} not covered, {report.count('failed')} failed "
        f"({report.seconds:.0f} s{', quick' if quick else ''})"
    )
    for o in report.outcomes:
        if o.status == "failed":
            print(f"  FAILED {o.artifact.label}: {o.reason}")
        elif not o.built.ok:
            print(f"  MISMATCH {o.artifact.label}: see {report.out / 'index.html'}")
    return 0 if report.ok else 1
