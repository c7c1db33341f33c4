"""``instability-lines --file`` on a soil-track file that names a vehicle: the D-decomposition in the wheel
mass M along the real frequency axis at the file's speed, and the threshold mass; ``stability-map --file``:
the (v, M) map of the growing roots, one such D-decomposition per velocity (docs/soil.md).

The crossings are those of :func:`~moving_bogie.stability.maps.real_axis.real_axis_column` on the soil's
own track, up to the window's far-field radius (the radius ``frequencies --file`` counts in). M is in the
file's convention (per rail or per track); ``--range M=0:HI`` (kg) bounds the mass axis as on sleepers.
"""

from __future__ import annotations

import argparse
import math
import sys
from functools import partial
from typing import Any

from moving_bogie.errors import ParameterError

from .checks import named_values, value_range
from .common import first_given, option_flag, parameter_options, print_json, soil_settings

__all__ = ["run_soil_lines", "run_soil_map"]

#: The mass axis without --range M=0:HI: up to this many times the file's M; a map's velocity axis without
#: --range v=LO:HI: these times the file's v.
DEFAULT_MASSES = 4.0
DEFAULT_SPEEDS = (0.5, 1.5)
#: A soil map of over TIMED columns is timed on one column before it starts (cli/job_size.py).
TIMED = 4

_MODEL = "give the model and its values in the file (docs/soil.md)"
#: Options of instability-lines that a soil file does not take (dest -> why).
_REFUSED = {
    "case": _MODEL, "beam": _MODEL, "track": _MODEL, "vehicle": _MODEL, "d": _MODEL,
    "parameter": "on a soil track the vertical axis is the wheel mass M",
    "verify": "count the roots of a mass with frequencies --file (the argument principle on the soil)",
    "plot": "the crossings of one speed are printed (a figure of the (v, M) plane needs a map)",
}  # fmt: skip
#: Options of stability-map that a soil file does not take (dest -> why).
_MAP_REFUSED = {
    "case": _MODEL, "beam": _MODEL, "track": _MODEL, "vehicle": _MODEL, "d": _MODEL,
    "parameter": "on a soil track the vertical axis is the wheel mass M",
    "lines": "the map of a soil track always shows its D-lines",
    "npz": "a soil map writes its figure, its CSV and its JSON", "out": "a soil map is not a sweep store",
}  # fmt: skip


def _refuse(args: argparse.Namespace, refused: dict[str, str] = _REFUSED) -> None:
    """One message naming the first option that does not apply to a soil file, before any work."""
    table = refused | {name: _MODEL for name, _, _ in parameter_options() if name not in refused}
    if args.parameter == "eta_M":  # the default
        del table["parameter"]
    dest = first_given(args, table)
    if dest is not None:
        flag = option_flag(dest)
        raise ParameterError(flag.lstrip("-"), f"{flag} does not apply to a soil-track file: {table[dest]}")
    if args.alpha_min != 0.0 or args.alpha_max != 1.2 or args.theta_max != 200.0:
        raise ParameterError("--range", "on a soil track give the mass axis as --range M=0:HI (kg)")
    if getattr(args, "bar", "follows") != "follows":
        why = "--bar fixed: on a soil track the bar follows the wheel mass (Eq. (63))"
        raise ParameterError("--bar", why)


def _axes(args: argparse.Namespace, file_v: float, file_mass: float, *, speeds: bool) -> dict[str, Any]:
    """``--range`` v=LO:HI (m/s; a map's, default DEFAULT_SPEEDS times the file's v) and M=0:HI (kg,
    default DEFAULT_MASSES times the file's M); any other axis refused."""
    axes: dict[str, Any] = {"M": (0.0, DEFAULT_MASSES * file_mass)}
    if speeds:
        axes["v"] = (DEFAULT_SPEEDS[0] * file_v, DEFAULT_SPEEDS[1] * file_v)
    for name, spec in named_values(args.range, "--range", "NAME=LO:HI").items():
        if name == "v" and not speeds:
            raise ParameterError(
                "--range",
                "--range v: the D-decomposition on the soil runs at the file's v (the (v, M) map: "
                "stability-map --file)",
            )
        if name not in axes:
            raise ParameterError("--range", f"--range {name}: not an axis (known: {', '.join(axes)})")
        axes[name] = value_range(name, spec)
    if axes["M"][0] != 0:
        raise ParameterError("--range", "--range M=0:HI: the mass axis starts at 0 (counted from M -> 0)")
    if speeds and axes["v"][0] <= 0:
        raise ParameterError("--range", "--range v: the velocities must be positive")
    return axes


def soil_lines(args: argparse.Namespace) -> dict[str, Any]:
    """The crossings, the threshold and the speed regime of the file's vehicle (JSON-ready, SI)."""
    _refuse(args)
    from moving_bogie.api import load_soil_vehicle, threshold_mass

    data = load_soil_vehicle(args.file, soil_settings(args))
    physical, file_mass = data.physical, data.wheel_mass
    top = _axes(args, float(physical.v), file_mass, speeds=False)["M"][1]
    from .progress import progress_bar
    from .soil_frequencies_cmd import soil_speed_regime

    with progress_bar("D-decomposition on the soil", enabled=not args.json) as bar:
        found = threshold_mass(data, top, progress=bar)
    v = float(physical.v)
    regime = soil_speed_regime(data.input, v, physical.scales().v_ref)
    table = found.to_dict()
    return {
        "vehicle": physical.vehicle,
        "track": data.input.track.kind,
        "per": data.input.per,
        "k_ref": data.rail.k_ref,
        "v": v,
        "v_cr": regime.v_cr,
        "supercritical": regime.supercritical,
        "Omega_max_rad_s": table["Omega_max_rad_s"],
        "samples": table["samples"],
        "M_max": top,
        "M_min": table["M_min"],
        "M": file_mass,
        "crossings": table["crossings"],
        "threshold": table["threshold"],
        "count_at_M": found.count_at(file_mass),
        "notes": table["notes"],
    }


