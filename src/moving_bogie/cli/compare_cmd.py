"""``compare-tracks``: instability lines of one vehicle on a layered track and on the one-layer track."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING

from moving_bogie.errors import ParameterError

from .checks import nonnegative, positive
from .common import PROG, add_json_option, print_json
from .outputs import add_figure_option
from .progress import progress_bar

if TYPE_CHECKING:
    from moving_bogie.stability.lines.line_results import InstabilityLines

from .stability_options import (
    RAW,
    add_plane_options,
    add_track_vehicle_options,
    params_and_spacings,
    plane_ranges,
    plane_units,
    save_figure,
)


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add compare-tracks."""
    p = subparsers.add_parser(
        "compare-tracks",
        help="instability lines on a layered track and on the one-layer track, side by side",
        description=(
            "The instability lines (alpha, eta_M) of one vehicle on the track given by --track and on the\n"
            "one-layer track whose foundation is the first layer of it (k_f = k_1, c_f = c_1: the groups\n"
            "of the vehicle and eta_f are shared), with the critical velocity of each track (dotted).\n"
            "The layered track's own groups (mu_2, kappa_2, eta_2, ...) are required options."
        ),
        epilog=(
            "example:\n"
            f"  {PROG} compare-tracks --track two-layer --mu-2 4 --kappa-2 0.5 --eta-2 0.2 \\\n"
            "      --d 1,1.5,2 --plot compare.png"
        ),
        formatter_class=RAW,
    )
    add_track_vehicle_options(p, spacing_list=True)
    p.add_argument("--alpha-min", type=nonnegative, default=0.0, help="smallest velocity alpha (default 0)")
    p.add_argument("--alpha-max", type=nonnegative, default=1.2, help="largest velocity alpha (default 1.2)")
    p.add_argument(
        "--eta-M-max", dest="theta_max", type=positive, default=200.0, metavar="X",
        help="largest wheel mass ratio eta_M (default 200)",
    )  # fmt: skip
    p.add_argument("--quick", action="store_true", help="coarser seed grid and steps (a preview)")
    add_plane_options(p)
    add_figure_option(p, "--plot", help="write the two-panel figure")
    add_json_option(p)
    p.set_defaults(handler=run)


def lowest_subcritical(lines: InstabilityLines, alpha_cr: float) -> dict[float, tuple[float, float]]:
    """Per spacing d: the lowest point (alpha, eta_M) of its instability lines with alpha < alpha_cr."""
    out: dict[float, tuple[float, float]] = {}
    for b in lines.branches:
        sel = b.alpha < alpha_cr
        if not sel.any():
            continue
        k = int(b.theta[sel].argmin())
        point = (float(b.alpha[sel][k]), float(b.theta[sel][k]))
        if b.d not in out or point[1] < out[b.d][1]:
            out[b.d] = point
    return out


def run(args: argparse.Namespace) -> int:
    layered, spacings = params_and_spacings(args)
    if layered.model.periodic:
        raise ParameterError(
            "file",
            "compare-tracks compares a layered continuous track with the one-layer track, not "
            f"{layered.track}: stability-map --file draws a sleeper track beside its smeared track",
        )
    if layered.track == "one-layer":
        raise ParameterError("track", "compare-tracks needs a layered --track (e.g. two-layer) to compare")
    base = layered.replace(track="one-layer")
    shared = set(base.model.parameters)
    groups = {name: getattr(layered, name) for name in layered.model.parameters if name not in shared}
    units = plane_units(args, layered)
    alpha_min, alpha_max, theta_max = plane_ranges(args, units, "eta_M")
    if alpha_max <= alpha_min:
        raise ParameterError("alpha-max", "must be larger than --alpha-min")

    from moving_bogie.kernels.bound import bind
    from moving_bogie.stability.figures.track_comparison import compare_tracks, figure_track_comparison

    with progress_bar("instability lines on both tracks", enabled=not getattr(args, "json", False)) as bar:
        comparison = compare_tracks(
            bind(base),
            layered.track,
            groups,
            spacings=spacings,
            alpha_range=(alpha_min, alpha_max),
            theta_max=theta_max,
            quick=args.quick,
            progress=bar,
        )
    if args.plot:
        save_figure(figure_track_comparison(comparison, units), args.plot)
    lowest = [lowest_subcritical(lines, a) for lines, a in zip(comparison.lines, comparison.alpha_cr)]
    if args.json:
        data = comparison.to_dict()
        for entry, low in zip(data["tracks"], lowest):
            entry["lowest_subcritical"] = [{"d": d, "alpha": a, "eta_M": t} for d, (a, t) in low.items()]
            if units.si:
                v_cr = units.value("alpha", entry["alpha_cr"])
                entry[f"{units.name('alpha')}_cr"] = {"value": v_cr, "unit": units.unit("alpha")}
        print_json(units.with_si(data) | {"units": units.to_dict()})
        return 0
    v, m = units.name("alpha"), units.name("eta_M")
    for lines, a_cr, low in zip(comparison.lines, comparison.alpha_cr, lowest):
        critical = f"alpha_cr = {a_cr:.6f}"
        if units.si:
            critical += f" ({v}_cr = {units.value('alpha', a_cr):.6g} {units.unit('alpha')})"
        print(f"{lines.params.track} track: {critical}, {len(lines.branches)} line pieces")
        for d in spacings:
            if d in low:
                a, t = low[d]
                point = f"{m} = {units.value('eta_M', t):.4g} at {v} = {units.value('alpha', a):.4f}"
                if units.si:
                    point += f" [{units.unit('eta_M')}, {units.unit('alpha')}]"
                print(f"  {units.legend('d', d)}: lowest subcritical line point {point}")
            else:
                print(f"  {units.legend('d', d)}: no instability line below the critical velocity")
    return 0
