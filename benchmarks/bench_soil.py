"""The soil: dispersion of 100 frequencies, the critical velocity and a moving-load point, side by side.

    python benchmarks/bench_soil.py [--before REV] [--record]

In one run, wall time of:

- the surface-wave modes of ``examples/soil-ballasted.toml``'s layered soil at 100 frequencies (1 to
  300 rad/s), every mode (target: under 1 s), beside a brute-force scan (the same secular function on a grid
  20 times finer, no dip refinement) and beside disba (Dunkin's method, another code, when installed; its
  numba kernels compiled before the timing), with the largest difference between them;
- the same, only the fundamental mode;
- ``critical-velocity`` of the same file (its guided waves on 32 frequencies and the refinements; target
  under 2 s), beside the uncoupled intersection estimate alone;
- the moving-load deflection under the load at one speed (70 m/s) and at rest;
- the rail's receptance G(0, Omega) (docs/soil.md, Eq. (S9)) at Omega = 0 beside that deflection per unit
  load (the same integral by another integrator), and at 32 complex Omega in one call (the k nodes shared)
  beside one Omega alone;
- the induced frequencies of a vehicle on the soil track (``examples/soil-mass.toml``: the window's count,
  the roots, the verdict and the band of decaying roots above the axis; the ``frequencies --file``
  command adds the critical velocity, above),
  target under 10 s, and a DAF curve of 100 speeds (20 to 120 m/s, ``moving_load``: every grid speed,
  the static deflection and the peak refined between grid speeds), target under 10 s; each beside the
  same work by the code before when ``--before REV`` names a commit (checked out into a temporary
  worktree) or a checkout, run in a subprocess of this script, with the answers of both;
- the machine's load average over the run (the timings scale with it on a shared machine).

Prints a table; nothing is asserted (tests/test_soil_*.py check the values).
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
from bench_sweep import checkout

from moving_bogie.soil.critical import critical_velocity
from moving_bogie.soil.file import load_soil_file
from moving_bogie.soil.moving_load import deflection, moving_load
from moving_bogie.soil.rayleigh import soil_modes
from moving_bogie.soil.receptance import soil_receptance

FILE = Path(__file__).resolve().parent.parent / "examples" / "soil-ballasted.toml"
VEHICLE = FILE.with_name("soil-mass.toml")


def _timed(func):
    start = time.perf_counter()
    out = func()
    return time.perf_counter() - start, out


def _disba(soil, omega):
    try:
        from disba import PhaseDispersion
    except ImportError:
        return None
    layers = soil.layers
    th = np.array([layer.h if np.isfinite(layer.h) else 0.0 for layer in layers]) / 1e3
    vp, vs = (np.array([getattr(layer, c) for layer in layers]) / 1e3 for c in ("c_p", "c_s"))
    rho = np.array([layer.rho for layer in layers]) / 1e3
    pd = PhaseDispersion(th, vp, vs, rho, algorithm="dunkin", dc=1e-5)
    period = np.sort(2 * np.pi / omega)
    pd(period[:3], mode=0)  # compile
    seconds, result = _timed(lambda: pd(period, mode=0))
    return seconds, result.velocity[::-1] * 1e3


def _receptance_rows(data, w_per_load: float, t_ml: float) -> list[tuple[str, str, str, str]]:
    """The rail's receptance G at Omega = 0 beside the moving load (the same integral), and at 32 complex
    Omega of a contour's side in one call beside one Omega alone."""
    v = 70.0
    t_0, g0 = _timed(lambda: soil_receptance(data.track, data.soil, v, [0.0]))
    diff = abs(g0.G[0, 0].real / w_per_load - 1)
    rows = [
        ("receptance G(0, Omega = 0), 70 m/s",
         f"{t_0:.1f} s ({g0.nodes} k nodes, {g0.chi_quadratures} chi quadratures)",
         f"moving-load deflection / P: {t_ml:.1f} s, relative difference {diff:.1e}", "-")
    ]  # fmt: skip
    omega = np.linspace(0.0, 300.0, 32) - 100j
    t_32, g32 = _timed(lambda: soil_receptance(data.track, data.soil, v, omega))
    t_1, g1 = _timed(lambda: soil_receptance(data.track, data.soil, v, omega[16:17]))
    rows.append(
        ("receptance at 32 complex Omega in one call (0..300 - 100i rad/s)", f"{t_32 / 32:.2f} s per Omega "
         f"(largest error / |G| {np.max(g32.error / np.abs(g32.G[:, 0])):.1e})",
         f"one Omega alone: {t_1:.2f} s", "frequencies < 10 s")
    )  # fmt: skip
    return rows


