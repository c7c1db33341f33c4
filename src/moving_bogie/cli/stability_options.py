"""Options and helpers shared by the stability subcommands (Sections 3.5-3.8)."""

from __future__ import annotations

import argparse
import math
from fractions import Fraction
from pathlib import Path
from typing import TYPE_CHECKING

from moving_bogie.errors import ParameterError

from .checks import decimal_number, named_values, number_list, value_range
from .common import (
    MODEL_OPTIONS,
    add_model_options,
    add_set_option,
    add_units_option,
    apply_settings,
    parameter_options,
    si_input,
)

if TYPE_CHECKING:  # the stability package imports the numerical modules: not before the arguments are checked
    from matplotlib.figure import Figure

    from moving_bogie.model.params import DimensionlessParams
    from moving_bogie.stability.figures.plot_units import PlaneUnits

#: Help layout of the stability subcommands (their descriptions hold line breaks and formulas).
RAW = argparse.RawDescriptionHelpFormatter


def add_track_vehicle_options(parser: argparse.ArgumentParser, *, spacing_list: bool) -> None:
    """Parameters of the instability-lines / stability-map family (no alpha, no eta_M: they are the axes)."""
    g = parser.add_argument_group("parameters", "A Table 1 case as base (optional), then overrides.")
    g.add_argument("--case", type=int, metavar="N", help="take the other parameters from Table 1 case N")
    if spacing_list:
        g.add_argument("--d", type=number_list, metavar="D1,D2,...", help="wheel spacing(s) d (default 1)")
    else:
        g.add_argument("--d", type=decimal_number, metavar="X", help="wheel spacing d (default 1)")
    for opt, dest, text in (
        ("--eta-f", "eta_f", "foundation damping (> 0; default 0.05)"),
        ("--eta-s", "eta_s", "Pasternak shear layer (default 0)"),
        ("--cf1", "cf1", "bar mass mu_v = cf1 eta_M, Eq. (63) (default 1.7)"),
        ("--cf2", "cf2", "bar inertia J_b = cf2 eta_M d^2, Eq. (63) (default 0.01)"),
        ("--kappa-v", "kappa_v", "suspension stiffness (default 0.02)"),
        ("--eta-v", "eta_v", "suspension damping (default 0)"),
        ("--S", "S", "Timoshenko shear parameter, Eq. (59) (with --beam tr)"),
        ("--r", "r", "radius of gyration, Eq. (59) (with --beam tr)"),
    ):
        g.add_argument(opt, dest=dest, type=decimal_number, metavar="X", help=text)
    g.add_argument(
        "--file",
        type=Path,
        metavar="F.toml",
        help="take the parameters from a TOML file (a layered track's too)",
    )
    for name, opt, text in track_group_options():
        g.add_argument(opt, dest=name, type=decimal_number, metavar="X", help=f"{text} (its --track)")
    add_model_options(parser)


#: Groups set by the options above, or the axes and the Eq. (63) coefficients of the plane.
_PLANE_GROUPS = {"alpha", "eta_f", "eta_s", "S", "r", "eta_M", "d", "mu_v", "J_b", "kappa_v", "eta_v"}
_PLANE_GROUPS |= {"cf1", "cf2"}


def track_group_options() -> list[tuple[str, str, str]]:
    """(name, option, help) of the groups that only some tracks have (the layers' mu_j, kappa_j, eta_j)."""
    return [row for row in parameter_options() if row[0] not in _PLANE_GROUPS]


PLANE_DEFAULTS = dict(
    eta_f="0.05", eta_M=20, d=1, cf1="1.7", cf2="0.01", kappa_v="0.02", eta_v=0, alpha="0.5"
)


def params_and_spacings(args: argparse.Namespace) -> tuple[DimensionlessParams, list[float]]:
    from moving_bogie.model.cases import table1_case
    from moving_bogie.model.params import DimensionlessParams

    if getattr(args, "file", None) is not None and args.case is not None:
        raise ParameterError("case", "give either --case or --file, not both")
    physical = None
    if getattr(args, "file", None) is not None:
        from .common import read_params_file

        base, physical = read_params_file(args.file)
        if getattr(args, "set", None):  # SI changes of a [physical] file, before the group options
            physical, base = apply_settings(physical, args.set)
    elif getattr(args, "set", None):
        apply_settings(None, args.set)  # refused: no [physical] file
    elif args.case is not None:
        base = table1_case(args.case)
    else:
        base = DimensionlessParams.from_coefficients(**PLANE_DEFAULTS)
    changes = {
        k: getattr(args, k) for k in ("eta_f", "eta_s", "cf1", "cf2", "kappa_v", "eta_v", "S", "r")
    } | {k: getattr(args, k, None) for k in MODEL_OPTIONS.values()}
    changes |= {name: getattr(args, name, None) for name, _, _ in track_group_options()}
    changes = {k: v for k, v in changes.items() if v is not None}
    spacings = args.d if isinstance(args.d, list) else ([args.d] if args.d is not None else None)
    if spacings:
        changes["d"] = spacings[0]
    try:
        params = base.replace(**changes)
    except ParameterError as exc:
        if exc.parameter in {name for name, _, _ in track_group_options()} and "missing" in str(exc):
            option = "--" + exc.parameter.replace("_", "-")
            raise ParameterError(exc.parameter, f"{exc}: give {option} or --file F.toml") from None
        raise
    if physical is not None and changes:
        physical = physical.with_dimensionless(params)
    args.model = params.vehicle
    args.physical = physical  # the SI parameters of a [physical] file (read by plane_units)
    if spacings:
        return params, [float(Fraction(d)) for d in spacings]
    return params, [] if params.d is None else [float(params.d)]  # a vehicle of one wheel has no d


