"""Shared pieces of the subcommands: parameter options, error reporting, atomic output files."""

from __future__ import annotations

import argparse
import json
import sys
from fractions import Fraction
from pathlib import Path
from typing import Any

from moving_bogie.errors import ParameterError
from moving_bogie.model.cases import TABLE1_CASES, table1_case
from moving_bogie.model.files import load_params_file
from moving_bogie.model.params import BEAMS, DimensionlessParams
from moving_bogie.model.physical import PhysicalParams
from moving_bogie.output import atomic_write  # noqa: F401  (re-exported for the commands)

from .outputs import add_output_option  # noqa: F401  (re-exported for the commands)
from .reporting import PROG, handle_errors  # noqa: F401  (re-exported for the commands)

__all__ = [
    "PARAMETER_OPTIONS",
    "add_json_option",
    "add_output_option",
    "add_parameter_options",
    "atomic_write",
    "handle_errors",
    "params_from_args",
    "print_json",
]


#: Override option of each dimensionless parameter: (name, option, help).
PARAMETER_OPTIONS: tuple[tuple[str, str, str], ...] = (
    ("eta_f", "--eta-f", "foundation damping ratio c_f/(2 sqrt(m k_f)), 0 <= eta_f < 1, Eq. (17)"),
    ("eta_s", "--eta-s", "Pasternak shear layer k_s/(2 sqrt(k_f EI)), >= 0"),
    ("eta_M", "--eta-M", "wheel mass ratio M chi/m, Eq. (17)"),
    ("d", "--d", "wheel spacing d chi, Eq. (16)"),
    ("cf1", "--cf1", "bar mass coefficient: mu_v = cf1 eta_M, Eq. (63)"),
    ("cf2", "--cf2", "bar inertia coefficient: J_b = cf2 eta_M d^2, Eq. (63)"),
    ("mu_v", "--mu-v", "bar mass ratio M_b chi/m, Eq. (17) (instead of --cf1)"),
    ("J_b", "--J-b", "bar mass moment of inertia chi^3 J_b/m, Eq. (17) (instead of --cf2)"),
    ("kappa_v", "--kappa-v", "primary suspension stiffness k_v chi/k_f, Eq. (17)"),
    ("eta_v", "--eta-v", "primary suspension damping c_v chi/(2 sqrt(m k_f)), Eq. (17)"),
    ("alpha", "--alpha", "velocity ratio v/v_ref, Eq. (16)"),
    ("S", "--S", "Timoshenko shear parameter G Abar/(2 sqrt(k_f EI)), Eq. (59) (with --beam tr)"),
    ("r", "--r", "radius of gyration r chi, Eq. (59) (with --beam tr)"),
)
_OPTION = {name: option for name, option, _ in PARAMETER_OPTIONS}
_REQUIRED = ("eta_f", "eta_M", "d", "cf1", "cf2", "kappa_v", "eta_v", "alpha")
_ALTERNATIVE = {"cf1": "mu_v", "cf2": "J_b"}


def _decimal_text(text: str) -> str:
    """argparse type: keep the text (converted exactly later) once it is known to be a number."""
    try:
        Fraction(text.strip())
    except (ValueError, ZeroDivisionError):
        raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None
    return text


def add_parameter_options(parser: argparse.ArgumentParser) -> None:
    """Add ``--case``, ``--file`` and one override option per dimensionless parameter to `parser`.

    Overrides are kept as decimal text and converted exactly. Read them back with :func:`params_from_args`.
    """
    source = parser.add_argument_group(
        "parameters", "Start from a Table 1 case or a TOML file, then override single parameters."
    )
    source.add_argument(
        "--case",
        type=int,
        metavar="N",
        help=f"Table 1 case of the paper ({TABLE1_CASES[0]}-{TABLE1_CASES[-1]})",
    )
    source.add_argument(
        "--file",
        type=Path,
        metavar="F.toml",
        help="TOML parameter file ([dimensionless] or [physical] table)",
    )
    for name, option, text in PARAMETER_OPTIONS:
        source.add_argument(option, dest=name, type=_decimal_text, metavar="X", help=text)
    source.add_argument(
        "--beam", choices=BEAMS, help="beam theory: eb Euler-Bernoulli, tr Timoshenko-Rayleigh"
    )


def params_from_args(args: argparse.Namespace) -> tuple[DimensionlessParams, PhysicalParams | None]:
    """Parameters selected by the options of :func:`add_parameter_options`.

    The base is ``--case`` or ``--file``; the override options then change single parameters
    (:meth:`DimensionlessParams.replace` semantics: changing eta_M or d keeps cf1 and cf2). Without a
    base, the overrides must name every required parameter. When a ``[physical]`` file is overridden,
    the physical parameters are recomputed for the same track and wheel load
    (:meth:`PhysicalParams.with_dimensionless`).

    Raises
    ------
    ParameterError
        For conflicting or missing options and invalid values.
    """
    overrides = {name: getattr(args, name) for name in (*_OPTION, "beam") if getattr(args, name) is not None}
    if args.case is not None and args.file is not None:
        raise ParameterError("case", "give either --case or --file, not both")
    if args.case is not None:
        return table1_case(args.case).replace(**overrides), None
    if args.file is not None:
        params, physical = load_params_file(args.file)
        if not overrides:
            return params, physical
        params = params.replace(**overrides)
        if physical is not None:
            physical = physical.with_dimensionless(params)
        return params, physical
    if not overrides:
        needed = " ".join(f"{_OPTION[name]} X" for name in _REQUIRED)
        raise ParameterError("case", f"no parameters given: use --case N, --file F.toml, or all of {needed}")
    for name in _REQUIRED:
        alternative = _ALTERNATIVE.get(name)
        if name not in overrides and alternative not in overrides:
            option = f"{_OPTION[name]} or {_OPTION[alternative]}" if alternative else _OPTION[name]
            raise ParameterError(
                name, f"missing parameter {name} ({option}); or start from --case N or --file F.toml"
            )
    return DimensionlessParams.from_mapping(overrides), None


def add_json_option(parser: argparse.ArgumentParser) -> None:
    """Add ``--json``: print machine-readable JSON instead of the readable table."""
    parser.add_argument("--json", action="store_true", help="print JSON instead of a readable table")


def print_json(data: Any) -> None:
    """Print `data` as indented JSON on stdout."""
    json.dump(data, sys.stdout, indent=2)
    sys.stdout.write("\n")
