"""Command line interface: ``moving-bogie COMMAND [options]`` (argparse).

Each subcommand lives in its own module of this package that exposes ``register(subparsers)``; the
parser it adds must ``set_defaults(handler=run)`` with ``run(args) -> int``. Adding a subcommand is
one line in :data:`SUBCOMMAND_MODULES`. Subcommand modules are imported for every invocation (to
build ``--help``), so they should import heavy dependencies inside ``run``.
"""

from __future__ import annotations

import argparse
import importlib
from collections.abc import Sequence

from moving_bogie import __version__

from .common import PROG, handle_errors

__all__ = ["SUBCOMMAND_MODULES", "build_parser", "main"]

#: Modules of this package that define subcommands, in the order ``--help`` lists them.
SUBCOMMAND_MODULES: list[str] = [
    "models_cmd",
    "params_cmd",
    "frequencies_cmd",
    "reproduce_cmd",
    "validate_cmd",
    "timeseries_cmd",
    "stability_cmd",
]


def build_parser() -> argparse.ArgumentParser:
    """The ``moving-bogie`` parser with every subcommand of :data:`SUBCOMMAND_MODULES` registered."""
    parser = argparse.ArgumentParser(
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
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line `argv` (default: ``sys.argv[1:]``) and return the exit status.

    Expected failures print one line ``moving-bogie: error: ...`` and return 2 (see
    :func:`~moving_bogie.cli.common.handle_errors`); usage errors exit 2 through argparse.
    """
    args = build_parser().parse_args(argv)
    return handle_errors(args.handler)(args)
