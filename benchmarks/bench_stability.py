"""Time the stability jobs against their targets and print a table (not a test: run it by hand).

    python benchmarks/bench_stability.py [--quick]

Targets (issue 6): Figure 3 complete under 60 s; a 400 x 400 stability map under 60 s on 2 cores. Wall
time depends on what else runs on the machine; CPU time (this process and its workers) does not, and is
printed next to it.
"""

from __future__ import annotations

import argparse
import resource
import time

import numpy as np


def _cpu() -> float:
    own = resource.getrusage(resource.RUSAGE_SELF)
    kids = resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + kids.ru_utime + kids.ru_stime


def _timed(label, target, func):
    w0, c0 = time.perf_counter(), _cpu()
    out = func()
    wall, cpu = time.perf_counter() - w0, _cpu() - c0
    return label, wall, cpu, target, out


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--quick", action="store_true", help="smaller jobs (a smoke run)")
    from records import add_record_option

    add_record_option(parser)
    args = parser.parse_args()

    from moving_bogie.api import (
        critical_stiffness,
        d_decomposition,
        frequency_lines,
        instability_lines,
        stability_map,
    )
    from moving_bogie.model.cases import table1_case
    from moving_bogie.model.catalogue import get_model
    from moving_bogie.paper import stability_figures as plots_stability
    from moving_bogie.stability.velocity.critical_velocity import critical_velocity

    n = 100 if args.quick else 400
    case1 = table1_case(1)
    rows = [
        _timed(
            "critical velocity, TR (30 digits)",
            None,
            lambda: critical_velocity(get_model(beam="tr"), S=10, r="0.09"),
        ),
        _timed(
            "instability lines, masses, 6 spacings (1 panel)",
            None,
            lambda: instability_lines(
                case1.replace(eta_f="0.05").replace(vehicle="masses"), spacings=plots_stability.SPACINGS
            ),
        ),
        _timed(
            "instability lines, bogie, 6 spacings (1 panel)",
            None,
            lambda: instability_lines(case1.replace(eta_f="0.05"), spacings=plots_stability.SPACINGS),
        ),
        _timed(
            "Figure 3 (6 panels x 6 spacings, masses)",
            60.0,
            lambda: plots_stability.figure3(quick=args.quick),
        ),
        _timed(
            f"stability map {n} x {n}, bogie, Case 1 (2 workers)",
            60.0,
            lambda: stability_map(
                case1, alphas=np.linspace(0.005, 1.2, n), thetas=np.linspace(0.5, 200, n), workers=2
            ),
        ),
        _timed("D-decomposition, one alpha (6000 q samples)", None, lambda: d_decomposition(case1, 0.9)),
        _timed("frequency lines, Case 1, 13 checkpoints", None, lambda: frequency_lines(case1)),
        _timed(
            "critical stiffness, Case 5, 15 alphas",
            None,
            lambda: critical_stiffness(table1_case(5), np.linspace(0.3, 1.0, 15), kappa_max=0.6),
        ),
    ]
    print(f"{'job':58s} {'wall [s]':>9s} {'CPU [s]':>9s} {'target':>8s}")
    for label, wall, cpu, target, _ in rows:
        t = "" if target is None else f"< {target:g}"
        print(f"{label:58s} {wall:9.1f} {cpu:9.1f} {t:>8s}")
    if args.record:
        from records import row, write_record

        out = [
            row(
                label,
                f"{wall:.1f} s wall, {cpu:.1f} s CPU",
                "-",
                "-" if target is None else f"< {target:g} s",
            )
            for label, wall, cpu, target, _ in rows
        ]
        write_record(__file__, "Stability analysis", out)


if __name__ == "__main__":
    main()
