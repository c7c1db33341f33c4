"""Instability lines and stability maps in the (alpha, eta_M) plane (Section 3.5, Figures 3, 4, 7, 8)."""

from __future__ import annotations

import argparse
import sys
from functools import partial
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from moving_bogie.model.params import DimensionlessParams
    from moving_bogie.stability.figures.plot_units import PlaneUnits
    from moving_bogie.stability.lines.line_results import InstabilityLines
    from moving_bogie.stability.maps.map import StabilityMap

from moving_bogie.errors import ParameterError
from moving_bogie.model.bar import bar_note, held_groups
from moving_bogie.presentation import field_lines, json_clean, quantity

from . import lines_on_supports
from .checks import count, nonnegative, positive, workers
from .common import (
    PROG,
    add_bar_option,
    add_json_option,
    add_output_option,
    print_json,
    si_input,
    soil_file_given,
)
from .job_size import SHORTER, add_yes_option, estimate_grid
from .lines_on_supports import sleeper_data
from .outputs import add_figure_option
from .progress import add_resume_option, checkpoint_options, progress_bar
from .stability_options import (
    RAW,
    add_plane_options,
    add_track_vehicle_options,
    params_and_spacings,
    plane_ranges,
    plane_units,
    save_figure,
)

#: The most grid points per axis of a stability map (--n); a map of over TIMED cells per axis is timed on
#: one column before it starts (cli/job_size.py).
MAX_N = 1000
TIMED = 100


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add instability-lines and stability-map."""
    _register_instability_lines(subparsers)
    _register_stability_map(subparsers)


# -- instability-lines --------------------------------------------------------------------------------
def _register_instability_lines(subparsers: argparse._SubParsersAction) -> None:
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
            "  moving-bogie instability-lines --model masses --d 1.5 --eta-f 0 --plot undamped.png\n"
            "  moving-bogie instability-lines --file examples/uic60-bogie.toml --set d=2.5 --plot si.png\n"
            "  moving-bogie instability-lines --file examples/sleepers_zones.toml --range v=50:250\n\n"
            "A file on a sleeper track (docs/sleepers.md): the D-decomposition in the wheel mass M at 60\n"
            "velocities of --range v=LO:HI (m/s), up to --range M=0:HI (kg); --verify checks the counts by\n"
            "floquet_frequencies."
        ),
        formatter_class=RAW,
    )
    add_track_vehicle_options(p, spacing_list=True)
    p.add_argument("--alpha-min", type=nonnegative, default=0.0, help="smallest velocity alpha (default 0)")
    p.add_argument("--alpha-max", type=nonnegative, default=1.2, help="largest velocity alpha (default 1.2)")
    p.add_argument(
        "--eta-M-max", dest="theta_max", type=positive, default=200.0, metavar="X",
        help="largest value of the vertical axis (eta_M, or the --parameter; default 200)",
    )  # fmt: skip
    p.add_argument(
        "--parameter", choices=("eta_M", "kappa_v", "eta_v"), default="eta_M", help="vertical axis"
    )
    p.add_argument("--q-max", type=positive, default=1.5, help="largest real induced frequency searched")
    p.add_argument(
        "--verify",
        action="store_true",
        help="count unstable roots (induced_frequencies) on both sides of each branch",
    )
    add_plane_options(p)
    add_bar_option(p)
    add_figure_option(p, "--plot", help="write the figure")
    add_json_option(p)
    p.set_defaults(handler=run_instability_lines)


def run_instability_lines(args: argparse.Namespace) -> int:
    if soil_file_given(args):
        from .soil_lines_cmd import run_soil_lines

        return run_soil_lines(args)
    sleepers = sleeper_data(args)
    if sleepers is not None:
        return lines_on_supports.run_sleeper_lines(args, sleepers)
    params, spacings = params_and_spacings(args)
    units = plane_units(args, params)
    alpha_min, alpha_max, theta_max = plane_ranges(args, units, args.parameter)

    from moving_bogie.kernels.bound import bind
    from moving_bogie.stability.lines.instability_lines import instability_lines
    from moving_bogie.stability.lines.line_ends import EXPLANATIONS
    from moving_bogie.stability.lines.undamped_lines import KIND_TEXT
    from moving_bogie.stability.maps.undamped import MECHANISMS

    with progress_bar("instability lines", enabled=not args.json) as bar:
        res = instability_lines(
            bind(params),
            spacings=spacings,
            parameter=args.parameter,
            alpha_range=(alpha_min, alpha_max),
            theta_max=theta_max,
            q_max=args.q_max,
            verify=args.verify,
            progress=bar,
            held=held_groups(params, args.bar),
        )
    if args.plot:
        fig = instability_figure(res, units, (alpha_min, alpha_max), theta_max)
        save_figure(fig, args.plot)
    if args.json:
        note = {"bar": bar_note(params, args.bar, args.parameter)}
        print_json(units.with_si(res.to_dict()) | {"units": units.to_dict()} | note)
    else:
        if units.si:
            print(_si_line(units, args.parameter, params))
        if res.statement:
            print(res.statement)
            print(f"method: {res.method}")
        for b in res.branches:
            k = len(b.alpha)
            kind = "" if b.kind == "crossing" else f" [{b.kind}: {KIND_TEXT[b.kind]}]"
            x, y = units.value("alpha", b.alpha), units.value(args.parameter, b.theta)
            x_name, y_name = units.name("alpha"), units.name(args.parameter)
            print(
                f"{units.legend('d', b.d)}{kind}: {k} points, {x_name} {x.min():.4f}..{x.max():.4f}, "
                f"{y_name} {y.min():.4g}..{y.max():.4g}, unstable side: {b.unstable_side}"
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


def instability_figure(
    res: InstabilityLines, units: PlaneUnits, alpha_range: tuple[float, float], theta_max: float
) -> Figure:
    """The figure of ``instability-lines``: the lines in ``units`` (SI for a [physical] file), the line
    ends explained, alpha = 1 dotted, the operating point marked."""
    from matplotlib.figure import Figure

    from moving_bogie.stability.figures.plots import end_mark_handles, plot_instability_lines
    from moving_bogie.stability.maps.undamped import title

    fig = Figure(figsize=(7, 5), layout="constrained")
    ax = fig.subplots()
    marks = plot_instability_lines(ax, res, units=units)
    units.critical(ax)
    ax.set_xlim(*(units.value("alpha", a) for a in alpha_range))
    ax.set_ylim(0, units.value(res.parameter, theta_max))
    ax.set_xlabel(units.label("alpha"))
    ax.set_ylabel(units.label(res.parameter))
    units.mark(ax, "alpha", res.parameter)
    handles, _ = ax.get_legend_handles_labels()
    ax.legend(handles=handles + end_mark_handles(marks), fontsize=8)
    if res.statement:
        ax.set_title(title(res.params.eta_f), fontsize=9)
    return fig


# -- stability-map ------------------------------------------------------------------------------------
def _register_stability_map(subparsers: argparse._SubParsersAction) -> None:
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
            "  moving-bogie stability-map --d 1.5 --n 400 --lines --plot map.png\n"
            "  moving-bogie stability-map --file examples/uic60-bogie.toml --range v=0:400 \\\n"
            "      --range M=0:3000 --plot map.png   (SI axes, the file's operating point marked)\n"
            "  moving-bogie stability-map --file examples/sleepers_zones.toml --range v=20:400 \\\n"
            "      --range M=0:3000 --n 100 --workers 2 --plot map.png --csv map.csv\n\n"
            "A file on a sleeper track (docs/sleepers.md): the unstable count of each cell from the\n"
            "D-decomposition in M at each velocity (none at M -> 0, then the signed crossings), checked by\n"
            "floquet_frequencies at a few cells, beside the continuous track of the same smeared support.\n\n"
            "Every finished column is kept: after Ctrl-C, the same command with --resume computes only the\n"
            "columns missing (kept under $MOVING_BOGIE_CACHE, else ~/.cache/moving-bogie, until the map\n"
            "is done)."
        ),
        formatter_class=RAW,
    )
    add_track_vehicle_options(p, spacing_list=False)
    p.add_argument("--alpha-min", type=nonnegative, default=0.0, help="smallest velocity alpha (default 0)")
    p.add_argument("--alpha-max", type=nonnegative, default=1.2, help="largest velocity alpha (default 1.2)")
    p.add_argument(
        "--eta-M-max", dest="theta_max", type=positive, default=200.0, metavar="X",
        help="largest value of the vertical axis (eta_M, or the --parameter; default 200)",
    )  # fmt: skip
    p.add_argument(
        "--parameter", choices=("eta_M", "kappa_v", "eta_v"), default="eta_M", help="vertical axis"
    )
    p.add_argument("--n", type=count(2, MAX_N), default=200, help="grid points per axis (default 200)")
    p.add_argument("--workers", type=workers, default=None, help="processes (default: CPUs)")
    p.add_argument("--lines", action="store_true", help="draw the instability lines on the plot")
    add_yes_option(p)
    p.add_argument(
        "--margin",
        action="store_true",
        help="a sleeper-track file: colour every cell by its margin, the smallest Im Omega of a strip search "
        "at its (v, M) (1-3 s per cell; the continuous map gives the margin without it)",
    )
    add_plane_options(p)
    add_bar_option(p)
    add_figure_option(p, "--plot", help="write the figure")
    add_output_option(p, "--npz", metavar="F.npz", formats=("npz",), help="save the arrays")
    add_output_option(
        p, "--out", folder=True, metavar="S.zarr", help="save as a 2-D sweep store (sweep-plot, xarray)"
    )
    p.add_argument("--overwrite", action="store_true", help="replace an existing --out store")
    add_resume_option(p)
    add_output_option(
        p, "--csv", metavar="F.csv", formats=("csv",), help="save the cells as CSV (a sleeper track's file)"
    )
    add_json_option(p)
    p.set_defaults(handler=run_stability_map)


def run_stability_map(args: argparse.Namespace) -> int:
    """``stability-map``: the jobs it runs (a map; on sleepers the continuous map beside it) keep their
    parts until the command is done, so ``--resume`` after any of them computes only what is missing."""
    from moving_bogie.checkpoint import kept_until_done

    with kept_until_done():
        if soil_file_given(args):
            from .soil_lines_cmd import run_soil_map

            return run_soil_map(args)
        return _stability_map(args)


def _check_map_options(args: argparse.Namespace) -> None:
    """The continuous map's own options: no --margin (every cell has its margin), --out not overwritten."""
    if args.margin:
        raise ParameterError("--margin", "--margin: the continuous map gives every cell's margin without it")
    if args.out is not None and args.out.exists() and not args.overwrite:
        raise ParameterError("--out", f"--out {args.out} exists: pass --overwrite to replace it")


