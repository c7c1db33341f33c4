"""What ``moving-bogie timeseries`` and ``shape`` print and write: the closed-form series of a continuous
track (Eqs. (35)-(47)) and its deflection shape; on periodic supports the steady response over a bay and the
free vibrations (docs/sleepers.md, "The time series on sleepers"). Text, CSV and JSON."""

from __future__ import annotations

import os
from collections.abc import Sequence
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import numpy as np

    from moving_bogie.response.bay_response import BayResponse
    from moving_bogie.response.closed_form import TimeSeries

from .common import atomic_write, print_json


def _units_line(ts: TimeSeries) -> str:
    """``units: tau [...], ...``: the wheels' deflections as ``w``, then the bodies' DOFs, names of one unit
    together (the bogie: ``w, u [w_st], theta [w_st chi]``)."""
    groups: list[tuple[list[str], str]] = []
    wheel_unit = ts.response_units[ts.names[0]]
    labels = [("w", wheel_unit)] + [(n, ts.response_units[n]) for n in ts.names[ts.contacts :]]
    for label, unit in labels:
        if groups and groups[-1][1] == unit:
            groups[-1][0].append(label)
        else:
            groups.append(([label], unit))
    time = f"{_time_name(ts)} [{ts.units['tau']}]"
    return f"units: {time}, " + ", ".join(f"{', '.join(g)} [{unit}]" for g, unit in groups)


def _time_name(ts: TimeSeries) -> str:
    """``t`` for a series in seconds (SI parameters), else the dimensionless ``tau`` of Eq. (16)."""
    return "t" if ts.units.get("tau") == "s" else "tau"


def write_csv_series(ts: TimeSeries, path: str | os.PathLike[str]) -> None:
    """The series as CSV: tau, then every response under its DOF name, a units line below the header (on
    periodic supports the bay's columns, :func:`_write_bay_csv`)."""
    if ts.bay is not None:
        return _write_bay_csv(ts.bay, path)
    names = ("tau", *ts.responses)
    units = [ts.units["tau"], *ts.response_units.values()]
    columns = [ts.tau, *ts.responses.values()]
    lines = [",".join(names), "# units: " + ",".join(units)]
    for row in zip(*columns):
        lines.append(",".join(repr(float(v)) for v in row))
    atomic_write(path, "\n".join(lines) + "\n")


def format_series(
    ts: TimeSeries, rows: bool = True, csv: str | os.PathLike[str] | None = None, plots: Sequence[str] = ()
) -> str:
    """The readable series: summary lines, then one row per time (``rows``), then the notes; without the
    rows, one line saying where they went (``csv``, the data file) or were drawn (``plots``). On periodic
    supports the bay's summary and rows, then the free vibrations (:func:`_format_bay`)."""
    from moving_bogie.presentation import quantity_text

    if ts.bay is not None:
        return _format_bay(ts.bay, rows, [str(f) for f in (csv, *plots) if f])
    roots = () if ts.frequencies is None else ts.frequencies.roots

    bc = (
        "all times"
        if ts.branch_cut_until == float("inf")
        else (
            f"{_time_name(ts)} <= {quantity_text(ts.branch_cut_until, ts.units['tau'])}"
            if ts.branch_cut
            else "not included"
        )
    )
    lines = [
        f"Closed-form response ({ts.model}); {len(roots)} induced-frequency pair(s); branch-cut part: {bc}",
        "steady parts: " + "  ".join(f"{n} {v:.10g}" for n, v in ts.steady.items()),
        _units_line(ts),
        f"{_time_name(ts):>14} " + " ".join(f"{n:>18}" for n in ts.responses),
    ]
    columns = [ts.tau, *ts.responses.values()]
    if rows:
        for row in zip(*columns):
            lines.append(" ".join(f"{v:>{14 if k == 0 else 18}.10g}" for k, v in enumerate(row)))
    else:
        if csv:
            lines[-1] = f"{len(ts.tau)} rows written to {csv}; --rows prints them here too"
        else:
            drawn = f"drawn in {', '.join(plots)}; " if plots else ""
            lines[-1] = f"{len(ts.tau)} rows not printed ({drawn}--rows prints them, --csv F.csv writes them)"
    lines += [f"note: {n}" for n in ts.notes]
    return "\n".join(lines)


def print_shape(
    xi: np.ndarray,
    w: np.ndarray,
    *,
    tau: float,
    model: str,
    units: dict[str, str],
    with_cut: bool,
    notes: Sequence[str],
    json_mode: bool,
) -> None:
    """The deflection shape w(xi) at ``tau`` as JSON or as text (one row per xi, then the notes)."""
    if json_mode:
        print_json(
            {
                "tau": tau,
                "xi": xi.tolist(),
                "w": [float(v) for v in w],
                "model": model,
                "units": units,
                "branch_cut": with_cut,
                "notes": list(notes),
            }
        )
        return
    lines = [
        f"Deflection shape at tau = {tau:g} [{units['tau']}] ({model}); "
        f"branch-cut part: {'included' if with_cut else 'not included'}"
    ]
    lines.append(f"{'xi':>14} {'w':>18}")
    lines += [f"{x:>14.8g} {v:>18.10g}" for x, v in zip(xi, w)]
    lines += [f"note: {n}" for n in notes]
    print("\n".join(lines))


def write_shape_csv(
    xi: np.ndarray, w: np.ndarray, units: dict[str, str], path: str | os.PathLike[str]
) -> None:
    """The deflection shape as CSV: xi, w, a units line below the header."""
    text = "xi,w\n# units: " + f"{units['xi']},{units['w']}\n"
    text += "".join(f"{x!r},{float(v)!r}\n" for x, v in zip(xi.tolist(), w))
    atomic_write(path, text)


# --- on periodic supports -----------------------------------------------------------------------------


def _wheel_lines(series: BayResponse) -> list[str]:
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


def _free_lines(series: BayResponse) -> list[str]:
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


def _format_bay(series: BayResponse, rows: bool = True, files: list[str] | None = None) -> str:
    """The readable output: the bay, the convergence, the per-wheel summary, the rows, the free vibrations."""
    from moving_bogie.response.bay_response import not_converged

    status = (
        f"converged: changes by {series.change:.2g} < {series.tol:g} of the largest value when N doubles"
        if series.converged
        else not_converged(series)
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


def _write_bay_csv(series: BayResponse, path: str | os.PathLike[str]) -> None:
    """The series as CSV: t, x (rear wheel's position), then F_j, w_j per wheel; a units line below."""
    names = ["t", "x"] + [f"{q}_{j}" for j in range(series.wheels) for q in ("F", "w")]
    units = ["s", "m"] + ["N", "m"] * series.wheels
    columns = [series.time, series.position]
    for j in range(series.wheels):
        columns += [series.contact_force[j], series.deflection[j]]
    lines = [",".join(names), "# units: " + ",".join(units)]
    lines += [",".join(repr(float(v)) for v in row) for row in zip(*columns)]
    atomic_write(path, "\n".join(lines) + "\n")
