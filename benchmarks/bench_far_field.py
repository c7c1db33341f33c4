"""Benchmark the complete lower half-plane search (far-field radius) against the old fixed window.

Run: ``OPENBLAS_NUM_THREADS=1 python benchmarks/bench_far_field.py``. A script, not a test: nothing is
asserted, the numbers are printed (about a minute on 2 idle cores).

For each parameter set, in the same run:

* ``far-field check``: :func:`moving_bogie.roots.count.far_field.far_field_radius` alone (the samples of
  |E_chr - E_lead| / |E_lead| on half circles R..32R and rays, the half Re q >= 0 of them), and beside it
  the same check on the whole symmetric set of samples (both halves, as it was before the mirror symmetry
  rho(-conj q) = rho(q) was used): the radius and the largest rho must be the same;
* ``new default``: :func:`moving_bogie.roots.frequencies.induced_frequencies` with its default window (the
  far-field radius, the verdict about every root with Im q < 0);
* ``old window``: the same search in the window of the previous default (``default_window``: X = max(3, 3 f))
  with the check in a window twice as large, and no far field.

Wall and CPU seconds, the radius R, and the number of unstable roots each finds.
"""

from __future__ import annotations

import time

import numpy as np

from moving_bogie.api import induced_frequencies
from moving_bogie.kernels.bound import bind
from moving_bogie.model.cases import table1_case
from moving_bogie.roots.count import far_field
from moving_bogie.roots.count.far_field import far_field_radius
from moving_bogie.roots.frequencies import default_window

SETS = [
    ("Case 1", table1_case(1)),
    ("Case 5", table1_case(5)),
    ("Case 13", table1_case(13)),
    ("Case 1, alpha = 5", table1_case(1).replace(alpha=5)),
    ("Case 7, alpha = 3, eta_M = 5", table1_case(7).replace(alpha=3, eta_M=5)),
    ("Case 1, TR S = 10, r = 0.09", table1_case(1).replace(beam="tr", S=10, r="0.09")),
]


def _timed(func, *args, **kwargs):
    wall, cpu = time.perf_counter(), time.process_time()
    out = func(*args, **kwargs)
    return out, time.perf_counter() - wall, time.process_time() - cpu


def _both_halves(radius: float) -> np.ndarray:
    """The far-field samples with their mirrors -conj(q): the whole symmetric set."""
    half = _HALF(radius)
    return np.concatenate([half, -np.conj(half)])


_HALF = far_field.sample_points


def _check_both_halves(bound, start):
    far_field.sample_points = _both_halves
    try:
        return far_field_radius(bound, start)
    finally:
        far_field.sample_points = _HALF


def main() -> None:
    head = (
        f"{'parameters':<30} {'R':>6} {'check s':>8} {'both halves s':>14} {'new s (cpu)':>14} "
        f"{'old s (cpu)':>14} {'unstable new/old':>17}"
    )
    print(head)
    print("-" * len(head))
    for label, p in SETS:
        X = default_window(bind(p)).x1
        far, t_far, _ = _timed(far_field_radius, bind(p), X)
        both, t_both, _ = _timed(_check_both_halves, bind(p), X)
        assert (both.radius, both.rho) == (far.radius, far.rho), "the mirror halves disagree"
        new, t_new, c_new = _timed(induced_frequencies, p, dps=30)
        old, t_old, c_old = _timed(induced_frequencies, p, dps=30, window=default_window(bind(p)))
        print(
            f"{label:<30} {far.radius or float('nan'):>6.3g} {t_far:>8.2f} {t_both:>14.2f} "
            f"{t_new:>7.2f} ({c_new:>4.1f})"
            f" {t_old:>7.2f} ({c_old:>4.1f}) {len(new.unstable_roots):>8}/{len(old.unstable_roots)}"
        )


if __name__ == "__main__":
    main()
