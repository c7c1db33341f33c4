"""Random parameter sets through the root search: failures, time distribution, agreement with a scan.

    python benchmarks/bench_search_random.py [--layered N] [--one-layer N] [--seed S] [--reference K]
                                              [--only two-layer|three-layer|eb|tr] [--verbose]

Draws (fixed seed) ``--layered`` two- and three-layer tracks in SI units (UIC-like rails on pads over a
sleeper layer that is realistic, m_2 = 150-350 kg/m, or light, m_2 = 60-100 kg/m; a ballast layer for the
three-layer track; ordinary or heavy wheels; the bogie or two masses) and ``--one-layer`` dimensionless
Euler-Bernoulli and Timoshenko-Rayleigh sets, each at a speed v/v_cr drawn from 0.3-0.99 (half of them
from 0.85-0.99, where instability lives), v_cr the critical velocity of the track
(:func:`~moving_bogie.stability.velocity.critical_velocity.critical_velocity`). For every set it runs
``induced_frequencies`` and records:

- a *failure*: an exception (the CLI's exit 2) -- there must be none;
- the verdict (an UNDETERMINED one with its reason) and the CPU time of the search;
- on ``--reference`` sets (every n-th), the roots in the lower half of the window against an independent
  brute-force reference (:func:`scan_roots`): the local minima of |E_chr| on a dense grid, polished by
  Newton's method in double precision then by mpmath.findroot, kept when they are roots; they must agree to
  1e-8 and give the same verdict.

Prints one line per set with ``--verbose``, then a table per family (Ctrl-C stops the run and still prints
the table of the sets done): sets, failures, undetermined verdicts,
CPU median / 90 % / max, the largest unsearched height, reference agreement. CPU time is per process and
does not depend much on the load of the machine; it is what the targets in the README are about.
"""

from __future__ import annotations

import argparse
import os
import resource
import sys
import time
import traceback

# CPU time per process is what this measures: BLAS threads spinning beside the work would count in it (a
# set of 88 roots took 6 s with the default threads and 3.8 s with one); set them before numpy loads
for _variable in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_variable, "1")

import mpmath  # noqa: E402
import numpy as np  # noqa: E402

from moving_bogie.kernels.bound import bind  # noqa: E402

FAMILIES = ("two-layer", "three-layer", "eb", "tr")


def _cpu() -> float:
    own = resource.getrusage(resource.RUSAGE_SELF)
    return own.ru_utime + own.ru_stime


def _si_set(rng, track: str) -> dict:
    """SI values of a ballasted track under a bogie (per rail), realistic or light sleeper layer."""
    light = rng.random() < 0.5
    heavy = rng.random() < 0.3
    values = {
        "EI": rng.uniform(4.0e6, 7.0e6),
        "m": rng.uniform(50.0, 65.0),
        "k_1": rng.uniform(1.0e8, 6.0e8),
        "c_1": rng.uniform(2.0e4, 1.0e5),
        "m_2": rng.uniform(60.0, 100.0) if light else rng.uniform(150.0, 350.0),
        "k_2": rng.uniform(5.0e7, 3.0e8),
        "c_2": rng.uniform(3.0e4, 2.0e5),
        "P": rng.uniform(5.0e4, 1.1e5),
        "M": rng.uniform(1500.0, 3000.0) if heavy else rng.uniform(600.0, 1000.0),
        "M_b": rng.uniform(800.0, 2000.0),
        "J_b": rng.uniform(500.0, 2000.0),
        "k_v": rng.uniform(5.0e5, 2.0e6),
        "c_v": rng.uniform(5.0e3, 3.0e4),
        "d": rng.uniform(1.8, 3.0),
        "v": 50.0,  # replaced by a fraction of v_cr
    }
    if track == "three-layer":
        values |= {
            "m_3": rng.uniform(300.0, 900.0),
            "k_3": rng.uniform(5.0e7, 3.0e8),
            "c_3": rng.uniform(5.0e4, 3.0e5),
        }
    return values


