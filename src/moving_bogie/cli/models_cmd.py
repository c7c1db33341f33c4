"""``moving-bogie models``: the generated catalogue in a few lines, or one model with its parameters."""

from __future__ import annotations

import argparse
import textwrap
from collections.abc import Sequence
from typing import cast

from moving_bogie.errors import ParameterError, suggestion
from moving_bogie.model.catalogue import Model, default_catalogue
from moving_bogie.model.physical import PER_RAIL_CONVENTION

from .common import add_json_option, print_json


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``models`` subcommand."""
    parser = subparsers.add_parser(
        "models",
        help="list the models (beams x tracks x vehicles); NAME or --verbose for the parameters",
        description=(
            "List the models of the generated catalogue: its beams, tracks and vehicles (a model is one\n"
            "of each, NAME = beam/track/vehicle) and the rails on discrete supports. With a model NAME,\n"
            "or --verbose for every model, the degrees of N and Q in p (Eq. (24)) and each parameter: its\n"
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
    """Print the catalogue: its beams x tracks x vehicles in a few lines, or the parameters of NAME (of every
    model with --verbose)."""
    catalogue = default_catalogue()
    models = catalogue.models()
    if args.name is not None:
        if args.name in sleeper_tracks() and not args.json:
            print(sleeper_tracks()[args.name])
            return 0
        chosen = [model for model in models if model.name == args.name]
        if not chosen:
            names = [model.name for model in models] + list(sleeper_tracks())
            hint = suggestion(args.name, names, listing="one of")
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


def _choices(names: Sequence[str], width: int = 100, indent: int = 12) -> list[str]:
    """``names`` joined by commas, wrapped to ``width`` under an indent of ``indent``."""
    return textwrap.wrap(", ".join(names), width - indent)


def format_summary(models: Sequence[Model]) -> str:
    """The catalogue in a few lines: its beams, tracks and vehicles (each model one combination of them, all
    combinations declared, the rails on discrete supports among the tracks), and how to see one model's
    parameters."""
    beams = list(dict.fromkeys(model.beam for model in models))
    tracks = list(dict.fromkeys(model.track for model in models))
    vehicles = list(dict.fromkeys(model.vehicle for model in models))
    product = len(models) == len(beams) * len(tracks) * len(vehicles)
    every = "every beam on every track under every vehicle" if product else "these combinations"
    lines = [f"{len(models)} models, NAME = beam/track/vehicle: {every}"]
    for heading, names in (("beams", beams), ("tracks", tracks), ("vehicles", vehicles)):
        for k, line in enumerate(_choices(names)):
            lines.append(f"  {heading if k == 0 else '':<10}{line}")
    if not product:
        lines += [f"    {model.name}" for model in models]
    example = next(
        (model.name for model in models if model.vehicle == "bogie"), models[0].name if models else ""
    )
    lines.append(
        f"a model's parameters, ranges, equations and SI units: moving-bogie models NAME (e.g. {example}); "
        "every model: --verbose"
    )
    return "\n".join(lines)


def sleeper_tracks() -> dict[str, str]:
    """The rails on discrete supports (docs/sleepers.md) by name, beam/track: each one's description and SI
    inputs, as ``moving-bogie models NAME`` prints them."""
    from moving_bogie.generated import sleepers

    out = {}
    for track, meta in sleepers.TRACKS.items():
        for beam in sleepers.BEAMS:
            table = cast(dict[str, dict[str, str]], sleepers.PARAMETERS[track][beam])
            names = ", ".join(spec["si"] for spec in table.values())
            reference = cast(tuple[str, str, str], meta["reference"])  # (SI name, unit, meaning)
            out[f"{beam}/{track}"] = (
                f"{beam}/{track}  ({meta['description']}; Floquet, any vehicle)\n"
                f"  SI inputs of a [physical] file: EI, m, {reference[0]}, {names}"
            )
    return out


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
