"""Every script of benchmarks/ loads: its imports name modules and functions that exist (a benchmark is
run by hand, so a module moved or a function renamed in the package would otherwise go unnoticed until
someone runs it). Loading runs no benchmark: each script's work sits behind ``if __name__ == "__main__"``."""

from __future__ import annotations

import pytest
from scripts import ROOT, load_script

SCRIPTS = sorted(path.relative_to(ROOT).as_posix() for path in (ROOT / "benchmarks").glob("*.py"))


def test_the_scripts_are_found():
    assert "benchmarks/bench_sweep.py" in SCRIPTS and len(SCRIPTS) > 20


@pytest.mark.parametrize("script", SCRIPTS)
def test_every_benchmark_script_loads(script):
    module = load_script(script)
    assert module.__doc__, f"{script} says what it measures"