def _one_layer_set(rng, beam: str) -> dict:
    """Dimensionless groups of the paper's one-layer track (ranges around Table 1's)."""
    values = {
        "eta_f": rng.uniform(0.01, 0.3),
        "eta_M": rng.uniform(0.5, 5.0) if rng.random() < 0.7 else rng.uniform(5.0, 15.0),
        "d": rng.uniform(1.0, 6.0),
        "cf1": rng.uniform(1.0, 4.0),  # M_b/M and J_b/(M d^2) (Eq. 63), turned into mu_v, J_b below
        "cf2": rng.uniform(0.02, 0.3),
        "kappa_v": rng.uniform(0.1, 3.0),
        "eta_v": rng.uniform(0.05, 1.0),
    }
    values["mu_v"] = values["cf1"] * values["eta_M"]
    values["J_b"] = values.pop("cf2") * values["eta_M"] * values["d"] ** 2
    del values["cf1"]
    if beam == "tr":
        values |= {"S": rng.uniform(5.0, 100.0), "r": rng.uniform(0.02, 0.1)}
    return values


def _speed(rng) -> float:
    return rng.uniform(0.85, 0.99) if rng.random() < 0.5 else rng.uniform(0.3, 0.85)


def draw_sets(seed: int = 24, layered: int = 200, one_layer: int = 100, only: str | None = None) -> list:
    """The random sets: a list of (family, label, DimensionlessParams), reproducible from ``seed``."""
    from moving_bogie.model.params import DimensionlessParams
    from moving_bogie.model.physical import PhysicalParams
    from moving_bogie.stability.velocity.critical_velocity import critical_velocity

    rng = np.random.default_rng(seed)
    out = []
    for k in range(layered + one_layer):
        family = ("two-layer", "three-layer")[k % 2] if k < layered else ("eb", "tr")[(k - layered) % 2]
        vehicle = "bogie" if rng.random() < 0.7 else "masses"
        fraction = _speed(rng)
        if family in ("two-layer", "three-layer"):
            si = _si_set(rng, family)
            if vehicle == "masses":
                si = {key: v for key, v in si.items() if key not in ("M_b", "J_b", "k_v", "c_v")}
            if only is not None and only != family:
                continue
            params = PhysicalParams(beam="eb", track=family, vehicle=vehicle, **si).to_dimensionless(
                digits=12
            )
            label = f"m_2={si['m_2']:.0f} M={si['M']:.0f}"
        else:
            groups = _one_layer_set(rng, family)
            if vehicle == "masses":
                groups = {key: v for key, v in groups.items() if key in ("eta_f", "eta_M", "d", "S", "r")}
            if only is not None and only != family:
                continue
            groups = {key: f"{v:.4g}" for key, v in groups.items()}
            params = DimensionlessParams(
                beam=family, track="one-layer", vehicle=vehicle, alpha="0.1", **groups
            )
            label = f"eta_f={groups['eta_f']} eta_M={groups['eta_M']}"
        alpha_cr = float(critical_velocity(params, dps=15).alpha_cr)
        params = params.replace(alpha=f"{fraction * alpha_cr:.6g}")
        out.append((family, f"{vehicle} v/v_cr={fraction:.3f} {label}", params))
    return out


