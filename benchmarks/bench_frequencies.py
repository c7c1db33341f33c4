"""Benchmark the search for induced frequencies (paper, Table 2) and print tables.

Run: ``OPENBLAS_NUM_THREADS=1 python benchmarks/bench_frequencies.py [--grid N] [--no-grid]
[--no-cxroots] [--cx-method romb|quad] [--cases 1,5,13]``. A script, not a test: nothing is asserted,
the numbers are printed. All methods: ~8 min on 2 idle cores; ours alone (``--no-grid --no-cxroots``) ~5 s.
The command ``moving-bogie table2`` as a whole, side by side with another checkout: ``bench_commands.py``.
Results and their reading: docs/performance.md.

The whole of Table 2 (the 13 cases of Table 1, 4 roots each with Re q >= 0) is computed from scratch at
30 digits by three methods applied to the same function E_chr(q) of Eq. (48), in the same run:

* ``argument principle``: :func:`moving_bogie.roots.frequencies.induced_frequencies` with its defaults
(count in
  the window and in the window twice as large, bisect, polish and confirm at 30 + 15 digits).
* ``grid + findroot``: ``mpmath.findroot`` (Newton, with the same analytic derivative and the same
  mpmath E_chr) from an N x N grid of starting points (cell centres) over the same window, at 30 digits;
  converged points are folded to Re q >= 0 (pairs q, -conj(q)), deduplicated, kept if inside the window
  and confirmed by the same precision ladder as ours
  (:func:`moving_bogie.roots.refine.polish.polish_and_confirm`).
* ``cxroots, our tiles``: ``cxroots.Rectangle(...).roots(f, df, int_method="romb")`` (quadrature
  argument principle and contour moments, double precision, our analytic E_chr' as df) on exactly the
  rectangles our tiling used for that case (they keep 1e-7 from the cut of K and 1e-5 from its branch
  point), then the same polish and confirm.
* ``cxroots, widened tiles``: the same on our tiling with margins 1e-3 from the cut and 1e-2 from the
  branch point (a strip that nothing searches; no Table 2 root lies in it).
  Both cxroots rows are skipped with a note when cxroots is not installed (it is not a dependency:
  ``pip install cxroots``).

Roots are compared with the argument-principle roots (which match the print of Cases 1-6 and add up to
the argument-principle count in every case): "missed" are reference roots a method did not return,
"extra" are roots it returned that are not in the reference. E_chr evaluations are counted separately in
double precision (numpy arrays, counted per point; for cxroots f and f' separately) and in mpmath (one
count per E_chr or (E_chr, E_chr') evaluation, split by working precision).
"""

from __future__ import annotations

import argparse
import collections
import contextlib
import logging
import os
import platform
import time
import warnings

import mpmath
import numpy as np

from moving_bogie.errors import MovingBogieError
from moving_bogie.kernels.bound import bind
from moving_bogie.kernels.characteristic import Characteristic, CharacteristicArray
from moving_bogie.kernels.cut import cut_locus
from moving_bogie.model.cases import TABLE1_CASES, table1_case
from moving_bogie.roots import frequencies
from moving_bogie.roots.frequencies import default_window
from moving_bogie.roots.refine.polish import PolishError, polish_and_confirm
from moving_bogie.roots.search.search_regions import tile_window

