"""Commands on a track on the soil (docs/soil.md): ``dispersion``, ``moving-load``, and the soil path of
``critical-velocity --file`` (:func:`run_soil_critical_velocity`)."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from .checks import count, exact_number
from .common import add_json_option, add_set_option, print_json, soil_settings
from .outputs import add_figure_option
from .stability_options import RAW

__all__ = ["add_soil_set_option", "register", "run_soil_critical_velocity"]


#: The most frequencies (--omega) or speeds (--range v=LO:HI:N) of one run.
MAX_SAMPLES = 10_000


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add ``dispersion`` and ``moving-load``."""
    p = subparsers.add_parser(
        "dispersion",
        help="surface-wave modes of the soil and free waves of a track on it (soil-track file)",
        description=(
            "The soil's Rayleigh modes (phase velocity against frequency, the fundamental first) and the\n"
            "free waves of the track on the soil: its own curve without the soil, and the guided waves of\n"
            "the coupled track and soil (undamped), at the frequencies of --omega (rad/s)."
        ),
        epilog=(
            "examples:\n  moving-bogie dispersion --file examples/soil-ballasted.toml --omega 1,10,50 --json"
        ),
        formatter_class=RAW,
    )
    p.add_argument("--file", type=Path, required=True, metavar="F.toml", help="a soil-track file")
    p.add_argument(
        "--omega",
        type=_omega_list,
        default=None,
        metavar="W1,W2,...",
        help="frequencies in rad/s (default 32 from 0.6 to 600, geometric)",
    )
    p.add_argument(
        "--modes", type=count(1, 1000), default=None, metavar="N", help="report the N slowest soil modes"
    )
    add_figure_option(p, "--plot", help="write the dispersion figure")
    add_soil_set_option(p)
    add_json_option(p)
    p.set_defaults(handler=run_dispersion)
    q = subparsers.add_parser(
        "moving-load",
        help="steady deflection of a track on the soil under a moving constant load, against speed",
        description=(
            "The deflection under the load P of the file (downwards, m) at each speed of\n"
            "--range v=LO:HI[:N] (m/s), the static deflection, the peak refined between grid points and\n"
            "its amplification over static, and the deflection along the track at the peak speed. The soil\n"
            "needs eta > 0."
        ),
        epilog=(
            "examples:\n"
            "  moving-bogie moving-load --file examples/soil-ballasted.toml --range v=20:120 --json"
        ),
        formatter_class=RAW,
    )
    q.add_argument("--file", type=Path, required=True, metavar="F.toml", help="a soil-track file with P")
    q.add_argument(
        "--range",
        dest="speeds",
        type=_speed_range,
        required=True,
        metavar="v=LO:HI[:N]",
        help="speeds in m/s (N points, default 21)",
    )
    add_figure_option(q, "--plot", help="write the amplification against speed")
    add_soil_set_option(q)
    add_json_option(q)
    q.set_defaults(handler=run_moving_load)


def add_soil_set_option(parser: argparse.ArgumentParser) -> None:
    """``--set KEY=VALUE`` of a soil-track file: a [physical] key or a layer key numbered from the top."""
    add_set_option(
        parser,
        help="change a value of the file, in its unit: a [physical] key (--set EI=1.3e7) or a soil layer's "
        "key with the layer's number, 1 at the top (--set c_s1=90, --set h2=8; docs/soil.md)",
    )


def _omega_list(text: str) -> list[float]:
    try:
        values = [float(exact_number(x)) for x in text.split(",") if x.strip()]
    except ValueError as exc:
        raise argparse.ArgumentTypeError(
            f"--omega {text!r}: expected numbers separated by commas ({exc})"
        ) from None
    if len(values) > MAX_SAMPLES:
        raise argparse.ArgumentTypeError(f"--omega: at most {MAX_SAMPLES} frequencies (got {len(values)})")
    if not values or any(not w > 0 for w in values):
        raise argparse.ArgumentTypeError(f"--omega {text!r}: give positive frequencies in rad/s")
    return sorted(values)


def _speed_range(text: str) -> tuple[float, float, int]:
    name, eq, rest = text.partition("=")
    parts = rest.split(":")
    try:
        if name.strip() != "v" or not eq or len(parts) not in (2, 3):
            raise ValueError
        lo, hi = float(exact_number(parts[0])), float(exact_number(parts[1]))
        n = int(parts[2]) if len(parts) == 3 else 21
    except ValueError as exc:
        reason = f" ({exc})" if "range" in str(exc) else ""
        raise argparse.ArgumentTypeError(
            f"--range {text!r}: expected v=LO:HI or v=LO:HI:N (m/s){reason}"
        ) from None
    if not 0 < lo < hi or not 3 <= n <= MAX_SAMPLES:
        raise argparse.ArgumentTypeError(f"--range {text!r}: need 0 < LO < HI and 3 <= N <= {MAX_SAMPLES}")
    return lo, hi, n


def _header(data: Any) -> dict[str, Any]:
    return {"track": data.track.kind, "per": data.per, "soil": data.soil.to_dict()}


