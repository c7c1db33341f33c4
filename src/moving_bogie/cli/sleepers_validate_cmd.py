"""``moving-bogie validate --file F`` on a sleeper track: the finite rail against the Floquet theory."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING, Any

from moving_bogie.cli.common import print_json, refuse_for_sleepers

if TYPE_CHECKING:
    from moving_bogie.model.sleeper_input import SleeperInput
    from moving_bogie.validation.sleepers_check import SleeperCheck

#: options of ``validate`` that the continuous tracks' check takes and a sleeper file does not, and why
_MODEL = "give the model in the file"
_NOT_HERE = {
    "case": _MODEL, "beam": _MODEL, "track": _MODEL, "vehicle": _MODEL,
    "tmax": "the check runs its own times (growth over periods, a steady bay)",
    "no_correction": "the rail on sleepers is meshed in beam elements, not in truncated sine modes",
    "no_estimate": "the rail on sleepers has no second run of the error estimate",
}  # fmt: skip


def _refuse(args: argparse.Namespace) -> None:
    """One message naming the first option that does not apply to a sleeper file (before any work)."""
    from moving_bogie.errors import ParameterError

    refuse_for_sleepers(args, _NOT_HERE)
    if args.modes != 500:
        raise ParameterError(
            "modes", "--modes does not apply to a sleeper-track file: its rail is meshed in beam elements"
        )


def run_sleeper_validation(args: argparse.Namespace, data: SleeperInput) -> int:
    """The three comparisons of :func:`~moving_bogie.validation.sleepers_check.check_sleepers` on the
    parameters ``data`` (the file's, ``--set`` applied), printed."""
    from moving_bogie.validation.on_supports import check_on_supports

    _refuse(args)
    from .progress import progress_bar

    with progress_bar("Floquet theory + finite rail", enabled=not args.json) as update:
        result = check_on_supports(data, tol=args.tol, progress=update)
    if args.plot:
        from moving_bogie.response.plots import save_figure
        from moving_bogie.validation.sleepers_plots import plot_sleeper_check

        title = f"{data.beam}/{data.track}/{data.vehicle}, v = {data.physical['v']:g} m/s"
        newtons, metres = data.si_units()
        figure = plot_sleeper_check(result, title=title, newtons=newtons, metres=metres)
        save_figure(figure, args.plot, dpi=150)
    out = sleeper_check_dict(result, data)
    if args.plot:
        out["plot"] = str(args.plot)
    if args.json:
        print_json(out)
    else:
        print(format_sleeper_check(out))
        if args.plot:
            print(f"figure written to {args.plot}")
    return 0 if result.agrees else 1


def sleeper_check_dict(result: SleeperCheck, data: SleeperInput) -> dict[str, Any]:
    """The check's summary with SI values beside the dimensionless ones (rates and frequencies in 1/s and
    rad/s, forces in N: the static load 2 is P)."""
    out = {"model": f"{data.beam}/{data.track}/{data.vehicle}", **result.to_dict()}
    to_si = {"growth rate -Im q": 1 / data.t_scale, "dominant frequency": 1 / data.t_scale}
    force = data.physical.get("P", 2.0) / 2
    for item in out["comparisons"]:
        scale = to_si.get(item["quantity"], force)
        item["unit_si"] = (
            "N"
            if item["quantity"].startswith("steady")
            else ("1/s" if "rate" in item["quantity"] else "rad/s")
        )
        item["floquet_si"], item["finite_beam_si"] = item["floquet"] * scale, item["finite_beam"] * scale
    out["finite_beam"]["dt_s"] = out["finite_beam"]["dt"] * data.t_scale
    return out


def _dt_text(finite_beam: dict[str, Any]) -> str:
    """The finite rail's time step: in s when known (``dt_s``), else per unit tau."""
    if "dt_s" in finite_beam:
        return f"{finite_beam['dt_s']:.4g} s"
    return f"{finite_beam['dt']:.4g}"


def format_sleeper_check(out: dict[str, Any]) -> str:
    """The table: quantity, Floquet, finite beam (SI), relative difference, and the verdict line."""
    fb = out["finite_beam"]
    lines = [
        f"model {out['model']}: finite rail of {fb['bays']} bays "
        f"({fb['elements_per_bay']} quintic elements per bay, "
        f"{fb['unknowns']} unknowns, dt = {_dt_text(fb)}) against the Floquet theory "
        f"(verdict {out['floquet_verdict'].upper()})",
        f"  {'quantity':<26}{'Floquet':>14}{'finite beam':>14}  {'unit':<6}{'rel. diff':>10}  within",
    ]
    for c in out["comparisons"]:
        lines.append(
            f"  {c['quantity']:<26}{c['floquet_si']:>14.6g}{c['finite_beam_si']:>14.6g}  {c['unit_si']:<6}"
            f"{c['relative_diff']:>10.3%}  {'yes' if c['within'] else 'NO'}"
        )
    lines.append(
        "rule: |finite - Floquet| <= tol |Floquet| for the rate and the frequency; for the steady force "
        "max |difference| over the last bay <= tol x the Floquet force's peak-to-peak"
    )
    t = out["timings"]
    lines.append(f"time: Floquet {t['floquet_s']:.2f} s, finite beam {t['finite_beam_s']:.2f} s")
    lines += [f"NOTE: {note}" for note in out["notes"]]
    judged = "; ".join(
        f"{c['quantity']} {c['floquet_si']:.6g} (Floquet) vs {c['finite_beam_si']:.6g} (finite beam) "
        f"{c['unit_si']}: {c['relative_diff']:.3%} {'<=' if c['within'] else '>'} {c['tolerance']:.2%}"
        for c in out["comparisons"]
    )
    lines.append(f"verdict: {'AGREE' if out['agrees'] else 'DISAGREE'}: {judged or 'nothing compared'}")
    return "\n".join(lines)
