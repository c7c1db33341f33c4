"""``moving-bogie models``: the models of the generated catalogue, one line each, or with their parameters."""

from __future__ import annotations

import argparse
import textwrap
from collections.abc import Sequence

from moving_bogie.errors import ParameterError, suggestion
from moving_bogie.model.catalogue import Model, default_catalogue
from moving_bogie.model.physical import PER_RAIL_CONVENTION

from .common import add_json_option, print_json


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``models`` subcommand."""
    parser = subparsers.add_parser(
        "models",
        help="list every model (beam x track x vehicle), one line each; NAME or --verbose for the parameters",
        description=(
            "List the models of the generated catalogue, one line each: beam/track/vehicle, the degrees\n"
            "of N and Q in p (Eq. (24)) and the number of dimensionless parameters. With a\n"
            "model NAME (as listed: beam/track/vehicle), or --verbose for every model, each parameter: its\n"
            "meaning, range, default, defining equation, command-line option and SI counterpart with its\n"
            "unit. Everything comes from derivations/ through python -m derivations. SI inputs are per rail\n"
            "(one rail and the half vehicle on it); the listing ends with the convention and the\n"
            "whole-vehicle conversion."
        ),
        epilog=(
            "examples:\n  moving-bogie models\n  moving-bogie models eb/one-layer/bogie\n"
            "  moving-bogie models --verbose\n  moving-bogie models --json"
        ),
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    parser.add_argument("name", nargs="?", metavar="NAME", help="one model's parameters (beam/track/vehicle)")
    parser.add_argument("--verbose", "-v", action="store_true", help="every model with its parameters")
    add_json_option(parser)
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Print the catalogue: one line per model, or the parameters of NAME (of every model with --verbose)."""
    catalogue = default_catalogue()
    models = catalogue.models()
    if args.name is not None:
        chosen = [model for model in models if model.name == args.name]
        if not chosen:
            hint = suggestion(args.name, [model.name for model in models], listing="one of")
            raise ParameterError("model", f"no model {args.name!r}; {hint}")
        models = chosen
    if args.json:
        print_json({"models": [model.to_dict() for model in models], "convention": PER_RAIL_CONVENTION})
        return 0
    if args.verbose or args.name is not None:
        print(format_catalogue(models))
    else:
        print(format_summary(models))
    return 0


def format_summary(models: Sequence[Model]) -> str:
    """One line per model: its name, the degrees of N and Q in p, its parameters; then where to look next."""
    width = max(len(model.name) for model in models)
    lines = [f"{len(models)} models (beam/track/vehicle):"]
    for model in models:
        degrees = model.degrees
        supports = "; periodic supports (one strip of width Omega_0)" if model.periodic else ""
        lines.append(
            f"  {model.name:<{width}}  N of degree {degrees['N_in_p']}, Q of degree {degrees['Q_in_p']} "
            f"in p; {len(model.specs)} parameters{supports}"
        )
    lines.append(
        "a model's parameters, their SI units and the per-rail convention of SI inputs: "
        "moving-bogie models NAME (every model: --verbose)"
    )
    return "\n".join(lines)


def format_catalogue(models: Sequence[Model]) -> str:
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
        if model.periodic:
            scales = ", ".join(f"{k} [{v['unit']}]" for k, v in model.scale_parameters.items())
            lines.append(f"  on periodic supports (docs/sleepers.md); SI scale parameters: {scales}")
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