def run_dispersion(args: argparse.Namespace) -> int:
    import numpy as np

    from moving_bogie.soil.critical import DEFAULT_OMEGA, critical_velocity
    from moving_bogie.soil.file import load_soil_file
    from moving_bogie.soil.rayleigh import soil_modes

    data = load_soil_file(args.file, soil_settings(args))
    omega = np.array(args.omega) if args.omega is not None else DEFAULT_OMEGA
    modes = soil_modes(omega, data.soil)
    crit = critical_velocity(data.track, data.soil, omega)
    out = _header(data) | {
        "soil_modes": modes.to_list(args.modes),
        "track_waves": {
            "omega": omega.tolist(),
            "c_coupled": [[c for c in row if np.isfinite(c)] for row in crit.waves.c],
            "c_uncoupled": [c if np.isfinite(c) else None for c in crit.c_track],
        },
        "units": {"omega": "rad/s", "c": "m/s"},
    }
    if args.plot is not None:
        _save(args.plot, _dispersion_plot(modes, crit, data))
    if args.json:
        print_json(out)
        return 0
    print(f"track {data.track.kind} (input per {data.per}) on {len(data.soil.layers)} soil layer(s)")
    print(f"{'omega [rad/s]':>14} {'soil modes c [m/s], fundamental first':<40} {'track c [m/s]'}")
    for i, w in enumerate(omega):
        soil = ", ".join(f"{c:.4f}" for c in modes.c[i] if np.isfinite(c))
        track = ", ".join(f"{c:.4f}" for c in crit.waves.c[i] if np.isfinite(c)) or "-"
        print(f"{w:14.6g} {soil:<40} {track}")
    return 0


def _dispersion_plot(modes: Any, crit: Any, data: Any) -> Any:
    from moving_bogie.soil.plots import dispersion_figure

    return dispersion_figure(modes, crit, f"{data.track.kind} track on {len(data.soil.layers)}-layer soil")


def _save(path: Path, fig: Any) -> None:
    from .stability_options import save_figure

    save_figure(fig, path)


def run_soil_critical_velocity(args: argparse.Namespace) -> int:
    """``critical-velocity --file`` on a soil-track file: v_cr (coupled) and v_cr_uncoupled (m/s)."""
    import numpy as np

    from moving_bogie.soil.critical import critical_velocity
    from moving_bogie.soil.file import load_soil_file
    from moving_bogie.soil.rayleigh import soil_modes

    data = load_soil_file(args.file, soil_settings(args))
    crit = critical_velocity(data.track, data.soil)
    out = _header(data) | crit.to_dict() | {"units": {"v": "m/s", "omega": "rad/s", "k": "rad/m"}}
    plot = getattr(args, "plot", None)
    if plot is not None:
        _save(plot, _dispersion_plot(soil_modes(crit.waves.omega, data.soil, modes=6), crit, data))
    if args.json:
        print_json(out)
        return 0
    print(f"track {data.track.kind} (input per {data.per}) on {len(data.soil.layers)} soil layer(s)")
    v = (
        f"{crit.v_cr:.6g} m/s at omega = {crit.omega_cr:.6g} rad/s"
        if np.isfinite(crit.v_cr)
        else "none found"
    )
    print(f"v_cr             {v}  (least phase velocity of the coupled guided waves)")
    u = crit.v_cr_uncoupled
    estimate = f"{u:.6g} m/s at omega = {crit.omega_uncoupled:.6g} rad/s" if np.isfinite(u) else "none"
    print(f"v_cr_uncoupled   {estimate}  (intersection estimate, Mezher et al. 2016)")
    for w, c, where in crit.minima:
        print(f"branch minimum   {c:.6g} m/s at omega = {w:.6g} rad/s ({where})")
    for note in crit.notes:
        print(f"note             {note}")
    return 0


def run_moving_load(args: argparse.Namespace) -> int:
    import numpy as np

    from moving_bogie.errors import ParameterError
    from moving_bogie.soil.file import load_soil_file
    from moving_bogie.soil.moving_load import deflection, moving_load

    data = load_soil_file(args.file, soil_settings(args))
    if data.load is None:
        raise ParameterError("P", f"{args.file}: P (N) is missing from [physical]: the moving load")
    if any(layer.eta <= 0 for layer in data.soil.layers):
        raise ParameterError(
            "eta", "a moving load needs Kelvin-Voigt damping eta > 0 in every [[soil]] layer"
        )
    lo, hi, n = args.speeds
    result = moving_load(data.track, data.soil, data.load, np.linspace(lo, hi, n))
    xi = np.linspace(-30.0, 30.0, 121)
    shape = deflection(data.track, data.soil, data.load, result.v_peak, xi)
    out = _header(data) | {
        "P": data.load / data.rail_factor,
        "P_unit": f"N per {data.per}",
        "w_static": result.w_static,
        "v": result.v.tolist(),
        "w": result.w.tolist(),
        "daf": result.daf.tolist(),
        "v_peak": result.v_peak,
        "w_peak": result.w_peak,
        "daf_peak": result.daf_peak,
        "error": result.error,
        "shape_at_peak": {"xi": xi.tolist(), "w": shape.w.tolist()},
        "units": {"w": "m (downwards)", "v": "m/s", "xi": "m (ahead of the load)"},
    }
    if args.plot is not None:
        from moving_bogie.soil.plots import moving_load_figure

        _save(args.plot, moving_load_figure(result, f"{data.track.kind} track: moving load"))
    if args.json:
        print_json(out)
        return 0
    print(f"track {data.track.kind} (input per {data.per}); load P = {out['P']:g} {out['P_unit']}")
    print(f"w_static         {result.w_static:.6g} m")
    print(f"{'v [m/s]':>10} {'w(0) [m]':>14} {'DAF':>8}")
    for v, w, a in zip(result.v, result.w, result.daf, strict=True):
        print(f"{v:10.4g} {w:14.6g} {a:8.4f}")
    print(
        f"peak             DAF {result.daf_peak:.5g} at v = {result.v_peak:.6g} m/s "
        f"(w = {result.w_peak:.6g} m)"
    )
    return 0
