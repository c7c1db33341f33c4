"""Time the finite-beam check on sleepers beside the continuous track's, and print its convergence.

Run: ``OPENBLAS_NUM_THREADS=1 python benchmarks/bench_sleepers_finite_beam.py [--convergence] [--record]``.
A script, not a test: nothing is asserted, the tables are printed.

Timing (one run, in one process): the finite-beam check of a sleeper case (``check_sleepers``: the finite
rail's free vibration, and for a stable case its loaded run; the Floquet search timed apart), for

- the unstable case of tests/test_sleepers_finite_beam.py (bay 2.5 / chi, alpha 0.24, eta_M 14, light
  damping: the principal parametric zone) and
- examples/sleepers.toml (stable: the steady force),

beside the continuous track's finite-beam check (``validate`` of Table 1 Case 7, without the estimate
run: its finite beam and its closed form timed apart).

``--convergence [unstable|example]``: the relative differences from the Floquet theory as the finite
model is refined one setting at a time from the defaults (elements per bay, time steps per period, the
rail beyond the wheel's path, the periods of the free run), the Floquet side computed once (N up to 6).

``--zone``: the growth rate across the principal zones of ``examples/sleepers_zones.toml`` at v = 97.2881
and 71.5 m/s (M from 5 kg inside one edge to 5 kg inside the other; the edges from ``moving-bogie
instability-lines --file examples/sleepers_zones.toml --range v=70:100 --range M=0:3000``), Floquet against
the finite rail at dt, at 2 dt and extrapolated to dt -> 0.

``--before SRC``: ``moving-bogie validate --file`` on ``examples/sleepers.toml``, on the zone example at
three points of its zone and with two wheels on Hertz springs beside it (``TWO_WHEELS``), run by this
checkout and by the package in ``SRC`` (another checkout's ``src``) side by side, one BLAS thread: CPU and
wall seconds, exit status, the first quantity each compares.
"""

from __future__ import annotations

import argparse
import dataclasses
import importlib
import sys
from pathlib import Path

from moving_bogie.generated import vehicle_mass
from moving_bogie.kernels.bound import bind
from moving_bogie.kernels.hill import VehicleMatrices
from moving_bogie.kernels.sleeper_track import SleeperTrack
from moving_bogie.model.cases import table1_case
from moving_bogie.model.catalogue import default_catalogue
from moving_bogie.model.sleeper_input import load_sleeper_file
from moving_bogie.response.steady_bay import static_loads
from moving_bogie.validation.compare import validate
from moving_bogie.validation.sleepers_check import (
    SleeperBeamSettings,
    SleeperCheck,
    check_sleepers,
    floquet_side,
)

HERE = Path(__file__).resolve().parent.parent
UNSTABLE = {"lam": 2.5, "alpha": 0.24, "kappa_f": 0.0, "eta_f": 0.01, "eta_sup": 0.01}


def unstable_case() -> tuple[SleeperTrack, VehicleMatrices, object]:
    values = {"eta_M": 14.0}
    vehicle = VehicleMatrices.from_module(vehicle_mass, values)
    return (
        SleeperTrack(default_catalogue().periodic["eb", "sleepers"], UNSTABLE),
        vehicle,
        static_loads(vehicle_mass, values),
    )


#: (v in m/s, M in kg) in the principal zones of examples/sleepers_zones.toml: at v = 97.2881 the zone is
#: M = 1375..1458 kg, at v = 71.5 M = 2606..2769 kg (instability-lines, module doc)
ZONE_POINTS = [("97.2881", m) for m in ("1380", "1390", "1400", "1416", "1440", "1453")] + [
    ("71.5", m) for m in ("2612", "2685", "2760")
]
#: the points of ZONE_POINTS that ``--before`` validates with both codes
VALIDATED = [("97.2881", "1400"), ("97.2881", "1416"), ("71.5", "2685")]


