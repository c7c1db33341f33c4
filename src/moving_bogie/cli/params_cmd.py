"""``moving-bogie params``: show the parameters a case, file and overrides resolve to."""

from __future__ import annotations

import argparse
import dataclasses

from moving_bogie.model.params import DimensionlessParams
from moving_bogie.model.physical import PHYSICAL_UNITS, PhysicalParams

from .common import add_json_option, add_parameter_options, params_from_args, print_json

#: One-line meaning of each dimensionless parameter, with its defining equation.
DESCRIPTIONS = {
    "eta_f": "foundation damping c_f/(2 sqrt(m k_f)), Eq. (17)",
    "eta_M": "wheel mass M chi/m, Eq. (17)",
    "d": "wheel spacing d chi, Eq. (16)",
    "mu_v": "bar mass M_b chi/m = cf1 eta_M, Eqs. (17), (63)",
    "J_b": "bar inertia chi^3 J_b/m = cf2 eta_M d^2, Eqs. (17), (63)",
    "kappa_v": "suspension stiffness k_v chi/k_f, Eq. (17)",
    "eta_v": "suspension damping c_v chi/(2 sqrt(m k_f)), Eq. (17)",
    "alpha": "velocity v/v_ref, Eq. (16)",
    "eta_s": "shear layer k_s/(2 sqrt(k_f EI))",
    "beam": "eb Euler-Bernoulli, tr Timoshenko-Rayleigh",
    "S": "shear G Abar/(2 sqrt(k_f EI)), Eq. (59)",
    "r": "radius of gyration r chi, Eq. (59)",
    "cf1": "M_b/M, Eq. (64)",
    "cf2": "J_b/(M d^2), Eq. (64)",
}
_SCALE_UNITS = {"chi": "1/m", "v_ref": "m/s", "w_st": "m", "t_scale": "s"}


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``params`` subcommand."""
    parser = subparsers.add_parser(
        "params",
        help="show the resolved model parameters",
        description=(
            "Resolve a Table 1 case or a TOML parameter file plus overrides, validate them and print\n"
            "the dimensionless parameters of Eqs. (15)-(17), (59), (63). For a [physical] file, also\n"
            "print the SI parameters and the reference scales of Eqs. (15)-(16)."
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
    if args.json:
        print_json(
            {
                "dimensionless": params.to_dict(),
                "physical": None if physical is None else physical.to_dict(),
                "scales": None if physical is None else dataclasses.asdict(physical.scales()),
            }
        )
    else:
        print(format_table(params, physical))
    return 0


def format_table(params: DimensionlessParams, physical: PhysicalParams | None) -> str:
    """Aligned text table of the parameters (and, if given, SI parameters and scales)."""
    rows = [(name, value or "-", DESCRIPTIONS[name]) for name, value in params.to_dict().items()]
    sections = [("Dimensionless parameters", rows)]
    if physical is not None:
        sections.append(
            (
                "Physical parameters (SI)",
                [(name, value or "-", PHYSICAL_UNITS[name]) for name, value in physical.to_dict().items()],
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
