"""Errors before work: output options checked before computing, one-line usage errors, JSON errors."""

import json
import os
import time

import pytest

from moving_bogie.cli import main


@pytest.fixture
def unwritable(tmp_path):
    """A folder nobody may write into (root ignores permissions: then /proc, where nobody creates files)."""
    folder = tmp_path / "locked"
    folder.mkdir()
    folder.chmod(0o500)
    yield folder if os.geteuid() != 0 else "/proc"
    folder.chmod(0o700)


@pytest.mark.parametrize(
    ("argv", "option"),
    [
        (["timeseries", "--case", "1", "--tmax", "10", "--csv", "{locked}/x.csv"], "--csv"),
        (["timeseries", "--case", "1", "--tmax", "10", "--plot", "{tmp}"], "--plot"),
        (["shape", "--case", "1", "--tau", "5", "--plot", "{file}/sub/x.png"], "--plot"),
        (["validate", "--case", "1", "--plot", "{locked}/x.png"], "--plot"),
        (["stability-map", "--case", "7", "--npz", "{tmp}"], "--npz"),
        (["stability-figure", "3", "--out", "{file}/x.png"], "--plot"),
        (["reproduce", "--out", "{file}"], "--out"),
    ],
)
def test_bad_output_path_fails_before_work_naming_the_option(capsys, tmp_path, unwritable, argv, option):
    a_file = tmp_path / "a-file"
    a_file.write_text("x")
    argv = [a.format(locked=unwritable, tmp=tmp_path, file=a_file) for a in argv]
    start = time.perf_counter()
    assert main(argv) == 2
    elapsed = time.perf_counter() - start
    err = capsys.readouterr().err
    assert err.startswith(f"moving-bogie: error: {option}: ") and err.count("\n") == 1, err
    assert ".tmp" not in err and "File exists" not in err
    assert elapsed < 5  # nothing was computed (the checks take milliseconds; generous for a loaded machine)


def test_json_errors_are_json(capsys, tmp_path):
    assert main(["frequencies", "--case", "1", "--alpha", "fast", "--json"]) == 2
    out = capsys.readouterr().out
    assert json.loads(out) == {"error": "argument --alpha: not a number: 'fast'", "option": "--alpha"}
    assert main(["frequencies", "--case", "1", "--eta-M", "-3", "--json"]) == 2
    data = json.loads(capsys.readouterr().out)
    assert data["option"] == "--eta-M" and "eta_M" in data["error"]
    argv = ["timeseries", "--case", "1", "--tmax", "5", "--csv", str(tmp_path), "--json"]
    assert main(argv) == 2
    assert json.loads(capsys.readouterr().out)["option"] == "--csv"


def test_unknown_option_is_one_line_plus_hint(capsys):
    assert main(["frequencies", "--case", "1", "--bogus"]) == 2
    out = capsys.readouterr()
    assert out.out == ""
    lines = out.err.splitlines()
    assert len(lines) == 2 and "--bogus" in lines[0] and lines[1].startswith("see: ")


def test_output_alias_and_preferred_spelling_agree():
    from moving_bogie.cli import build_parser

    parser = build_parser()
    a = parser.parse_args(["stability-figure", "3", "--out", "f.png"])
    b = parser.parse_args(["stability-figure", "3", "--plot", "f.png"])
    assert a.plot == b.plot


def test_every_output_option_of_every_command_is_checked():
    from moving_bogie.cli import build_parser
    from moving_bogie.cli.outputs import OutputPath

    parser = build_parser()
    commands = parser._subparsers._group_actions[0].choices  # noqa: SLF001
    outputs = {"--plot", "--plot-long", "--csv", "--npz", "--out", "--output"}
    found = 0
    for name, sub in commands.items():
        for action in sub._actions:  # noqa: SLF001
            if outputs & set(action.option_strings):
                assert isinstance(action, OutputPath), f"{name} {action.option_strings[0]} is not checked"
                found += 1
    assert found >= 10
