"""``moving-bogie timeseries --file F`` for a file on a sleeper track: the steady response over a bay and the
free vibrations (docs/sleepers.md, "The time series on sleepers"); the logic is
:func:`moving_bogie.response.sleeper_series.sleeper_series`."""

from __future__ import annotations

import argparse
import os
import sys
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from moving_bogie.model.sleeper_input import SleeperInput
    from moving_bogie.response.sleeper_series import SleeperSeries

from .common import print_json

#: the options of the continuous-track time series that a sleeper file does not take, and what to do instead
_MODEL = (
    "the file's [model] and [physical] tables set the model and its SI values (--set NAME=VALUE changes one)"
)
_NOT_FOR_SLEEPERS = {
    "case": _MODEL,
    "beam": _MODEL,
    "track": _MODEL,
    "vehicle": _MODEL,
    "tau": "the steady response spans --bays bays on --points points",
    "tmax": "the steady response spans --bays bays on --points points",
    "branch_cut": "the steady response over a bay is a sum of harmonics, without a branch cut",
    "plot_long": "--plot draws the steady response over the bays",
    "dps": "the Floquet runtime works in double precision",
}
_MAX_POINTS = 1_000_000
_MAX_BAYS = 10_000
SLEEPER_POINTS = 201


def check_sleeper_options(args: argparse.Namespace) -> None:
    """Refuse, naming it, the first option that does not apply to a sleeper file; check --bays, --points."""
    from moving_bogie.errors import ParameterError

    from .common import refuse_for_sleepers

    # --no-branch-cut sets False: refused too
    refuse_for_sleepers(args, _NOT_FOR_SLEEPERS, unset=(None,))
    bays = 1 if args.bays is None else args.bays
    if not 1 <= bays <= _MAX_BAYS:
        raise ParameterError("bays", f"--bays must be between 1 and {_MAX_BAYS} (got {bays})")
    points = SLEEPER_POINTS * bays if args.points is None else args.points
    if not 2 <= points <= _MAX_POINTS:
        raise ParameterError("points", f"--points must be between 2 and {_MAX_POINTS} (got {points})")
    args.bays, args.points = bays, points


def run_sleeper_timeseries(args: argparse.Namespace, data: SleeperInput) -> int:
    """Print (or write) the steady response over ``--bays`` bays and the free vibrations in SI of the
    parameters ``data`` (the file's, ``--set`` applied)."""
    check_sleeper_options(args)
    from moving_bogie.response.sleeper_series import sleeper_series

    series = sleeper_series(data, bays=args.bays, points=args.points)
    if args.csv:
        write_sleeper_csv(series, args.csv)
    if args.plot:
        from moving_bogie.response.plots import save_figure
        from moving_bogie.response.sleeper_plots import sleeper_series_figure

        save_figure(sleeper_series_figure(series, title=f"{args.file.name} ({series.model})"), args.plot)
    if args.json:
        print_json(series.to_dict())
    else:
        files = [str(f) for f in (args.csv, args.plot) if f]
        print(format_sleeper_series(series, rows=args.rows or not files, files=files))
    warnings = [] if series.converged else [_not_converged(series)]
    warnings += list(series.free_notes)
    for text in warnings:
        print(f"warning: {text}", file=sys.stderr)
    from moving_bogie.roots.verdict import UNDETERMINED

    return 0 if series.converged and series.free_verdict != UNDETERMINED else 1


def _not_converged(series: SleeperSeries) -> str:
    return (
        f"the steady response has NOT converged: it changed by {series.change:.3g} (relative) at "
        f"N = {series.harmonics}, tolerance {series.tol:g}"
    )


def _wheel_lines(series: SleeperSeries) -> list[str]:
    lines = [
        f"  {'wheel':>5} {'at [m]':>8} {'F mean [N]':>13} {'F p-p [N]':>12} {'w mean [m]':>13} "
        f"{'w p-p [m]':>12} {'w continuous [m]':>17}"
    ]
    for j in range(series.wheels):
        cont = series.continuous_deflection
        lines.append(
            f"  {j:>5} {series.wheel_positions[j]:>8.4g} {series.force_mean[j]:>13.7g} "
            f"{series.force_peak_to_peak[j]:>12.5g} {series.deflection_mean[j]:>13.6g} "
            f"{series.deflection_peak_to_peak[j]:>12.5g} "
            + (f"{cont[j]:>17.6g}" if cont is not None else f"{'-':>17}")
        )
    return lines


