"""The benchmark gate's verdicts and CI's use of it, without timing anything.

``benchmarks/bench_gate.py`` times commands against a calibration; here its measurements are replaced by
given ratios (the timing itself stays out of the tests), and the end of ``.ci/run`` is run with the tests and
the gate replaced by commands that pass or fail.
"""

from __future__ import annotations

import json
import subprocess
from pathlib import Path

import pytest
from scripts import load_script

ROOT = Path(__file__).resolve().parent.parent


@pytest.fixture
def gate():
    return load_script("benchmarks/bench_gate.py")


def test_a_ratio_past_twice_its_record_fails(gate):
    assert gate.judge(1.99, 1.0) == "ok"
    assert gate.judge(2.01, 1.0) == "SLOWER"
    assert gate.judge(0.5, None) == "NO RECORD"


def _fake_runs(monkeypatch, gate, ratios: dict[str, float]) -> list[str]:
    """``measure`` returning ``ratios`` (a calibration of 1 s: CPU seconds are ratios); the labels run."""
    ran: list[str] = []
    run_type = load_script("benchmarks/bench_commands.py").Run

    def measure(label, unit):
        ran.append(label)
        return run_type(0.0, ratios[label] * unit, "", 0), ratios[label]

    monkeypatch.setattr(gate, "calibration", lambda repeat=3: 1.0)
    monkeypatch.setattr(gate, "measure", measure)
    return ran


def test_the_gate_fails_on_a_command_twice_as_slow_and_prints_its_table(gate, monkeypatch, capsys):
    recorded = json.loads(gate.BASELINE.read_text())["ratios"]
    assert set(recorded) == set(gate.COMMANDS), (
        "record the baseline again: python benchmarks/bench_gate.py --record"
    )
    ran = _fake_runs(monkeypatch, gate, {label: 1.5 * r for label, r in recorded.items()})
    assert gate.main([]) == 0
    assert ran == list(gate.COMMANDS)  # each once: none over the limit
    slow = next(iter(recorded))
    ran = _fake_runs(
        monkeypatch, gate, {label: (2.2 if label == slow else 1.0) * r for label, r in recorded.items()}
    )
    assert gate.main([]) == 1
    assert ran.count(slow) == 2  # run again before it fails
    out = capsys.readouterr().out
    assert f"the benchmark gate FAILED: {slow}" in out
    assert all(label in out for label in gate.COMMANDS)


def _ci_tail(tests: str, gate: str) -> int:
    """The exit status of ``.ci/run`` from its benchmark gate on, with ``tests`` and ``gate`` (shell
    commands) in place of pytest and the benchmark gate; the gate runs first, so that pytest's summary
    closes the log."""
    text = (ROOT / ".ci" / "run").read_text()
    tail = text[text.index("gate=0") :]
    assert "pytest -q -n 2 ||" in tail and "python benchmarks/bench_gate.py ||" in tail
    assert tail.index("python benchmarks/bench_gate.py ||") < tail.index("pytest -q -n 2 ||")
    tail = tail.replace("pytest -q -n 2 ||", f"{tests} ||").replace(
        "python benchmarks/bench_gate.py ||", f"{gate} ||"
    )
    return subprocess.run(["bash", "-c", "set -euo pipefail\n" + tail], capture_output=True).returncode


def test_ci_runs_the_gate_before_the_tests_and_fails_with_it():
    assert _ci_tail("true", "true") == 0
    assert _ci_tail("true", "false") != 0  # the gate fails CI
    assert _ci_tail("(exit 3)", "true") == 3  # a test failure is still what CI reports
    assert _ci_tail("(exit 3)", "false") == 3
