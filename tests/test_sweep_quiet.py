"""A sweep from the command line is quiet: no Dask log line or traceback in a normal run, and Ctrl-C
(SIGINT to the whole process group, as a terminal sends it) prints one line and keeps a resumable store."""

from __future__ import annotations

import importlib.util
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

# Found, not imported: the sweeps run in subprocesses, and every worker collects this module.
if importlib.util.find_spec("distributed") is None:
    pytest.skip("distributed is not installed", allow_module_level=True)

# 20 blocks of 8 points (a block is at least one row of the last dimension): many chunks to interrupt
SWEEP = [sys.executable, "-m", "moving_bogie", "sweep", "--case", "1", "--vary", "alpha=0.5:1.1:20",
         "--vary", "eta_M=5:100:8", "--chunk-points", "8", "--check", "0", "--workers", "2"]  # fmt: skip


def _default_sigint() -> None:
    """In the child before Python starts: SIGINT as a terminal gives it (a background job has it ignored)."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def _chunks(store: Path) -> int:
    folder = store / "computed" / "c"
    return sum(1 for _ in folder.rglob("*") if _.is_file()) if folder.exists() else 0


@pytest.mark.slow
def test_ctrl_c_prints_one_line_and_the_store_resumes(tmp_path):
    store = tmp_path / "s.zarr"
    proc = subprocess.Popen(
        SWEEP + ["--out", str(store)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
        start_new_session=True, preexec_fn=_default_sigint,
    )  # fmt: skip
    deadline = time.monotonic() + 300
    while _chunks(store) == 0 and proc.poll() is None and time.monotonic() < deadline:
        time.sleep(0.05)
    assert proc.poll() is None, "the sweep ended before it could be interrupted"
    os.killpg(proc.pid, signal.SIGINT)
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == 130
    assert "Traceback" not in err and "distributed" not in err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "--resume" in lines[0] and str(store) in lines[0], err
    # resumed in this process (no --workers: a small sweep starts no cluster), as a user would after Ctrl-C
    resume = SWEEP[: SWEEP.index("--workers")] + ["--out", str(store), "--resume", "--json"]
    done = subprocess.run(resume, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert "Traceback" not in done.stderr and "distributed" not in done.stderr
    assert '"points_computed": ' in done.stdout and '"points_computed": 160' not in done.stdout
    assert '"scheduler": "in-process"' in done.stdout, done.stdout
