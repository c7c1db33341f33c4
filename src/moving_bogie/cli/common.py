"""Shared pieces of the subcommands: parameter options, error reporting, atomic output files."""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Iterable
from fractions import Fraction
from pathlib import Path
from typing import Any

from moving_bogie.errors import ParameterError
from moving_bogie.model.bar import BAR_RULES, DEFAULT_BAR
from moving_bogie.model.cases import TABLE1_CASES, table1_case
from moving_bogie.model.catalogue import Catalogue, default_catalogue
from moving_bogie.model.files import load_params_file
from moving_bogie.model.params import DimensionlessParams
from moving_bogie.model.physical import PhysicalParams
from moving_bogie.output import atomic_write  # noqa: F401  (re-exported for the commands)

from .checks import decimal_number, exact_number, named_values
from .outputs import add_output_option  # noqa: F401  (re-exported for the commands)
from .reporting import PROG, handle_errors  # noqa: F401  (re-exported for the commands)

__all__ = [
    "MODEL_OPTIONS",
    "add_model_options",
    "add_bar_option",
    "add_json_option",
    "add_output_option",
    "add_parameter_options",
    "add_set_option",
    "add_units_option",
    "apply_settings",
    "atomic_write",
    "handle_errors",
    "parameter_options",
    "params_from_args",
    "print_json",
    "read_params_file",
    "set_numbers",
    "si_input",
    "soil_settings",
    "vary_texts",
]


def _catalogue() -> Catalogue:
    return default_catalogue()


def read_params_file(path: Path) -> tuple[DimensionlessParams, PhysicalParams | None]:
    """:func:`~moving_bogie.model.files.load_params_file` whose errors name the ``--file`` option."""
    try:
        return load_params_file(path)
    except ParameterError as exc:
        raise ParameterError(exc.parameter, f"--file {exc}") from None


def parameter_options() -> list[tuple[str, str, str]]:
    """(name, option, help) of every dimensionless group and alternative, from the generated metadata."""
    catalogue = _catalogue()
    rows = [
        (s.name, s.option, f"{s.meaning}, {s.range_text}, Eq. {s.equation}") for s in catalogue.specs.values()
    ]
    for name, meta in catalogue.parameters.ALTERNATIVES.items():
        sets = catalogue.specs[meta["sets"]].option if meta["sets"] in catalogue.specs else meta["sets"]
        rows.append((name, "--" + name.replace("_", "-"), f"{meta['meaning']} (instead of {sets})"))
    return rows


def option_flag(dest: str) -> str:
    """The command-line spelling of an option's ``dest`` (``eta_f`` -> ``--eta-f``)."""
    return "--" + dest.replace("_", "-")


def first_given(
    args: argparse.Namespace, dests: Iterable[str], unset: tuple[object, ...] = (None, False)
) -> str | None:
    """The first of ``dests`` that the command line set: its value is none of ``unset`` (the parsers'
    defaults: None, and False for a flag; pass ``(None,)`` where ``--no-X`` sets False) nor an empty list.
    Compared by identity, so that a number 0 counts as given."""
    for dest in dests:
        value = getattr(args, dest, None)
        if any(value is u for u in unset) or (isinstance(value, list) and not value):
            continue
        return dest
    return None


#: The model options refused on a sleeper-track file, and why: the file sets the model.
MODEL_FROM_THE_FILE = dict.fromkeys(
    ("case", "beam", "track", "vehicle"),
    "the file's [model] and [physical] tables set the model and its SI values (--set NAME=VALUE changes one)",
)


def refuse_for_sleepers(
    args: argparse.Namespace, reasons: dict[str, str], unset: tuple[object, ...] = (None, False)
) -> None:
    """One :class:`ParameterError` naming the first option of ``reasons`` (dest -> why it does not apply)
    given for a sleeper-track file, and every parameter option (the file sets the model), before any work
    (``unset``: :func:`first_given`)."""
    why_model = "give the model and its values in the file (--set NAME=VALUE changes one)"
    table = dict(reasons) | {name: why_model for name, _, _ in parameter_options() if name not in reasons}
    dest = first_given(args, table, unset)
    if dest is not None:
        flag = option_flag(dest)
        why = table[dest]
        raise ParameterError(flag.lstrip("-"), f"{flag} does not apply to a sleeper-track file: {why}")


#: Model choices: option -> (dest, what it chooses).
MODEL_OPTIONS = {"--beam": "beam", "--track": "track", "--vehicle": "vehicle"}


def add_parameter_options(parser: argparse.ArgumentParser) -> None:
    """Add the model options, ``--case``, ``--file`` and one override option per dimensionless group.

    The groups and their options come from the generated metadata (``moving-bogie models`` lists them).
    Overrides are kept as decimal text and converted exactly. Read them back with :func:`params_from_args`.
    """
    add_model_options(parser)
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
        help="TOML parameter file ([model], and a [dimensionless] or [physical] table)",
    )
    for name, option, text in parameter_options():
        source.add_argument(option, dest=name, type=decimal_number, metavar="X", help=text)
    add_set_option(source)


