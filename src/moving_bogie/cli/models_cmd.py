"""``moving-bogie models``: every model of the generated catalogue with its parameters and units."""

from __future__ import annotations

import argparse
import textwrap

from moving_bogie.model.catalogue import default_catalogue
from moving_bogie.model.physical import PER_RAIL_CONVENTION

from .common import add_json_option, print_json


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``models`` subcommand."""
    parser = subparsers.add_parser(
        "models",
        help="list every model (beam x track x vehicle) with its parameters and SI units",
        description=(
            "List the models of the generated catalogue: each beam on each track under each vehicle, with\n"
            "the degrees of N and Q in p (Eq. (24)) and every dimensionless parameter: meaning, range,\n"
            "default, defining equation, command-line option and SI counterpart with its unit. Everything\n"
            "comes from derivations/ through python -m derivations. SI inputs are per rail (one rail and\n"
            "the half vehicle on it); the listing ends with the convention and the whole-vehicle conversion."
        ),
        epilog="examples:\n  moving-bogie models\n  moving-bogie models --json",
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    add_json_option(parser)
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Print the catalogue."""
    catalogue = default_catalogue()
    models = catalogue.models()
    if args.json:
        print_json({"models": [model.to_dict() for model in models], "convention": PER_RAIL_CONVENTION})
        return 0
    print(format_catalogue(models))
    return 0


def format_catalogue(models) -> str:
    """Readable listing: one block per model, one line per parameter."""
    blocks = []
    for model in models:
        degrees = model.degrees
        lines = [
            f"{model.name}  (--beam {model.beam} --track {model.track} --vehicle {model.vehicle})",
            f"  {model.foundation.DESCRIPTION}",
            f"  vehicle: {model.catalogue.vehicles[model.vehicle]}",
            f"  N of degree {degrees['N_in_p']} and Q of degree {degrees['Q_in_p']} in p",
        ]
        width = max(len(spec.option) for spec in model.specs.values())
        for spec in model.specs.values():
            default = "required" if spec.default is None else f"default {spec.default}"
            lines.append(
                f"    {spec.option:<{width}}  {spec.meaning}; {spec.range_text}, {default}, "
                f"Eq. {spec.equation};"
                f" SI {spec.si} [{spec.unit}]"
            )
        for name, meta in model.alternatives.items():
            lines.append(
                f"    --{name:<{width - 2}}  {meta['meaning']} "
                f"(instead of --{meta['sets'].replace('_', '-')})"
            )
        blocks.append("\n".join(lines))
    scale = models[0].catalogue.parameters.SCALE_PARAMETERS if models else {}
    tail = "SI scale parameters of a [physical] file: " + ", ".join(
        f"{k} [{v['unit']}]" for k, v in scale.items()
    )
    convention = "\n".join(textwrap.wrap("Convention: " + PER_RAIL_CONVENTION, 100))
    return "\n\n".join([*blocks, tail, convention])
