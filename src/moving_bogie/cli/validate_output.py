"""What ``moving-bogie validate`` prints: the table of a check and its verdict line, on every track (the
finite beam against the closed form; on periodic supports the finite rail against the Floquet theory, in SI
where the check has SI values)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from moving_bogie.validation.verdict import ValidationResult

__all__ = ["format_result", "format_sleeper_check"]


def format_result(result: ValidationResult) -> str:
    """Readable summary of a :class:`~moving_bogie.validation.verdict.ValidationResult` (on periodic
    supports :func:`format_sleeper_check`)."""
    from moving_bogie.validation.verdict import beam_title

    if result.supports is not None:
        return format_sleeper_check(result.to_dict())
    finite = result.finite_beam
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