def add_plane_options(parser: argparse.ArgumentParser, *, set_option: bool = True) -> None:
    """``--units``, ``--range NAME=LO:HI`` (SI names with a [physical] file) and ``--set NAME=VALUE`` (unless
    the parser has it from :func:`~moving_bogie.cli.common.add_parameter_options`) of the plane commands."""
    add_units_option(parser)
    if set_option:
        add_set_option(parser)
    parser.add_argument(
        "--range",
        action="append",
        default=[],
        metavar="NAME=LO:HI",
        help="range of an axis by its shown name: v=0:400 (m/s) and M=0:3000 (kg) with a [physical] file, "
        "alpha=0:1.2 and eta_M=0:200 otherwise (instead of --alpha-min/--alpha-max/--eta-M-max; the "
        "vertical axis starts at 0)",
    )


def plane_units(args: argparse.Namespace, params: DimensionlessParams) -> PlaneUnits:
    """How the plane of ``params`` is shown: SI for a [physical] file (unless --units dimensionless); the
    operating point is the file's own (a --file input); the vertical axis of the wheel mass says whether the
    bar follows it or is held (``--bar``)."""
    from dataclasses import replace

    from moving_bogie.stability.figures.plot_units import PlaneUnits

    physical = si_input(args, getattr(args, "physical", None))
    units = PlaneUnits.of(params, physical, operating=getattr(args, "file", None) is not None)
    parameter = getattr(args, "parameter", params.model.wheel_mass)
    bar = [m["sets"] for m in params.model.alternatives.values() if parameter in m["depends"]]
    if not bar:
        return units
    verb = "fixed" if getattr(args, "bar", "follows") == "fixed" else f"follow {units.name(parameter)}"
    return replace(units, notes={parameter: f"{', '.join(units.name(g) for g in bar)} {verb}"})


def plane_ranges(args: argparse.Namespace, units: PlaneUnits, parameter: str) -> tuple[float, float, float]:
    """(alpha_min, alpha_max, theta_max) from --alpha-min/--alpha-max/--eta-M-max, or --range in the
    shown units (converted to the groups); theta_max is nan for a command without a vertical axis."""
    alpha_min: float = args.alpha_min
    alpha_max: float = args.alpha_max
    theta_max: float = getattr(args, "theta_max", math.nan)
    axes = {units.name("alpha"): "alpha", units.name(parameter): parameter}
    for name, spec in named_values(args.range, "--range", "NAME=LO:HI").items():
        if name not in axes:
            raise ParameterError("--range", f"--range {name}: not an axis (known: {', '.join(axes)})")
        lo, hi = value_range(name, spec)
        if axes[name] == "alpha":
            alpha_min, alpha_max = units.group_value("alpha", lo), units.group_value("alpha", hi)
        elif lo != 0:
            raise ParameterError("--range", f"--range {name}={spec}: the vertical axis starts at 0")
        else:
            theta_max = units.group_value(parameter, hi)
    if alpha_min < 0:
        raise ParameterError("--range", "the velocity range must be >= 0")
    if not alpha_max > alpha_min:
        raise ParameterError(
            "--alpha-max", f"--alpha-max ({alpha_max:g}) must exceed --alpha-min ({alpha_min:g})"
        )
    if not (math.isnan(theta_max) or theta_max > 0):
        raise ParameterError("--eta-M-max", f"--eta-M-max must be positive (got {theta_max:g})")
    return alpha_min, alpha_max, theta_max


def save_figure(fig: Figure, path: Path) -> None:
    """Write a matplotlib figure (format from the suffix) atomically, at 120 dpi; the folder exists (the
    output options are checked first)."""
    from moving_bogie.response.plots import save_figure as write

    write(fig, path, dpi=120)