def scan_roots(params, window, *, n=(801, 801), tol=1e-9) -> list:
    """Roots of E_chr in ``window`` (a Rectangle) with Im q < 0 found by brute force, independently of the
    contour code: the local minima of |E_chr| on an n[0] x n[1] grid, polished by double-precision Newton
    steps (analytic derivative; where they settle) and then by mpmath.findroot at 30 digits; a minimum is kept
    when the polished point lies in the window and E_chr vanishes there. Returns complex roots, duplicates
    merged."""
    from moving_bogie.kernels.characteristic import Characteristic, CharacteristicArray

    fast = CharacteristicArray(bind(params))
    precise = Characteristic(bind(params))
    xs = np.linspace(window.x0, window.x1, n[0])
    # the grid reaches a few rows above Im q = 0, so that a root just below the real axis is an interior
    # minimum (a minimum on the last row is not seen)
    top = min(window.y1, 0.0)
    dy = (top - window.y0) / (n[1] - 1)
    ys = np.linspace(window.y0, top + 3 * dy, n[1] + 3)
    Z = xs[None, :] + 1j * ys[:, None]
    A = np.abs(fast(Z.ravel())).reshape(Z.shape)
    A = np.where(np.isfinite(A), A, np.inf)
    inner = A[1:-1, 1:-1]
    is_min = np.ones(inner.shape, dtype=bool)
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            if dy or dx:
                is_min &= inner <= A[1 + dy : A.shape[0] - 1 + dy, 1 + dx : A.shape[1] - 1 + dx]
    starts = Z[1:-1, 1:-1][is_min]
    q = starts.copy()
    step = np.zeros_like(q)
    for _ in range(40):
        E, dE = fast.value_and_derivative(q)
        with np.errstate(all="ignore"):
            step = np.where((dE != 0) & np.isfinite(dE), E / dE, np.inf)
        q = q - np.where(np.isfinite(step), step, 0)
    # a minimum where Newton's last step is still above 1e-6 relative is no root within 1e-6 of q (near a
    # root the step is the distance to it): findroot from there could only give what is rejected below
    settled = np.abs(step) <= 1e-6 * np.maximum(1.0, np.abs(q))
    roots = []
    with mpmath.workdps(30):
        for z in q[settled]:
            if not (np.isfinite(z) and window.contains(z) and z.imag < 0):
                continue
            try:
                r = complex(mpmath.findroot(precise, mpmath.mpc(z)))
            except (ValueError, ZeroDivisionError):
                continue
            if abs(r - z) > 1e-6 * max(1.0, abs(z)) or not window.contains(r) or r.imag >= 0:
                continue
            if all(abs(r - o) > tol * max(1.0, abs(r)) for o in roots):
                roots.append(r)
    return roots


def compare(result, reference) -> tuple[bool, float]:
    """Whether the roots with Im q < 0 of ``result`` and the reference match one to one, and the largest
    distance between matched roots."""
    found = [complex(r.q) for r in result.roots if complex(r.q).imag < 0 and complex(r.q).real >= 0]
    ref = [z for z in reference if z.real >= -1e-9]
    if len(found) != len(ref):
        return False, float("inf")
    worst = 0.0
    for z in ref:
        worst = max(worst, min((abs(z - f) for f in found), default=float("inf")))
    return worst <= 1e-8 * max(1.0, max((abs(z) for z in ref), default=1.0)), worst


def run(sets, reference_every: int = 0, verbose: bool = False, scan_points: dict | None = None) -> dict:
    """Run the search on every set; returns per-family records. ``scan_points``: grid points per side of
    the reference scan per family (default 801 for every family)."""
    from moving_bogie.api import induced_frequencies

    records = {f: [] for f in FAMILIES}
    try:
        _run_sets(sets, records, reference_every, verbose, induced_frequencies, scan_points or {})
    except KeyboardInterrupt:  # the table of the sets done so far is still worth printing
        done = sum(len(r) for r in records.values())
        print(f"interrupted after {done} of {len(sets)} sets", flush=True)
    return records


def _run_sets(sets, records, reference_every, verbose, induced_frequencies, scan_points) -> None:
    for k, (family, label, params) in enumerate(sets):
        c0 = _cpu()
        record = {"label": label, "params": params}
        try:
            res = induced_frequencies(params)
        except Exception as exc:  # noqa: BLE001 - every failure is a finding here
            record |= {"failure": f"{type(exc).__name__}: {exc}", "cpu": _cpu() - c0}
            if verbose:
                traceback.print_exc()
        else:
            record |= {
                "failure": None,
                "cpu": _cpu() - c0,
                "verdict": res.verdict,
                "sliver": max((u.height for u in res.unsearched), default=0.0),
                "roots": len(res.roots),
            }
            if reference_every and len(records[family]) % reference_every == 0:  # every n-th of its family
                n = scan_points.get(family, 801)
                ref = scan_roots(params, res.window, n=(n, n))
                ok, worst = compare(res, ref)
                scan_verdict = "unstable" if ref else "stable"
                # an UNDETERMINED verdict does not contradict the scan; its roots must still agree
                same = res.verdict.state == scan_verdict or not res.verdict.determined
                record["reference"] = (ok and same, worst, len(ref))
        records[family].append(record)
        if verbose:
            v = record.get("verdict")
            state = "FAIL " + record["failure"][:150] if record["failure"] else v.state
            ref = record.get("reference")
            extra = "" if ref is None else f" ref={'ok' if ref[0] else 'DIFFERS'}({ref[2]} unstable)"
            if record.get("sliver", 0.0) > 1e-8:
                extra += f" unsearched={record['sliver']:.1e}"
            print(f"{k:4d} {family:<11} {record['cpu']:7.2f}s {state:<12} {label}{extra}", flush=True)


