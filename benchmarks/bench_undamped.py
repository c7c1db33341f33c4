"""Stability commands on an undamped foundation, timed beside the ordinary ones at small eta_f, with the
convergence of the limit boundaries (not a test: run it by hand).

    python benchmarks/bench_undamped.py

Rows: instability lines and critical stiffness at eta_f = 0 (boundaries by counts and bisection,
stability/maps/undamped.py) next to the ordinary computation (continuation, D-decomposition) at eta_f = 1e-4,
wall and CPU time in the same run. Then the limit eta_f -> 0+ boundaries against the D-decomposition
crossings at eta_f = 1e-2, 1e-3, 1e-4 (the difference should fall at least like eta_f).
"""

from __future__ import annotations

import resource
import time

import numpy as np

from moving_bogie.kernels.bound import bind


def _cpu() -> float:
    own = resource.getrusage(resource.RUSAGE_SELF)
    return own.ru_utime + own.ru_stime


def _timed(func):
    w0, c0 = time.perf_counter(), _cpu()
    out = func()
    return time.perf_counter() - w0, _cpu() - c0, out


def main() -> None:
    from moving_bogie.api import critical_stiffness, d_decomposition, instability_lines
    from moving_bogie.model.cases import table1_case
    from moving_bogie.stability.maps.undamped import UndampedCounter, boundaries, parameter_grid

    masses = table1_case(2).replace(d="1.5")
    jobs = [
        (
            "instability lines, two masses, d = 1.5",
            lambda p: instability_lines(p.replace(vehicle="masses")),
            masses,
        ),
        ("instability lines, bogie, Case 2 (d = 2)", lambda p: instability_lines(p), table1_case(2)),
        (
            "critical stiffness, Case 5, 19 alphas",
            lambda p: critical_stiffness(p, np.linspace(0.3, 1.2, 19)),
            table1_case(5),
        ),
    ]
    print(f"{'job':42s} {'eta_f = 0 wall/CPU [s]':>24s} {'eta_f = 1e-4 wall/CPU [s]':>27s}")
    for label, func, params in jobs:
        w0, c0, _ = _timed(lambda func=func, params=params: func(params.replace(eta_f=0)))
        w1, c1, _ = _timed(lambda func=func, params=params: func(params.replace(eta_f="0.0001")))
        print(f"{label:42s} {w0:12.1f} / {c0:<9.1f} {w1:14.1f} / {c1:<9.1f}")
    print()
    print("limit eta_f -> 0+ boundary against the D-decomposition at small eta_f (|difference|)")
    print(f"{'boundary':44s} {'limit':>16s} {'1e-2':>9s} {'1e-3':>9s} {'1e-4':>9s}")
    for name, p, model, parameter, alpha, top in (
        ("two masses, d = 1.5, alpha = 0.8, eta_M", masses, "masses", "eta_M", 0.8, 200.0),
        ("Case 5, alpha = 0.7, kappa_v", table1_case(5), "bogie", "kappa_v", 0.7, 0.6),
    ):
        bounds, _, _ = boundaries(
            UndampedCounter(bind(p.replace(vehicle=model)), parameter),
            alpha,
            parameter_grid(top, 20),
            tol=1e-12 * top,
        )
        limit = [b.theta for b in bounds if b.kind == "limit"]
        crossings = [
            d_decomposition(
                p.replace(eta_f=e, alpha=str(alpha)).replace(vehicle=model),
                parameter=parameter,
                theta_max=top,
            ).crossings
            for e in ("0.01", "0.001", "0.0001")
        ]
        for k, theta in enumerate(limit):
            diffs = " ".join(f"{abs(c[k].theta - theta):9.1e}" for c in crossings)
            print(f"{name:44s} {theta:16.10f} {diffs}")


if __name__ == "__main__":
    main()
