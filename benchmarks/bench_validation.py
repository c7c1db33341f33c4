"""Finite beam against the closed form (paper, Section 3.2): timing, mode and length convergence.

Run: ``OPENBLAS_NUM_THREADS=1 python benchmarks/bench_validation.py [--quick] [--calibrate]``.

1. Timing: Case 1 of Table 1 to tau = 400 with 500 modes (target < 30 s), the finite beam against
   the closed form (``moving_bogie.response.closed_form.closed_form_response``, frequency search
   included), and
   the whole ``validate`` call (which adds the 2N-mode reference run of the error estimate).
2. Convergence: max |finite - closed| over each run's comparison window for N = 250, 500, 1000,
   2000 modes on two beam lengths (the default length of the 500-mode run and half of it), Cases 1
   and 7 to tau = 200 (damped) and Case 2 to tau = 100 (undamped). The closed form is the
   reference; a priori truncation ``8 / (3 pi k_max^3)`` alongside.
3. ``--calibrate`` (slow, ~5 min per model on 2 idle cores): how well the tolerance's error
   estimate ``8/7 max |X_N - X_(2N, dt/2)|`` predicts the true error ``max |X_N - X_true|`` of the
   default run, with ``X_true`` = 4000 modes and dt/4 on the same beam, for all 13 cases of Table 1.
"""

from __future__ import annotations

import argparse
import os
import platform
import time

import numpy as np

from moving_bogie.model.cases import TABLE1_CASES, table1_case
from moving_bogie.response.closed_form import closed_form_response
from moving_bogie.validation.compare import (
    comparison_window,
    default_tau_max,
    truncation_a_priori,
    validate,
)
from moving_bogie.validation.finite_beam import simulate_finite_beam
from moving_bogie.validation.geometry import choose_geometry

NAMES = ("w_rear", "u", "theta")


def table(header: list[str], rows: list[list[str]]) -> str:
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(row) + " |" for row in rows]
    return "\n".join(lines)


def timing(tau_max: float = 400.0, n_modes: int = 500) -> None:
    params = table1_case(1)
    tau = np.linspace(0.0, tau_max, int(round(tau_max / 0.05)) + 1)
    start = time.perf_counter()
    finite = simulate_finite_beam(params, tau_max, n_modes=n_modes, tau_out=tau)
    finite_s = time.perf_counter() - start
    start = time.perf_counter()
    closed = closed_form_response(params, tau)
    closed_s = time.perf_counter() - start
    start = time.perf_counter()
    result = validate(params, n_modes=n_modes, tau_max=tau_max)
    validate_s = time.perf_counter() - start
    window = comparison_window(params, finite)
    inside = tau <= window
    diffs = [float(np.max(np.abs(getattr(finite, k) - getattr(closed, k))[inside])) for k in NAMES]
    print(f"\n## Timing: Case 1, tau_max = {tau_max:g}, {n_modes} modes\n")
    print(
        table(
            [
                "finite beam s",
                "(stepping s)",
                "closed form s",
                "ratio",
                "validate() s",
                "window",
                "tau_valid",
                "diff w_rear",
                "diff u",
                "diff theta",
                "agrees",
            ],
            [
                [
                    f"{finite_s:.2f}",
                    f"{finite.elapsed_s:.2f}",
                    f"{closed_s:.2f}",
                    f"{finite_s / closed_s:.2g}",
                    f"{validate_s:.2f}",
                    f"{window:.1f}",
                    f"{finite.tau_valid:.1f}",
                    *(f"{d:.3g}" for d in diffs),
                    str(result.agrees),
                ]
            ],
        )
    )
    q = result.quantities
    print(
        f"\nL = {finite.length:.1f}, x0 = {finite.entry:.1f}, k_max = {finite.k_max:.2f}, "
        f"dt = {finite.dt:.4f}; tolerances w_rear {q['rear'].tolerance:.3g}, u {q['u'].tolerance:.3g}, "
        f"theta {q['theta'].tolerance:.3g}; closed form vs the 2N run: "
        + ", ".join(f"{k} {v.reference_diff:.3g}" for k, v in q.items())
    )