def _work(name: str) -> tuple[float, str]:
    """(seconds, the answer) of the work ``name`` (``frequencies`` or ``daf``) with the code imported."""
    if name == "frequencies":
        from moving_bogie.api import induced_frequencies, load_soil_vehicle

        seconds, res = _timed(lambda: induced_frequencies(load_soil_vehicle(VEHICLE)))
        state = res.verdict.state
        band = getattr(res, "band", None)  # the decaying band (absent from older code)
        above = "" if band is None else f", {band.count} decaying in the band"
        return seconds, f"count {res.count}, {len(res.roots)} roots, {state}{above}, {res.evaluations} E_chr"
    data = load_soil_file(FILE)
    speeds = np.linspace(20.0, 120.0, 100)
    seconds, ml = _timed(lambda: moving_load(data.track, data.soil, data.load, speeds))
    return seconds, f"peak DAF {ml.daf_peak:.5f} at {ml.v_peak:.3f} m/s"


def _before_rows(before: str | None) -> list[tuple[str, str, str, str]]:
    """The search on the soil and the 100-speed DAF, here and (``--before``) in the code before."""
    rows = []
    labels = {
        "frequencies": ("induced frequencies, soil-mass.toml (count, roots, verdict)", "< 10 s"),
        "daf": ("moving load, DAF curve of 100 speeds (20-120 m/s) and its peak", "< 10 s"),
    }
    with checkout(before) if before else contextlib.nullcontext((None, "")) as (src, _):
        for name, (label, target) in labels.items():
            seconds, answer = _work(name)
            alternative = "code before: run with --before REV"
            if src is not None:
                argv = [sys.executable, __file__, "--work", name]
                env = os.environ | {"PYTHONPATH": str(src)}
                out = subprocess.run(argv, env=env, capture_output=True, text=True, check=True).stdout
                old = json.loads(out.strip().splitlines()[-1])
                alternative = f"code before ({before}): {old['seconds']:.1f} s, {old['answer']}"
            rows.append((label, f"{seconds:.1f} s ({answer})", alternative, target))
    return rows


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--record", action="store_true", help="write benchmarks/results/bench_soil.json")
    parser.add_argument("--before", help="a commit or a checkout: the code before, for the last two rows")
    parser.add_argument("--work", choices=("frequencies", "daf"), help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.work:  # one work, for the code before (a subprocess)
        seconds, answer = _work(args.work)
        print(json.dumps({"seconds": seconds, "answer": answer}))
        return 0
    data = load_soil_file(FILE)
    omega = np.linspace(1.0, 300.0, 100)
    rows = []
    t_all, modes = _timed(lambda: soil_modes(omega, data.soil))
    t_brute, brute = _timed(lambda: soil_modes(omega, data.soil, points=4000))
    same = modes.c.shape == brute.c.shape and np.allclose(modes.c, brute.c, rtol=1e-9, equal_nan=True)
    rows.append(
        ("soil modes, 100 frequencies, every mode", f"{t_all:.2f} s",
         f"scan 20x finer: {t_brute:.2f} s ({'same modes' if same else 'DIFFERENT modes'})", "< 1 s")
    )  # fmt: skip
    t_one, fundamental = _timed(lambda: soil_modes(omega, data.soil, modes=1))
    reference = _disba(data.soil, omega)
    if reference is None:
        alternative = "disba not installed"
    else:
        diff = np.max(np.abs(fundamental.c[:, 0] / reference[1] - 1))
        alternative = f"disba (Dunkin): {reference[0]:.2f} s, largest difference {diff:.1e}"
    rows.append(("soil modes, 100 frequencies, fundamental only", f"{t_one:.2f} s", alternative, "< 1 s"))
    t_cr, crit = _timed(lambda: critical_velocity(data.track, data.soil))
    rows.append(
        ("critical velocity (coupled guided waves)", f"{t_cr:.1f} s (v_cr = {crit.v_cr:.4f} m/s)",
         f"uncoupled estimate {crit.v_cr_uncoupled:.4f} m/s, from the same run", "< 2 s")
    )  # fmt: skip
    t_ml, moving = _timed(lambda: deflection(data.track, data.soil, data.load, 70.0))
    t_st, static = _timed(lambda: deflection(data.track, data.soil, data.load, 0.0))
    daf = moving.w[0] / static.w[0]
    rows.append(
        ("moving-load deflection under the load, one speed", f"{t_ml:.1f} s (DAF {daf:.3f})",
         f"at rest: {t_st:.1f} s", "100 speeds < 10 s")
    )  # fmt: skip
    rows += _receptance_rows(data, moving.w[0] / data.load, t_ml)
    rows += _before_rows(args.before)
    rows.append(("load average of the machine (1 min, at the end)", f"{os.getloadavg()[0]:.1f}", "-", "-"))
    header = ("work", "measured", "alternative", "target")
    widths = [max(len(str(r[k])) for r in [*rows, header]) for k in range(4)]
    for r in [header, *rows]:
        print(" | ".join(str(v).ljust(w) for v, w in zip(r, widths, strict=True)))
    if args.record:
        from records import row, write_record

        write_record(__file__, "The soil under the track", [row(*r) for r in rows], entries=())
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
