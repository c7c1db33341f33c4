"""``moving-bogie frequencies`` and ``moving-bogie table2``: induced frequencies and the verdict."""

from __future__ import annotations

import argparse
import sys
from dataclasses import replace
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from moving_bogie.model.physical import PhysicalParams
    from moving_bogie.roots.frequency_result import FrequencyResult
    from moving_bogie.roots.proof.certify import Certificate
    from moving_bogie.stability.velocity.supercritical import SpeedRegime

from .checks import count, exact_number
from .common import (
    PROG,
    add_json_option,
    add_parameter_options,
    add_units_option,
    params_from_args,
    print_json,
    si_input,
)


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``frequencies`` and ``table2`` subcommands."""
    parser = subparsers.add_parser(
        "frequencies",
        help="all induced frequencies (roots of E_chr, Eq. (48)) and the stability verdict",
        description=(
            "Find every induced frequency q (root of E_chr, Eq. (48)) with Re q >= 0 in the search window,\n"
            "with no starting guesses: the roots are counted by the argument principle on contours that\n"
            "avoid the cut of K, located, polished at --dps digits and confirmed at higher precision.\n"
            "The motion is unstable when some root has Im q < 0. The default window holds every root with\n"
            "Im q < 0 (a radius R beyond which E_chr has none is checked first), so the verdict is about\n"
            "every root; when the search is incomplete the verdict is UNDETERMINED with the reason."
        ),
        epilog=(
            "exit status:\n"
            "  0  verdict STABLE or UNSTABLE, every root in the window found (also above the critical\n"
            "     velocity: the 'speed: SUPERCRITICAL' line, and \"supercritical\" in --json, say so)\n"
            "  1  verdict UNDETERMINED, the count and the roots found disagree (see the warnings),\n"
            "     or with --certify a root or the count is not proven\n"
            "  2  bad input (the message names the option)\n"
            "warnings and errors go to stderr; the table and the verdict to stdout. With --json an error\n"
            'is the JSON object {"error": ..., "option": ...} on stdout.\n\n'
            "examples:\n  moving-bogie frequencies --case 1\n"
            "  moving-bogie frequencies --case 7 --alpha 0.7 --json\n"
            "  moving-bogie frequencies --case 1 --beam tr --S 100 --r 0.03\n"
            "  moving-bogie frequencies --case 5 --model masses\n"
            "  moving-bogie frequencies --case 1 --certify"
        ),
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    add_parameter_options(parser)
    _add_search_options(parser)
    add_units_option(parser)
    add_json_option(parser)
    parser.set_defaults(handler=run_frequencies)

    table = subparsers.add_parser(
        "table2",
        help="Table 2 of the paper: induced frequencies of the 13 cases of Table 1",
        description=(
            "Compute the induced frequencies of every Table 1 case and print them like the paper's Table 2\n"
            "(q^r with +-, q^i), with the printed value and the difference where the paper prints one.\n"
            "Exit status 1 on any difference beyond the print's rounding, any count mismatch or any\n"
            "UNDETERMINED verdict."
        ),
        epilog="examples:\n  moving-bogie table2\n  moving-bogie table2 --decimals 12\n"
        "  moving-bogie table2 --json\n  moving-bogie table2 --certify",
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    table.add_argument(
        "--decimals", type=count(0, 30), default=6, help="decimals shown in the text table (default 6)"
    )
    table.add_argument(
        "--dps",
        type=count(15, 1000, "digits"),
        default=30,
        help="working precision in decimal digits (default 30)",
    )
    _add_certify_option(table)
    add_json_option(table)
    table.set_defaults(handler=run_table2)


def _add_certify_option(parser: argparse._ActionsContainer) -> None:
    parser.add_argument(
        "--certify",
        action="store_true",
        help="prove every root (alone in a square of half-side 1e-26), the count and the verdict in ball "
        "arithmetic (exit status 1 if a root or a count is not proven; see docs/frequencies.md)",
    )


def _add_search_options(parser: argparse._ActionsContainer) -> None:
    parser.add_argument(
        "--dps",
        type=count(15, 1000, "digits"),
        default=30,
        help="working precision in decimal digits (default 30)",
    )
    parser.add_argument(
        "--window",
        metavar="X,Y",
        help="search window 0 <= Re q <= X, -Y <= Im q <= Y + eta_f (default: see docs/frequencies.md)",
    )
    _add_certify_option(parser)


def _check_dps(dps: int) -> None:
    from moving_bogie.errors import ParameterError

    if not 15 <= dps <= 1000:
        raise ParameterError("dps", f"dps must be between 15 and 1000 (got {dps})")


def run_frequencies(args: argparse.Namespace) -> int:
    from moving_bogie.errors import ParameterError
    from moving_bogie.soil.file import is_soil_file

    if args.file is not None and is_soil_file(args.file):
        return _print_soil(args)
    _check_dps(args.dps)
    params, physical = params_from_args(args)  # every input checked before the heavy imports
    periodic = params.model.periodic
    if periodic:
        _refuse_on_a_strip(args)
    window = None
    if args.window:
        try:
            x, y = (float(exact_number(v)) for v in args.window.split(","))
        except ValueError as exc:
            reason = str(exc) if "range" in str(exc) else f"got {args.window!r}"
            raise ParameterError("window", f"window must be two numbers X,Y ({reason})") from None
        if not (x > 0 and y > 0):
            raise ParameterError("window", "window sizes must be positive")

    from moving_bogie.api import bind, induced_frequencies, speed_regime
    from moving_bogie.roots.count.contour import Rectangle
    from moving_bogie.roots.damping_limit import damping_limit

    from .progress import progress_bar

    if args.window:
        window = Rectangle(-1e-3 * x, x, -y, y + float(params.eta_f))
    options = {} if periodic else {"dps": args.dps, "window": window, "certify": args.certify}
    with progress_bar("induced frequencies", enabled=not args.json) as update:
        result = induced_frequencies(bind(params), progress=update, **options)
    physical = si_input(args, physical)  # the units shown: SI for a [physical] file unless --units says
    if physical is not None:
        result = replace(result, scales=physical.scales())
    limit = None if periodic else damping_limit(result)
    regime = speed_regime(params, physical)
    if args.json:
        data = with_si(result.to_dict(), result, physical)
        data["verdict"] = with_regime(data.get("verdict"), regime)
        data["damping_limit"] = None if limit is None else limit.to_dict()
        speed = {"alpha_cr": regime.alpha_cr, "v_cr": regime.v_cr, "supercritical": regime.supercritical}
        print_json(data | speed | {"speed": regime.to_dict()})
    else:
        if physical is not None:  # the roots in SI in place of q
            print(format_si(result, physical))
        print(format_result(result))
        if limit is not None:
            print(limit.statement())
        print(regime.line())
    for line in format_warnings(result):
        print(line, file=sys.stderr)
    proven = result.certificate is None or result.certificate.all_proven
    return 0 if result.count_ok and result.verdict.determined and proven else 1


def _print_soil(args: argparse.Namespace) -> int:
    """``frequencies --file`` on a soil-track file with a vehicle (:mod:`.soil_frequencies_cmd`), printed
    as on every track."""
    from .soil_frequencies_cmd import soil_frequencies

    run = soil_frequencies(args)
    result, physical, regime = run.result, run.physical, run.regime
    if args.json:
        data = with_si(result.to_dict(), result, physical)
        data["verdict"] = with_regime(data.get("verdict"), regime)
        data["damping_limit"] = None
        speed = {"alpha_cr": regime.alpha_cr, "v_cr": regime.v_cr, "supercritical": regime.supercritical}
        print_json(data | speed | {"speed": regime.to_dict(), "soil": run.soil})
    else:
        print(run.title())
        print(format_si(result, physical))
        print(format_result(result))
        print(regime.line())
    for line in format_warnings(result):
        print(line, file=sys.stderr)
    return 0 if result.count_ok and result.verdict.determined else 1


def _refuse_on_a_strip(args: argparse.Namespace) -> None:
    """--window and --certify do not apply to a track on periodic supports (one message, exit status 2)."""
    from moving_bogie.errors import ParameterError

    if args.window:
        raise ParameterError(
            "window",
            "--window does not apply to a sleeper track: it is searched in one strip of width Omega_0",
        )
    if args.certify:
        raise ParameterError("certify", "--certify is not available on a sleeper track (periodic supports)")


def with_regime(verdict: Any, regime: SpeedRegime) -> Any:
    """The JSON verdict object with ``supercritical``, ``alpha_cr`` (and ``v_cr`` in m/s) added (any other
    JSON value as it is)."""
    extra = {"supercritical": regime.supercritical, "alpha_cr": regime.alpha_cr}
    if regime.v_cr is not None:
        extra["v_cr"] = regime.v_cr
    if isinstance(verdict, dict):
        return verdict | extra
    return verdict


def with_si(data: dict[str, Any], result: FrequencyResult, physical: PhysicalParams | None) -> dict[str, Any]:
    """For a ``[physical]`` input: each root also as ``omega`` [rad/s], Hz and growth time [s]."""
    if physical is None:
        return data
    from moving_bogie.model.si_results import root_in_si

    t_scale = physical.scales().t_scale
    for entry, root in zip(data["roots"], result.roots):
        entry.update(root_in_si(root.q, t_scale, digits=min(12, root.digits)))
    data["si"] = {"t_scale_s": repr(t_scale), "physical": physical.to_dict(), "time_factor": "exp(i omega t)"}
    if "region" in data:
        region = data["region"]
        region["Omega_0_rad_s"] = region["Omega_0"] / t_scale
        waves = region["free_waves_im"]
        region["free_waves_im_rad_s"] = None if waves is None else waves / t_scale
        data["margin_1_s"] = None if result.margin is None else float(result.margin) / t_scale
    return data


def format_si(result: FrequencyResult, physical: PhysicalParams) -> str:
    """The roots of a ``[physical]`` input in SI units, one line each."""
    from moving_bogie.model.si_results import root_in_si

    t_scale = physical.scales().t_scale
    lines = [
        f"Induced frequencies ({result.model}, {result.params.beam.upper()} beam) in SI, time factor "
        "exp(i omega t) (Im omega < 0 grows):"
    ]
    for k, root in enumerate(result.roots, 1):
        si = root_in_si(root.q, t_scale, digits=min(8, root.digits))
        growth = f", growth time {si['growth_time_s']} s" if si["growth_time_s"] else ""
        pair = "" if result.periodic else "+-"
        lines.append(
            f"  {k:>2} omega = {pair}{si['omega']['re']} + {si['omega']['im']}i rad/s, "
            f"f = {si['frequency_hz']} Hz{growth}"
        )
    if result.margin is not None:
        rate = float(result.margin) / t_scale
        lines.append(
            f"  margin: the least-damped vibration decays at {rate:.6g} 1/s ({result.margin_source})"
        )
    return "\n".join(lines)


def format_result(result: FrequencyResult) -> str:
    """The roots (q to their confirmed digits; left to :func:`format_si` for a result in SI, which has
    ``scales``), the count, what was searched and the verdict."""
    lines = []
    region = result.region
    pair = "" if result.periodic else "+-"
    if result.scales is None:
        lines.append(
            f"Induced frequencies ({result.model}, {result.params.beam.upper()} beam), {result.dps} digits:"
        )
        if region is not None and region.periodic:
            lines[0] = (
                f"Induced frequencies ({result.model}, {result.params.beam.upper()} beam on "
                f"{result.params.track}), one strip of width Omega_0 = {region.period:.6g}, harmonics "
                f"{region.harmonics[0]}..{region.harmonics[-1]}, double precision:"
            )
        lines.append(f"  {'':2}{'Re q':>36}  {'Im q':>36}  side   digits")
        for k, r in enumerate(result.roots, 1):
            flag = "unstable" if r.unstable else ("real" if r.marginal else "")
            lines.append(
                f"  {k:<2}{pair + r.re_text:>36}  {r.im_text:>36}  {r.side:<5}  {r.digits:>3}  {flag}"
            )
    lines.append(f"count (argument principle): {result.count}, found: {result.found}")
    lines += _searched_lines(result)
    lines.append(verdict_line(result))
    if result.certificate is not None:
        lines += format_certificate(result.certificate)
    return "\n".join(lines)


def verdict_line(result: FrequencyResult) -> str:
    """``verdict: ...`` with, when unstable, the fastest growth (Im q, or 1/s and s for a result in SI)."""
    import mpmath

    verdict, q = result.verdict, "q" if result.scales is None else "omega"
    if verdict.state == "undetermined":
        return "verdict: UNDETERMINED: " + "; ".join(note.text for note in verdict.reasons)
    if verdict.state == "stable":
        real = sum(r.marginal for r in result.roots)
        neutral = f"; {real} real, neutral (constant amplitude)" if real else ""
        return f"verdict: STABLE (no induced frequency with Im {q} < 0{neutral})"
    if not result.unstable_roots:
        return (
            f"verdict: UNSTABLE, {result.strip_unstable} root(s) with Im {q} < 0 counted in the strip just "
            "below the cut (not located)"
        )
    kind = "root(s) in the strip" if result.periodic else "pair(s)"
    pairs = f"verdict: UNSTABLE, {len(result.unstable_roots)} unstable {kind}"
    if result.scales is not None:
        rate = -float(result.degree_of_instability) / result.scales.t_scale
        return f"{pairs}; growth rate -min Im omega = {rate:.6g} 1/s, growth time {1 / rate:.6g} s"
    growth = mpmath.nstr(result.growth_time, 6)
    degree = mpmath.nstr(result.degree_of_instability, 6)
    return f"{pairs}; degree of instability {degree}, growth time 1/|Im q| = {growth}"


def _searched_lines(result: FrequencyResult) -> list[str]:
    """Where the search went: the sliver around the cut not searched, the far field (Im q, or Im omega [1/s]
    and |omega| [rad/s] for a result in SI)."""
    scale = 1.0 if result.scales is None else result.scales.t_scale
    name, rate, freq = ("q", "", "") if result.scales is None else ("omega", " 1/s", " rad/s")
    lines = []
    if result.periodic:
        w = result.window
        lines.append(
            f"searched: {w.x0 / scale:.6g} <= Re {name} <= {w.x1 / scale:.6g}{freq}, "
            f"{w.y0 / scale:.6g} <= Im {name} <= {w.y1 / scale:.6g}{rate}"
        )
        if result.scales is None and result.margin is not None:
            import mpmath

            lines.append(
                f"margin: the least-damped vibration decays at Im q = {mpmath.nstr(result.margin, 6)} "
                f"({result.margin_source})"
            )
    if result.unsearched:
        height = max(u.height for u in result.unsearched) / scale
        lines.append(
            f"not searched: a sliver of height <= {height:.1e}{rate} around the cut of K "
            "('unsearched' in --json)"
        )
    if result.strip is not None:
        lines.append("below the axis: " + result.strip.statement())
    far, window = result.far_field, result.window
    if far is not None and far.radius is not None:
        lines.append(
            f"far field: no root with Im {name} < 0 beyond |{name}| = {far.radius / scale:g}{freq} "
            f"(|E_chr - E_lead| / |E_lead| <= {far.rho:.2f} there); searched: Re {name} <= "
            f"{window.x1 / scale:g}{freq}, {window.y0 / scale:g} <= Im {name} <= {window.y1 / scale:g}{rate}"
        )
    return lines


def format_warnings(result: FrequencyResult) -> list[str]:
    """The WARNING/ERROR lines of ``result`` (printed on stderr)."""
    lines = [f"{PROG}: warning: {w}" for w in result.warnings]
    if not result.count_ok:
        lines.append(f"{PROG}: error: the count and the roots found disagree: a root may be missing")
    return lines


def format_certificate(c: Certificate) -> list[str]:
    """Lines reporting the ball-arithmetic proof (roots, count, unsearched strip, verdict)."""
    lines = [
        f"certified ({c.seconds:.1f} s): {c.proven_roots}/{len(c.roots)} roots proven, each alone in a "
        f"square of half-side {c.roots[0].radius if c.roots else '-'}; count proven: {c.count}"
        + ("" if c.all_proven else " (NOT all roots proven)")
    ]
    if c.unsearched:
        lo, hi = min(u.y0 for u in c.unsearched), max(u.y1 for u in c.unsearched)
        left, right = min(u.x0 for u in c.unsearched), max(u.x1 for u in c.unsearched)
        lines.append(
            f"  not searched by the proof: {lo:.4g} <= Im q <= {hi:.4g}, {left:.6g} <= Re q <= {right:.4g} "
            "(along the cut of K)"
        )
    lines.append(f"  proven verdict: {c.verdict.upper()} in the window ({c.reason})")
    for p in c.problems:
        lines.append(f"  not proven: {p}")
    return lines


def run_table2(args: argparse.Namespace) -> int:
    from moving_bogie.roots.table2 import compute_table2, format_table2
    from moving_bogie.stability.velocity.supercritical import SUPERCRITICAL_MEANING, speed_regime

    from .progress import progress_bar

    _check_dps(args.dps)
    with progress_bar("Table 2", enabled=not args.json) as update:
        table = compute_table2(dps=args.dps, progress=update, certify=args.certify)
    regimes = [speed_regime(row.result.params) for row in table.rows]
    if args.json:
        data = table.to_dict()
        for entry, regime in zip(data["cases"], regimes):
            entry["verdict"] = with_regime(entry.get("verdict"), regime)
            entry |= {"alpha_cr": regime.alpha_cr, "supercritical": regime.supercritical}
        print_json(data)
    else:
        print(format_table2(table, decimals=args.decimals))
        above = [row.case for row, regime in zip(table.rows, regimes) if regime.supercritical]
        if above:
            print(f"speed: SUPERCRITICAL in case(s) {', '.join(map(str, above))}: {SUPERCRITICAL_MEANING}")
        else:
            known = [r.alpha / r.alpha_cr for r in regimes if r.alpha_cr is not None]
            unknown = [row.case for row, r in zip(table.rows, regimes) if r.alpha_cr is None]
            text = f"alpha / alpha_cr <= {max(known):.4g}" if known else "no critical velocity determined"
            if unknown:
                print(f"speed: critical velocity UNDETERMINED in case(s) {', '.join(map(str, unknown))}")
            else:
                print(f"speed: every case subcritical ({text}; v_cr of each track)")
    proven = all(row.result.certificate is None or row.result.certificate.all_proven for row in table.rows)
    decided = all(row.result.verdict.determined for row in table.rows)
    return 0 if table.ok and proven and decided else 1
