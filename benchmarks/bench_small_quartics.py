"""One quartic at a time: the scalar path of ``quartic_roots`` against the batched one, side by side.

    python benchmarks/bench_small_quartics.py [--repeat N]

The continuation of instability lines (:mod:`moving_bogie.stability.lines.continuation`) evaluates E_chr at
one
point per Newton step, so ``quartic_roots`` (the p-roots of N, Euler-Bernoulli and Timoshenko-Rayleigh)
is called thousands of times on a single polynomial. Batches of at most ``_SCALAR_BATCH`` quartics run the
same formulas on Python complex numbers; this script times, in one run:

- ``quartic_roots`` on 1, 3 and 8 quartics, scalar path against the batched one (the scalar path turned
  off by setting the batch limit to 0), and numpy's companion eigenvalues (``np.roots``) for scale;
- the instability lines of Figure 4(a) (bogie, eta_f = 0.05, six spacings, the quick grid of
  ``moving-bogie reproduce --quick``), CPU time, both paths.

Prints a table; nothing is asserted (tests/test_stability_kernel.py checks the roots).
"""

from __future__ import annotations

import argparse
import time
import timeit

import numpy as np

from moving_bogie.kernels import polyroots


def _per_call(func, repeat) -> float:
    return min(timeit.repeat(func, number=repeat, repeat=3)) / repeat * 1e6


def _lines_cpu() -> float:
    from moving_bogie.api import instability_lines
    from moving_bogie.paper import stability_figures as sf

    start = time.process_time()
    instability_lines(sf._base("0.05"), spacings=sf.SPACINGS, alpha_range=(0, 1), **sf._grid(True))
    return time.process_time() - start


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=2000, help="calls per timing (default 2000)")
    args = parser.parse_args()
    rng = np.random.default_rng(0)
    limit = polyroots._SCALAR_BATCH
    rows = []
    for n in (1, 3, 8):
        c = rng.normal(size=(n, 5)) + 1j * rng.normal(size=(n, 5))
        scalar = _per_call(lambda c=c: polyroots.quartic_roots(c), args.repeat)
        polyroots._SCALAR_BATCH = 0
        try:
            batched = _per_call(lambda c=c: polyroots.quartic_roots(c), args.repeat)
        finally:
            polyroots._SCALAR_BATCH = limit
        eig = _per_call(lambda c=c: [np.roots(row) for row in c], args.repeat)
        label = f"quartic_roots, {n} quartic(s)"
        rows.append((label, f"{scalar:.0f} us", f"{batched:.0f} us", f"{eig:.0f} us"))
    scalar = _lines_cpu()
    polyroots._SCALAR_BATCH = 0
    try:
        batched = _lines_cpu()
    finally:
        polyroots._SCALAR_BATCH = limit
    label = "Figure 4(a) instability lines, quick grid (CPU)"
    rows.append((label, f"{scalar:.1f} s", f"{batched:.1f} s", ""))
    header = ("", "scalar path", "batched path", "np.roots")
    widths = [max(len(str(r[k])) for r in rows + [header]) for k in range(4)]
    for row in [header] + rows:
        print(" | ".join(str(v).ljust(w) for v, w in zip(row, widths)))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
