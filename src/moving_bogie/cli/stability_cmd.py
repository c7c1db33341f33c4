"""Stability subcommands (Sections 3.5-3.8): critical-velocity, frequency-lines, critical-stiffness and
stability-figure (instability-lines and stability-map: :mod:`.lines_cmd`)."""

from __future__ import annotations

import argparse
import math
from pathlib import Path
from typing import TYPE_CHECKING, Any

from moving_bogie.model.catalogue import Model, ParameterSpec, default_catalogue

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from moving_bogie.model.params import DimensionlessParams
    from moving_bogie.model.physical import PhysicalParams
    from moving_bogie.model.scales import Scales
    from moving_bogie.stability.figures.plot_units import PlaneUnits
    from moving_bogie.stability.lines.frequency_lines import FrequencyLine, FrequencyLines

from .checks import count, decimal_number, nonnegative, positive
from .common import (
    add_json_option,
    add_parameter_options,
    add_set_option,
    apply_settings,
    continuous_track_only,
    params_from_args,
    print_json,
    si_input,
)
from .outputs import add_figure_option
from .progress import progress_bar
from .stability_options import (
    RAW,
    add_plane_options,
    plane_ranges,
    save_figure,
)

BEAM_CHOICES = tuple(default_catalogue().beams)
FIGURES = (2, 3, 4, 7, 8, 16)


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add critical-velocity, frequency-lines, critical-stiffness and stability-figure."""
    _register_critical_velocity(subparsers)
    _register_frequency_lines(subparsers)
    _register_critical_stiffness(subparsers)
    _register_figure(subparsers)


# -- critical-velocity --------------------------------------------------------------------------------
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
    from moving_bogie.soil.file import is_soil_file

    physical = None
    groups = {name: getattr(args, name) for name in _track_groups() if getattr(args, name) is not None}
    chosen = {k: getattr(args, k) for k in ("beam", "track") if getattr(args, k) is not None}
    if args.file is not None and is_soil_file(args.file):
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
    from moving_bogie.errors import ParameterError
    from moving_bogie.kernels.sleeper_track import SleeperTrack
    from moving_bogie.model.sleeper_input import sleeper_input_of
    from moving_bogie.model.smeared import smeared_physical
    from moving_bogie.paper.critical_velocity_formulas import paper_formula
    from moving_bogie.stability.velocity.critical_velocity import critical_velocity

    if given:
        flag = "--" + next(iter(given)).replace("_", "-")
        why = f"{flag} does not apply to a sleeper track: use --set NAME=VALUE"
        raise ParameterError(flag.lstrip("-"), why)
    data_in = sleeper_input_of(params, physical)
    smeared = smeared_physical(physical) if physical is not None else None
    if smeared is None:
        raise ParameterError("track", f"{params.model.name} has no smeared continuous track")
    res = critical_velocity(smeared.to_dimensionless(), formula=paper_formula)
    data = res.to_dict()
    scales = smeared.scales()
    data["v_cr"] = f"{float(data['alpha_cr']) * scales.v_ref:.10g}"
    data["v_cr_unit"] = "m/s"
    for minimum in data["minima"]:
        minimum["v"] = f"{float(minimum['alpha']) * scales.v_ref:.10g}"
    track = SleeperTrack(data_in.beam, data_in.track, data_in.groups)
    to_si = 1 / data_in.t_scale
    pinned, passing = track.pinned_pinned() * to_si, track.Omega0 * to_si
    data["on_supports"] = {
        "model": params.model.name,
        "smeared_track": smeared.model.name,
        "alpha_cr": float(res.alpha_cr) * scales.v_ref / data_in.v_ref,
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


# -- frequency-lines ----------------------------------------------------------------------------------
def _register_frequency_lines(subparsers: argparse._SubParsersAction) -> None:
    p = subparsers.add_parser(
        "frequency-lines",
        help="induced frequencies followed over the velocity (Figure 2)",
        description=(
            "Follow every induced frequency over alpha: all roots are found afresh at --checkpoints\n"
            "velocities (argument principle) and followed in between by continuation; a line ends where\n"
            "it meets the cut of K (Im q = eta_f for Euler-Bernoulli). The parameters' alpha is ignored."
        ),
        epilog=(
            "examples:\n  moving-bogie frequency-lines --case 1 --plot fig2.png\n"
            "  moving-bogie frequency-lines --case 1 --json\n"
            "  moving-bogie frequency-lines --file examples/uic60-bogie.toml --range v=0:300 --plot f.png"
        ),
        formatter_class=RAW,
    )
    add_parameter_options(p)
    p.add_argument("--alpha-min", type=nonnegative, default=0.0, help="smallest velocity alpha (default 0)")
    p.add_argument("--alpha-max", type=nonnegative, default=1.2, help="largest velocity alpha (default 1.2)")
    p.add_argument(
        "--checkpoints", type=count(2, 200), default=13, help="velocities where all roots are found afresh"
    )
    add_plane_options(p, set_option=False)
    add_figure_option(p, "--plot", help="write the figure")
    add_json_option(p)
    p.set_defaults(handler=run_frequency_lines)


def run_frequency_lines(args: argparse.Namespace) -> int:
    from moving_bogie.stability.figures.plot_units import PlaneUnits

    params, physical = params_from_args(args)
    continuous_track_only(
        params, "frequency-lines", "frequencies --file F --set v=... gives the roots at each speed"
    )
    units = PlaneUnits.of(params, si_input(args, physical), operating=args.file is not None)
    alpha_min, alpha_max, _ = plane_ranges(args, units, "alpha")

    from moving_bogie.kernels.bound import bind
    from moving_bogie.stability.lines.frequency_lines import frequency_lines

    with progress_bar("frequency lines", enabled=not getattr(args, "json", False)) as bar:
        res = frequency_lines(
            bind(params),
            alpha_range=(alpha_min, alpha_max),
            checkpoints=args.checkpoints,
            progress=bar,
        )
    if args.plot:
        save_figure(_frequency_figure(res, units), args.plot)
    if args.json:
        data = res.to_dict() | {"units": units.to_dict()}
        if units.si:
            for entry, line in zip(data["lines"], res.lines):
                entry["si"] = _line_in_si(line, units)
        print_json(data)
    else:
        x, f = units.name("alpha"), "omega" if units.si else "q"
        if units.si:
            print(f"units: SI ([physical] file): {x} [{units.unit('alpha')}], omega = q / t_scale [rad/s]")
        for k, line in enumerate(res.lines, 1):
            a, q = units.value("alpha", line.alpha), units.frequency(line.q)
            print(
                f"line {k}: {x} {a[0]:.4f} -> {a[-1]:.4f} ({line.start} -> {line.end}), "
                f"{f} {q[0]:.6f} -> {q[-1]:.6f}"
            )
        for w in res.warnings:
            print(f"warning: {w}")
    return 0


def _line_in_si(line: FrequencyLine, units: PlaneUnits) -> dict[str, Any]:
    """One frequency line in SI: the velocities and omega = q / t_scale, each with its unit."""
    omega = units.frequency(line.q)
    return {
        units.name("alpha"): {
            "values": units.value("alpha", line.alpha).tolist(),
            "unit": units.unit("alpha"),
        },
        "omega": {"re": omega.real.tolist(), "im": omega.imag.tolist(), "unit": units.frequency_unit},
    }


def _frequency_figure(res: FrequencyLines, units: PlaneUnits) -> Figure:
    """One panel per line: Re and Im of the induced frequency over the velocity (SI for a [physical] file)."""
    from matplotlib.figure import Figure

    n = max(1, len(res.lines))
    fig = Figure(figsize=(7, 1.9 * n + 0.6), layout="constrained")
    axs = fig.subplots(n, 1, sharex=True, squeeze=False)[:, 0]
    name, unit = ("omega", f" [{units.frequency_unit}]") if units.si else ("q", "")
    for ax, line in zip(axs, res.lines):
        x, q = units.value("alpha", line.alpha), units.frequency(line.q)
        ax.plot(x, q.real, color="tab:blue")
        ax2 = ax.twinx()
        ax2.plot(x, q.imag, color="tab:orange")
        ax.set_ylabel(f"Re {name}{unit}", color="tab:blue")
        ax2.set_ylabel(f"Im {name}{unit}", color="tab:orange")
        if "alpha" in units.operating:
            ax.axvline(
                units.value("alpha", units.operating["alpha"]), color="gold", lw=2, label="operating point"
            )
    axs[-1].set_xlabel(units.label("alpha"))
    return fig


# -- critical-stiffness -------------------------------------------------------------------------------
def _register_critical_stiffness(subparsers: argparse._SubParsersAction) -> None:
    p = subparsers.add_parser(
        "critical-stiffness",
        help="critical primary-suspension stiffness over the velocity (Figure 16)",
        description=(
            "For each alpha, the kappa_v intervals where the bogie is stable or unstable: boundaries\n"
            "from the D-decomposition in kappa_v, counts from the argument principle. The parameters'\n"
            "kappa_v and alpha are ignored.\n\n"
            "Undamped foundation (--eta-f 0): K on the cut (the real q-axis beyond the branch point) is\n"
            "the limit from below, eta_f -> 0+; an induced frequency is unstable when Im q < 0, a real one\n"
            "is neutral. The D-decomposition degenerates there (real induced frequencies fill whole\n"
            "intervals): the intervals come from root counts on a kappa_v grid, every change bisected, at\n"
            "eta_f = 0 exactly, with the limit eta_f -> 0+ (real roots that a small foundation damping\n"
            "destabilises count as unstable) beside them. 0 < eta_f < 1e-5 (near-undamped) gives the\n"
            "limit, to first order in eta_f. The output says which."
        ),
        epilog=(
            "examples:\n"
            "  moving-bogie critical-stiffness --case 5 --alpha-min 0.3 --alpha-max 1 --kappa-max 0.6\n"
            "  moving-bogie critical-stiffness --case 5 --eta-f 0 --alphas 3 --kappa-max 0.6"
        ),
        formatter_class=RAW,
    )
    add_parameter_options(p)
    p.add_argument("--alpha-min", type=nonnegative, default=0.3, help="smallest velocity alpha (default 0.3)")
    p.add_argument("--alpha-max", type=nonnegative, default=1.2, help="largest velocity alpha (default 1.2)")
    p.add_argument("--alphas", type=count(1, 1000), default=19, help="number of velocities")
    p.add_argument(
        "--kappa-max",
        type=positive,
        default=1.0,
        help="largest suspension stiffness kappa_v searched (default 1)",
    )
    p.add_argument(
        "--q-max", type=positive, default=1.5, help="largest real induced frequency searched (default 1.5)"
    )
    add_json_option(p)
    p.set_defaults(handler=run_critical_stiffness)


def run_critical_stiffness(args: argparse.Namespace) -> int:
    import numpy as np

    params, _ = params_from_args(args)

    from moving_bogie.kernels.bound import bind
    from moving_bogie.stability.stiffness.critical_stiffness import critical_stiffness

    with progress_bar("critical stiffness", enabled=not getattr(args, "json", False)) as bar:
        res = critical_stiffness(
            bind(params),
            np.linspace(args.alpha_min, args.alpha_max, args.alphas).tolist(),
            kappa_max=args.kappa_max,
            q_max=args.q_max,
            progress=bar,
        )
    if args.json:
        print_json(res.to_dict())
    else:
        if res.limit_intervals is not None:
            from moving_bogie.stability.maps.undamped import CONVENTION

            print(f"{res.regime} foundation (eta_f = {float(params.eta_f):g}); convention: {CONVENTION}")
            print(f"method: {res.method}")
        limits = res.limit_intervals or [None] * len(res.alphas)
        for a, crit, ivs, lim in zip(res.alphas, res.critical, res.intervals, limits):
            parts = ", ".join(f"({lo:.4g}, {hi:.4g}]: {n}" for lo, hi, n in ivs)
            print(f"alpha={a:.4f}  critical kappa_v: {[round(c, 6) for c in crit]}  unstable counts: {parts}")
            if lim is not None and res.regime == "undamped":
                parts = ", ".join(f"({lo:.4g}, {hi:.4g}]: {n}" for lo, hi, n in lim)
                print(f"              limit eta_f -> 0+ unstable counts: {parts}")
        for w in res.warnings:
            print(f"warning: {w}")
    return 0


# -- stability-figure ---------------------------------------------------------------------------------
def _register_figure(subparsers: argparse._SubParsersAction) -> None:
    p = subparsers.add_parser(
        "stability-figure",
        help="build Figure 2, 3, 4, 7, 8 or 16 of the paper",
        description="Build one of the paper's stability figures into a PNG file.",
        epilog=(
            "examples:\n  moving-bogie stability-figure 3 --plot fig3.png\n"
            "  moving-bogie stability-figure 16 --quick --plot fig16.png"
        ),
        formatter_class=RAW,
    )
    p.add_argument("number", type=int, choices=FIGURES, help="the figure of the paper")
    add_figure_option(
        p,
        "--plot",
        "--out",
        dest="plot",
        required=True,
        metavar="F.png",
        help="write the figure (--out: alias)",
    )
    p.add_argument("--quick", action="store_true", help="reduced grids (CI)")
    p.set_defaults(handler=run_figure)


def run_figure(args: argparse.Namespace) -> int:
    from moving_bogie.paper import stability_figures as plots_stability

    with progress_bar(f"figure {args.number}", enabled=not getattr(args, "json", False)) as bar:
        fig = getattr(plots_stability, f"figure{args.number}")(quick=args.quick, progress=bar)
    save_figure(fig, args.plot)
    print(args.plot)
    return 0