def zone_file(folder: Path, v: str, M: str, vehicle: str = "") -> Path:
    """examples/sleepers_zones.toml with its v and M replaced, written in ``folder``; ``vehicle``, a vehicle's
    name and the lines it adds to [physical] (``"masses\nd = 2.0\nk_H = 1.4e9"``), replaces the wheel."""
    text = (HERE / "examples" / "sleepers_zones.toml").read_text()
    text = text.replace("\nM = 600 ", f"\nM = {M} ").replace("\nv = 100 ", f"\nv = {v} ")
    if vehicle:
        name, _, lines = vehicle.partition("\n")
        text = text.replace('vehicle = "mass"', f'vehicle = "{name}"') + lines + "\n"
    path = folder / f"zones_v{v}_M{M}{vehicle.split(chr(10))[0]}.toml"
    path.write_text(text)
    return path


#: the two wheels 2 m apart on Hertz springs of docs/sleepers.md (S27) that ``--before`` validates too
TWO_WHEELS = ("97.2881", "1400", "masses\nd = 2.0\nk_H = 1.4e9")


def example_case(
    path: Path = HERE / "examples" / "sleepers.toml",
) -> tuple[SleeperTrack, VehicleMatrices, object]:
    data = load_sleeper_file(path)
    module = importlib.import_module(f"moving_bogie.generated.vehicle_{data.vehicle}")
    vehicle = VehicleMatrices.from_module(module, data.vehicle_groups)
    return (
        SleeperTrack(data.foundation, data.groups),
        vehicle,
        static_loads(module, data.vehicle_groups),
    )


def _row(label: str, check: SleeperCheck) -> list[str]:
    worst = max(c.relative for c in check.comparisons)
    names = ", ".join(c.quantity for c in check.comparisons)
    return [label, f"{check.finite_s:.2f}", f"{check.floquet_s:.2f}", f"{worst:.2e}", names]


def timing(record: bool = False) -> None:
    rows = []
    for label, case, harmonics in (
        ("sleepers, unstable", unstable_case(), (1, 6)),
        ("examples/sleepers.toml", example_case(), (1, 6)),
    ):
        track, vehicle, loads = case
        rows.append(_row(label, check_sleepers(track, vehicle, loads, harmonics=harmonics)))  # type: ignore[arg-type]
    result = validate(bind(table1_case(7)), estimate=False)
    worst = max(result.relative_diff.values())
    rows.append(
        [
            "continuous, Case 7",
            f"{result.finite_beam_s:.2f}",
            f"{result.closed_form_s:.2f}",
            f"{worst:.2e}",
            "every DOF over the window",
        ]
    )
    header = ["case", "finite beam [s]", "reference [s]", "worst rel. diff", "compared"]
    _print(header, rows)
    print(
        "reference: the Floquet search (+ steady force) on sleepers; the closed form on the continuous track"
    )
    if record:
        _record(rows)


def _record(rows: list[list[str]]) -> None:
    """benchmarks/results/bench_sleepers_finite_beam.json: each sleeper case beside the continuous one."""
    from records import row, write_record

    continuous = rows[-1]
    alternative = f"the continuous track's finite beam (Table 1 Case 7): {continuous[1]} s"
    out = [
        row(
            f"finite-beam check on sleepers, {label} (compared: {compared})",
            f"{finite} s finite beam (Floquet side {reference} s), worst rel. diff {worst}",
            alternative,
            "< 30 s",
        )
        for label, finite, reference, worst, compared in rows[:-1]
    ]
    write_record(
        __file__,
        "The finite-beam check on sleepers",
        out,
        entries=("moving_bogie.__main__", "moving_bogie.cli.validate_cmd"),
    )


