"""The shared checks of option values (cli/checks.py) and the size of long jobs (cli/job_size.py)."""

import argparse

import pytest

from moving_bogie.cli import main
from moving_bogie.cli.checks import count, named_values, number, value_range, workers
from moving_bogie.cli.job_size import ASK, SAY, check_points, duration, estimate_grid
from moving_bogie.errors import ParameterError


@pytest.mark.parametrize("text", ["nan", "inf", "-inf", "1e400", "-1e400", "1e-400", "abc", ""])
def test_number_refuses_what_double_precision_cannot_hold(text):
    with pytest.raises(argparse.ArgumentTypeError):
        number(text)


def test_counts_and_workers_have_one_range():
    assert count(2, 5)("5") == 5
    for text in ("1", "6", "2.5", "x"):
        with pytest.raises(argparse.ArgumentTypeError):
            count(2, 5)(text)
    with pytest.raises(argparse.ArgumentTypeError, match="from 1 to"):
        workers("0")


@pytest.mark.parametrize("command", ["stability-map", "sweep"])
def test_map_and_sweep_refuse_the_same_workers(command, capsys):
    """One type for --workers in every command (issue: the map took 0 and -3, the sweep refused them)."""
    for value in ("0", "-3"):
        assert main([command, "--case", "1", "--workers", value]) == 2
        assert "argument --workers: must be from 1 to 1024 processes" in capsys.readouterr().err


def test_named_values_refuses_a_name_given_twice_and_malformed_entries():
    assert named_values(["v=80", "M=1000"], "--set") == {"v": "80", "M": "1000"}
    with pytest.raises(ParameterError, match="v is given twice"):
        named_values(["v=80", "v=90"], "--set")
    for text in ("v", "=80", "v=", " = "):
        with pytest.raises(ParameterError, match="expected NAME=VALUE"):
            named_values([text], "--set")


def test_value_range_needs_two_ordered_numbers():
    assert value_range("v", "0:400") == (0.0, 400.0)
    for spec in ("400:0", "1:1", "0:nan", "0:1e400", "0", "0:1:2"):
        with pytest.raises(ParameterError, match="--range v="):
            value_range("v", spec)


def test_duration_text():
    assert [duration(s) for s in (45, 720, 3.6e4, 3e5)] == ["45 s", "12 min", "10.0 h", "3.47 days"]


@pytest.mark.parametrize(("per_column", "expected"), [(2.0, 100.0), (6.0, 300.0), (80.0, 4000.0)])
def test_a_grid_job_says_its_size_and_needs_yes_beyond_an_hour(capsys, monkeypatch, per_column, expected):
    """The estimate is the timed column times the columns per worker: 100 columns of 2 s on 2 workers is
    100 s (quiet), of 6 s 300 s (said on stderr), of 80 s 4000 s (refused without --yes)."""
    import moving_bogie.cli.job_size as job_size

    ticks = [0.0, per_column] * 2  # two estimates, each timing one column
    monkeypatch.setattr(job_size.time, "perf_counter", lambda: ticks.pop(0))
    args = ("stability map", (100, 100), 2, lambda: None)
    if expected > ASK:
        with pytest.raises(ParameterError, match=r"100 x 100 = 10000 cells.*pass --yes") as info:
            estimate_grid(*args, yes=False, shorter="lower --n")
        assert info.value.parameter == "--yes"
    assert estimate_grid(*args, yes=True, shorter="lower --n") == pytest.approx(expected)
    assert ("about" in capsys.readouterr().err) == (expected > SAY)


def test_a_sweep_is_bounded_before_its_store_is_made():
    check_points(10_000_000)
    with pytest.raises(ParameterError, match="more than a sweep holds"):
        check_points(10_000_001)
