"""``instability-lines`` and ``stability-map`` for a file on a sleeper track: the D-decomposition lines in
(v, M) and the map of unstable counts built from them, beside the continuous track (docs/sleepers.md)."""

from __future__ import annotations

import argparse
import sys
from functools import partial
from typing import TYPE_CHECKING

from moving_bogie.errors import ParameterError

from .checks import named_values, value_range
from .common import print_json, refuse_for_sleepers
from .job_size import SHORTER, estimate_grid
from .progress import checkpoint_options, progress_bar

if TYPE_CHECKING:
    import numpy as np

    from moving_bogie.model.physical import PhysicalParams
    from moving_bogie.stability.maps.sleeper_map import SleeperMap

#: a sleeper map of over TIMED cells per axis is timed on one column before it starts
TIMED = 50

#: the velocity and mass axes without --range, m/s and kg
DEFAULT_RANGES = {"v": (20.0, 400.0), "M": (0.0, 3000.0)}

#: options of the continuous plane that a sleeper file does not take (dest -> why), refused when given
_MODEL = "give the model and its values in the file"
_NOT_APPLICABLE = {
    "case": _MODEL, "beam": _MODEL, "track": _MODEL, "vehicle": _MODEL,
    "npz": "a sleeper map writes its figure and its JSON only", "out": "a sleeper map is not a sweep store",
}  # fmt: skip


def sleeper_data(args: argparse.Namespace) -> PhysicalParams | None:
    """The SI parameters of ``--file`` (``--set`` applied) when its model is on periodic supports, else
    None."""
    if getattr(args, "file", None) is None:
        return None
    from .common import params_from_args

    params, physical = params_from_args(args)
    if not params.model.periodic:
        return None
    if physical is None:
        raise ParameterError(
            "file", f"{params.model.name}: a sleeper track takes a [physical] table in SI units"
        )
    return physical


def _refuse_options(args: argparse.Namespace) -> None:
    """One message naming the first option that does not apply to a sleeper file (before any work)."""
    refuse_for_sleepers(args, _NOT_APPLICABLE)
    if getattr(args, "parameter", "eta_M") != "eta_M":
        raise ParameterError("--parameter", "on a sleeper track the vertical axis is the wheel mass M")
    if args.alpha_min != 0.0 or args.alpha_max != 1.2 or getattr(args, "theta_max", 200.0) != 200.0:
        raise ParameterError("--range", "on a sleeper track give the axes as --range v=LO:HI --range M=0:HI")
    if getattr(args, "units", None) == "dimensionless":
        raise ParameterError("--units", "a sleeper map is in SI units (v in m/s, M in kg)")
    if getattr(args, "lines", False):
        raise ParameterError("--lines", "--lines: the map of a sleeper track always shows its D-lines")


def _ranges(args: argparse.Namespace) -> dict[str, tuple[float, float]]:
    ranges = dict(DEFAULT_RANGES)
    for name, spec in named_values(args.range, "--range", "NAME=LO:HI").items():
        if name not in ranges:
            raise ParameterError("--range", f"--range {name}: not an axis (known: v, M)")
        ranges[name] = value_range(name, spec)
    if ranges["v"][0] <= 0:
        raise ParameterError("--range", "--range v: the velocities must be positive on a sleeper track")
    if ranges["M"][0] < 0:
        raise ParameterError("--range", "--range M: the masses must not be negative")
    return ranges


def _check_bar(args: argparse.Namespace, physical: PhysicalParams) -> None:
    """A bar that would follow the wheel mass is refused, naming ``--bar``: the D-decomposition on sleepers
    is a pencil in the wheel's mass alone (S19), so the map holds the bar's M_b and J_b (``--bar fixed``)."""
    from moving_bogie.model.bar import moves_bar

    model = physical.model
    if getattr(args, "bar", "fixed") != "fixed" and moves_bar(model, model.wheel_mass):
        raise ParameterError(
            "--bar",
            "--bar follows does not apply on sleepers: the map holds the bar's M_b and J_b along M (its "
            "D-decomposition is a pencil in the wheel mass alone, Eq. (S19)): give --bar fixed",
        )


def sleeper_plane(
    args: argparse.Namespace, n: int, physical: PhysicalParams
) -> tuple[np.ndarray, np.ndarray]:
    """The grid (velocities, masses) of the SI parameters: every option checked before any computation.

    The masses are n points up to the top of the M axis, from its bottom (from M = top / n when it starts
    at 0: the counts are taken from M -> 0 up in any case)."""
    import numpy as np

    _refuse_options(args)
    ranges = _ranges(args)
    values = physical.values()
    if "M" not in values:
        raise ParameterError("vehicle", f"vehicle {physical.model.vehicle!r} has no wheel mass M")
    if not values.get("c_f", 0) > 0:
        raise ParameterError(
            "c_f", "c_f must be positive: the D-decomposition runs along the real axis (S15)"
        )
    _check_bar(args, physical)
    (v0, v1), (m0, m1) = ranges["v"], ranges["M"]
    masses = np.linspace(m1 / n, m1, n) if m0 == 0 else np.linspace(m0, m1, n)
    return np.linspace(v0, v1, n), masses