def convergence(which: str) -> None:
    cases = {"unstable": unstable_case, "example": example_case}
    for label in list(cases) if which == "both" else [which]:
        track, vehicle, loads = cases[label]()
        side = floquet_side(track, vehicle, loads)  # type: ignore[arg-type]
        base = SleeperBeamSettings()
        variants = [("defaults", base)]
        for name, values in (
            ("elements", (4, 16)),
            ("steps_per_period", (100, 400)),
            ("margin", (20.0,)),
            ("periods", (30, 60)),
        ):
            variants += [(f"{name} = {v}", dataclasses.replace(base, **{name: v})) for v in values]
        rows = []
        for name, settings in variants:
            check = check_sleepers(track, vehicle, loads, settings=settings, floquet=side)  # type: ignore[arg-type]
            rows.append([name] + [f"{c.relative:.2e}" for c in check.comparisons] + [f"{check.finite_s:.2f}"])
        state = side.result.verdict.state.upper()
        print(f"\n{label}: Floquet {state}, root {side.root}, N = {side.result.harmonics}")
        _print(["setting"] + [c.quantity for c in check.comparisons] + ["finite beam [s]"], rows)


def zone() -> None:
    """The table of ``--zone`` (module doc)."""
    import tempfile

    rows = []
    with tempfile.TemporaryDirectory() as folder:
        for v, M in ZONE_POINTS:
            path = zone_file(Path(folder), v, M)
            scale = load_sleeper_file(path).t_scale
            check = check_sleepers(*example_case(path), time_scale=scale)  # type: ignore[arg-type]
            rate = check.comparisons[0]
            assert check.coarse is not None, "the zone points are unstable"
            rows.append(
                [v, M]
                + [f"{x / scale:.6g}" for x in (rate.floquet, check.fit.rate, check.coarse.rate, rate.finite)]
                + [f"{100 * abs(check.fit.rate / rate.floquet - 1):.3f} %", f"{100 * rate.relative:.3f} %"]
            )
            print(f"  v = {v}, M = {M}: done", file=sys.stderr)
    header = ["v [m/s]", "M [kg]", "-Im q [1/s]", "finite, dt", "finite, 2 dt", "finite, dt -> 0"]
    _print(header + ["rel. diff at dt", "rel. diff at dt -> 0"], rows)


def before_after(before: Path) -> None:
    """The table of ``--before`` (module doc)."""
    import json
    import tempfile

    from bench_commands import run_child

    rows = [["file", "code", "CPU s", "wall s", "exit", "quantity", "Floquet", "finite beam", "rel. diff"]]
    with tempfile.TemporaryDirectory() as folder:
        files = [("examples/sleepers.toml", HERE / "examples" / "sleepers.toml")] + [
            (f"sleepers_zones.toml, v = {v}, M = {M}", zone_file(Path(folder), v, M)) for v, M in VALIDATED
        ]
        files.append(
            (
                "sleepers_zones.toml, two wheels on Hertz springs, M = 1400",
                zone_file(Path(folder), *TWO_WHEELS),
            )
        )
        for label, path in files:
            for who, src in (("before", before), ("this", HERE / "src")):
                run = run_child(src, ["validate", "--file", str(path), "--json"])
                first = json.loads(run.stdout)["comparisons"][0]
                values = [first["quantity"]]
                values += [f"{first[key]:.6g} {first['unit_si']}" for key in ("floquet_si", "finite_beam_si")]
                values += [f"{100 * first['relative_diff']:.3f} %"]
                rows.append([label, who, f"{run.cpu:.2f}", f"{run.wall:.1f}", str(run.code), *values])
                label = ""
            print(f"  {path.name}: done", file=sys.stderr)
    _print(rows[0], rows[1:])


def _print(header: list[str], rows: list[list[str]]) -> None:
    widths = [max(len(str(r[i])) for r in [header, *rows]) for i in range(len(header))]
    for row in [header, *rows]:
        print("  ".join(str(x).ljust(w) for x, w in zip(row, widths)))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--convergence",
        nargs="?",
        const="both",
        choices=("both", "unstable", "example"),
        help="the convergence tables (of both cases, or of one) instead of the timing",
    )
    from records import add_record_option

    parser.add_argument("--zone", action="store_true", help="the rate across the zones of the zone example")
    parser.add_argument("--before", metavar="SRC", type=Path, help="validate side by side with this src")
    add_record_option(parser)
    args = parser.parse_args()
    if args.zone:
        zone()
    elif args.before:
        before_after(args.before)
    else:
        convergence(args.convergence) if args.convergence else timing(args.record)


if __name__ == "__main__":
    main()
