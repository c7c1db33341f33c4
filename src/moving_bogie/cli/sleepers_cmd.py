"""``moving-bogie frequencies --file F`` for a file on a sleeper track: the Floquet induced frequencies."""

from __future__ import annotations

import argparse
import sys

from moving_bogie.cli.common import print_json


def sleeper_settings(texts: list[str] | None) -> dict[str, float]:
    """``--set NAME=VALUE`` as SI floats, the overrides of a sleeper file's ``[physical]`` values."""
    from moving_bogie.errors import ParameterError

    from .checks import exact_number, named_values

    out: dict[str, float] = {}
    for name, value in named_values(texts or (), "--set", "NAME=NUMBER").items():
        try:
            out[name] = float(exact_number(value))
        except ValueError as exc:
            raise ParameterError("--set", f"--set {name}={value}: expected NAME=NUMBER ({exc})") from None
    return out


def run_sleeper_frequencies(args: argparse.Namespace) -> int:
    """Every root in one strip of width Omega_0 up to the stated Im Omega in rad/s, the harmonics, the
    verdict and a stable result's margin [1/s]."""
    import importlib

    from moving_bogie.errors import ParameterError
    from moving_bogie.floquet.inputs import load_sleeper_file

    from .common import refuse_for_sleepers

    model = "give the model and its values in the file"
    reasons = dict.fromkeys(("case", "beam", "track", "vehicle"), model)
    refuse_for_sleepers(args, reasons | {"window": "the search covers one strip of width Omega_0"})
    data = load_sleeper_file(args.file, overrides=sleeper_settings(getattr(args, "set", None)))
    if data.groups["alpha"] <= 0:
        raise ParameterError(
            "v", "v must be positive on a sleeper track (the Floquet strip has width 2 pi v / l)"
        )

    from moving_bogie.floquet.hill import VehicleMatrices, harmonic_set
    from moving_bogie.floquet.strip import floquet_frequencies
    from moving_bogie.floquet.track import SleeperTrack

    track = SleeperTrack(data.beam, data.track, data.groups)
    module = importlib.import_module(f"moving_bogie.generated.vehicle_{data.vehicle}")
    vehicle = VehicleMatrices.from_module(module, data.vehicle_groups)
    result = floquet_frequencies(track, vehicle)
    to_si = 1 / data.t_scale
    roots = [
        {
            "q": [r.q.real, r.q.imag],
            "Omega_rad_s": [r.q.real * to_si, r.q.imag * to_si],
            "residual": r.residual,
            "step_at_last_harmonic": r.step,
        }
        for r in result.roots
    ]
    out = {
        "model": f"{data.beam}/{data.track}/{data.vehicle}",
        "Omega0_rad_s": result.Omega0 * to_si,
        "strip_rad_s": [result.window.x0 * to_si, result.window.x1 * to_si],
        "window_im_rad_s": [result.window.y0 * to_si, result.window.y1 * to_si],
        "harmonics": [int(n) for n in harmonic_set(result.harmonics)],
        "converged": result.converged,
        "count": result.count,
        "roots": roots,
        "verdict": result.verdict,
        "margin_1_s": None if result.margin is None else result.margin * to_si,
        "margin_source": result.margin_source,
        "free_waves_im_rad_s": result.free_waves * to_si,
        "unsearched": list(result.unsearched(to_si, " rad/s")),
        "notes": list(result.notes),
        "evaluations": result.evaluations,
    }
    if args.json:
        print_json(out)
    else:
        print(format_sleeper_result(out))
    for note in result.notes:
        print(f"warning: {note}", file=sys.stderr)
    return 0 if result.verdict != "UNDETERMINED" else 1


def format_sleeper_result(out: dict) -> str:
    """The text table: the strip, the harmonics, each root in rad/s and the verdict."""
    lines = [
        f"model {out['model']}: Floquet induced frequencies in one strip of width Omega_0 = "
        f"{out['Omega0_rad_s']:.6g} rad/s",
        f"strip Re Omega in [{out['strip_rad_s'][0]:.6g}, {out['strip_rad_s'][1]:.6g}] rad/s, "
        f"Im Omega in [{out['window_im_rad_s'][0]:.6g}, {out['window_im_rad_s'][1]:.6g}] rad/s",
        f"harmonics n = {out['harmonics'][0]}..{out['harmonics'][-1]}"
        + (" (roots converged)" if out["converged"] else " (roots NOT converged)"),
        f"{out['count']} root(s) counted by the argument principle, {len(out['roots'])} located",
    ]
    if out["roots"]:
        lines.append(f"  {'Re Omega [rad/s]':>18}  {'Im Omega [rad/s]':>18}")
        for r in out["roots"]:
            lines.append(f"  {r['Omega_rad_s'][0]:18.10g}  {r['Omega_rad_s'][1]:18.10g}")
    lines.append(f"verdict: {out['verdict']}")
    if out["margin_1_s"] is not None:
        lines.append(
            f"margin: the least-damped vibration decays at {out['margin_1_s']:.6g} 1/s "
            f"({out['margin_source']})"
        )
    lines += [f"not searched: {band}" for band in out["unsearched"]]
    return "\n".join(lines)
