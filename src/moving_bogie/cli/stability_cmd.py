"""Stability subcommands (Sections 3.5-3.8): critical-velocity, frequency-lines, instability-lines,
stability-map, critical-stiffness and stability-figure."""

from __future__ import annotations

import argparse
import sys
from fractions import Fraction
from pathlib import Path

from moving_bogie.errors import ParameterError
from moving_bogie.model.catalogue import default_catalogue

from .common import (
    MODEL_OPTIONS,
    PROG,
    add_json_option,
    add_model_options,
    add_output_option,
    add_parameter_options,
    params_from_args,
    print_json,
)
from .progress import progress_bar

BEAM_CHOICES = tuple(default_catalogue().beams)
_RAW = argparse.RawDescriptionHelpFormatter
FIGURES = (2, 3, 4, 7, 8, 16)


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the stability subcommands."""
    _register_critical_velocity(subparsers)
    _register_frequency_lines(subparsers)
    _register_instability_lines(subparsers)
    _register_stability_map(subparsers)
    _register_critical_stiffness(subparsers)
    _register_figure(subparsers)


# -- shared options -----------------------------------------------------------------------------------
def _number(text: str) -> str:
    try:
        Fraction(text.strip())
    except (ValueError, ZeroDivisionError):
        raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None
    return text


def _number_list(text: str) -> list[str]:
    return [_number(t) for t in text.split(",") if t.strip()]


def _add_track_vehicle_options(parser, *, spacing_list: bool) -> None:
    """Parameters of the instability-lines / stability-map family (no alpha, no eta_M: they are the axes)."""
    g = parser.add_argument_group("parameters", "A Table 1 case as base (optional), then overrides.")
    g.add_argument("--case", type=int, metavar="N", help="take the other parameters from Table 1 case N")
    if spacing_list:
        g.add_argument("--d", type=_number_list, metavar="D1,D2,...", help="wheel spacing(s) d (default 1)")
    else:
        g.add_argument("--d", type=_number, metavar="X", help="wheel spacing d (default 1)")
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
        g.add_argument(opt, dest=dest, type=_number, metavar="X", help=text)
    add_model_options(parser)


_DEFAULTS = dict(eta_f="0.05", eta_M=20, d=1, cf1="1.7", cf2="0.01", kappa_v="0.02", eta_v=0, alpha="0.5")


def _params_and_spacings(args):
    from moving_bogie.model.cases import table1_case
    from moving_bogie.model.params import DimensionlessParams

    base = (
        table1_case(args.case)
        if args.case is not None
        else DimensionlessParams.from_coefficients(**_DEFAULTS)
    )
    changes = {
        k: getattr(args, k) for k in ("eta_f", "eta_s", "cf1", "cf2", "kappa_v", "eta_v", "S", "r")
    } | {k: getattr(args, k, None) for k in MODEL_OPTIONS.values()}
    changes = {k: v for k, v in changes.items() if v is not None}
    spacings = args.d if isinstance(args.d, list) else ([args.d] if args.d is not None else None)
    if spacings:
        changes["d"] = spacings[0]
    params = base.replace(**changes)
    args.model = params.vehicle
    return params, [float(Fraction(d)) for d in spacings] if spacings else [float(params.d)]


# -- critical-velocity --------------------------------------------------------------------------------
def _track_groups() -> dict:
    """Groups of the tracks (every foundation's, without alpha and the damping groups): name -> spec."""
    catalogue = default_catalogue()
    names = set()
    for model in catalogue.models():
        module = model.foundation
        names |= set(module.MODEL_PARAMETERS) - {"alpha"} - set(getattr(module, "DAMPING", ()))
    return {name: spec for name, spec in catalogue.specs.items() if name in names}


def _register_critical_velocity(subparsers) -> None:
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
            "  moving-bogie critical-velocity --file examples/two-layer.toml"
        ),
        formatter_class=_RAW,
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
            spec.option, dest=name, type=_number, default=None, metavar="X", help=f"{spec.meaning}"
        )
    add_json_option(p)
    p.set_defaults(handler=run_critical_velocity)


