"""The critical-velocity subcommand (Section 3.5, Eq. (16)) on any track: a continuous one (the paper's), a
rail on sleepers (its smeared track, the pinned-pinned and sleeper-passing frequencies) or a track on the
soil (:mod:`.soil_cmd`)."""

from __future__ import annotations

import argparse
import math
from pathlib import Path
from typing import TYPE_CHECKING, Any

from moving_bogie.model.catalogue import Model, ParameterSpec, default_catalogue

if TYPE_CHECKING:
    from moving_bogie.model.params import DimensionlessParams
    from moving_bogie.model.physical import PhysicalParams
    from moving_bogie.model.scales import Scales

from .checks import decimal_number
from .common import (
    add_json_option,
    add_set_option,
    apply_settings,
    print_json,
    soil_file_given,
)
from .outputs import add_figure_option
from .stability_options import (
    RAW,
)

BEAM_CHOICES = tuple(default_catalogue().beams)


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add critical-velocity."""
    _register_critical_velocity(subparsers)


def _track_groups() -> dict[str, ParameterSpec]:
    """Groups of the tracks (every foundation's, without alpha and the damping groups): name -> spec."""
    catalogue = default_catalogue()
    names: set[str] = set()
    for model in catalogue.models():
        module = model.foundation
        names |= set(module.MODEL_PARAMETERS) - {"alpha"} - set(getattr(module, "DAMPING", ()))
    return {name: spec for name, spec in catalogue.specs.items() if name in names}


def _register_critical_velocity(subparsers: argparse._SubParsersAction) -> None:
    p = subparsers.add_parser(
        "critical-velocity",
        help="critical velocity of a constant moving force, Eqs. (65)-(66), checked numerically",
        description=(
            "Critical velocity alpha_cr of a constant force: the smallest local minimum of the phase speed\n"
            "Omega_j(p)/p of free waves over the dispersion branches of the undamped track (a real double\n"
            "root of N(p, 0) in p), polished at 30 digits, with every local minimum and its branch, next to\n"
            "the closed form of Eq. (65) (Euler-Bernoulli, sqrt(1 + eta_s)) or Eq. (66) (Timoshenko-\n"
            "Rayleigh) on the paper's track. On a layered track the lowest branch is bounded (its phase\n"
            "speed tends to 0), so the global infimum is 0 and only local minima are critical velocities."
        ),
        epilog=(
            "examples:\n  moving-bogie critical-velocity --eta-s 0.5\n"
            "  moving-bogie critical-velocity --beam tr --S 100 --r 0.03 --json\n"
            "  moving-bogie critical-velocity --file examples/two-layer.toml\n"
            "  moving-bogie critical-velocity --file examples/sleepers.toml --set v=80\n"
            "On a sleeper track (docs/sleepers.md): the critical velocity of the smeared track (the\n"
            "supports spread along the rail), the rail's pinned-pinned frequency and the sleeper-passing\n"
            "frequency 2 pi v / l."
        ),
        formatter_class=RAW,
    )
    p.add_argument("--beam", choices=BEAM_CHOICES, default=None, help="beam (default eb, or the file's)")
    p.add_argument(
        "--track",
        choices=tuple(default_catalogue().tracks),
        default=None,
        help="track (default one-layer, or the file's; moving-bogie models lists them)",
    )
    p.add_argument(
        "--file",
        type=Path,
        metavar="F.toml",
        help="take the track from a parameter file; [physical] adds v_cr in m/s",
    )
    for name, spec in _track_groups().items():
        p.add_argument(
            spec.option, dest=name, type=decimal_number, default=None, metavar="X", help=f"{spec.meaning}"
        )
    add_figure_option(p, "--plot", help="write the dispersion figure (a track on soil: docs/soil.md)")
    add_set_option(p)
    add_json_option(p)
    p.set_defaults(handler=run_critical_velocity)


def run_critical_velocity(args: argparse.Namespace) -> int:
    from moving_bogie.errors import ParameterError
    from moving_bogie.model.catalogue import get_model

    physical = None
    groups = {name: getattr(args, name) for name in _track_groups() if getattr(args, name) is not None}
    chosen = {k: getattr(args, k) for k in ("beam", "track") if getattr(args, k) is not None}
    if soil_file_given(args):
        if chosen or groups:
            raise ParameterError(
                next(iter({**chosen, **groups})), "give a soil-track file's values in the file"
            )
        from .soil_cmd import run_soil_critical_velocity

        return run_soil_critical_velocity(args)
    if args.plot is not None:
        raise ParameterError(
            "plot", "--plot draws the dispersion figure of a track on soil (a soil-track --file)"
        )
    if args.file is not None:
        from .common import read_params_file

        params, physical = read_params_file(args.file)
        if args.set:
            physical, params = apply_settings(physical, args.set)
        if params.model.periodic:
            return _critical_velocity_on_supports(args, params, physical, chosen | groups)
        if chosen or groups:
            params = params.replace(**chosen, **groups)
            if physical is not None:
                physical = physical.with_dimensionless(params)
        source: DimensionlessParams | Model = params
    else:
        source = get_model(**chosen)

    from moving_bogie.paper.critical_velocity_formulas import paper_formula
    from moving_bogie.stability.velocity.critical_velocity import critical_velocity

    res = critical_velocity(source, groups=groups, formula=paper_formula)
    data = res.to_dict()
    if physical is not None:
        v_ref = physical.scales().v_ref
        data["v_cr"] = f"{float(data['alpha_cr']) * v_ref:.10g}"
        data["v_cr_unit"] = "m/s"
        for minimum in data["minima"]:
            minimum["v"] = f"{float(minimum['alpha']) * v_ref:.10g}"
    if args.json:
        print_json(data)
    else:
        print("\n".join(critical_velocity_lines(data, None if physical is None else physical.scales())))
    return 0


def _critical_velocity_on_supports(
    args: argparse.Namespace, params: DimensionlessParams, physical: PhysicalParams | None, given: dict
) -> int:
    """critical-velocity of a track on periodic supports: that of its smeared track (the supports spread
    along the rail, docs/sleepers.md), its pinned-pinned frequency and the sleeper-passing frequency."""
    from moving_bogie.api import bind_with_scales
    from moving_bogie.errors import ParameterError
    from moving_bogie.kernels.periodic_track import PeriodicTrack
    from moving_bogie.model.smeared import smeared_physical
    from moving_bogie.paper.critical_velocity_formulas import paper_formula
    from moving_bogie.stability.velocity.critical_velocity import critical_velocity

    if given:
        flag = "--" + next(iter(given)).replace("_", "-")
        why = f"{flag} does not apply to a sleeper track: use --set NAME=VALUE"
        raise ParameterError(flag.lstrip("-"), why)
    smeared = smeared_physical(physical) if physical is not None else None
    if smeared is None or physical is None:
        raise ParameterError("track", f"{params.model.name} has no smeared continuous track")
    bound, own = bind_with_scales(physical)
    assert isinstance(bound.track, PeriodicTrack) and own is not None
    res = critical_velocity(smeared.to_dimensionless(), formula=paper_formula)
    data = res.to_dict()
    scales = smeared.scales()
    data["v_cr"] = f"{float(data['alpha_cr']) * scales.v_ref:.10g}"
    data["v_cr_unit"] = "m/s"
    for minimum in data["minima"]:
        minimum["v"] = f"{float(minimum['alpha']) * scales.v_ref:.10g}"
    track = bound.track.sleepers
    to_si = 1 / own.t_scale
    pinned, passing = track.pinned_pinned() * to_si, track.Omega0 * to_si
    data["on_supports"] = {
        "model": params.model.name,
        "smeared_track": smeared.model.name,
        "alpha_cr": float(res.alpha_cr) * scales.v_ref / own.v_ref,
        "pinned_pinned_rad_s": pinned,
        "pinned_pinned_hz": pinned / (2 * math.pi),
        "sleeper_passing_rad_s": passing,
        "sleeper_passing_hz": passing / (2 * math.pi),
    }
    if args.json:
        print_json(data)
        return 0
    lines = critical_velocity_lines(data, scales)
    supports = data["on_supports"]
    lines.append(f"on supports      {supports['model']}: v_cr of the smeared track ({smeared.model.name})")
    lines.append(f"pinned-pinned    {pinned:.6g} rad/s ({supports['pinned_pinned_hz']:.6g} Hz)")
    lines.append(f"sleeper passing  {passing:.6g} rad/s ({supports['sleeper_passing_hz']:.6g} Hz) at v")
    print("\n".join(lines))
    return 0


def critical_velocity_lines(data: dict[str, Any], scales: Scales | None) -> list[str]:
    """The readable critical velocity: in the groups (alpha_cr, p_cr), or in SI for SI parameters (v_cr
    [m/s] and the critical wavelength 2 pi / (p_cr chi) [m], Eq. (16))."""
    lines = []
    if scales is not None:
        wavelength = 2 * math.pi / (float(data["p_cr"]) * scales.chi)
        lines.append(
            f"v_cr             {data['v_cr']} m/s  (wavelength {wavelength:.6g} m, branch {data['branch']}, "
            f"{data['digits']} digits confirmed)"
        )
    lines.append(f"model            {data['model']}  ({data['branches']} dispersion branch(es))")
    if scales is None:
        lines.append(
            f"alpha_cr         {data['alpha_cr']}  (p_cr = {data['p_cr']}, branch {data['branch']}, "
            f"{data['digits']} digits confirmed)"
        )
    if data["formula"]:
        shown = "" if scales is not None else f"{data['alpha_cr_formula']}  "
        lines.append(f"closed form      {shown}({data['formula']}; agrees: {data['agrees']})")
    for minimum in data["minima"]:
        where = (
            f"v = {minimum['v']} m/s"
            if scales is not None
            else f"alpha = {minimum['alpha']} at p = {minimum['p']}"
        )
        lines.append(f"local minimum    branch {minimum['branch']}: {where}")
    for j in data["branches_without_minimum"]:
        lines.append(f"branch {j}         no local minimum of the phase speed on 0 < p <= {data['p_max']}")
    if "note" in data:
        lines.append(f"note             {data['note']}")
    lines.append(f"method           {data['method']}")
    return lines
