"""Finite-beam validation of the closed form (paper, Section 3.2; ``moving_bogie.validation.compare``).

References used here:

* the closed form (``moving_bogie.response.closed_form.closed_form_response``: steady part + residues at the
  induced frequencies + branch-cut integral, Eqs. (35)-(43)) is the infinite-beam reference the finite
  beam must approach as its modes grow;
* the tolerance is fixed in advance (1 % of each quantity's largest value over the window), never
  derived from either run; a test perturbs the closed form by 2 % and the validation must fail;
* the comparison window is checked against a finite beam twice as long with the same ``k_max``
  (the same model without the supports' reflections in that window).
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from moving_bogie.api import validate
from moving_bogie.errors import MovingBogieError
from moving_bogie.model.cases import table1_case
from moving_bogie.validation.compare import (
    comparison_window,
    default_tau_max,
    plot_validation,
    reflection_bound,
    truncation_a_priori,
)
from moving_bogie.validation.finite_beam import simulate_finite_beam
from moving_bogie.validation.track_modes import ModalTrack

SCRIPT = Path(sys.executable).with_name("moving-bogie")


@pytest.fixture(scope="module")
def case2():
    """Case 2 (undamped, Figure 9) with the defaults: 500 modes, tau_max 100."""
    return validate(table1_case(2))


def test_defaults_follow_damping():
    assert default_tau_max(table1_case(2)) == 100.0  # eta_f = 0
    assert default_tau_max(table1_case(7)) == 200.0  # eta_f = 0.05
    # Reference: (8/pi) int_4^inf dp / (p^4 + 4) by QUADPACK (one-layer EB point-load spectrum), below the
    # bound 8 / (3 pi k^3) of its p^-4 tail.
    from scipy.integrate import quad

    share = truncation_a_priori(4.0, ModalTrack.of(table1_case(2)))
    assert share == pytest.approx(8 / math.pi * quad(lambda p: 1 / (p**4 + 4), 4.0, np.inf)[0], rel=1e-6)
    assert share < 8 / (3 * math.pi * 64)


def test_reflection_bound_is_zero_until_the_fastest_wave_is_back():
    # Reference: the finite beam's hard window tau_valid = 2 x0 / (c(k_max) - alpha) (geometry module).
    r = simulate_finite_beam(table1_case(2), 100.0, n_modes=500, tau_out=np.linspace(0, 100, 11))
    p = table1_case(2)
    tau = np.linspace(0.0, 300.0, 3001)
    bound = reflection_bound(
        tau, track=ModalTrack.of(p), length=r.length, entry=r.entry, d=float(p.d), k_max=r.k_max
    )
    assert np.all(bound[tau < r.tau_valid * 0.999] == 0.0)
    assert bound[-1] > 1e-2 and np.all(np.diff(bound) >= -1e-15)  # undamped: grows, never decays
    damped = reflection_bound(
        tau,
        track=ModalTrack.of(p.replace(eta_f="0.05")),
        length=r.length,
        entry=r.entry,
        d=float(p.d),
        k_max=r.k_max,
    )
    assert damped.max() < 1e-3  # 0.05 damping: every reflection returns below 1e-3


@pytest.mark.slow
def test_window_is_justified_by_a_longer_beam():
    # Reference: the same finite-beam model on a beam twice as long with twice the modes (same k_max,
    # same time step), whose supports are twice as far: the difference in the window bounds what the
    # supports' reflections add. Case 7 is damped, so the window (150) runs past tau_valid (98).
    p = table1_case(7)
    tau = np.linspace(0.0, 150.0, 1501)
    short = simulate_finite_beam(p, 150.0, n_modes=500, tau_out=tau)
    window = comparison_window(p, short)
    assert short.tau_valid < 100.0 and window == pytest.approx(150.0)
    long = simulate_finite_beam(
        p,
        150.0,
        n_modes=1000,
        length=2 * short.length,
        entry=short.entry + 0.5 * short.length,
        dt=short.dt,
        tau_out=tau,
    )
    for name in ("w_rear", "w_front", "u", "theta"):
        assert np.max(np.abs(getattr(short, name) - getattr(long, name))) < 1e-3, name


@pytest.mark.slow
def test_undamped_window_is_the_strict_one(case2):
    assert case2.finite.tau_valid <= case2.window[1] <= 1.02 * case2.finite.tau_valid


@pytest.mark.slow
def test_few_modes_converge_towards_the_closed_form():
    # Reference: the closed form of Case 1 (eta_f = 0.1). Fixed beam L = 200, N = 100, 200, 400:
    # k_max = 1.6, 3.1, 6.3. Truncation error of the plain modal model ~ k_max^-3 (docs/finite_beam.md):
    # each doubling of N should cut the difference by several times (8 asymptotically).
    from moving_bogie.api import closed_form_response

    p = table1_case(1)
    tau = np.linspace(0.0, 60.0, 601)
    closed = closed_form_response(p, tau)
    diffs = []
    for n in (100, 200, 400):
        r = simulate_finite_beam(
            p, 60.0, n_modes=n, length=200.0, entry=60.0, tau_out=tau, static_correction=False
        )
        inside = tau <= comparison_window(p, r)
        assert inside.sum() > 500
        diffs.append([np.max(np.abs(getattr(r, k) - closed[k])[inside]) for k in ("w_rear", "u")])
    diffs = np.array(diffs)
    assert np.all(diffs[1] < diffs[0] / 4) and np.all(diffs[2] < diffs[1] / 4), diffs
    assert diffs[2, 0] < 0.02 * np.max(np.abs(closed["w_rear"]))


def _check_agrees(result):
    assert result.agrees, result.relative_diff
    for q in result.quantities.values():
        assert q.tolerance == 0.01 and q.relative == q.max_abs_diff / q.amplitude
        # The time-step estimate (twice the step, second order) is of the size of the difference: the
        # difference is the finite beam's own error, not a closed-form error.
        assert q.error_estimate < 2 * q.max_abs_diff, q


@pytest.mark.slow
def test_case_2_undamped_agrees(case2):
    # Reference: closed form of Case 2 (real induced frequencies, Table 2; Figure 9).
    _check_agrees(case2)


@pytest.mark.slow
def test_case_5_unstable_agrees():
    # Reference: closed form of Case 5 (one induced frequency with Im q = -0.000472, Table 2; Figure 12).
    # tau_max 100 instead of the default 200 keeps the test fast; the CLI test runs a default length.
    result = validate(table1_case(5), tau_max=100.0)
    assert result.window == (0.0, pytest.approx(100.0))
    _check_agrees(result)


@pytest.mark.slow
def test_cli_case_7_json(tmp_path):
    # Reference: closed form of Case 7 (damped foundation and suspension; Figure A1), via the CLI.
    if not SCRIPT.exists():
        pytest.fail(f"console script {SCRIPT} is not installed: run pip install -e '.[dev]'")
    proc = subprocess.run(
        [str(SCRIPT), "validate", "--case", "7", "--json"], capture_output=True, text=True, timeout=300
    )
    assert proc.returncode == 0, proc.stderr
    data = json.loads(proc.stdout)
    for key in ("max_abs_diff_rear", "max_abs_diff_u", "max_abs_diff_theta", "max_abs_diff_front"):
        assert isinstance(data[key], float) and data[key] >= 0
    assert data["agrees"] is True and data["case"] == 7 and data["model"] == "bogie"
    assert data["n_modes"] == 500 and data["L"] == pytest.approx(500 * math.pi / 4)
    assert data["static_correction"] is True and data["tolerance"] == 0.01
    assert 0 < data["entry"] < data["L"] and data["k_max"] == pytest.approx(4.0)
    assert data["window"][0] == 0.0 and data["window"][1] == pytest.approx(200.0)
    assert set(data["relative_diff"]) == {"w_rear", "w_front", "u", "theta"}
    assert all(0 <= v <= 0.01 for v in data["relative_diff"].values())
    for k, q in data["quantities"].items():
        assert q["relative_diff"] == pytest.approx(q["max_abs_diff"] / q["amplitude"]) and q["within"], k
    timings = data["timings"]
    assert {"finite_beam_s", "closed_form_s", "ratio_finite_to_closed", "reference_run_s"} <= set(timings)
    assert data["params"]["alpha"] == "0.4"


def test_cli_exits_1_when_outside_tolerance(capsys):
    # 60 modes without the correction: k_max ~ 1, truncation misses far more than 1 % of the deflection.
    from moving_bogie.cli import main

    code = main(["validate", "--case", "2", "--modes", "60", "--tmax", "20", "--no-correction", "--json"])
    data = json.loads(capsys.readouterr().out)
    assert code == 1 and data["agrees"] is False and max(data["relative_diff"].values()) > 0.01
    from moving_bogie.validation.verdict import CHECK_KEYS, VERDICT_KEYS

    assert set(VERDICT_KEYS) <= set(data)  # the keys every track's check has (a sleeper file's too)
    assert set(data) - {"case", "max_abs_diff_u", "max_abs_diff_theta"} == set(CHECK_KEYS)


def test_cli_rejects_a_bad_tolerance(capsys):
    from moving_bogie.cli import main

    assert main(["validate", "--case", "2", "--tol", "1.5"]) == 2
    assert "--tol" in capsys.readouterr().err


@pytest.mark.slow
def test_perturbed_closed_form_fails(monkeypatch):
    # The acceptance test of the validation itself: the same finite beam against the closed form
    # scaled by 1.02 (2 % off everywhere) must fail on every quantity, while the true closed form passes.
    import dataclasses

    import moving_bogie.response.closed_form as closed_form

    params = table1_case(7)
    honest = validate(params, tau_max=40.0, estimate=False)
    assert honest.agrees, honest.relative_diff
    ts = honest.closed  # same tau grid: no second frequency search

    def perturbed(*args, **kwargs):
        responses = {k: 1.02 * v for k, v in ts.responses.items()}  # every response, by DOF name
        return dataclasses.replace(ts, responses=responses)

    monkeypatch.setattr(closed_form, "closed_form_response", perturbed)
    result = validate(params, tau_max=40.0, estimate=False)
    assert not result.agrees
    assert all(not q.within and q.relative > 0.015 for q in result.quantities.values()), result.relative_diff


def _check_panels_show_the_comparison(fig, result):
    """Each panel by content: its solid and dashed curves, read back from the artists, differ inside the
    comparison window by exactly the max |finite - closed| the verdict judged, relative to the dashed
    curve's amplitude (validation/verdict.py)."""
    panels = [ax for ax in fig.axes if ax.get_ylabel()]
    names = ("w_rear", "u", "theta") if result.model == "bogie" else ("w_rear",)  # the panels, top to bottom
    assert len(panels) == len(names)
    t0, t1 = result.window
    for ax, name in zip(panels, names):
        quantity = result.quantities[name]
        curves = {ln.get_linestyle(): ln for ln in ax.get_lines() if len(ln.get_xdata()) > 2}
        tau = np.asarray(curves["-"].get_xdata(), float)
        finite = np.asarray(curves["-"].get_ydata(), float)
        closed = np.asarray(curves["--"].get_ydata(), float)
        inside = (tau >= t0) & (tau <= t1)
        assert np.max(np.abs(finite - closed)[inside]) == pytest.approx(quantity.max_abs_diff, rel=1e-12), (
            name
        )
        assert np.max(np.abs(closed[inside])) == pytest.approx(quantity.amplitude, rel=1e-12), name