def run_critical_velocity(args) -> int:
    from moving_bogie.model.catalogue import get_model
    from moving_bogie.stability.critical_velocity import critical_velocity

    physical = None
    groups = {name: getattr(args, name) for name in _track_groups() if getattr(args, name) is not None}
    chosen = {k: getattr(args, k) for k in ("beam", "track") if getattr(args, k) is not None}
    if args.file is not None:
        from moving_bogie.model.files import load_params_file

        params, physical = load_params_file(args.file)
        if chosen or groups:
            params = params.replace(**chosen, **groups)
            if physical is not None:
                physical = physical.with_dimensionless(params)
        source = params
    else:
        source = get_model(**chosen)
    res = critical_velocity(source, groups=groups)
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
        print(f"model            {data['model']}  ({data['branches']} dispersion branch(es))")
        print(
            f"alpha_cr         {data['alpha_cr']}  (p_cr = {data['p_cr']}, branch {data['branch']}, "
            f"{data['digits']} digits confirmed)"
        )
        if data["formula"]:
            print(
                f"closed form      {data['alpha_cr_formula']}  ({data['formula']}; agrees: {data['agrees']})"
            )
        for minimum in data["minima"]:
            v = f", v = {minimum['v']} m/s" if "v" in minimum else ""
            print(
                f"local minimum    branch {minimum['branch']}: alpha = {minimum['alpha']} "
                f"at p = {minimum['p']}{v}"
            )
        for j in data["branches_without_minimum"]:
            print(f"branch {j}         no local minimum of the phase speed on 0 < p <= {data['p_max']}")
        if "note" in data:
            print(f"note             {data['note']}")
        print(f"method           {data['method']}")
        if "v_cr" in data:
            print(f"v_cr             {data['v_cr']} m/s")
    return 0


# -- frequency-lines ----------------------------------------------------------------------------------
def _register_frequency_lines(subparsers) -> None:
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
            "  moving-bogie frequency-lines --case 1 --json"
        ),
        formatter_class=_RAW,
    )
    add_parameter_options(p)
    p.add_argument("--alpha-min", type=float, default=0.0)
    p.add_argument("--alpha-max", type=float, default=1.2)
    p.add_argument("--checkpoints", type=int, default=13, help="velocities where all roots are found afresh")
    add_output_option(p, "--plot", metavar="F.png", help="write the figure")
    add_json_option(p)
    p.set_defaults(handler=run_frequency_lines)


def run_frequency_lines(args) -> int:
    from moving_bogie.stability.frequency_lines import frequency_lines

    params, _ = params_from_args(args)
    with progress_bar("frequency lines") as bar:
        res = frequency_lines(
            params,
            args.model,
            alpha_range=(args.alpha_min, args.alpha_max),
            checkpoints=args.checkpoints,
            progress=bar,
        )
    if args.plot:
        _save(_frequency_figure(res), args.plot)
    if args.json:
        print_json(res.to_dict())
    else:
        for k, line in enumerate(res.lines, 1):
            print(
                f"line {k}: alpha {line.alpha[0]:.4f} -> {line.alpha[-1]:.4f} ({line.start} -> {line.end}), "
                f"q {line.q[0]:.6f} -> {line.q[-1]:.6f}"
            )
        for w in res.warnings:
            print(f"warning: {w}")
    return 0


def _frequency_figure(res):
    from matplotlib.figure import Figure

    n = max(1, len(res.lines))
    fig = Figure(figsize=(7, 1.9 * n + 0.6), layout="constrained")
    axs = fig.subplots(n, 1, sharex=True, squeeze=False)[:, 0]
    for ax, line in zip(axs, res.lines):
        ax.plot(line.alpha, line.q.real, color="tab:blue")
        ax2 = ax.twinx()
        ax2.plot(line.alpha, line.q.imag, color="tab:orange")
        ax.set_ylabel("Re q", color="tab:blue")
        ax2.set_ylabel("Im q", color="tab:orange")
    axs[-1].set_xlabel("alpha")
    return fig


# -- instability-lines --------------------------------------------------------------------------------
def _register_instability_lines(subparsers) -> None:
    p = subparsers.add_parser(
        "instability-lines",
        help="instability lines in the (alpha, eta_M) plane (Figures 3, 4, 7, 8)",
        description=(
            "Curves where an induced frequency is real: crossing one changes the number of unstable\n"
            "induced frequencies by one. Seeded on a grid (E_chr is a polynomial in eta_M) and traced by\n"
            "3-D pseudo-arclength continuation; each point carries its real frequency q and which side\n"
            "(larger or smaller eta_M) is the more unstable one."
        ),
        epilog=(
            "examples:\n"
            "  moving-bogie instability-lines --model masses --d 1,1.25,1.5 --eta-f 0.1 --plot f.png\n"
            "  moving-bogie instability-lines --d 1.5 --cf2 0.1 --kappa-v 0.2 --beam tr --S 10 --r 0.09"
        ),
        formatter_class=_RAW,
    )
    _add_track_vehicle_options(p, spacing_list=True)
    p.add_argument("--alpha-min", type=float, default=0.0)
    p.add_argument("--alpha-max", type=float, default=1.2)
    p.add_argument("--eta-M-max", dest="theta_max", type=float, default=200.0)
    p.add_argument(
        "--parameter", choices=("eta_M", "kappa_v", "eta_v"), default="eta_M", help="vertical axis"
    )
    p.add_argument("--q-max", type=float, default=1.5, help="largest real induced frequency searched")
    p.add_argument(
        "--verify",
        action="store_true",
        help="count unstable roots (induced_frequencies) on both sides of each branch",
    )
    add_output_option(p, "--plot", metavar="F.png", help="write the figure")
    add_json_option(p)
    p.set_defaults(handler=run_instability_lines)