def summary(records) -> None:
    head = (
        f"{'family':<12} {'sets':>5} {'fail':>5} {'undet':>6} {'cpu med':>8} {'cpu 90%':>8} {'cpu max':>8} "
        f"{'sliver max':>11} {'reference':>10}"
    )
    print(head)
    for family, recs in records.items():
        if not recs:
            continue
        cpu = np.array([r["cpu"] for r in recs])
        fails = sum(r["failure"] is not None for r in recs)
        undet = sum(r["failure"] is None and not r["verdict"].determined for r in recs)
        slivers = [r["sliver"] for r in recs if r["failure"] is None]
        refs = [r["reference"] for r in recs if "reference" in r]
        agree = f"{sum(x[0] for x in refs)}/{len(refs)}"
        print(
            f"{family:<12} {len(recs):5d} {fails:5d} {undet:6d} {np.median(cpu):8.2f} "
            f"{np.quantile(cpu, 0.9):8.2f} {cpu.max():8.2f} {max(slivers, default=0):11.1e} {agree:>10}"
        )


def main() -> int:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--layered", type=int, default=200, help="two- and three-layer sets (alternating)")
    parser.add_argument("--one-layer", type=int, default=100, help="one-layer EB and TR sets (alternating)")
    parser.add_argument("--seed", type=int, default=24)
    parser.add_argument("--reference", type=int, default=10, help="scan every n-th set per family (0: none)")
    parser.add_argument("--only", choices=FAMILIES, default=None)
    parser.add_argument("--verbose", action="store_true")
    from records import add_record_option

    add_record_option(parser)
    args = parser.parse_args()
    t0 = time.perf_counter()
    sets = draw_sets(args.seed, args.layered, args.one_layer, args.only)
    records = run(sets, args.reference, args.verbose)
    summary(records)
    print(
        f"wall {time.perf_counter() - t0:.0f} s (the machine may be shared: CPU times are per process; "
        f"OPENBLAS_NUM_THREADS={os.environ['OPENBLAS_NUM_THREADS']})"
    )
    if args.record:
        record_rows(records)
    return 1 if any(r["failure"] for recs in records.values() for r in recs) else 0


#: The aims of the search on random sets, CPU seconds per set (median and maximum).
TARGETS = {
    "two-layer": "median 1 s, max 3 s",
    "three-layer": "max 5 s",
    "eb": "max 3 s",
    "tr": "max 3 s",
}


def record_rows(records) -> None:
    """benchmarks/results/bench_search_random.json: one row per family."""
    from records import row, write_record

    out = []
    for family, recs in records.items():
        if not recs:
            continue
        cpu = np.array([r["cpu"] for r in recs])
        fails = sum(r["failure"] is not None for r in recs)
        undet = sum(r["failure"] is None and not r["verdict"].determined for r in recs)
        refs = [r["reference"] for r in recs if "reference" in r]
        sliver = max((r["sliver"] for r in recs if r["failure"] is None), default=0.0)
        measured = (
            f"CPU per set median {np.median(cpu):.2f} s, 90 % {np.quantile(cpu, 0.9):.2f} s, "
            f"max {cpu.max():.2f} s;"
            f" {fails} failures, {undet} UNDETERMINED; tallest unsearched region {sliver:.1e}"
        )
        agree = f"brute-force scan: {sum(x[0] for x in refs)}/{len(refs)} sets agree" if refs else "-"
        out.append(
            row(f"{len(recs)} random {family} sets through the search", measured, agree, TARGETS[family])
        )
    write_record(__file__, "The root search on random parameter sets", out)


if __name__ == "__main__":
    sys.exit(main())