def _text(smap: SleeperMap, *, crossings: bool) -> str:
    s = smap.summary()
    lines = [
        f"model {s['model']}: unstable roots {smap.region}, {s['method']}",
        f"v {s['v_m_s'][0]:.6g}..{s['v_m_s'][1]:.6g} m/s ({s['v_m_s'][2]}), "
        f"M {s['M_kg'][0]:.6g}..{s['M_kg'][1]:.6g} kg ({s['M_kg'][2]})",
        f"unstable cells {s['unstable_cells']} of {s['cells']}, most unstable roots {s['max_count']}, "
        f"crossings {s['crossings']}, uncertain columns {s['uncertain_columns']}",
    ]
    if smap.margin is not None:
        decay = s["min_decay_rate_1_s"]
        told = "no stable cell measured" if decay is None else f"{decay:.6g} 1/s"
        lines.append(f"margin (smallest Im Omega of a strip search per cell): the stable cells' least {told}")
    if crossings:
        for p in smap.lines():
            lines.append(
                f"  v {p['v']:10.4f} m/s  M {p['M']:12.6g} kg  Omega {p['Omega_rad_s']:12.6g} rad/s  "
                f"count {p['change']:+d} as M grows"
            )
    for c in s["checks"]:
        mark = "agrees" if c["agrees"] else "DISAGREES"
        lines.append(
            f"check v {c['v']:.6g} m/s, M {c['M']:.6g} kg: map {c['map_count']}, floquet_frequencies "
            f"{c['search_count']} ({c['verdict']}): {mark}"
        )
    return "\n".join(lines)


def run_sleeper_lines(args: argparse.Namespace, physical: PhysicalParams) -> int:
    """``instability-lines --file F`` on sleepers: every crossing of every velocity column."""
    from moving_bogie.api import sleeper_map

    vs, ms = sleeper_plane(args, getattr(args, "n", 60), physical)
    with progress_bar("D-decomposition lines", enabled=not args.json) as bar:
        smap = sleeper_map(physical, vs, ms, verify=3 if args.verify else 0, progress=bar)
    return report(args, smap, _operating(physical), crossings=True, continuous=None)


def run_sleeper_map(args: argparse.Namespace, on_supports: PhysicalParams) -> int:
    """``stability-map --file F`` on sleepers: the map, the continuous track's map on the same grid."""
    from moving_bogie.api import sleeper_map
    from moving_bogie.kernels.bound import bind
    from moving_bogie.model.smeared import smeared_physical
    from moving_bogie.stability.maps.map import StabilityMap, stability_map

    vs, ms = sleeper_plane(args, args.n, on_supports)
    if args.n > TIMED and not getattr(args, "resume", False):  # a long map says so before it starts
        middle = vs[args.n // 2 : args.n // 2 + 1]
        column = partial(sleeper_map, on_supports, middle, ms, verify=0, workers=1)
        estimate_grid("sleeper map", (args.n, args.n), args.workers, column, yes=args.yes, shorter=SHORTER)
    physical = smeared_physical(on_supports)  # None: no continuous counterpart, the sleeper map alone
    kept = checkpoint_options(args)
    with progress_bar("sleeper map", enabled=not args.json) as bar:
        smap = sleeper_map(
            on_supports, vs, ms, workers=args.workers, progress=bar, margin=args.margin, **kept
        )
    continuous: StabilityMap | None = None
    if physical is not None:
        with progress_bar("continuous map", enabled=not args.json) as bar:
            continuous = stability_map(
                bind(physical.to_dimensionless()),
                parameter="eta_M",
                alphas=(vs / physical.si_factor("alpha")).tolist(),
                thetas=(ms / physical.si_factor("eta_M")).tolist(),
                workers=args.workers,
                progress=bar,
                **kept,
            )
    return report(args, smap, _operating(on_supports), crossings=False, continuous=continuous)


def _operating(physical: PhysicalParams) -> tuple[float, float]:
    """The file's (v, M), marked on the figure."""
    return (float(physical.v), float(physical.M))


def report(
    args: argparse.Namespace, smap: SleeperMap, operating: tuple[float, float] | None, **kw: object
) -> int:
    """Print a map of D-decomposition columns (``crossings``: with every crossing; ``continuous``: the
    continuous track's map beside it, or None), write its ``--csv`` and ``--plot``; exit 1 on notes."""
    from moving_bogie.stability.maps.map import StabilityMap

    continuous = kw["continuous"]
    assert continuous is None or isinstance(continuous, StabilityMap)
    if getattr(args, "csv", None):
        from .common import atomic_write

        atomic_write(args.csv, smap.to_csv().encode())
    if args.plot:
        from moving_bogie.stability.figures.sleeper_map_figure import sleeper_map_figure

        from .stability_options import save_figure

        label = "continuous one-layer track, k_f = k_sup / l + k_f, c_f = c_sup / l + c_f"
        save_figure(
            sleeper_map_figure(smap, continuous, operating=operating, continuous_label=label), args.plot
        )
    extra = {}
    if continuous is not None:
        extra["continuous"] = {
            "model": continuous.model,
            "unstable_cells": int((continuous.count > 0).sum()),
            "uncertain_cells": int(continuous.uncertain.sum()),
        }
    if args.json:
        print_json((smap.to_dict() if kw["crossings"] else smap.summary()) | extra)
    else:
        print(_text(smap, crossings=bool(kw["crossings"])))
        if extra:
            c = extra["continuous"]
            print(f"continuous track ({c['model']}), same grid: unstable cells {c['unstable_cells']}")
    for note in smap.notes:
        print(f"warning: {note}", file=sys.stderr)
    return 0 if not smap.notes else 1
