"""``moving-bogie validate``: the finite beam against the closed form, side by side (Section 3.2); on periodic
supports the finite rail against the Floquet theory (docs/sleepers.md, "The finite rail on sleepers")."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING, Any, cast

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from moving_bogie.model.params import DimensionlessParams
    from moving_bogie.model.physical import PhysicalParams
    from moving_bogie.validation.sleeper_verdict import SleeperCheck
    from moving_bogie.validation.verdict import ValidationResult

from .checks import count, number
from .common import add_json_option, add_parameter_options, params_from_args, print_json, refuse_for_sleepers
from .outputs import add_figure_option


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``validate`` subcommand."""
    parser = subparsers.add_parser(
        "validate",
        help="finite-beam validation of the closed-form time series (paper, Section 3.2)",
        description=(
            "Run the finite-beam modal model (simply supported beam, --modes sine modes, with the\n"
            "quasi-static response of the truncated modes added back; on a layered track each mode of\n"
            "the rail coupled with the same mode of every mass layer) and the closed-form response on\n"
            "one tau grid, and compare the rear- and front-wheel deflections, the bar bounce and the bar\n"
            "pitch over the window before reflections from the supports can matter. They agree when\n"
            "every quantity's largest difference is within --tol (default 1 %) of its largest value\n"
            "over the window. A second run with twice the time step estimates the finite beam's own\n"
            "error, for information (see docs/finite_beam.md).\n"
            "Exit status 1 when some quantity differs by more than --tol, 2 on bad input."
        ),
        epilog=(
            "examples:\n  moving-bogie validate --case 7\n"
            "  moving-bogie validate --case 7 --beam tr --S 10 --r 0.09\n"
            "  moving-bogie validate --file examples/two-layer.toml\n"
            "  moving-bogie validate --case 1 --tmax 400 --plot case1.png\n"
            "  moving-bogie validate --case 2 --modes 1000 --json\n"
            "  moving-bogie validate --case 5 --model masses --plot masses5.png\n"
            "  moving-bogie validate --file examples/sleepers.toml --plot sleepers.png\n"
            "On a sleeper track (--file naming track = sleepers or sleepers-two-layer) the finite rail is\n"
            "compared with the Floquet theory instead: the growth rate and dominant frequency of the free\n"
            "vibration (unstable case) or the steady contact force over a bay (stable case); see\n"
            "docs/sleepers.md."
        ),
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    add_parameter_options(parser)
    parser.add_argument(
        "--modes",
        type=count(4, 20_000),
        default=500,
        metavar="N",
        help="sine modes of the finite beam (default 500)",
    )
    parser.add_argument(
        "--tmax",
        type=number,
        metavar="T",
        help="end of the run in dimensionless time (default 200 with foundation damping, 100 without)",
    )
    parser.add_argument(
        "--tol",
        type=number,
        default=0.01,
        metavar="X",
        help="relative tolerance per quantity, a fraction of its largest value (default 0.01)",
    )
    parser.add_argument(
        "--no-correction",
        action="store_true",
        help="plain N-mode finite beam, without the static correction of the truncated modes",
    )
    parser.add_argument(
        "--no-estimate",
        action="store_true",
        help="skip the second run (twice the time step) of the error estimate",
    )
    add_figure_option(parser, "--plot", help="write the paper-style figure (PNG, PDF, SVG, ...)")
    add_json_option(parser)
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """One call of :func:`moving_bogie.validate` (the finite beam against the closed form, or on periodic
    supports the finite rail against the Floquet theory: the library dispatches on the bound model), its
    figure, its JSON or its table."""
    params, physical = _checked(args)  # every input checked before the heavy imports
    periodic = params.model.periodic
    from moving_bogie.api import validate

    from .progress import progress_bar

    target = physical if periodic and physical is not None else params
    what = "Floquet theory + finite rail" if periodic else "finite beam + closed form"
    with progress_bar(what, enabled=not args.json) as update:
        result = validate(target, progress=update, **_options(args, periodic))
    if args.plot:
        from moving_bogie.response.plots import save_figure

        save_figure(_figure(args, result, target), args.plot, dpi=150)
    data = result.to_dict()
    if args.case is not None:
        data["case"] = args.case
    if args.plot:
        data["plot"] = str(args.plot)
    if args.json:
        print_json(data)
    else:
        print(format_sleeper_check(data) if periodic else format_result(cast("ValidationResult", result)))
        if args.plot:
            print(f"figure written to {args.plot}")
    return 0 if result.agrees else 1


def _checked(args: argparse.Namespace) -> tuple[DimensionlessParams, PhysicalParams | None]:
    """The parameters, every option checked for the kind of track (one message naming the first wrong)."""
    from moving_bogie.errors import ParameterError

    if args.file is not None:
        params, physical = params_from_args(args)
        if params.model.periodic:
            if not (0 < args.tol < 1):
                raise ParameterError("tol", f"--tol must be a fraction between 0 and 1 (got {args.tol})")
            _refuse_on_supports(args)
            return params, physical
    if args.modes < 4:
        raise ParameterError("modes", f"--modes must be at least 4 (got {args.modes})")
    if args.tmax is not None and not (args.tmax > 0 and args.tmax < float("inf")):
        raise ParameterError("tmax", f"--tmax must be a positive number (got {args.tmax})")
    if not (0 < args.tol < 1):
        raise ParameterError("tol", f"--tol must be a fraction between 0 and 1 (got {args.tol})")
    return params_from_args(args)


def _options(args: argparse.Namespace, periodic: bool) -> dict[str, Any]:
    """The options of the check of this kind of track (a sleeper file takes ``--tol`` only)."""
    if periodic:
        return {"tol": args.tol}
    return {
        "n_modes": args.modes,
        "tau_max": args.tmax,
        "tol": args.tol,
        "static_correction": not args.no_correction,
        "estimate": not args.no_estimate,
    }


def _figure(
    args: argparse.Namespace,
    result: ValidationResult | SleeperCheck,
    params: DimensionlessParams | PhysicalParams,
) -> Figure:
    """The paper-style figure of the continuous check, or the finite rail's on sleepers."""
    from moving_bogie.validation.sleeper_verdict import SleeperCheck

    if isinstance(result, SleeperCheck):
        from moving_bogie.validation.sleepers_plots import plot_sleeper_check

        return plot_sleeper_check(result, title=_check_title(result, params))
    from moving_bogie.validation.compare import plot_validation
    from moving_bogie.validation.verdict import beam_title

    name = f"Case {args.case}" if args.case is not None else "moving bogie"
    beam = f", {beam_title(params)}"
    track = getattr(params, "track", "one-layer")
    beam += "" if track == "one-layer" else f", {track} track"
    title = f"{name} ({args.model}{beam}): finite beam (solid) vs closed form (dashed)"
    return plot_validation(result, title=title)


def format_result(result: ValidationResult) -> str:
    """Readable summary of a :class:`~moving_bogie.validation.verdict.ValidationResult`."""
    from moving_bogie.validation.verdict import beam_title

    finite = result.finite
    correction = "with" if finite.static_correction else "without"
    track = getattr(result.params, "track", "one-layer")
    on = "" if track == "one-layer" else f" on a {track} track"
    lines = [
        f"Finite {beam_title(result.params)}{on} ({finite.n_modes} modes {correction} static correction, "
        f"L = {finite.length:.1f}, entry x0 = {finite.entry:.1f}, k_max = {finite.k_max:.2f}, "
        f"dt = {finite.dt:.4f}) vs closed form, {result.model}",
        f"comparison window: tau in [0, {result.window[1]:.1f}] of [0, {result.tau[-1]:g}] "
        f"(strict reflection-free tau_valid = {finite.tau_valid:.1f})",
        f"  {'quantity':<9}{'max |diff|':>12}{'max |X|':>10}{'relative':>10}{'est. error':>12}  verdict",
    ]
    for name, q in result.quantities.items():
        verdict = "ok" if q.within else "EXCEEDS"
        estimate = "-" if q.error_estimate != q.error_estimate else f"{q.error_estimate:.2g}"  # NaN: not run
        lines.append(
            f"  {name:<9}{q.max_abs_diff:>12.4g}{q.amplitude:>10.4g}{q.relative:>10.3%}"
            f"{estimate:>12}  {verdict}"
        )
    lines.append(
        f"tolerance: max|X_finite - X_closed| <= {result.tolerance:.3g} max|X_closed| over the window "
        "(est. error: |X_dt - X_2dt| / 3, information only)"
    )
    lines.append(
        f"time: finite beam {result.finite_beam_s:.2f} s (estimate run {result.reference_s:.2f} s), "
        f"closed form {result.closed_form_s:.2f} s"
    )
    for note in result.notes:
        lines.append(f"NOTE: {note}")
    if result.agrees:
        lines.append(f"verdict: AGREE (every quantity within {result.tolerance:.3g})")
    else:
        lines.append(f"verdict: DISAGREE (some quantity differs by more than {result.tolerance:.3g})")
    return "\n".join(lines)


# --- on periodic supports -----------------------------------------------------------------------------

#: options of ``validate`` that the continuous tracks' check takes and a sleeper file does not, and why
_MODEL = "give the model in the file"
_NOT_HERE = {
    "case": _MODEL, "beam": _MODEL, "track": _MODEL, "vehicle": _MODEL,
    "tmax": "the check runs its own times (growth over periods, a steady bay)",
    "no_correction": "the rail on sleepers is meshed in beam elements, not in truncated sine modes",
    "no_estimate": "the rail on sleepers has no second run of the error estimate",
}  # fmt: skip


def _refuse_on_supports(args: argparse.Namespace) -> None:
    """One message naming the first option that does not apply to a sleeper file (before any work)."""
    from moving_bogie.errors import ParameterError

    refuse_for_sleepers(args, _NOT_HERE)
    if args.modes != 500:
        raise ParameterError(
            "modes", "--modes does not apply to a sleeper-track file: its rail is meshed in beam elements"
        )


def _check_title(result: SleeperCheck, params: DimensionlessParams | PhysicalParams) -> str:
    """The figure's title: the model and its speed (in m/s for SI parameters)."""
    speed = (
        f"v = {float(params.v):g} m/s" if result.scales is not None else f"alpha = {float(params.alpha):g}"
    )
    return f"{result.model}, {speed}"


def _dt_text(finite_beam: dict[str, Any]) -> str:
    """The finite rail's time step: in s when known (``dt_s``), else per unit tau."""
    if "dt_s" in finite_beam:
        return f"{finite_beam['dt_s']:.4g} s"
    return f"{finite_beam['dt']:.4g}"


def _in_si(comparison: dict[str, Any]) -> dict[str, Any]:
    """A comparison of a check's ``to_dict()`` with its SI values (a dimensionless check: its own, unit 1)."""
    keys = {"floquet_si": "floquet", "finite_beam_si": "finite_beam"}
    return {k: comparison.get(v) for k, v in keys.items()} | {"unit_si": "1"} | comparison


def format_sleeper_check(out: dict[str, Any]) -> str:
    """The table: quantity, Floquet, finite beam (SI), relative difference, and the verdict line."""
    from moving_bogie.validation.sleeper_verdict import TOLERANCE_RULE

    fb = out["finite_beam"]
    lines = [
        f"model {out['model']}: finite rail of {fb['bays']} bays "
        f"({fb['elements_per_bay']} quintic elements per bay, "
        f"{fb['unknowns']} unknowns, dt = {_dt_text(fb)}) against the Floquet theory "
        f"(verdict {out['floquet_verdict'].upper()})",
        f"  {'quantity':<26}{'Floquet':>14}{'finite beam':>14}  {'unit':<6}{'rel. diff':>10}  within",
    ]
    comparisons = [_in_si(c) for c in out["comparisons"]]
    for c in comparisons:
        lines.append(
            f"  {c['quantity']:<26}{c['floquet_si']:>14.6g}{c['finite_beam_si']:>14.6g}  {c['unit_si']:<6}"
            f"{c['relative_diff']:>10.3%}  {'yes' if c['within'] else 'NO'}"
        )
    lines.append(f"rule: {TOLERANCE_RULE}")
    t = out["timings"]
    lines.append(f"time: Floquet {t['floquet_s']:.2f} s, finite beam {t['finite_beam_s']:.2f} s")
    lines += [f"NOTE: {note}" for note in out["notes"]]
    judged = "; ".join(
        f"{c['quantity']} {c['floquet_si']:.6g} (Floquet) vs {c['finite_beam_si']:.6g} (finite beam) "
        f"{c['unit_si']}: {c['relative_diff']:.3%} {'<=' if c['within'] else '>'} {c['tolerance']:.2%}"
        for c in comparisons
    )
    lines.append(f"verdict: {'AGREE' if out['agrees'] else 'DISAGREE'}: {judged or 'nothing compared'}")
    return "\n".join(lines)
