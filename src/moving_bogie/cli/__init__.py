"""Command line interface: ``moving-bogie COMMAND [options]`` (argparse).

Each subcommand lives in its own module of this package that exposes ``register(subparsers)``; the
parser it adds must ``set_defaults(handler=run)`` with ``run(args) -> int``. Adding a subcommand is
one line in :data:`SUBCOMMAND_MODULES`. Subcommand modules are imported for every invocation (to
build ``--help``), so they should import heavy dependencies inside ``run``.
"""

from __future__ import annotations

import argparse
import importlib
import sys
from collections.abc import Sequence

from moving_bogie import __version__

from .outputs import check_input_paths, check_output_paths
from .reporting import PROG, Parser, UsageError, handle_errors, suggest_option, usage_failure

__all__ = ["SUBCOMMAND_MODULES", "build_parser", "main"]

#: Modules of this package that define subcommands, in the order ``--help`` lists them.
SUBCOMMAND_MODULES: list[str] = [
    "models_cmd",
    "params_cmd",
    "frequencies_cmd",
    "reproduce_cmd",
    "validate_cmd",
    "timeseries_cmd",
    "velocity_cmd",
    "stability_cmd",
    "lines_cmd",
    "compare_cmd",
    "sweep_cmd",
    "soil_cmd",
]


def build_parser() -> Parser:
    """The ``moving-bogie`` parser with every subcommand of :data:`SUBCOMMAND_MODULES` registered."""
    parser = Parser(
        prog=PROG,
        description=(
            "Stability and vibrations of a bogie moving on an infinite beam on a viscoelastic "
            "foundation (Dimitrovova 2025). Run 'moving-bogie COMMAND --help' for a command's options."
        ),
    )
    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    subparsers = parser.add_subparsers(title="commands", metavar="COMMAND", required=True)
    for name in SUBCOMMAND_MODULES:
        importlib.import_module(f"{__name__}.{name}").register(subparsers)
    parser.commands = subparsers.choices  # the subcommand parsers by name (read by suggest_option)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line `argv` (default: ``sys.argv[1:]``) and return the exit status.

    Usage errors and expected failures print one line naming the option (a JSON object on stdout with
    ``--json``) and return 2 (see :mod:`~moving_bogie.cli.reporting`). Every output option and input path
    is checked (:func:`~moving_bogie.cli.outputs.check_output_paths`,
    :func:`~moving_bogie.cli.outputs.check_input_paths`) before the command computes anything.
    """
    argv = list(sys.argv[1:] if argv is None else argv)
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except UsageError as exc:
        return usage_failure(suggest_option(exc, argv, parser.commands), argv)

    def run(args: argparse.Namespace) -> int | None:
        check_output_paths(args)
        check_input_paths(args)
        return args.handler(args)

    return handle_errors(run, argv)(args)
