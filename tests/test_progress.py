"""Long jobs show progress on a terminal and nothing on a pipe; reproduce shows the recipe under way.

The progress within an artefact is checked on the quick run of tests/test_reproduce.py.
"""

from __future__ import annotations

import os
import pty
import subprocess
import sys

import pytest


def _run_on_a_terminal(args, cwd):
    """stderr and stdout of ``moving-bogie ARGS`` on a pseudo-terminal (what a user sees)."""
    main, child = pty.openpty()
    proc = subprocess.Popen(
        [sys.executable, "-m", "moving_bogie", *args], stdin=child, stdout=child, stderr=child, cwd=cwd,
        env=os.environ | {"COLUMNS": "120", "TERM": "xterm"},
    )  # fmt: skip
    os.close(child)
    chunks = []
    while True:
        try:
            data = os.read(main, 4096)
        except OSError:
            break
        if not data:
            break
        chunks.append(data)
    proc.wait(timeout=600)
    os.close(main)
    return proc.returncode, b"".join(chunks).decode(errors="replace")


def test_reproduce_shows_the_recipe_on_a_terminal_and_nothing_on_a_pipe(tmp_path):
    # Table 1 is the cheapest artefact with a recipe: the bars (and the recipe's name) are drawn by the
    # command around any recipe, so one that builds in a moment shows the same (the progress within an
    # artefact: tests/test_reproduce.py).
    args = ["reproduce", "--quick", "--only", "table1", "--out", str(tmp_path / "out")]
    code, screen = _run_on_a_terminal(args, tmp_path)
    assert code == 0 and "reproducing the paper" in screen and "Table 1" in screen and "%" in screen
    piped = subprocess.run([sys.executable, "-m", "moving_bogie", *args], capture_output=True, text=True)
    assert piped.returncode == 0 and "%" not in piped.stderr and "reproducing the paper" not in piped.stderr


@pytest.mark.slow
def test_a_map_shows_its_time_left_on_a_terminal_and_nothing_with_json(tmp_path):
    args = ["stability-map", "--case", "1", "--n", "9", "--workers", "1"]
    code, screen = _run_on_a_terminal(args, tmp_path)
    assert code == 0 and "stability map" in screen and "ETA" in screen
    code, screen = _run_on_a_terminal([*args, "--json"], tmp_path)
    assert code == 0 and "ETA" not in screen and "stability map" not in screen
