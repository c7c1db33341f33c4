"""benchmarks/bench_commands.py compares what two codes print: the numbers of every path both print.

The comparison is what says "the same work, done faster, prints the same numbers"; these cases are
written by hand (two small JSON outputs), so each result is known without the benchmark.
"""

from __future__ import annotations

import json

from scripts import load_script


def _compare():
    return load_script("benchmarks/bench_commands.py").largest_difference


def test_common_paths_are_compared_and_the_others_counted():
    largest_difference = _compare()
    old = json.dumps({"w": [1.0, 2.0], "root": "0.25", "steady": 3.0, "timings": {"s": 9.0}})
    new = json.dumps({"w": [1.0, 2.5], "root": "0.25", "timings": {"s": 1.0}})
    assert largest_difference(old, new) == "5.0e-01 (at /w); 1 field(s) printed by one code only"
    assert largest_difference(new, new) == "0.0e+00"
    printed_root = json.dumps({"w": [1.0, 2.5], "root": "0.2500001"})
    assert largest_difference(new, printed_root) == "1.0e-07 (at /root)"


def test_a_changed_shape_or_nan_is_not_a_difference_of_zero():
    largest_difference = _compare()
    a = json.dumps({"w": [1.0, 2.0], "u": [float("nan"), 1.0]})
    shorter = json.dumps({"w": [1.0], "u": [float("nan"), 1.0]})
    assert largest_difference(a, shorter) == "0.0e+00; 1 field(s) printed by one code only"
    assert largest_difference(a, json.dumps({"w": [1.0, 2.0], "u": [0.0, 1.0]})).startswith("NaN MISMATCH")
    assert (
        largest_difference(a, json.dumps({"v": [1.0]}))
        == "DIFFERENT FIELDS; 3 field(s) printed by one code only"
    )
    assert largest_difference(a, "not json") == "(no numbers)"