def _stability_map(args: argparse.Namespace) -> int:
    import numpy as np

    sleepers = sleeper_data(args)
    if sleepers is not None:
        return lines_on_supports.run_sleeper_map(args, sleepers)
    params, _ = params_and_spacings(args)
    _check_map_options(args)
    units = plane_units(args, params)
    alpha_min, alpha_max, theta_max = plane_ranges(args, units, args.parameter)

    from moving_bogie.kernels.bound import bind
    from moving_bogie.stability.lines.instability_lines import instability_lines
    from moving_bogie.stability.maps.map import map_columns, stability_map

    bound = bind(params)  # bound once: the map and its lines share it
    held = held_groups(params, args.bar)
    alphas = np.linspace(alpha_min, alpha_max, args.n)
    thetas = np.linspace(theta_max / args.n, theta_max, args.n)
    if args.n > TIMED and not getattr(args, "resume", False):  # a long map says so before it starts
        column = partial(map_columns, bound, args.parameter, [alphas[args.n // 2]], thetas, held=held)
        estimate_grid("stability map", (args.n, args.n), args.workers, column, yes=args.yes, shorter=SHORTER)
    with progress_bar("stability map", enabled=not args.json) as bar:
        smap = stability_map(
            bound,
            parameter=args.parameter,
            alphas=alphas.tolist(),
            thetas=thetas.tolist(),
            workers=args.workers,
            progress=bar,
            held=held,
            **checkpoint_options(args),
        )
    lines = None
    if args.lines:
        with progress_bar("instability lines", enabled=not args.json) as bar:
            lines = instability_lines(
                bound,
                parameter=args.parameter,
                alpha_range=(alpha_min, alpha_max),
                theta_max=theta_max,
                progress=bar,
                held=held,
            )
    if args.npz:
        import io

        from .common import atomic_write

        buffer = io.BytesIO()
        smap.save_npz(buffer)
        atomic_write(args.npz, buffer.getvalue())
    if args.out:
        from moving_bogie.sweep.map_store import write_map

        write_map(args.out, smap, bound, overwrite=args.overwrite, physical=si_input(args, args.physical))
    if args.plot:
        from moving_bogie.stability.figures.plots import plot_stability_map

        save_figure(plot_stability_map(smap, lines, units=units), args.plot)
    summary = _map_summary(smap, units, bar_note(params, args.bar, args.parameter))
    if args.json:
        print_json(summary)
    else:
        if units.si:
            print(_si_line(units, args.parameter, params))
        hidden = ["params", "uncertain", "axes", "units", "bar"]
        if units.si:  # the groups' values, in SI on the lines below
            hidden += ["max_degree", "alpha_range", f"{args.parameter}_range"]
        print("\n".join(field_lines(summary, skip=hidden)))
        for key, axis in summary["axes"].items():
            (lo, hi), name = axis["range"], axis["name"]
            note = f" ({axis['note']})" if "note" in axis else ""
            points = f"{axis['count']} points{note}"
            print(f"{key + ' axis':18s} {name} {lo:.6g}..{hi:.6g} [{axis['unit']}], {points}")
        for cell in summary["uncertain"]:
            print("uncertain cell     " + ", ".join(units.legend(k, v) for k, v in cell.items()))
    return 0


def _map_summary(smap: StabilityMap, units: PlaneUnits, bar: dict[str, str] | None) -> dict[str, Any]:
    """The map's summary with its axes in ``units``, the rule of the bar, and in SI the rates in 1/s."""
    summary = smap.summary()
    summary["axes"] = {
        "x": units.axis("alpha", smap.alphas[0], smap.alphas[-1], len(smap.alphas)),
        "y": units.axis(smap.parameter, smap.thetas[0], smap.thetas[-1], len(smap.thetas)),
    }
    summary = units.with_si(summary) | {"units": units.to_dict(), "bar": bar}
    if units.si:  # the degree of instability as a growth rate: Im omega = Im q / t_scale
        summary["max_growth_rate"] = quantity(units.frequency(summary["max_degree"]), "1/s")
        if summary["min_decay_rate"] is not None:
            summary["min_decay_rate"] = quantity(units.frequency(summary["min_decay_rate"]), "1/s")
    return json_clean(summary)


def _si_line(units: PlaneUnits, parameter: str, params: DimensionlessParams) -> str:
    """Lines saying the plane is shown in SI: each axis as its group times a factor, and what follows the
    vertical axis (the groups an alternative input of Eq. (63) keeps in proportion, as in the paper)."""
    text = (
        f"units: SI ([physical] file): {units.label('alpha')} = alpha x {units.value('alpha', 1.0):.6g}, "
        f"{units.label(parameter)} = {parameter} x {units.value(parameter, 1.0):.6g}, "
        f"{units.label('d')} = d x {units.value('d', 1.0):.6g}"
    )
    follow = [
        f"{units.name(meta['sets'])} ({name} = {float(getattr(params, name)):.6g} fixed)"
        for name, meta in params.model.alternatives.items()
        if parameter in meta["depends"]
    ]
    if follow:
        text += f"\nalong {units.name(parameter)} the bar follows the wheel, Eq. (63): " + ", ".join(follow)
        text += "; moving-bogie sweep holds them fixed instead"
    return text
