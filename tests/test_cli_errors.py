"""Errors before work: output options checked before computing, one-line usage errors, JSON errors."""

import json
import os
import subprocess
import sys
import time
from pathlib import Path

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


# -- errors before work: each one exit 2, one line naming the option, nothing created ------------------
EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def _bad_toml(path: Path, old: str, new: str) -> Path:
    """The example file of Case 7 with one key or value misspelt, written to ``path``."""
    text = (EXAMPLES / "dimensionless_eb.toml").read_text()
    assert old in text
    path.write_text(text.replace(old, new, 1))
    return path


ERRORS_BEFORE_WORK = [
    # (argv, option named, a word the message must hold)
    (["timeseries", "--case", "1", "--tmax", "10", "--plot", "{tmp}/out.xyz"], "--plot", "'.xyz'"),
    (["timeseries", "--case", "1", "--tmax", "10", "--plot", "{tmp}/out"], "--plot", "suffix"),
    (["timeseries", "--case", "1", "--tmax", "10", "--plot-long", "{tmp}/no/x.png"], "--plot-long", "exist"),
    (["shape", "--case", "1", "--tau", "5", "--plot", "{tmp}/no/dir/x.png"], "--plot", "does not exist"),
    (["validate", "--case", "7", "--plot", "{tmp}/v.jpgg"], "--plot", "did you mean 'jpg'"),
    (["stability-map", "--case", "1", "--plot", "{tmp}/out.xyz"], "--plot", "'.xyz'"),
    (["stability-map", "--case", "1", "--npz", "{tmp}/map.np"], "--npz", "did you mean 'npz'"),
    (["stability-map", "--case", "1", "--out", "{tmp}/no/s.zarr"], "--out", "does not exist"),
    (["instability-lines", "--case", "1", "--plot", "{tmp}/no/x.png"], "--plot", "does not exist"),
    (["frequency-lines", "--case", "1", "--plot", "{tmp}/x.xyz"], "--plot", "'.xyz'"),
    (["compare-tracks", "--track", "two-layer", "--plot", "{tmp}/x.xyz"], "--plot", "'.xyz'"),
    (["stability-figure", "3", "--plot", "{tmp}/no/x.png"], "--plot", "does not exist"),
    (["sweep", "--case", "1", "--vary", "alpha=0.3:1:3", "--out", "{tmp}/no/s.zarr"], "--out", "exist"),
    (
        ["sweep-plot", "{tmp}/s.zarr", "--x", "alpha", "--y", "eta_M", "--out", "{tmp}/x.png"],
        "S.zarr",
        "store",
    ),
    (["reproduce", "--out", "{tmp}/no/figures"], "--out", "does not exist"),
    (["frequencies", "--file", "{tmp}/nosuch.toml"], "--file", "no such file"),
    (["critical-velocity", "--file", "{tmp}/nosuch.toml"], "--file", "no such file"),
    (["instability-lines", "--file", "{tmp}/nosuch.toml"], "--file", "no such file"),
    (["frequencies", "--file", "{alpah}"], "--file", "did you mean 'alpha'"),
    (["frequencies", "--file", "{bogy}"], "--file", "did you mean 'bogie'"),
    (["frequencies", "--case", "1", "--vehicle", "bogy"], "--vehicle", "did you mean 'bogie'"),
    (["frequencies", "--case", "1", "--beam", "ebb"], "--beam", "did you mean 'eb'"),
    (["stability-map", "--track", "two-layr"], "--track", "did you mean 'two-layer'"),
    (["frequencies", "--case", "14"], "case", "valid cases of Table 1: 1, 2"),
    (["params", "--case", "1", "--alpah", "0.3"], "--alpah", "did you mean '--alpha'"),
]


@pytest.mark.parametrize(("argv", "option", "word"), ERRORS_BEFORE_WORK)
def test_errors_before_work_name_the_option_and_create_nothing(capsys, tmp_path, argv, option, word):
    files = {
        "alpah": _bad_toml(tmp_path / "alpah.toml", "alpha =", "alpah ="),
        "bogy": _bad_toml(tmp_path / "bogy.toml", '"bogie"', '"bogy"'),
    }
    before = sorted(tmp_path.rglob("*"))
    argv = [a.format(tmp=tmp_path, **files) for a in argv]
    assert main(argv) == 2
    out = capsys.readouterr()
    lines = out.err.splitlines()
    assert out.out == "" and "Traceback" not in out.err
    assert lines[0].startswith("moving-bogie"), lines
    assert option in lines[0] and word in lines[0], lines[0]
    assert len(lines) == 1 or (len(lines) == 2 and lines[1].startswith("see: ")), lines  # a usage hint
    assert sorted(tmp_path.rglob("*")) == before  # no file, no folder


def test_the_figure_formats_are_those_matplotlib_writes():
    """The static list (checked without importing matplotlib) against matplotlib's own."""
    from matplotlib.figure import Figure

    from moving_bogie.cli.outputs import FIGURE_FORMATS

    assert sorted(FIGURE_FORMATS) == sorted(Figure().canvas.get_supported_filetypes())


def test_an_error_path_does_not_import_the_heavy_modules():
    """The error of a bad --plot comes before matplotlib, the kernels and the root finder are imported."""
    code = (
        "import sys\nfrom moving_bogie.cli import main\n"
        "code = main(['timeseries', '--case', '1', '--tmax', '10', '--plot', 'out.xyz'])\n"
        "heavy = [m for m in ('matplotlib', 'moving_bogie.roots.frequencies', 'moving_bogie.kernels.bound') "
        "if m in sys.modules]\n"
        "print(code, heavy)"
    )
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert run.stdout.strip() == "2 []", run.stdout + run.stderr


def test_a_close_name_is_suggested_and_a_far_one_lists_the_valid_names():
    from moving_bogie.errors import did_you_mean, suggestion

    assert did_you_mean("two-layr", ["one-layer", "two-layer", "three-layer"]) == "did you mean 'two-layer'?"
    assert did_you_mean("xyz", ["png", "pdf"]) == ""
    assert suggestion("zzz", ["beam", "track"]) == "expected one of beam, track"