def add_set_option(parser: argparse._ActionsContainer, help: str | None = None) -> None:
    """Add ``--set NAME=VALUE``: an SI parameter of a ``[physical]`` file (see :func:`apply_settings`), or
    of a soil-track file (``help`` says which)."""
    parser.add_argument(
        "--set",
        action="append",
        default=[],
        metavar="NAME=VALUE",
        help=help
        or "change an SI parameter of a [physical] --file, in its unit (e.g. --set v=900 --set M=1200; "
        "'moving-bogie models' lists the names and units, and docs/soil.md a soil-track file's); applied "
        "before the group options",
    )


def apply_settings(
    physical: PhysicalParams | None, texts: Iterable[str]
) -> tuple[PhysicalParams, DimensionlessParams]:
    """``physical`` with the ``--set NAME=VALUE`` changes (exact decimal values in the SI units), and its
    dimensionless parameters: (PhysicalParams, DimensionlessParams).

    Raises
    ------
    ParameterError
        Naming ``--set`` for malformed text, an unknown SI name, an invalid value, or no ``[physical]`` file.
    """
    if physical is None:
        raise ParameterError(
            "--set",
            "--set needs a [physical] parameter file (--file F.toml); use the group options otherwise",
        )
    changes = set_numbers(texts)
    try:
        values: dict[str, Any] = physical.values() | changes  # Fractions, passed as **values
        physical = PhysicalParams(model=physical.model, **values)
        return physical, physical.to_dimensionless()
    except ParameterError as exc:
        raise ParameterError("--set", f"--set: {exc}") from None


def set_numbers(texts: Iterable[str]) -> dict[str, Fraction]:
    """The ``--set NAME=VALUE`` texts as {NAME: exact value}; malformed text or a name given twice names
    ``--set``."""
    changes = {}
    for name, value in named_values(texts, "--set", "NAME=NUMBER").items():
        try:
            changes[name] = exact_number(value)
        except ValueError as exc:
            raise ParameterError("--set", f"--set {name}={value}: expected NAME=NUMBER ({exc})") from None
    return changes


def soil_file_given(args: argparse.Namespace) -> bool:
    """Whether ``--file`` names a soil-track file (the commands that take one hand it to their soil path)."""
    from moving_bogie.soil.file import is_soil_file

    return getattr(args, "file", None) is not None and is_soil_file(args.file)


def soil_settings(args: argparse.Namespace) -> dict[str, float]:
    """The ``--set`` changes of a soil-track file (key -> SI value; :mod:`moving_bogie.soil.settings`)."""
    return {name: float(value) for name, value in set_numbers(getattr(args, "set", None) or ()).items()}


def add_model_options(parser: argparse.ArgumentParser) -> None:
    """Add ``--beam``, ``--track`` and ``--vehicle`` (alias ``--model``), choices from the catalogue."""
    catalogue = _catalogue()
    model = parser.add_argument_group(
        "model", "The model: a beam on a track under a vehicle (default: the paper's eb, one-layer, bogie)."
    )
    model.add_argument(
        "--beam",
        choices=tuple(catalogue.beams),
        help="; ".join(f"{k}: {v}" for k, v in catalogue.beams.items()),
    )
    model.add_argument(
        "--track", choices=tuple(catalogue.tracks), help="track model (moving-bogie models lists them)"
    )
    model.add_argument(
        "--vehicle",
        "--model",
        dest="vehicle",
        choices=tuple(catalogue.vehicles),
        help=vehicle_help(catalogue) + "; --model is an alias",
    )


def vehicle_help(catalogue: Catalogue) -> str:
    """Every vehicle of the catalogue with the first clause of its description: 'mass: one wheel; ...'."""
    parts = []
    for name, text in catalogue.vehicles.items():
        short = text.split(":")[0].rstrip(".")
        parts.append(f"{name}: {short[:1].lower()}{short[1:]}")
    return "; ".join(parts)


def continuous_track_only(params: DimensionlessParams, command: str, instead: str) -> None:
    """Refuse a track on periodic supports in a command that works on continuous tracks only, naming
    ``--file`` and the command that answers on sleepers (``instead``), before any work.

    Raises
    ------
    ParameterError
        When ``params`` are of a track on periodic supports.
    """
    if params.model.periodic:
        raise ParameterError(
            "file", f"{command} works on continuous tracks, not {params.track}: on sleepers, {instead}"
        )