def _free_lines(series: SleeperSeries) -> list[str]:
    x0, x1 = series.free_strip
    y0, y1 = series.free_window
    lines = [
        f"free vibrations: Floquet roots Omega (e^(i Omega t)) with Re Omega in [{x0:.6g}, {x1:.6g}] rad/s "
        f"(one copy modulo Omega_0) and Im Omega in [{y0:.6g}, {y1:.6g}] rad/s: the growing ones and, up to "
        "the rail's free waves, the decaying ones",
        f"{series.free_count} root(s) counted by the argument principle, {len(series.free)} located",
    ]
    if series.free:
        lines.append(
            f"  {'f [rad/s]':>12} {'f [Hz]':>10} {'growth [1/s]':>13} {'doubles in [s]':>15} "
            f"{'halves in [s]':>14}  state"
        )
    for r in series.free:
        double = "-" if r.doubling_time is None else f"{r.doubling_time:.4g}"
        halve = "-" if r.halving_time is None else f"{r.halving_time:.4g}"
        lines.append(
            f"  {r.frequency_rad_s:>12.6g} {r.frequency_hz:>10.5g} {r.growth_rate:>13.5g} {double:>15} "
            f"{halve:>14}  {r.state}"
        )
    lines.append(f"verdict: {series.free_verdict.upper()}")
    return lines


def format_sleeper_series(series: SleeperSeries, rows: bool = True, files: list[str] | None = None) -> str:
    """The readable output: the bay, the convergence, the per-wheel summary, the rows, the free vibrations."""
    status = (
        f"converged: changes by {series.change:.2g} < {series.tol:g} of the largest value when N doubles"
        if series.converged
        else _not_converged(series)
    )
    lines = [
        f"Steady response under the constant loads on {series.model}, v = {series.v:g} m/s, bay l = "
        f"{series.bay:g} m: sleeper-passing frequency Omega_0 = {series.Omega0:.6g} rad/s "
        f"({series.Omega0 / (2 * 3.141592653589793):.5g} Hz), period {series.period:.5g} s",
        f"harmonics n = -{series.harmonics}..{series.harmonics}; {status}",
        "per wheel (F: contact force, w: rail deflection under the wheel; mean over a bay, peak-to-peak; "
        + (
            f"w continuous: the {series.continuous_model} track with the same smeared supports)"
            if series.continuous_model
            else "no continuous track has the same smeared supports)"
        ),
        *_wheel_lines(series),
    ]
    header = f"{'t [s]':>12} {'x [m]':>10} " + " ".join(
        f"{f'F{j} [N]':>14} {f'w{j} [m]':>14}" for j in range(series.wheels)
    )
    lines.append(header)
    if rows:
        for i in range(series.time.size):
            cells = " ".join(
                f"{series.contact_force[j, i]:>14.8g} {series.deflection[j, i]:>14.8g}"
                for j in range(series.wheels)
            )
            lines.append(f"{series.time[i]:>12.6g} {series.position[i]:>10.5g} {cells}")
    else:
        written = ", ".join(files or [])
        lines[-1] = f"{series.time.size} rows written to {written}; --rows prints them here too"
    return "\n".join(lines + _free_lines(series))


def write_sleeper_csv(series: SleeperSeries, path: str | os.PathLike[str]) -> None:
    """The series as CSV: t, x (rear wheel's position), then F_j, w_j per wheel; a units line below."""
    from .common import atomic_write

    names = ["t", "x"] + [f"{q}_{j}" for j in range(series.wheels) for q in ("F", "w")]
    units = ["s", "m"] + ["N", "m"] * series.wheels
    columns = [series.time, series.position]
    for j in range(series.wheels):
        columns += [series.contact_force[j], series.deflection[j]]
    lines = [",".join(names), "# units: " + ",".join(units)]
    lines += [",".join(repr(float(v)) for v in row) for row in zip(*columns)]
    atomic_write(path, "\n".join(lines) + "\n")
