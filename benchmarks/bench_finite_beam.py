"""Time the finite-beam validation model (paper, Section 3.2) and print a table.

Run: ``OPENBLAS_NUM_THREADS=1 python benchmarks/bench_finite_beam.py [--quick]``. The Woodbury step
uses no threaded BLAS; the dense comparison does, and threads competing for 2 busy cores make it
~10 times slower still.

Rows: with and without the static correction of the truncated modes (the default is with), Case 1
of Table 1 (eta_f 0.1, eta_M 20, d 1, cf1 1.7 -> mu_v 34, cf2 0.01 -> J_b 0.2, kappa_v 0.02,
eta_v 0, alpha 0.8) to tau = 400 with 500 modes (the target: under 30 s on 2 cores),
the same with 1000 modes and with the two-masses model, and for comparison the cost of one step
solved densely (``numpy.linalg.solve`` on the full effective matrix) instead of by Woodbury.
"""

from __future__ import annotations

import argparse
import os
import platform
import time

import numpy as np

from moving_bogie.model.cases import table1_case
from moving_bogie.validation.finite_beam import simulate_finite_beam
from moving_bogie.validation.geometry import choose_geometry
from moving_bogie.validation.modal import ModalBeam, ModalSystem, Vehicle
from moving_bogie.validation.newmark import effective_matrix_dense
from moving_bogie.validation.track_modes import ModalTrack

CASE_1 = table1_case(1)


def run_row(label: str, tau_max: float, n_modes: int, model: str, correction: bool = True) -> list[str]:
    result = simulate_finite_beam(
        CASE_1.replace(vehicle=model), tau_max, n_modes=n_modes, static_correction=correction
    )
    steps = result.tau.size - 1
    return [
        label,
        model,
        "yes" if correction else "no",
        f"{n_modes}",
        f"{tau_max:g}",
        f"{result.length:.1f}",
        f"{result.entry:.1f}",
        f"{result.k_max:.2f}",
        f"{result.dt:.4f}",
        f"{steps}",
        f"{result.elapsed_s:.2f}",
        f"{1e3 * result.elapsed_s / steps:.3f}",
        f"{result.tau_valid:.1f}",
    ]


def dense_row(n_modes: int, repeats: int = 20) -> list[str]:
    """Per-step cost of a dense solve of the same effective matrix (what Woodbury avoids)."""
    track = ModalTrack.of(table1_case(1))  # Case 1: alpha = 0.8, eta_f = 0.1
    geometry = choose_geometry(track=track, d=1.0, tau_max=400.0, n_modes=n_modes)
    vehicle = Vehicle("bogie", 20.0, 1.0, 34.0, 0.2, 0.02, 0.0, 0.8, geometry.entry)
    system = ModalSystem(ModalBeam(geometry.length, n_modes, track), vehicle)
    start = time.perf_counter()
    for i in range(repeats):
        matrices = system.assemble(0.01 * i)
        np.linalg.solve(effective_matrix_dense(matrices, 0.02), matrices.force)
    per_step = (time.perf_counter() - start) / repeats
    return [
        "dense step",
        "bogie",
        "no",
        f"{n_modes}",
        "-",
        "-",
        "-",
        "-",
        "-",
        f"{repeats}",
        "-",
        f"{1e3 * per_step:.3f}",
        "-",
    ]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="only the Case 1 / 500 modes row")
    args = parser.parse_args()
    header = [
        "run",
        "model",
        "correction",
        "N",
        "tau_max",
        "L",
        "x0",
        "k_max",
        "dt",
        "steps",
        "wall s",
        "ms/step",
        "tau_valid",
    ]
    # The static correction (default) side by side with the plain modal model, same beam and steps.
    rows = [run_row("Case 1", 400.0, 500, "bogie"), run_row("Case 1", 400.0, 500, "bogie", False)]
    if not args.quick:
        rows += [
            run_row("Case 1", 400.0, 1000, "bogie"),
            run_row("Case 1", 400.0, 500, "masses"),
            run_row("Case 1", 400.0, 500, "masses", False),
            dense_row(500),
        ]
    widths = [max(len(r[i]) for r in [header, *rows]) for i in range(len(header))]
    print(f"# finite beam, Python {platform.python_version()}, numpy {np.__version__}, {os.cpu_count()} CPUs")
    for row in [header, ["-" * w for w in widths], *rows]:
        print("  ".join(cell.rjust(w) for cell, w in zip(row, widths, strict=True)))


if __name__ == "__main__":
    main()