@pytest.mark.slow
def test_plot_files(case2, tmp_path):
    fig = plot_validation(case2, tmp_path / "case2.png", title="Case 2")
    assert len(fig.axes) == 3
    assert (tmp_path / "case2.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    _check_panels_show_the_comparison(fig, case2)


@pytest.mark.slow
def test_masses_model_one_panel(tmp_path):
    # Reference: closed form of the two masses of Case 5 (Fig. 1a); short run, 200 modes.
    result = validate(table1_case(5).replace(vehicle="masses"), n_modes=200, tau_max=40.0)
    assert set(result.quantities) == {"w_rear", "w_front"}
    data = result.to_dict()  # a difference per DOF: no body, none for a bar's u or theta
    assert "max_abs_diff_u" not in data and "max_abs_diff_theta" not in data
    assert result.agrees
    fig = plot_validation(result, tmp_path / "m.svg")
    assert len(fig.axes) == 1 and (tmp_path / "m.svg").read_text().lstrip().startswith("<?xml")
    _check_panels_show_the_comparison(fig, result)


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"n_modes": 2}, "n_modes"),
        ({"tau_max": -1.0}, "tau_max"),
    ],
)
def test_bad_input(kwargs, match):
    with pytest.raises(MovingBogieError, match=match):
        validate(table1_case(7), **kwargs)


def test_supercritical_undamped_needs_the_plain_model():
    # The static correction needs a decaying moving-load deflection: alpha = 1.2 > 1 without damping.
    params = table1_case(2).replace(alpha="1.2")
    with pytest.raises(MovingBogieError, match="critical velocity"):
        validate(params, n_modes=60, tau_max=5.0, estimate=False)


def test_too_few_modes_for_the_correction_are_flagged():
    # k_max = 20 pi / 83 = 0.76: the truncated modes are no faster than the forcing (docs/finite_beam.md).
    result = validate(table1_case(13), n_modes=20, tau_max=10.0, estimate=False)
    assert result.finite.k_max < 2 and any("static correction is unreliable" in n for n in result.notes)
