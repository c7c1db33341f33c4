"""Finite beam against the closed form (paper, Section 3.2): every case at the defaults, and convergence.

Run: ``OPENBLAS_NUM_THREADS=1 python benchmarks/bench_validation.py [--quick] [--convergence]``.

1. ``validate`` at its defaults (500 modes, static correction, tolerance 1 %) for the 13 cases of
   Table 1, bogie and two masses: ``relative_diff`` per quantity (max |finite - closed| over the
   window divided by max |closed|), wall time of the whole call and of its parts; side by side, the
   same finite beam without the static correction (the alternative: the plain 500-mode model).
   ``--tr``: the same for the Timoshenko-Rayleigh beam with the two parameter sets of Figure 8
   (S = 10, r = 0.09 and S = 100, r = 0.03), bogie. ``--vehicles``: the finite beam under the car
   (four wheels, ten degrees of freedom, the generated matrices) beside the bogie, same track and modes;
   then ``validate`` for ``examples/car.toml`` beside its bogie alone (``--quick``: tau_max 40).
2. ``--convergence``: for each case, the largest ``relative_diff`` over the four quantities against
   the number of modes N (fixed beam: the default length of the 500-mode run, so ``k_max = N pi /
   L``), with and without the static correction. Reference: the closed form
   (``moving_bogie.response.closed_form.closed_form_response``).
"""

from __future__ import annotations

import argparse
import os
import platform
import time

import numpy as np

from moving_bogie.api import closed_form_response, validate
from moving_bogie.model.cases import TABLE1_CASES, table1_case
from moving_bogie.validation.compare import comparison_window, default_tau_max
from moving_bogie.validation.finite_beam import simulate_finite_beam
from moving_bogie.validation.geometry import choose_geometry
from moving_bogie.validation.track_modes import ModalTrack

NAMES = {"bogie": ("w_rear", "w_front", "u", "theta"), "masses": ("w_rear", "w_front")}


def table(header: list[str], rows: list[list[str]]) -> str:
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(row) + " |" for row in rows]
    return "\n".join(lines)


def defaults(model: str, cases: tuple[int, ...], tr: tuple[int, str] | None = None) -> None:
    rows = []
    worst = 0.0
    for case in cases:
        params = table1_case(case)
        if tr is not None:
            params = params.replace(beam="tr", S=tr[0], r=tr[1])
        start, cpu = time.perf_counter(), time.process_time()
        result = validate(params.replace(vehicle=model))
        total, cpu = time.perf_counter() - start, time.process_time() - cpu
        plain = validate(params.replace(vehicle=model), static_correction=False, estimate=False)
        rel = result.relative_diff
        worst = max(worst, *rel.values())
        rows.append(
            [
                f"{case}",
                f"{result.window[1]:.0f}",
                *(f"{v:.3%}" for v in rel.values()),
                "yes" if result.agrees else "NO",
                f"{total:.1f} ({cpu:.1f})",
                f"{result.finite_beam_s:.1f} / {result.reference_s:.1f} / {result.closed_form_s:.1f}",
                " ".join(f"{v:.1%}" for v in plain.relative_diff.values()),
                "yes" if plain.agrees else "no",
            ]
        )
    names = list(result.quantities)
    beam = "" if tr is None else f", Timoshenko-Rayleigh S = {tr[0]}, r = {tr[1]}"
    print(f"\n## validate, {model}{beam}, defaults (500 modes, tolerance 1 %): relative_diff\n")
    print(
        table(
            [
                "case",
                "window",
                *names,
                "agrees",
                "validate s (CPU s)",
                "finite / estimate / closed s",
                "without correction (" + ", ".join(names) + ")",
                "agrees",
            ],
            rows,
        )
    )
    print(f"\nlargest relative_diff with the correction: {worst:.3%}", flush=True)


def convergence(cases: tuple[int, ...], modes: tuple[int, ...]) -> None:
    rows = []
    for case in cases:
        params = table1_case(case)
        tau_max = default_tau_max(params)
        tau = np.linspace(0.0, tau_max, int(round(tau_max / 0.05)) + 1)
        closed = closed_form_response(params, tau)
        length = choose_geometry(
            track=ModalTrack.of(params), d=float(params.d), tau_max=tau_max, n_modes=500
        ).length
        cells = {True: [], False: []}
        for correction in (False, True):
            for n in modes:
                r = simulate_finite_beam(
                    params, tau_max, n_modes=n, length=length, tau_out=tau, static_correction=correction
                )
                inside = tau <= comparison_window(params, r)
                rel = max(
                    float(np.max(np.abs(getattr(r, k) - getattr(closed, k))[inside]))
                    / float(np.max(np.abs(getattr(closed, k))[inside]))
                    for k in NAMES["bogie"]
                )
                cells[correction].append(f"{rel:.2%}")
        rows.append([f"{case}", f"{length:.0f}", *cells[False], *cells[True]])
    print("\n## Largest relative_diff over rear, front, u, theta against N (bogie, default beam length)\n")
    kmax = ", ".join(f"N = {n}" for n in modes)
    print(f"(columns: {kmax} without the correction, then the same with it)\n")
    print(
        table(
            ["case", "L", *(f"{n} plain" for n in modes), *(f"{n} corrected" for n in modes)],
            rows,
        )
    )