def params_from_args(args: argparse.Namespace) -> tuple[DimensionlessParams, PhysicalParams | None]:
    """Parameters selected by the options of :func:`add_parameter_options`.

    The base is ``--case`` or ``--file``; the model options and the override options then change it
    (:meth:`DimensionlessParams.replace` semantics: changing eta_M or d keeps cf1 and cf2). Without a
    base, the overrides must name every required parameter. When a ``[physical]`` file is overridden,
    the physical parameters are recomputed for the same track and wheel load
    (:meth:`PhysicalParams.with_dimensionless`). ``args.model`` is set to the resolved vehicle.

    Raises
    ------
    ParameterError
        For conflicting or missing options and invalid values.
    """
    options = {name: option for name, option, _ in parameter_options()}
    overrides = {name: getattr(args, name) for name in options if getattr(args, name, None) is not None}
    if getattr(args, "set", None) and args.file is None:
        apply_settings(None, args.set)  # refused: no [physical] file
    models = {k: getattr(args, k) for k in MODEL_OPTIONS.values() if getattr(args, k, None) is not None}
    if args.case is not None and args.file is not None:
        raise ParameterError("case", "give either --case or --file, not both")
    physical = None
    try:
        if args.case is not None:
            params = table1_case(args.case).replace(**models, **overrides)
        elif args.file is not None:
            params, physical = read_params_file(args.file)
            if getattr(args, "set", None):
                physical, params = apply_settings(physical, args.set)
            if (overrides or models) and physical is not None and physical.model.periodic:
                dest = next(iter(overrides or models))
                flag = options.get(dest) or option_flag(dest)
                raise ParameterError(
                    flag.lstrip("-"),
                    f"{flag} does not apply to a [physical] file on a sleeper track (periodic supports): "
                    "change its SI value with --set NAME=VALUE",
                )
            if overrides or models:
                params = params.replace(**models, **overrides)
                if physical is not None:
                    physical = physical.with_dimensionless(params)
        elif not overrides:
            raise ParameterError(
                "case",
                "no parameters given: use --case N, --file F.toml, or give every parameter as an option "
                "(moving-bogie models lists them)",
            )
        else:
            params = DimensionlessParams.from_mapping(overrides | models)
    except ParameterError as exc:
        option = options.get(exc.parameter) or next(
            (o for o, dest in MODEL_OPTIONS.items() if dest == exc.parameter), None
        )
        if option and "missing" in str(exc):
            if args.case is None and args.file is None:
                hint = f"give {option}, or start from --case N or --file F.toml"
            else:
                base = f"case {args.case} of Table 1" if args.case is not None else str(args.file)
                hint = f"{base} does not set it; give {option}, or use a file that has it"
            raise ParameterError(exc.parameter, f"{exc}: {hint}") from None
        raise
    args.model = params.vehicle
    return params, physical


def add_bar_option(parser: argparse._ActionsContainer) -> None:
    """Add ``--bar follows|fixed``: what moves with the wheel mass along an axis or a varied M (the same
    default in every map, line and sweep; :mod:`~moving_bogie.model.bar`)."""
    parser.add_argument(
        "--bar",
        choices=tuple(BAR_RULES),
        default=DEFAULT_BAR,
        help="along the wheel mass M (eta_M), the bogie's bar (frame M_b, J_b): follows (default; M_b/M and "
        "J_b/(M d^2) held, Eq. (63), the paper's convention) or fixed (M_b, J_b held at the input's values)",
    )


def add_json_option(parser: argparse.ArgumentParser) -> None:
    """Add ``--json``: print machine-readable JSON instead of the readable table."""
    parser.add_argument("--json", action="store_true", help="print JSON instead of a readable table")


def print_json(data: Any) -> None:
    """Print `data` as indented JSON on stdout."""
    json.dump(data, sys.stdout, indent=2)
    sys.stdout.write("\n")


def add_units_option(parser: argparse.ArgumentParser) -> None:
    """Add ``--units si|dimensionless``: the units a command takes and reports (see :func:`si_input`)."""
    parser.add_argument(
        "--units",
        choices=("si", "dimensionless"),
        help="units of the varied and plotted quantities: si (the SI names v, M, k_v, ... of "
        "'moving-bogie models'; needs a [physical] --file) or dimensionless (the groups alpha, eta_M, ...); "
        "default: si for a [physical] file, else dimensionless",
    )


def si_input(args: argparse.Namespace, physical: PhysicalParams | None) -> PhysicalParams | None:
    """The SI parameters the command works in (None: dimensionless), from ``--units`` and the input.

    Raises
    ------
    ParameterError
        Naming ``--units`` for ``--units si`` without a ``[physical]`` parameter file.
    """
    units = getattr(args, "units", None)
    if units == "dimensionless":
        return None
    if units == "si" and physical is None:
        raise ParameterError(
            "--units",
            "--units si needs a [physical] parameter file (--file F.toml with EI, m, k_f, P and the SI "
            "parameters): Table 1 and [dimensionless] inputs have no SI scales",
        )
    return physical


def vary_texts(texts: list[str]) -> dict[str, str]:
    """``--vary NAME=SPEC`` options as {NAME: SPEC}; a malformed one or a name given twice is refused."""
    if not texts:
        raise ParameterError("--vary", "give at least one --vary NAME=START:STOP:COUNT or NAME=V1,V2,...")
    return named_values(texts, "--vary", "NAME=START:STOP:COUNT or NAME=V1,V2,...")
