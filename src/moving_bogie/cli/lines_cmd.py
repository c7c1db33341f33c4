"""Instability lines and stability maps in the (alpha, eta_M) plane (Section 3.5, Figures 3, 4, 7, 8)."""

from __future__ import annotations

import argparse
import sys

from moving_bogie.errors import ParameterError

from .common import (
    PROG,
    add_json_option,
    add_output_option,
    print_json,
)
from .progress import progress_bar
from .stability_options import (
    RAW,
    add_track_vehicle_options,
    params_and_spacings,
    save_figure,
)


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add instability-lines and stability-map."""
    _register_instability_lines(subparsers)
    _register_stability_map(subparsers)


# -- instability-lines --------------------------------------------------------------------------------
def _register_instability_lines(subparsers) -> None:
    p = subparsers.add_parser(
        "instability-lines",
        help="instability lines in the (alpha, eta_M) plane (Figures 3, 4, 7, 8)",
        description=(
            "Curves where an induced frequency is real: crossing one changes the number of unstable\n"
            "induced frequencies by one. Seeded on a grid (E_chr is a polynomial in eta_M) and traced by\n"
            "3-D pseudo-arclength continuation; each point carries its real frequency q and which side\n"
            "(larger or smaller eta_M) is the more unstable one.\n\n"
            "Undamped foundation (--eta-f 0): K on the cut (the real q-axis beyond the branch point) is\n"
            "the limit from below, eta_f -> 0+; an induced frequency is unstable when Im q < 0, a real one\n"
            "is neutral. Real induced frequencies then fill whole regions and the lines degenerate; the\n"
            "command computes instead the boundaries of instability, located by root counts on a grid with\n"
            "bisection: at eta_f = 0 exactly (kind 'undamped') and in the limit eta_f -> 0+ (kind 'limit':\n"
            "real roots that a small foundation damping destabilises count as unstable). 0 < eta_f < 1e-5\n"
            "(near-undamped) gives the limit only, to first order in eta_f. The output says so."
        ),
        epilog=(
            "examples:\n"
            "  moving-bogie instability-lines --model masses --d 1,1.25,1.5 --eta-f 0.1 --plot f.png\n"
            "  moving-bogie instability-lines --d 1.5 --cf2 0.1 --kappa-v 0.2 --beam tr --S 10 --r 0.09\n"
            "  moving-bogie instability-lines --model masses --d 1.5 --eta-f 0 --plot undamped.png"
        ),
        formatter_class=RAW,
    )
    add_track_vehicle_options(p, spacing_list=True)
    p.add_argument("--alpha-min", type=float, default=0.0, help="smallest velocity alpha (default 0)")
    p.add_argument("--alpha-max", type=float, default=1.2, help="largest velocity alpha (default 1.2)")
    p.add_argument(
        "--eta-M-max", dest="theta_max", type=float, default=200.0, metavar="X",
        help="largest value of the vertical axis (eta_M, or the --parameter; default 200)",
    )  # fmt: skip
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
    from moving_bogie.stability.undamped import MECHANISMS
    from moving_bogie.stability.undamped_lines import KIND_TEXT

    params, spacings = params_and_spacings(args)
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
        from moving_bogie.stability.undamped import title

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
        if res.statement:
            ax.set_title(title(params.eta_f), fontsize=9)
        save_figure(fig, args.plot)
    if args.json:
        print_json(res.to_dict())
    else:
        if res.statement:
            print(res.statement)
            print(f"method: {res.method}")
        for b in res.branches:
            k = len(b.alpha)
            kind = "" if b.kind == "crossing" else f" [{b.kind}: {KIND_TEXT[b.kind]}]"
            print(
                f"d={b.d:g}{kind}: {k} points, alpha {b.alpha.min():.4f}..{b.alpha.max():.4f}, "
                f"{args.parameter} {b.theta.min():.4g}..{b.theta.max():.4g}, unstable side: {b.unstable_side}"
                + ("" if b.verified is None else f", counts below/above: {b.verified[2]}/{b.verified[4]}")
            )
            for m in dict.fromkeys(b.mechanism):
                print(f"  {m}: {MECHANISMS[m]}")
            for end in b.stops_inside:
                print(
                    f"  stops inside the plot at alpha {end.alpha:.4f}, {args.parameter} {end.theta:.4g}, "
                    f"q {end.q:.4f}: {EXPLANATIONS[end.reason]}"
                )
        if res.q_max is not None and res.q_max != args.q_max:
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
        formatter_class=RAW,
    )
    add_track_vehicle_options(p, spacing_list=False)
    p.add_argument("--alpha-min", type=float, default=0.0, help="smallest velocity alpha (default 0)")
    p.add_argument("--alpha-max", type=float, default=1.2, help="largest velocity alpha (default 1.2)")
    p.add_argument(
        "--eta-M-max", dest="theta_max", type=float, default=200.0, metavar="X",
        help="largest value of the vertical axis (eta_M, or the --parameter; default 200)",
    )  # fmt: skip
    p.add_argument(
        "--parameter", choices=("eta_M", "kappa_v", "eta_v"), default="eta_M", help="vertical axis"
    )
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

    params, _ = params_and_spacings(args)
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
    if args.lines:
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

        save_figure(plot_stability_map(smap, lines), args.plot)
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