def run_instability_lines(args) -> int:
    from moving_bogie.stability.instability_lines import instability_lines
    from moving_bogie.stability.line_ends import EXPLANATIONS

    params, spacings = _params_and_spacings(args)
    with progress_bar("instability lines") as bar:
        res = instability_lines(
            params,
            args.model,
            spacings=spacings,
            parameter=args.parameter,
            alpha_range=(args.alpha_min, args.alpha_max),
            theta_max=args.theta_max,
            q_max=args.q_max,
            verify=args.verify,
            progress=bar,
        )
    if args.plot:
        from matplotlib.figure import Figure

        from moving_bogie.stability.plots import end_mark_handles, plot_instability_lines

        fig = Figure(figsize=(7, 5), layout="constrained")
        ax = fig.subplots()
        marks = plot_instability_lines(ax, res)
        ax.axvline(1.0, color="k", ls=":")
        ax.set_xlim(args.alpha_min, args.alpha_max)
        ax.set_ylim(0, args.theta_max)
        ax.set_xlabel("alpha")
        ax.set_ylabel(args.parameter)
        handles, _ = ax.get_legend_handles_labels()
        ax.legend(handles=handles + end_mark_handles(marks), fontsize=8)
        _save(fig, args.plot)
    if args.json:
        print_json(res.to_dict())
    else:
        for b in res.branches:
            k = len(b.alpha)
            print(
                f"d={b.d:g}: {k} points, alpha {b.alpha.min():.4f}..{b.alpha.max():.4f}, "
                f"{args.parameter} {b.theta.min():.4g}..{b.theta.max():.4g}, unstable side: {b.unstable_side}"
                + ("" if b.verified is None else f", counts below/above: {b.verified[2]}/{b.verified[4]}")
            )
            for end in b.stops_inside:
                print(
                    f"  stops inside the plot at alpha {end.alpha:.4f}, {args.parameter} {end.theta:.4g}, "
                    f"q {end.q:.4f}: {EXPLANATIONS[end.reason]}"
                )
        if res.q_max != args.q_max:
            print(f"q range raised to q_max = {res.q_max:g} (a line reached {args.q_max:g})")
        for w in res.warnings:
            print(f"{PROG}: warning: {w}", file=sys.stderr)
    return 0


# -- stability-map ------------------------------------------------------------------------------------
def _register_stability_map(subparsers) -> None:
    p = subparsers.add_parser(
        "stability-map",
        help="degree of instability over an (alpha, eta_M) grid, with the instability lines",
        description=(
            "Degree of instability (most negative Im q, 0 where stable) and number of unstable induced\n"
            "frequencies on a grid, in vectorised double precision: argument-principle counts on a contour\n"
            "in the lower half q-plane shared by a whole column of eta_M, roots by Newton's method."
        ),
        epilog=(
            "examples:\n  moving-bogie stability-map --case 1 --plot map.png --npz map.npz\n"
            "  moving-bogie stability-map --d 1.5 --n 400 --lines --plot map.png"
        ),
        formatter_class=_RAW,
    )
    _add_track_vehicle_options(p, spacing_list=False)
    p.add_argument("--alpha-min", type=float, default=0.0)
    p.add_argument("--alpha-max", type=float, default=1.2)
    p.add_argument("--eta-M-max", dest="theta_max", type=float, default=200.0)
    p.add_argument("--parameter", choices=("eta_M", "kappa_v", "eta_v"), default="eta_M")
    p.add_argument("--n", type=int, default=200, help="grid points per axis (default 200)")
    p.add_argument("--workers", type=int, default=None, help="processes (default: CPUs)")
    p.add_argument("--lines", action="store_true", help="draw the instability lines on the plot")
    add_output_option(p, "--plot", metavar="F.png", help="write the figure")
    add_output_option(p, "--npz", metavar="F.npz", help="save the arrays")
    add_output_option(
        p, "--out", folder=True, metavar="S.zarr", help="save as a 2-D sweep store (sweep-plot, xarray)"
    )
    p.add_argument("--overwrite", action="store_true", help="replace an existing --out store")
    add_json_option(p)
    p.set_defaults(handler=run_stability_map)


