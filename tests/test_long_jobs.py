"""Long jobs show progress on a terminal and keep their work: a map interrupted after k parts resumes by
computing only the others, and equals, cell by cell, the same map computed without interruption (the
reference: that uninterrupted run, by the same code on the same inputs)."""

from __future__ import annotations

import io
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from rich.console import Console

from moving_bogie import table1_case
from moving_bogie.checkpoint import Checkpoint, kept_until_done, run_parts
from moving_bogie.cli import main
from moving_bogie.cli.progress import counts_bar, progress_bar
from moving_bogie.errors import JobInterrupted
from moving_bogie.kernels.bound import bind
from moving_bogie.stability.maps.map import CELL_ARRAYS, stability_map

REPO = Path(__file__).resolve().parent.parent


def _terminal() -> tuple[Console, io.StringIO]:
    buffer = io.StringIO()
    return Console(file=buffer, force_terminal=True, width=100), buffer


def test_progress_bar_shows_the_time_left_on_a_terminal_only():
    console, buffer = _terminal()
    with progress_bar("stability map", console=console) as update:
        update(0.5)
        console.file.flush()
    screen = buffer.getvalue()
    assert "stability map" in screen and "50%" in screen and "ETA" in screen
    for enabled, console in ((False, _terminal()[0]), (True, Console(file=io.StringIO()))):
        with progress_bar("stability map", enabled=enabled, console=console) as update:
            update(0.5)
        assert console.file.getvalue() == ""  # --json, or not a terminal: nothing drawn


def test_counts_bar_shows_done_of_total_and_the_rate():
    console, buffer = _terminal()
    with counts_bar("sweep", "points", console=console) as update:
        update(0, 10)
        update(4, 10)
    screen = buffer.getvalue()
    assert "4/10" in screen and "points/s" in screen and "ETA" in screen


def _stop_after(k: int, n: int):
    """A progress callback that interrupts once k of n parts are done (Ctrl-C at that moment)."""

    def progress(fraction: float) -> None:
        if fraction >= k / n - 1e-12:
            raise KeyboardInterrupt

    return progress


def test_an_interrupted_map_resumes_to_the_uninterrupted_map(tmp_path):
    bound = bind(table1_case(1))
    grid = dict(alphas=np.linspace(0.3, 1.1, 4).tolist(), thetas=np.linspace(5.0, 120.0, 3).tolist())
    reference = stability_map(bound, workers=1, chunk=2, **grid)
    with pytest.raises(JobInterrupted) as stopped:
        stability_map(bound, workers=1, chunk=2, checkpoint=tmp_path, progress=_stop_after(1, 2), **grid)
    assert (stopped.value.done, stopped.value.total) == (1, 2) and "--resume" in stopped.value.advice()
    (folder,) = tmp_path.iterdir()
    assert [p.name for p in folder.glob("part-*")] == ["part-000000.npz"]
    seen: list[float] = []
    resumed = stability_map(
        bound, workers=1, chunk=2, checkpoint=tmp_path, resume=True, progress=seen.append, **grid
    )
    assert seen == pytest.approx([1 / 2, 1.0])  # one chunk read back, one computed
    for name in CELL_ARRAYS:
        assert np.array_equal(getattr(resumed, name), getattr(reference, name), equal_nan=True), name
    assert not any(tmp_path.iterdir())  # a finished map leaves nothing behind


def test_a_changed_map_is_computed_anew(tmp_path):
    kept = Checkpoint.open(tmp_path, "job", {"n": 1}, resume=False)
    kept.save(0, {"x": np.arange(3)})
    assert Checkpoint.open(tmp_path, "job", {"n": 1}, resume=True).load(0)["x"].tolist() == [0, 1, 2]
    assert Checkpoint.open(tmp_path, "job", {"n": 2}, resume=True).load(0) is None  # another job
    assert Checkpoint.open(tmp_path, "job", {"n": 1}, resume=False).load(0) is None  # without --resume


def test_parts_run_on_workers_come_back_in_order(tmp_path):
    kept = Checkpoint.open(tmp_path, "squares", {}, resume=False)
    parts = run_parts(_square, list(range(5)), workers=2, checkpoint=kept)
    assert [int(p["y"]) for p in parts] == [0, 1, 4, 9, 16]
    assert len(list(kept.folder.glob("part-*"))) == 5