def convergence(case: int, tau_max: float, modes: tuple[int, ...]) -> None:
    params = table1_case(case)
    tau = np.linspace(0.0, tau_max, int(round(tau_max / 0.05)) + 1)
    closed = closed_form_response(params, tau)
    long = choose_geometry(
        alpha=float(params.alpha),
        eta_f=float(params.eta_f),
        eta_s=float(params.eta_s),
        d=float(params.d),
        tau_max=tau_max,
        n_modes=500,
    ).length
    rows = []
    for length in (long, 0.5 * long):
        for n in modes:
            r = simulate_finite_beam(params, tau_max, n_modes=n, length=length, tau_out=tau)
            window = comparison_window(params, r)
            inside = tau <= window
            cells = []
            for k in NAMES:
                diff = float(np.max(np.abs(getattr(r, k) - getattr(closed, k))[inside]))
                amp = float(np.max(np.abs(getattr(closed, k))[inside]))
                cells.append(f"{diff:.2e} ({diff / amp:.2%})")
            eps = truncation_a_priori(r.k_max)
            rows.append(
                [
                    f"{length:.1f}",
                    f"{n}",
                    f"{r.k_max:.2f}",
                    f"{eps:.1e}",
                    f"{r.dt:.4f}",
                    f"{r.entry:.1f}",
                    f"{r.tau_valid:.1f}",
                    f"{window:.1f}",
                    *cells,
                    f"{r.elapsed_s:.1f}",
                ]
            )
    print(f"\n## Case {case}, tau_max = {tau_max:g}: max |finite - closed| over the window (relative)\n")
    print(
        table(
            [
                "L",
                "N",
                "k_max",
                "8/(3 pi k^3)",
                "dt",
                "x0",
                "tau_valid",
                "window",
                "w_rear",
                "u",
                "theta",
                "s",
            ],
            rows,
        )
    )


def calibrate(model: str) -> None:
    names = ("w_rear", "w_front", "u", "theta") if model == "bogie" else ("w_rear", "w_front")
    rows = []
    worst = np.inf
    for case in TABLE1_CASES:
        params = table1_case(case)
        tau_max = default_tau_max(params)
        tau = np.linspace(0.0, tau_max, int(round(tau_max / 0.05)) + 1)
        fine = simulate_finite_beam(params, tau_max, model=model, n_modes=500, tau_out=tau)
        geometry = {"length": fine.length, "entry": fine.entry, "tau_out": tau, "model": model}
        ref = simulate_finite_beam(params, tau_max, n_modes=1000, dt=fine.dt / 2, **geometry)
        true = simulate_finite_beam(params, tau_max, n_modes=4000, dt=fine.dt / 4, **geometry)
        inside = tau <= comparison_window(params, fine)
        cells = []
        for k in names:
            err = float(np.max(np.abs(getattr(fine, k) - getattr(true, k))[inside]))
            est = 8 / 7 * float(np.max(np.abs(getattr(fine, k) - getattr(ref, k))[inside]))
            amp = float(np.max(np.abs(getattr(true, k))[inside]))
            worst = min(worst, est / err)
            cells.append(f"{err:.3g} ({err / amp:.1%}), {est / err:.2f}")
        rows.append([f"{case}", f"{tau_max:g}", f"{fine.k_max:.2f}", *cells])
    print(
        f"\n## Error estimate of the default run ({model}, 500 modes): true error (relative), estimate/true\n"
    )
    print(table(["case", "tau_max", "k_max", *names], rows))
    print(f"\nsmallest estimate/true: {worst:.2f} (the tolerance is 2 x estimate + 1e-4 x amplitude)")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="timing and Case 7 only, N up to 1000")
    parser.add_argument("--calibrate", action="store_true", help="also the slow error-estimate check")
    args = parser.parse_args()
    print(
        f"# bench_validation: {platform.python_version()}, numpy {np.__version__}, "
        f"{os.cpu_count()} cores, OPENBLAS_NUM_THREADS={os.environ.get('OPENBLAS_NUM_THREADS', 'unset')}"
    )
    timing()
    modes = (250, 500, 1000) if args.quick else (250, 500, 1000, 2000)
    runs = ((7, 200.0),) if args.quick else ((1, 200.0), (7, 200.0), (2, 100.0))
    for case, tau_max in runs:
        convergence(case, tau_max, modes)
    if args.calibrate:
        calibrate("bogie")
        calibrate("masses")


if __name__ == "__main__":
    main()
