"""Stability subcommands (Sections 3.5-3.8): frequency-lines, critical-stiffness and stability-figure
(critical-velocity: :mod:`.velocity_cmd`; instability-lines and stability-map: :mod:`.lines_cmd`)."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from moving_bogie.stability.figures.plot_units import PlaneUnits
    from moving_bogie.stability.lines.frequency_lines import FrequencyLine, FrequencyLines

from .checks import count, nonnegative, positive
from .common import (
    add_json_option,
    add_parameter_options,
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

FIGURES = (2, 3, 4, 7, 8, 16)


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add frequency-lines, critical-stiffness and stability-figure."""
    _register_frequency_lines(subparsers)
    _register_critical_stiffness(subparsers)
    _register_figure(subparsers)


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
