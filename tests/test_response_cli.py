"""``moving-bogie timeseries`` and ``moving-bogie shape``: JSON shape, files, and clear failures.

References: the JSON layout promised in docs/vibrations.md; the homogeneous initial conditions (w(0,0) = 0);
Eq. (28) at xi = 0 (the shape's value at the rear wheel is the rear-wheel series).
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from moving_bogie.cli import main

SCRIPT = Path(sys.executable).with_name("moving-bogie")


# The in-process runs below search the same roots (Case 7 at the default 30 digits, four runs): once for the
# module. What each test checks is the command's output from those roots; the search itself is checked in
# tests/test_frequencies.py.
pytestmark = pytest.mark.usefixtures("same_search_once")


def test_timeseries_json_from_the_console_script():
    if not SCRIPT.exists():
        pytest.fail(f"console script {SCRIPT} is not installed: run pip install -e '.[dev]'")
    done = subprocess.run(
        [str(SCRIPT), "timeseries", "--case", "7", "--tau", "0,20", "--json"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr
    data = json.loads(done.stdout)
    for key in ("tau", "w_rear", "w_front", "u", "theta"):
        assert len(data[key]) == 2
    assert data["tau"] == [0.0, 20.0]
    assert data["branch_cut"] is True and data["units"]["tau"] == "1"
    assert set(data["steady"]) == {"w_rear", "w_front", "u", "theta"}
    assert isinstance(data["steady"]["w_rear"], float)
    assert abs(data["w_rear"][0]) < 1e-9


def test_timeseries_files_and_no_branch_cut(tmp_path, capsys, monkeypatch):
    import moving_bogie.response.plots as plots

    saved = []
    original = plots.save_figure
    monkeypatch.setattr(
        plots, "save_figure", lambda fig, path, **kw: saved.append(fig) or original(fig, path, **kw)
    )
    csv, png = tmp_path / "s.csv", tmp_path / "s.png"
    code = main(
        [
            "timeseries",
            "--case",
            "7",
            "--tmax",
            "10",
            "--points",
            "11",
            "--no-branch-cut",
            "--json",
            "--csv",
            str(csv),
            "--plot",
            str(png),
        ]
    )
    assert code == 0
    data = json.loads(capsys.readouterr().out)
    assert data["branch_cut"] is False and len(data["tau"]) == 11
    lines = csv.read_text().splitlines()
    assert lines[0] == "tau,w_rear,w_front,u,theta" and len(lines) == 13
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    # the figure by content: its three panels draw the series of the JSON (w_rear, u, theta against tau)
    (fig,) = saved
    panels = [ax for ax in fig.axes if ax.get_ylabel()]
    assert len(panels) == 3
    for ax, name in zip(panels, ("w_rear", "u", "theta")):
        (line,) = [ln for ln in ax.get_lines() if len(ln.get_xdata()) == 11]
        assert list(line.get_xdata()) == pytest.approx(data["tau"], rel=1e-12)
        assert list(line.get_ydata()) == pytest.approx(data[name], rel=1e-12, abs=1e-15), name


def test_shape_json_matches_the_rear_wheel_series(capsys):
    assert (
        main(
            [
                "shape",
                "--case",
                "7",
                "--tau",
                "20",
                "--xi-min",
                "0",
                "--xi-max",
                "2",
                "--points",
                "3",
                "--json",
            ]
        )
        == 0
    )
    shape = json.loads(capsys.readouterr().out)
    assert shape["xi"] == [0.0, 1.0, 2.0] and len(shape["w"]) == 3
    assert main(["timeseries", "--case", "7", "--tau", "20", "--json"]) == 0
    series = json.loads(capsys.readouterr().out)
    assert shape["w"][0] == pytest.approx(series["w_rear"][0], rel=1e-10)
    assert shape["w"][2] == pytest.approx(series["w_front"][0], rel=1e-10)


@pytest.mark.parametrize(
    ("argv", "needle"),
    [
        (["timeseries", "--case", "7", "--tau", "-1"], "tau"),
        (["timeseries", "--case", "7", "--tau", "1", "--tmax", "2"], "either --tau"),
        (["timeseries", "--case", "7", "--tau", "x"], "comma-separated"),
        (["timeseries", "--case", "99", "--tau", "1"], "unknown case"),
        (["shape", "--case", "7", "--tau", "1", "--xi-min", "3", "--xi-max", "1"], "xi_min < xi_max"),
        (  # undamped (eta_f = 0) above the critical velocity: the cut passes through q = 0
            ["timeseries", "--case", "2", "--tau", "1", "--alpha", "1.2", "--branch-cut"],
            "passes through q = 0",
        ),
    ],
)
def test_bad_input_exits_2_with_one_line(capsys, argv, needle):
    assert main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("moving-bogie: error:") and needle in err[0]


def test_failed_frequency_count_exits_2(capsys, monkeypatch):
    import dataclasses

    import moving_bogie.roots.frequencies as fq
    from moving_bogie.roots.count.outcomes import count_mismatch

    real = fq.induced_frequencies

    def broken(params, **kwargs):
        result = real(params, **kwargs)
        lost = result.roots[:-1]
        return dataclasses.replace(result, roots=lost, notes=(count_mismatch(result.count, len(lost)),))

    monkeypatch.setattr(fq, "induced_frequencies", broken)
    assert main(["timeseries", "--case", "7", "--tau", "1"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "induced frequencies incomplete" in err[0]