DPS = 30
EXTRA_DPS = max(10, DPS // 2)  # as induced_frequencies
MATCH = 1e-15  # two roots at 30 digits are the same root when closer than this (relative, |q| >= 1)


# --------------------------------------------------------------------------- counting instruments


class CountingArray(CharacteristicArray):
    """E_chr on numpy arrays; counts points (as the base class) and, separately, derivative points."""

    def __init__(self, params, **kwargs):
        super().__init__(params, **kwargs)
        self.derivative_evaluations = 0

    def derivative(self, q):
        """dE_chr/dq on arrays, chain rule of Eq. (40) with the double-pole residues of dK/dq."""
        q = np.asarray(q, dtype=complex)
        self.derivative_evaluations += q.size
        kv = self.kernel(q, [0.0, self.d, -self.d], derivative=True)
        E_q, E_K0, E_Kp, E_Km = self.module.e_chr_partials(q, *kv.K, **self.args)
        dK0, dKp, dKm = kv.dK
        return E_q + E_K0 * dK0 + E_Kp * dKp + E_Km * dKm


class CountingPrecise(Characteristic):
    """mpmath E_chr that also records the working precision of every evaluation."""

    def __init__(self, params, **kwargs):
        super().__init__(params, **kwargs)
        self.by_dps = collections.Counter()

    def __call__(self, q):
        self.by_dps[mpmath.mp.dps] += 1
        return super().__call__(q)

    def value_and_derivative(self, q):
        self.by_dps[mpmath.mp.dps] += 1
        return super().value_and_derivative(q)


@contextlib.contextmanager
def instrumented():
    """Patch the names used inside :mod:`moving_bogie.roots.frequencies` to count evaluations and time phases.

    Yields a dict filled per call of induced_frequencies: the evaluators it created, seconds and double
    evaluations per phase, and the tiles of the first (default-window) count.
    """
    record = {}
    saved = {
        name: getattr(frequencies, name)
        for name in (
            "CharacteristicArray",
            "Characteristic",
            "count_tiling",
            "locate",
            "polish_and_confirm",
        )
    }

    def make_array(params, **kwargs):
        record["fast"] = CountingArray(params, **kwargs)
        return record["fast"]

    def make_precise(params, **kwargs):
        record["precise"] = CountingPrecise(params, **kwargs)
        return record["precise"]

    def timed(phase_of, func):
        def wrapper(*args, **kwargs):
            phase = phase_of()
            fast = record.get("fast")
            e0 = fast.evaluations if fast else 0
            t0 = time.perf_counter()
            out = func(*args, **kwargs)
            record["seconds"][phase] += time.perf_counter() - t0
            record["double"][phase] += (fast.evaluations if fast else 0) - e0
            if func is saved["count_tiling"] and "tiles" not in record:
                record["tiles"] = out.tiling.regions
            return out

        return wrapper

    def count_phase():
        record["tilings"] = record.get("tilings", 0) + 1
        return "count window" if record["tilings"] == 1 else "count 2x window (frame)"

    frequencies.CharacteristicArray = make_array
    frequencies.Characteristic = make_precise
    frequencies.count_tiling = timed(count_phase, saved["count_tiling"])
    frequencies.locate = timed(lambda: "locate", saved["locate"])
    frequencies.polish_and_confirm = timed(lambda: "polish+confirm", saved["polish_and_confirm"])

    def reset():
        for key in [k for k in record if k != "reset"]:
            del record[key]
        record["seconds"] = collections.Counter()
        record["double"] = collections.Counter()

    record["reset"] = reset
    try:
        yield record
    finally:
        for name, value in saved.items():
            setattr(frequencies, name, value)


# --------------------------------------------------------------------------- helpers


def same(a, b) -> bool:
    return abs(complex(a) - complex(b)) <= MATCH * max(1.0, abs(complex(a)))


def fold(q):
    """The member of the pair q, -conj(q) with Re q >= 0."""
    return -mpmath.conj(q) if mpmath.re(q) < 0 else q


def compare(found, reference):
    """(number missed, number extra, text naming the missed and extra roots)."""
    missed = [r for r in reference if not any(same(r, f) for f in found)]
    extra = [f for f in found if not any(same(f, r) for r in reference)]
    text = "".join(f"; missed {mpmath.nstr(q, 6)}" for q in missed)
    text += "".join(f"; extra {mpmath.nstr(q, 6)}" for q in extra)
    return len(missed), len(extra), text


def confirm_all(precise, candidates):
    """Polish and confirm each candidate as ours does; drop failures; dedupe after polishing."""
    out = []
    for q in candidates:
        try:
            conf = polish_and_confirm(precise, q, dps=DPS, extra_dps=EXTRA_DPS)
        except (PolishError, MovingBogieError):
            continue
        q = fold(conf.q)
        if not any(same(q, o) for o in out):
            out.append(q)
    return out


Row = collections.namedtuple("Row", "case seconds cpu double mp by_dps roots missed extra note")


# --------------------------------------------------------------------------- the three methods


def run_ours(case, record):
    record["reset"]()
    t0, c0 = time.perf_counter(), time.process_time()
    result = frequencies.induced_frequencies(table1_case(case), dps=DPS)
    seconds, cpu = time.perf_counter() - t0, time.process_time() - c0
    precise = record["precise"]
    roots = [r.q for r in result.roots]
    note = "count ok" if result.count_ok else "COUNT MISMATCH: " + "; ".join(result.warnings)
    row = Row(
        case,
        seconds,
        cpu,
        record["fast"].evaluations,
        sum(precise.by_dps.values()),
        dict(precise.by_dps),
        len(roots),
        0,
        0,
        note,
    )
    return row, roots, dict(record["seconds"]), dict(record["double"]), record["tiles"]


def run_grid(case, reference, n):
    params = table1_case(case)
    window = default_window(bind(params))
    precise = CountingPrecise(params)
    cache = {}

    def f(q):
        cache["q"], cache["v"] = q, precise.value_and_derivative(q)
        return cache["v"][0]

    def df(q):
        return cache["v"][1] if cache.get("q") == q else precise.value_and_derivative(q)[1]

    xs = window.x0 + (np.arange(n) + 0.5) * window.width / n
    ys = window.y0 + (np.arange(n) + 0.5) * window.height / n
    t0, c0 = time.perf_counter(), time.process_time()
    converged, outside, failed = [], 0, 0
    with mpmath.workdps(DPS):
        for x in xs:
            for y in ys:
                try:
                    q = mpmath.findroot(f, mpmath.mpc(x, y), solver="newton", df=df, maxsteps=50)
                except (ValueError, ZeroDivisionError, MovingBogieError):
                    failed += 1
                    continue
                q = fold(q)
                if not window.contains(complex(q)):
                    outside += 1
                    continue
                if not any(same(q, o) for o in converged):
                    converged.append(q)
    roots = confirm_all(precise, converged)
    seconds, cpu = time.perf_counter() - t0, time.process_time() - c0
    missed, extra, which = compare(roots, reference)
    note = f"{n * n - failed}/{n * n} starts converged, {outside} outside the window{which}"
    mp = sum(precise.by_dps.values())
    return Row(case, seconds, cpu, 0, mp, dict(precise.by_dps), len(roots), missed, extra, note)


def widened_tiles(case, eps=1e-3, eps_branch=1e-2):
    """Our tiling of the default window with larger margins: 1e-3 from the cut, 1e-2 from its branch point."""
    params = table1_case(case)
    window = default_window(bind(params))
    cut = cut_locus(bind(params), window.x0, window.x1)
    gap_height = 0.1 * max(window.width, window.height)  # as the first try of frequencies._count_tiling
    return tile_window(window, cut, eps=eps, eps_branch=eps_branch, gap_height=gap_height).regions


def run_cxroots(case, reference, tiles, cxroots, int_method):
    """cxroots on each tile (our analytic f' supplied), then the same polish and confirm as ours.

    A tile on which cxroots raises is "raised"; a tile on which it returns without an error but some
    reference root inside it is missing from the confirmed roots is a "silent miss" (seen: a count that is
    right but three distinct roots returned as one root of multiplicity 3).
    """
    params = table1_case(case)
    fast = CountingArray(params)
    precise = CountingPrecise(params)
    t0, c0 = time.perf_counter(), time.process_time()
    candidates, ran = [], []
    for tile in tiles:
        contour = cxroots.Rectangle([tile.x0, tile.x1], [tile.y0, tile.y1])
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                result = contour.roots(fast, fast.derivative, int_method=int_method)
        except (RuntimeError, ValueError, MovingBogieError):
            continue
        ran.append(tile)
        candidates += [mpmath.mpc(complex(r)) for r in result.roots]
    roots = confirm_all(precise, candidates)
    seconds, cpu = time.perf_counter() - t0, time.process_time() - c0
    missed, extra, which = compare(roots, reference)
    raised = len(tiles) - len(ran)
    silent = sum(
        1
        for tile in ran
        if any(tile.contains(complex(r)) and not any(same(r, f) for f in roots) for r in reference)
    )
    note = f"{len(ran)}/{len(tiles)} tiles ran"
    if raised:
        note += f", {raised} raised"
    if silent:
        note += f", {silent} returned without error but missed roots"
    note += which
    double = (fast.evaluations, fast.derivative_evaluations)
    mp = sum(precise.by_dps.values())
    row = Row(case, seconds, cpu, double, mp, dict(precise.by_dps), len(roots), missed, extra, note)
    return row, raised, silent


# --------------------------------------------------------------------------- printing


def table(header, rows):
    rows = [[str(c) for c in r] for r in rows]
    widths = [max(len(r[i]) for r in [header, *rows]) for i in range(len(header))]
    lines = ["  ".join(c.rjust(w) for c, w in zip(header, widths, strict=True))]
    lines.append("  ".join("-" * w for w in widths))
    lines += ["  ".join(c.rjust(w) for c, w in zip(r, widths, strict=True)) for r in rows]
    return "\n".join(lines)


def fmt_double(d):
    if isinstance(d, tuple):
        return f"{d[0] + d[1]} ({d[0]} f + {d[1]} f')"
    return str(d)


def fmt_dps(by_dps):
    return " + ".join(f"{by_dps[k]}@{k}" for k in sorted(by_dps)) or "0"


def summary_row(method, rows, expected, certifies):
    total = sum(r.seconds for r in rows)
    cpu = sum(r.cpu for r in rows)
    double = [r.double for r in rows]
    if double and isinstance(double[0], tuple):
        double = (sum(d[0] for d in double), sum(d[1] for d in double))
    else:
        double = sum(double)
    by_dps = collections.Counter()
    for r in rows:
        by_dps.update(r.by_dps)
    return [
        method,
        f"{total:.2f}",
        f"{total / len(rows):.3f}",
        f"{cpu:.2f}",
        fmt_double(double),
        f"{sum(by_dps.values())} ({fmt_dps(by_dps)})",
        f"{sum(r.roots - r.extra for r in rows)}/{expected}",
        str(sum(r.missed for r in rows)),
        str(sum(r.extra for r in rows)),
        certifies,
    ]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--grid", type=int, default=20, help="grid of N x N starting points (default 20)")
    parser.add_argument("--no-grid", action="store_true", help="skip the grid + findroot method")
    parser.add_argument("--no-cxroots", action="store_true", help="skip the cxroots method")
    parser.add_argument(
        "--cx-method", default="romb", choices=("romb", "quad"), help="cxroots int_method (default romb)"
    )
    parser.add_argument("--cases", default=None, help="comma-separated case numbers (default: all 13)")
    from records import add_record_option

    add_record_option(parser)
    args = parser.parse_args()
    cases = tuple(int(c) for c in args.cases.split(",")) if args.cases else TABLE1_CASES

    cxroots, cx_note = None, ""
    if not args.no_cxroots:
        try:
            import cxroots  # not a dependency of the package

            logging.getLogger("cxroots").setLevel(logging.ERROR)
            cx_note = f"cxroots {cxroots.__version__} (int_method={args.cx_method}, analytic f')"
        except ImportError:
            cx_note = "cxroots not installed (pip install cxroots): its rows are skipped"

    _ = bind(table1_case(1)).vehicle  # imports outside the timings; no result is cached between cases
    print(
        f"# induced frequencies, Table 2 ({len(cases)} cases), {DPS} digits; "
        f"Python {platform.python_version()}, numpy {np.__version__}, mpmath {mpmath.__version__}, "
        f"{os.cpu_count()} CPUs, load average {os.getloadavg()[0]:.1f} at start"
        + (f"; {cx_note}" if cx_note else "")
    )

    ours, phases, phase_evals, reference, tiles = [], collections.Counter(), collections.Counter(), {}, {}
    with instrumented() as record:
        for case in cases:
            row, roots, sec, dbl, case_tiles = run_ours(case, record)
            ours.append(row)
            phases.update(sec)
            phase_evals.update(dbl)
            reference[case] = roots
            tiles[case] = case_tiles
    methods = [("argument principle (ours)", ours, "yes")]
    if not args.no_grid:
        grid = [run_grid(c, reference[c], args.grid) for c in cases]
        methods.append((f"grid {args.grid}x{args.grid} + mpmath.findroot", grid, "no"))
    if cxroots is not None:
        for label, tiling in (
            ("cxroots, our tiles", tiles),
            ("cxroots, widened tiles", {c: widened_tiles(c) for c in cases}),
        ):
            out = [run_cxroots(c, reference[c], tiling[c], cxroots, args.cx_method) for c in cases]
            failed = sum(o[1] for o in out)
            silent = sum(o[2] for o in out)
            if silent:
                verdict = f"no ({silent} tiles silently missed roots, {failed} raised)"
            elif failed:
                verdict = f"fails loudly ({failed} tiles raised)"
            else:
                verdict = "yes (by quadrature)"
            methods.append((label, [o[0] for o in out], verdict))

    expected = sum(len(reference[c]) for c in cases)
    header = [
        "method",
        "total s",
        "s/case",
        "CPU s",
        "E_chr evals double",
        "E_chr evals mpmath (n@dps)",
        "roots found/expected",
        "missed",
        "extra",
        "certifies count",
    ]
    print()
    print(table(header, [summary_row(label, rows, expected, cert) for label, rows, cert in methods]))

    print()
    print("per case: seconds (roots found, missed)")
    header = ["case", "ours double", "ours mpmath"] + [label for label, _, _ in methods]
    rows = []
    for k, case in enumerate(cases):
        line = [case, ours[k].double, ours[k].mp]
        for _, method_rows, _ in methods:
            r = method_rows[k]
            line.append(f"{r.seconds:.3f} ({r.roots - r.extra}, {r.missed})")
        rows.append(line)
    print(table(header, rows))
    bad = [r for r in ours if r.note != "count ok"]
    print(
        "ours: "
        + ("count ok in every case" if not bad else "; ".join(f"case {r.case}: {r.note}" for r in bad))
    )

    print()
    print("argument principle (ours): phases over all cases")
    total = sum(r.seconds for r in ours)
    rows = [
        [name, f"{phases[name]:.2f}", f"{100 * phases[name] / total:.0f}%", phase_evals[name]]
        for name in ("count window", "count 2x window (frame)", "locate", "polish+confirm")
    ]
    rest = total - sum(phases.values())
    rows.append(["other", f"{rest:.2f}", f"{100 * rest / total:.0f}%", "-"])
    print(table(["phase", "s", "share", "double evals"], rows))

    for label, method_rows, _ in methods[1:]:
        print()
        print(f"{label}:")
        for r in method_rows:
            print(f"  case {r.case:>2}: {r.note}")
    if cxroots is None and not args.no_cxroots:
        print()
        print(f"note: {cx_note}")
    if args.record:
        record_rows(methods, expected, len(cases))


def record_rows(methods, expected: int, n_cases: int) -> None:
    """benchmarks/results/bench_frequencies.json: our search, the other methods as its alternatives."""
    from records import row, write_record

    def cost(rows) -> str:
        total, cpu = sum(r.seconds for r in rows), sum(r.cpu for r in rows)
        found = sum(r.roots - r.extra for r in rows)
        return f"{total:.2f} s wall, {cpu:.2f} s CPU, {found}/{expected} roots"

    (_, ours, _), others = methods[0], methods[1:]
    alternative = "; ".join(f"{label}: {cost(rows)}" for label, rows, _ in others) or "-"
    work = f"Table 2 from scratch: {n_cases} cases, {expected} roots, {DPS} confirmed digits"
    write_record(__file__, "Induced frequencies (Table 2)", [row(work, cost(ours), alternative, "< 10 s")])


if __name__ == "__main__":
    main()
