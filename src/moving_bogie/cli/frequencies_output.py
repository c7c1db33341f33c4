"""What ``moving-bogie frequencies`` prints, on every track: the JSON and the text of a
:class:`~moving_bogie.roots.frequency_result.FrequencyResult` (the roots in SI, the count, the verdict
against the speed regime, the search's extent, the warnings and a certificate)."""

from __future__ import annotations

import sys
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import argparse

    from moving_bogie.model.physical import PhysicalParams
    from moving_bogie.roots.damping_limit import DampingLimit
    from moving_bogie.roots.frequency_result import FrequencyResult
    from moving_bogie.roots.proof.certify import Certificate
    from moving_bogie.stability.velocity.supercritical import SpeedRegime

from .common import PROG, print_json


def report(
    args: argparse.Namespace,
    result: FrequencyResult,
    physical: PhysicalParams | None,
    regime: SpeedRegime,
    *,
    limit: DampingLimit | None = None,
    extra: dict[str, Any] | None = None,
    title: str | None = None,
) -> None:
    """Print ``result`` as ``frequencies`` does on every track: the JSON (with the verdict against the speed
    regime, the damping limit and ``extra``) or the text (``title``, the roots in SI when ``physical`` is
    given, the count and verdict, the damping limit, the speed), then the warnings on stderr."""
    if args.json:
        data = with_si(result.to_dict(), result, physical)
        data["verdict"] = with_regime(data.get("verdict"), regime)
        data["damping_limit"] = None if limit is None else limit.to_dict()
        speed = {"alpha_cr": regime.alpha_cr, "v_cr": regime.v_cr, "supercritical": regime.supercritical}
        print_json(data | speed | {"speed": regime.to_dict()} | (extra or {}))
    else:
        if title is not None:
            print(title)
        if physical is not None:  # the roots in SI in place of q
            print(format_si(result, physical))
        print(format_result(result))
        if limit is not None:
            print(limit.statement())
        print(regime.line())
    for line in format_warnings(result):
        print(line, file=sys.stderr)


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
    if result.band is not None:
        data["margin_1_s"] = None if result.margin is None else float(result.margin) / t_scale
        data["margin_source"] = result.margin_source
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
    if result.band is not None:
        lines.append(result.band.statement())
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
