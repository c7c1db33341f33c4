"""``moving-bogie params``: show the parameters a case, file and overrides resolve to."""

from __future__ import annotations

import argparse
import dataclasses
from fractions import Fraction

from moving_bogie.model.params import DimensionlessParams
from moving_bogie.model.physical import PhysicalParams

from .common import add_json_option, add_parameter_options, params_from_args, print_json

_SCALE_UNITS = {
    "chi": "1/m",
    "v_ref": "m/s",
    "w_st": "m",
    "t_scale": "s",
    "load": "N (P / 2, the unit of force)",
}


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``params`` subcommand."""
    parser = subparsers.add_parser(
        "params",
        help="show the resolved model parameters",
        description=(
            "Resolve a Table 1 case or a TOML parameter file plus overrides, validate them and print\n"
            "the dimensionless parameters of Eqs. (15)-(17), (59), (63). For a [physical] file, also\n"
            "print the SI parameters and the reference scales of Eqs. (15)-(16). The last line says whether\n"
            "the speed is above the critical velocity of the track (supercritical)."
        ),
        epilog="examples:\n  moving-bogie params --case 7\n  moving-bogie params --case 1 --alpha 0.5 --json",
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    add_parameter_options(parser)
    add_json_option(parser)
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Print the parameters selected by `args`."""
    params, physical = params_from_args(args)

    from moving_bogie.api import speed_regime

    regime = speed_regime(params, physical)
    if args.json:
        print_json(
            {
                "dimensionless": params.to_dict(),
                "physical": None if physical is None else physical.to_dict(),
                "scales": None if physical is None else dataclasses.asdict(physical.scales()),
                "speed": regime.to_dict(),
            }
        )
    else:
        print(format_table(params, physical))
        print()
        print(regime.line())
    return 0


def params_text(value: Fraction) -> str:
    """A Fraction as decimal text (exact where finite)."""
    from moving_bogie.model.exact import fraction_to_text

    return fraction_to_text(value)


def format_table(params: DimensionlessParams, physical: PhysicalParams | None) -> str:
    """Aligned text table of the parameters (and, if given, SI parameters and scales)."""
    model = params.model
    rows = [(key, getattr(params, key), "model") for key in ("beam", "track", "vehicle")]
    for name, spec in model.specs.items():
        rows.append((name, params.to_dict()[name], f"{spec.meaning}, Eq. {spec.equation}"))
    for name, meta in model.alternatives.items():
        rows.append((name, params.to_dict()[name], meta["meaning"]))
    sections = [(f"Dimensionless parameters of {model.name}", rows)]
    if physical is not None:
        units = physical.units()
        values = physical.values()
        sections.append(
            (
                "Physical parameters (SI)",
                [(name, str(params_text(values[name])), units[name]) for name in values],
            )
        )
        scales = dataclasses.asdict(physical.scales())
        rows = [(name, repr(value), _SCALE_UNITS[name]) for name, value in scales.items()]
        sections.append(("Scales, Eqs. (15)-(16)", rows))
    name_width = max(len(row[0]) for _, rows in sections for row in rows)
    value_width = max(len(row[1]) for _, rows in sections for row in rows)
    blocks = []
    for title, rows in sections:
        lines = [f"  {name:<{name_width}}  {value:<{value_width}}  {note}" for name, value, note in rows]
        blocks.append("\n".join([title, *lines]))
    return "\n\n".join(blocks)