def run_stability_map(args) -> int:
    import numpy as np

    from moving_bogie.stability.instability_lines import instability_lines
    from moving_bogie.stability.map import stability_map

    params, _ = _params_and_spacings(args)
    if args.out is not None and args.out.exists() and not args.overwrite:
        raise ParameterError("--out", f"--out {args.out} exists: pass --overwrite to replace it")
    alphas = np.linspace(args.alpha_min, args.alpha_max, args.n)
    thetas = np.linspace(args.theta_max / args.n, args.theta_max, args.n)
    with progress_bar("stability map") as bar:
        smap = stability_map(
            params,
            args.model,
            parameter=args.parameter,
            alphas=alphas,
            thetas=thetas,
            workers=args.workers,
            progress=bar,
        )
    lines = None
    if args.lines and params.eta_f > 0:
        with progress_bar("instability lines") as bar:
            lines = instability_lines(
                params,
                args.model,
                parameter=args.parameter,
                alpha_range=(args.alpha_min, args.alpha_max),
                theta_max=args.theta_max,
                progress=bar,
            )
    if args.npz:
        args.npz.parent.mkdir(parents=True, exist_ok=True)
        smap.save_npz(args.npz)
    if args.out:
        from moving_bogie.sweep.store import write_map

        write_map(args.out, smap, overwrite=args.overwrite)
    if args.plot:
        from moving_bogie.stability.plots import plot_stability_map

        _save(plot_stability_map(smap, lines), args.plot)
    summary = smap.summary()
    if args.json:
        print_json(summary)
    else:
        for key, value in summary.items():
            if key not in ("params", "uncertain"):
                print(f"{key:18s} {value}")
        for cell in summary["uncertain"]:
            print("uncertain cell     " + ", ".join(f"{k} = {v:.6g}" for k, v in cell.items()))
    return 0


# -- critical-stiffness -------------------------------------------------------------------------------
def _register_critical_stiffness(subparsers) -> None:
    p = subparsers.add_parser(
        "critical-stiffness",
        help="critical primary-suspension stiffness over the velocity (Figure 16)",
        description=(
            "For each alpha, the kappa_v intervals where the bogie is stable or unstable: boundaries\n"
            "from the D-decomposition in kappa_v, counts from the argument principle. The parameters'\n"
            "kappa_v and alpha are ignored."
        ),
        epilog=(
            "examples:\n"
            "  moving-bogie critical-stiffness --case 5 --alpha-min 0.3 --alpha-max 1 --kappa-max 0.6"
        ),
        formatter_class=_RAW,
    )
    add_parameter_options(p)
    p.add_argument("--alpha-min", type=float, default=0.3)
    p.add_argument("--alpha-max", type=float, default=1.2)
    p.add_argument("--alphas", type=int, default=19, help="number of velocities")
    p.add_argument("--kappa-max", type=float, default=1.0)
    p.add_argument("--q-max", type=float, default=1.5)
    add_json_option(p)
    p.set_defaults(handler=run_critical_stiffness)


def run_critical_stiffness(args) -> int:
    import numpy as np

    from moving_bogie.stability.critical_stiffness import critical_stiffness

    params, _ = params_from_args(args)
    with progress_bar("critical stiffness") as bar:
        res = critical_stiffness(
            params,
            np.linspace(args.alpha_min, args.alpha_max, args.alphas),
            kappa_max=args.kappa_max,
            q_max=args.q_max,
            progress=bar,
        )
    if args.json:
        print_json(res.to_dict())
    else:
        for a, crit, ivs in zip(res.alphas, res.critical, res.intervals):
            parts = ", ".join(f"({lo:.4g}, {hi:.4g}]: {n}" for lo, hi, n in ivs)
            print(f"alpha={a:.4f}  critical kappa_v: {[round(c, 6) for c in crit]}  unstable counts: {parts}")
        for w in res.warnings:
            print(f"warning: {w}")
    return 0


# -- stability-figure ---------------------------------------------------------------------------------
def _register_figure(subparsers) -> None:
    p = subparsers.add_parser(
        "stability-figure",
        help="build Figure 2, 3, 4, 7, 8 or 16 of the paper",
        description="Build one of the paper's stability figures (plots_stability.figureN) into a PNG file.",
        epilog=(
            "examples:\n  moving-bogie stability-figure 3 --plot fig3.png\n"
            "  moving-bogie stability-figure 16 --quick --plot fig16.png"
        ),
        formatter_class=_RAW,
    )
    p.add_argument("number", type=int, choices=FIGURES)
    add_output_option(
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


def run_figure(args) -> int:
    from moving_bogie.stability import plots as plots_stability

    with progress_bar(f"figure {args.number}") as bar:
        fig = getattr(plots_stability, f"figure{args.number}")(quick=args.quick, progress=bar)
    _save(fig, args.plot)
    print(args.plot)
    return 0


def _save(fig, path: Path) -> None:
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=120)