#: A car per rail on Case 7's track (dimensionless; the bogie groups of Case 7, the body about five bogies).
CAR = dict(L_c="9", mu_c="8", J_c="60", kappa_sec="0.5", eta_sec="1")


def vehicles(tau_max: float = 200.0) -> None:
    """The finite beam under the car (4 wheels, 10 DOFs) beside the bogie (2 wheels, 4 DOFs), Case 7."""
    from types import SimpleNamespace

    base = table1_case(7)
    rows = []
    for name in ("bogie", "car"):
        values = {key: float(value) for key, value in base.values().items()}
        values |= {key: float(value) for key, value in CAR.items()} if name == "car" else {}
        params = SimpleNamespace(beam="eb", track="one-layer", vehicle=name, **values)
        start, cpu = time.perf_counter(), time.process_time()
        r = simulate_finite_beam(params, tau_max, n_modes=500)
        steps = round(tau_max / r.dt)
        rows.append(
            [
                name,
                f"{r.contacts}",
                f"{len(r.responses)}",
                f"{r.length:.1f}",
                f"{steps}",
                f"{time.perf_counter() - start:.2f}",
                f"{time.process_time() - cpu:.2f}",
                f"{1e3 * r.elapsed_s / steps:.3f}",
            ]
        )
    header = ["vehicle", "wheels", "DOFs", "L", "steps", "wall s", "CPU s", "ms/step"]
    print(f"\n## Finite beam, Case 7 track, 500 modes, static correction, tau_max = {tau_max:g}\n")
    print(table(header, rows))


def validate_vehicles(tau_max: float | None = None) -> None:
    """``validate`` (finite beam and closed form) for examples/car.toml and for its bogie alone, same run."""
    from pathlib import Path

    from moving_bogie.model.files import load_params_file

    car = load_params_file(Path(__file__).resolve().parents[1] / "examples" / "car.toml")[0]
    rows = []
    for name in ("bogie", "car"):
        params = car.replace(vehicle=name)
        start, cpu = time.perf_counter(), time.process_time()
        r = validate(params, tau_max=tau_max, estimate=False)
        rows.append(
            [
                name,
                f"{len(r.quantities)}",
                f"{r.tau[-1]:g}",
                f"{100 * max(r.relative_diff.values()):.4f}",
                "agree" if r.agrees else "DISAGREE",
                f"{r.finite_beam_s:.2f}",
                f"{r.closed_form_s:.2f}",
                f"{time.perf_counter() - start:.2f}",
                f"{time.process_time() - cpu:.2f}",
            ]
        )
    header = [
        "vehicle",
        "quantities",
        "tau_max",
        "max rel. diff %",
        "verdict",
        "finite s",
        "closed s",
        "wall s",
        "CPU s",
    ]
    print("\n## validate, examples/car.toml (SI, per rail) and its bogie alone, 500 modes\n")
    print(table(header, rows))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="Cases 1, 2, 7 only")
    parser.add_argument("--convergence", action="store_true", help="also the modes-vs-error table")
    parser.add_argument("--tr", action="store_true", help="only the Timoshenko-Rayleigh tables")
    parser.add_argument("--vehicles", action="store_true", help="only the car beside the bogie")
    args = parser.parse_args()
    print(
        f"# bench_validation: {platform.python_version()}, numpy {np.__version__}, "
        f"{os.cpu_count()} cores, OPENBLAS_NUM_THREADS={os.environ.get('OPENBLAS_NUM_THREADS', 'unset')}, "
        f"load average {os.getloadavg()[0]:.1f}"
    )
    cases = (1, 2, 7) if args.quick else tuple(TABLE1_CASES)
    if args.vehicles:
        vehicles()
        validate_vehicles(40.0 if args.quick else None)
        return
    if args.tr:
        for tr in ((10, "0.09"), (100, "0.03")):
            defaults("bogie", cases, tr)
        return
    defaults("bogie", cases)
    defaults("masses", cases)
    if args.convergence:
        convergence(cases, (125, 250, 500, 1000))


if __name__ == "__main__":
    main()