def _digits(moved: float) -> int:
    """Significant digits that a relative change ``moved`` (with a 100 times tighter receptance) leaves,
    at most 8 (Brent's tolerance in Omega, 1e-11, moves M by about 1e-10)."""
    return max(2, min(8, math.floor(-math.log10(2 * max(moved, 1e-11)))))


def _text(out: dict[str, Any]) -> str:
    unit = f"kg (per {out['per']})"
    regime = "no guided wave found" if out["v_cr"] is None else f"critical velocity {out['v_cr']:.6g} m/s"
    lines = [
        f"vehicle {out['vehicle']} on the {out['track']} track, v = {out['v']:.6g} m/s ({regime})",
        f"D-decomposition in M along real Omega in (0, {out['Omega_max_rad_s']:.6g}] rad/s "
        f"({out['samples']} samples), M from {out['M_min']:.6g} to {out['M_max']:.6g} {unit}",
    ]
    for c in out["crossings"]:
        n = _digits(c["moved"])
        lines.append(
            f"  Omega {c['Omega_rad_s']:12.{n}g} rad/s  M {c['M']:14.{n}g} {unit}  "
            f"count {c['change']:+d} as M grows"
        )
    t = out["threshold"]
    if t is None:
        lines.append(f"threshold mass: none up to {out['M_max']:.6g} {unit}: STABLE for every M up to it")
    else:
        n = _digits(t["moved"])
        lines.append(
            f"threshold mass {t['M']:.{n}g} {unit}: a root crosses into Im Omega < 0 at "
            f"Omega = {t['Omega_rad_s']:.{n}g} rad/s"
        )
    verdict = "UNSTABLE" if out["count_at_M"] > 0 else "STABLE"
    lines.append(f"the file's M = {out['M']:.6g} {unit}: {verdict} ({out['count_at_M']} growing root(s))")
    return "\n".join(lines)


def run_soil_lines(args: argparse.Namespace) -> int:
    """``instability-lines --file`` on a soil file; exit 1 when the crossings carry a note."""
    out = soil_lines(args)
    if args.json:
        print_json(out)
    else:
        print(_text(out))
    for note in out["notes"]:
        print(f"warning: {note}", file=sys.stderr)
    return 0 if not out["notes"] else 1


def _vehicle_at(data: Any, v: float) -> Any:
    """The file's vehicle on its soil at speed ``v`` (m/s): its SoilVehicle with [physical] v replaced."""
    import dataclasses

    from moving_bogie.api import soil_vehicle

    values = tuple((k, v if k == "v" else x) for k, x in data.input.vehicle_values)
    return soil_vehicle(dataclasses.replace(data.input, vehicle_values=values), tol=data.rail.tol)


def run_soil_map(args: argparse.Namespace) -> int:
    """``stability-map --file`` on a soil file with a vehicle: the (v, M) map of its growing roots, one
    D-decomposition per velocity (every option checked first; a map of over TIMED columns timed first)."""
    _refuse(args, _MAP_REFUSED)
    if getattr(args, "units", None) == "dimensionless":
        raise ParameterError("--units", "a soil map is in SI units (v in m/s, M in kg)")
    import numpy as np

    from moving_bogie.api import bind, load_soil_vehicle
    from moving_bogie.stability.maps.real_axis_map import real_axis_map

    from .job_size import estimate_grid
    from .lines_on_supports import report
    from .progress import checkpoint_options, progress_bar

    data = load_soil_vehicle(args.file, soil_settings(args))
    physical, unit = data.physical, data.mass_unit
    file_v, file_mass = float(physical.v), data.wheel_mass
    axes = _axes(args, file_v, file_mass, speeds=True)
    n = args.n
    (v0, v1), top = axes["v"], axes["M"][1]
    vs, ms = np.linspace(v0, v1, n), np.linspace(top / n, top, n)
    from moving_bogie.kernels.bound import BoundModel

    bounds = [bind(_vehicle_at(data, float(v))) for v in vs]
    omega_0 = bounds[0].track.omega_0  # type: ignore[attr-defined]
    columns = [(bound, BoundModel(bound.params)) for bound in bounds]
    layers = len(data.input.soil.layers)
    track = f"{data.input.track.kind} track on {layers} soil layer(s), per {data.input.per}"
    options: dict[str, Any] = dict(
        scales=(physical.scales().v_ref, unit, 1 / omega_0), name=f"soil/{physical.vehicle}", track=track
    )
    options["identity"] = repr((data.input, sorted(axes.items())))
    if n > TIMED and not getattr(args, "resume", False):  # a long map says so before it starts
        middle = slice(n // 2, n // 2 + 1)
        column = partial(real_axis_map, columns[middle], vs[middle], ms, workers=1, **options)
        estimate_grid("soil map", (n, n), args.workers, column, yes=args.yes, shorter="a smaller --n")
    with progress_bar("soil map", enabled=not args.json) as bar:
        smap = real_axis_map(
            columns, vs, ms, workers=args.workers, progress=bar, **options, **checkpoint_options(args)
        )
    return report(args, smap, (file_v, file_mass), crossings=False, continuous=None)
