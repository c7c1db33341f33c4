"""The finite rail on one-, two- and three-layer tracks beside the Bromwich integral: time and agreement.

    python benchmarks/bench_layered_finite_rail.py [--quick] [--modes N]

For the bogie of examples/two-layer.toml on its own track, on the one-layer track (k_f = k_1, c_f = c_1) and
on the three-layer track of examples/three-layer.toml, this runs the finite rail at the settings of
``validate`` (N modes, static correction, default geometry and time step, tau_max = 200; --quick: 100 modes,
tau_max = 40) and the Bromwich integral (``bromwich_line``, a numerical inverse Laplace transform independent
of both the finite rail and the closed form) at a few times in the comparison window, and prints the time of
each and the largest difference per quantity (relative to its largest value at those times).
Wall time depends on what else runs on the machine; CPU time does not, and is printed next to it.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

from moving_bogie.kernels.bound import bind

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def _clocks() -> np.ndarray:
    """Wall and CPU (this process) clocks."""
    return np.array([time.perf_counter(), time.process_time()])


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--quick", action="store_true", help="100 modes to tau = 40")
    parser.add_argument("--modes", type=int, default=None, help="sine modes (default 500, 100 with --quick)")
    args = parser.parse_args()

    from moving_bogie.model.files import load_params_file
    from moving_bogie.response.bromwich import bromwich_line
    from moving_bogie.validation.finite_beam import simulate_finite_beam
    from moving_bogie.validation.window import comparison_window

    two, _ = load_params_file(EXAMPLES / "two-layer.toml")
    three, _ = load_params_file(EXAMPLES / "three-layer.toml")
    tracks = (("one-layer", two.replace(track="one-layer")), ("two-layer", two), ("three-layer", three))
    modes = args.modes or (100 if args.quick else 500)
    tau_max = 40.0 if args.quick else 200.0
    grid = np.linspace(0.0, tau_max, int(round(tau_max / 0.05)) + 1)
    header = (
        f"{'track':<12} {'modes':>5} {'steps':>6} {'window':>7} {'finite wall/cpu [s]':>20} "
        f"{'us/step':>8} {'Bromwich wall/cpu [s]':>22}  max relative difference (rear, front, u, theta)"
    )
    print(header, flush=True)
    for name, params in tracks:
        start = _clocks()
        finite = simulate_finite_beam(params, tau_max, n_modes=modes, tau_out=grid)
        middle = _clocks()
        wf, cf = middle - start
        end = comparison_window(params, finite)
        pick = np.searchsorted(grid, np.linspace(end / 8, end, 8) - 1e-9)  # grid times in the window
        times = grid[pick]
        middle = _clocks()
        reference = bromwich_line(bind(params), times, a=0.02)
        wb, cb = _clocks() - middle
        diffs = []
        for key in ("w_rear", "w_front", "u", "theta"):
            x = getattr(finite, key)[pick]
            diffs.append(np.max(np.abs(x - reference[key])) / np.max(np.abs(reference[key])))
        steps = round(tau_max / finite.dt)
        print(
            f"{name:<12} {modes:>5} {steps:>6} {end:>7.1f} {wf:>9.2f} / {cf:>8.2f} "
            f"{1e6 * finite.elapsed_s / steps:>8.0f} {wb:>10.2f} / {cb:>9.2f}  "
            + ", ".join(f"{d:.1e}" for d in diffs),
            flush=True,
        )


if __name__ == "__main__":
    main()