def test_a_command_of_several_jobs_keeps_each_until_it_is_done(tmp_path):
    first = Checkpoint.open(tmp_path, "first", {}, resume=False)
    with pytest.raises(KeyboardInterrupt), kept_until_done():
        run_parts(_square, [1, 2], workers=1, checkpoint=first)
        first.remove()  # the first job is done ...
        raise KeyboardInterrupt  # ... and the second one interrupted
    assert len(list(first.folder.glob("part-*"))) == 2  # --resume reads the first job back
    with kept_until_done():
        first.remove()
        assert first.folder.exists()
    assert not first.folder.exists()  # the command done: nothing left


def _square(x: int) -> dict[str, np.ndarray]:
    return {"y": np.array(x * x)}


@pytest.mark.slow
def test_an_interrupted_sleeper_map_resumes_to_the_uninterrupted_map(tmp_path):
    from moving_bogie import load_parameters
    from moving_bogie.api import sleeper_map

    _, data = load_parameters(REPO / "examples" / "sleepers_zones.toml")
    vs, ms = np.array([150.0, 250.0, 350.0]), np.linspace(150.0, 3000.0, 12)
    reference = sleeper_map(data, vs, ms, verify=0, workers=1)
    with pytest.raises(JobInterrupted) as stopped:
        sleeper_map(data, vs, ms, verify=0, workers=1, checkpoint=tmp_path, progress=_stop_after(1, 3))
    assert stopped.value.done == 1 and stopped.value.what == "columns"
    resumed = sleeper_map(data, vs, ms, verify=0, workers=1, checkpoint=tmp_path, resume=True)
    assert np.array_equal(resumed.count, reference.count)
    assert resumed.columns == reference.columns  # every crossing, its frequency and its notes, bit for bit
    assert not any(tmp_path.iterdir())


@pytest.mark.slow
def test_the_map_command_says_how_to_resume_and_resumes(tmp_path, monkeypatch, capsys):
    from contextlib import contextmanager

    import moving_bogie.cli.lines_cmd as lines_cmd

    monkeypatch.setenv("MOVING_BOGIE_CACHE", str(tmp_path))
    args = ["stability-map", "--case", "1", "--n", "12", "--workers", "1", "--json"]
    assert main(args) == 0
    reference = json.loads(capsys.readouterr().out)

    @contextmanager
    def ctrl_c(*_args, **_kwargs):
        yield _stop_after(1, 2)

    with monkeypatch.context() as m:
        m.setattr(lines_cmd, "progress_bar", ctrl_c)
        assert main(args[:-1]) == 130
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "1 of 2 chunks of 8 columns" in err and "--resume" in err
    assert main([*args, "--resume"]) == 0
    assert json.loads(capsys.readouterr().out) == reference


@pytest.mark.slow
def test_ctrl_c_on_a_map_with_workers_prints_one_line_and_resumes(tmp_path):
    # a real Ctrl-C (SIGINT to the process group, as a terminal sends it) once the first chunk is kept
    env = os.environ | {"MOVING_BOGIE_CACHE": str(tmp_path), "PYTHONPATH": str(REPO / "src")}
    args = [
        sys.executable,
        "-m",
        "moving_bogie",
        "stability-map",
        "--case",
        "1",
        "--n",
        "40",
        "--workers",
        "2",
    ]
    proc = subprocess.Popen(
        args, env=env, start_new_session=True, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.default_int_handler),
    )  # fmt: skip
    deadline = time.monotonic() + 300
    while not list(tmp_path.glob("*/part-*")) and proc.poll() is None and time.monotonic() < deadline:
        time.sleep(0.1)
    os.killpg(proc.pid, signal.SIGINT)
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == 130, err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err and "--resume" in err
    done = subprocess.run([*args, "--resume", "--json"], env=env, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert not any(tmp_path.iterdir())


def _die(x: int) -> dict[str, np.ndarray]:
    if x == 1:
        os.kill(os.getpid(), signal.SIGKILL)  # a worker killed (out of memory, say)
    return {"y": np.array(x)}


def test_a_killed_worker_is_an_error_not_a_wait(tmp_path):
    from concurrent.futures.process import BrokenProcessPool

    kept = Checkpoint.open(tmp_path, "die", {}, resume=False)
    with pytest.raises(BrokenProcessPool):
        run_parts(_die, [0, 1, 2], workers=2, checkpoint=kept)
