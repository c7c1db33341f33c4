"""Command line: the installed console script run in a subprocess (``--version``, ``--help``), and in-process
checks of the commands through :func:`moving_bogie.cli.main`."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from moving_bogie.cli import SUBCOMMAND_MODULES, build_parser, main
from moving_bogie.output import atomic_write

SCRIPT = Path(sys.executable).with_name("moving-bogie")

CASE7 = {
    "eta_f": "0.05",
    "eta_M": "30",
    "d": "2",
    "cf1": "1.7",
    "cf2": "0.01",
    "kappa_v": "0.2",
    "eta_v": "0.05",
    "alpha": "0.4",
}


def run(*args: str, cwd: Path | None = None) -> subprocess.CompletedProcess[str]:
    if not SCRIPT.exists():
        pytest.fail(f"console script {SCRIPT} is not installed: run pip install -e '.[dev]'")
    return subprocess.run([str(SCRIPT), *args], capture_output=True, text=True, timeout=60, cwd=cwd)


def test_params_case_7_json_equals_table1_row_7(capsys):
    assert main(["params", "--case", "7", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert {key: data["dimensionless"][key] for key in CASE7} == CASE7
    assert data["dimensionless"]["mu_v"] == "51" and data["dimensionless"]["beam"] == "eb"
    assert data["physical"] is None


def test_negative_mass_in_file_is_one_line_naming_M(tmp_path, capsys):
    path = tmp_path / "bad.toml"
    path.write_text(
        "[physical]\nEI = 6.4e6\nm = 60\nk_f = 5e7\nc_f = 0\nM = -1500\nM_b = 2500\nJ_b = 40\n"
        "k_v = 8e6\nc_v = 0\nd = 1.7\nv = 300\nP = 1e5\n"
    )
    assert main(["params", "--file", str(path)]) != 0
    result = capsys.readouterr()
    assert result.out == ""
    lines = result.err.strip().splitlines()
    assert len(lines) == 1, result.err
    assert lines[0].startswith("moving-bogie: error: ") and " M must be" in lines[0]
    assert "Traceback" not in result.err


def test_physical_file_prints_physical_parameters_and_scales(tmp_path, capsys):
    path = tmp_path / "phys.toml"
    path.write_text(
        "[physical]\nEI = 6.4e6\nm = 60\nk_f = 5e7\nc_f = 0\nM = 1500\nM_b = 2500\nJ_b = 40\n"
        "k_v = 8e6\nc_v = 0\nd = 1.7\nv = 300\nP = 1e5\n"
    )
    assert main(["params", "--file", str(path)]) == 0
    table = capsys.readouterr().out
    assert "Physical parameters" in table and "Scales" in table
    assert main(["params", "--file", str(path), "--alpha", "0.5", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["dimensionless"]["alpha"] == "0.5"
    assert data["physical"]["M"] == "1500" and data["physical"]["v"] != "300"
    # Reference: Eqs. (15)-(17) of the paper evaluated here from the file's SI values (EI, m, k_f, P, M, d)
    EI, m, k_f, P = 6.4e6, 60.0, 5e7, 1e5
    chi = (k_f / (4 * EI)) ** 0.25
    v_ref = (4 * k_f * EI / m**2) ** 0.25
    scales = data["scales"]
    assert scales["chi"] == pytest.approx(chi, rel=1e-12)
    assert scales["v_ref"] == pytest.approx(v_ref, rel=1e-12)
    assert scales["w_st"] == pytest.approx(P * chi / (2 * k_f), rel=1e-12)
    assert scales["t_scale"] == pytest.approx((m / k_f) ** 0.5, rel=1e-12)  # tau = sqrt(k_f/m) t
    assert scales["load"] == P / 2  # the unit of force: a wheel's static load is 2, Eq. (16)
    assert float(data["physical"]["v"]) == pytest.approx(0.5 * v_ref, rel=1e-12)  # alpha = v / v_ref
    assert float(data["dimensionless"]["eta_M"]) == pytest.approx(1500 * chi / m, rel=1e-12)
    assert float(data["dimensionless"]["d"]) == pytest.approx(1.7 * chi, rel=1e-12)


def test_version_and_help():
    version = run("--version")
    assert version.returncode == 0 and version.stdout.startswith("moving-bogie ")
    top = run("--help")
    assert top.returncode == 0 and "params" in top.stdout


def test_every_subcommand_has_help(capsys):
    parser = build_parser()
    commands = parser._subparsers._group_actions[0].choices  # noqa: SLF001
    assert len(commands) >= len(SUBCOMMAND_MODULES)
    for name in commands:
        with pytest.raises(SystemExit) as info:
            main([name, "--help"])
        assert info.value.code == 0
        out = capsys.readouterr().out
        assert f"usage: moving-bogie {name}" in out and len(out) > 200


@pytest.mark.parametrize(
    ("argv", "fragment"),
    [
        (["params"], "no parameters given"),
        (["params", "--case", "99"], "valid cases of Table 1"),
        (
            ["params", "--case", "7", "--file", str(Path(__file__).parents[1] / "examples/car.toml")],
            "either --case or --file",
        ),
        (["params", "--eta-f", "0.1"], "missing parameter 'alpha' (velocity ratio v/v_ref): give --alpha"),
        (["params", "--case", "1", "--vehicle", "car"], "case 1 of Table 1 does not set it; give --L-c"),
        (["params", "--case", "7", "--eta-M", "-3"], "eta_M must be a positive finite number (got -3)"),
        (["params", "--case", "7", "--S", "100"], "S is not a parameter of the model eb/one-layer/bogie"),
        (["params", "--file", "does-not-exist.toml"], "--file: does-not-exist.toml: no such file"),
    ],
)
def test_errors_are_one_line_and_exit_2(capsys, argv, fragment):
    assert main(argv) == 2
    captured = capsys.readouterr()
    assert captured.out == ""
    assert captured.err.count("\n") == 1 and captured.err.startswith("moving-bogie: error: ")
    assert fragment in captured.err


def test_overrides_without_base(capsys):
    argv = [
        "params",
        "--json",
        "--eta-f",
        "0.05",
        "--eta-M",
        "30",
        "--d",
        "2",
        "--cf1",
        "1.7",
        "--cf2",
        "0.01",
    ]
    assert main([*argv, "--kappa-v", "0.2", "--eta-v", "0.05", "--alpha", "0.4"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert {key: data["dimensionless"][key] for key in CASE7} == CASE7


def test_case_override_and_timoshenko(capsys):
    assert main(["params", "--case", "12", "--beam", "tr", "--S", "100", "--r", "0.03", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)["dimensionless"]
    assert (d["beam"], d["S"], d["r"], d["alpha"]) == ("tr", "100", "0.03", "0.85")


def test_table_output_is_aligned(capsys):
    assert main(["params", "--case", "1"]) == 0
    table, speed = capsys.readouterr().out.rstrip().split("\n\n")  # the table, then the speed regime
    assert speed.startswith("speed: subcritical")
    title, *rows = table.splitlines()
    # 3 model names, the 9 groups of the paper's model and the 2 coefficients of Eq. (63)
    assert title == "Dimensionless parameters of eb/one-layer/bogie" and len(rows) == 14
    value_columns = {len(row) - len(row[2:].split(" ", 1)[1].lstrip()) for row in rows}
    assert len(value_columns) == 1


def test_bad_number_is_a_usage_error(capsys):
    assert main(["params", "--case", "7", "--alpha", "fast"]) == 2
    err = capsys.readouterr().err.splitlines()
    # One line naming the option, one hint; no argparse usage block.
    assert len(err) == 2 and "argument --alpha: not a number: 'fast'" in err[0]
    assert err[1] == "see: moving-bogie params --help"


def test_atomic_write_replaces_whole_file(tmp_path):
    target = tmp_path / "out" / "result.csv"
    atomic_write(target, "a,b\n1,2\n")
    assert target.read_text() == "a,b\n1,2\n"
    atomic_write(target, b"new")
    assert target.read_bytes() == b"new"
    assert [p.name for p in target.parent.iterdir()] == ["result.csv"]  # no temporary file left


def test_atomic_write_leaves_old_file_when_writing_fails(tmp_path, monkeypatch):
    target = tmp_path / "result.txt"
    target.write_text("old")

    def broken_replace(src, dst):
        raise OSError(28, "No space left on device", str(dst))

    monkeypatch.setattr("moving_bogie.output.os.replace", broken_replace)
    with pytest.raises(OSError):
        atomic_write(target, "new")
    assert target.read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["result.txt"]


def test_models_lists_beams_tracks_and_vehicles_and_a_name_gives_its_parameters(capsys):
    """The listing is the catalogue's beams x tracks x vehicles in a few lines (each model one of each), then
    the sleeper tracks; ``models NAME`` gives one model's details, for a sleeper track too."""
    from moving_bogie.generated import sleepers
    from moving_bogie.model.catalogue import default_catalogue

    models = default_catalogue().models()
    assert main(["models"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert len(lines) <= 10, lines
    # one catalogue: the rails on discrete supports (docs/sleepers.md) are tracks like the others
    rows: dict[str, list[str]] = {}
    for line in lines:  # a long row continues on more deeply indented lines
        if line[:2] == "  " and line[2] != " ":
            key, text = line.split(None, 1)
            rows[key] = []
        elif line[:2] == "  ":
            text = line.strip()
        else:
            continue
        rows[key] += [x for x in text.strip().rstrip(",").split(", ")]
    listed = {f"{b}/{t}/{v}" for b in rows["beams"] for t in rows["tracks"] for v in rows["vehicles"]}
    assert listed == {model.name for model in models} and len(listed) == len(models)
    assert f"{len(models)} models" in lines[0] and "every beam on every track under every vehicle" in lines[0]
    assert set(sleepers.TRACKS) <= set(rows["tracks"])
    assert main(["models", "tr/sleepers-two-layer"]) == 0
    assert "k_pad" in capsys.readouterr().out
    assert main(["models", "eb/sleepers/masses"]) == 0
    assert "--lam" in capsys.readouterr().out
    bogie = next(model for model in models if model.vehicle == "bogie")
    assert main(["models", bogie.name]) == 0
    out = capsys.readouterr().out
    assert all(spec.option in out for spec in bogie.specs.values())
    assert main(["models", bogie.name[:-1]]) == 2
    assert f"did you mean '{bogie.name}'?" in capsys.readouterr().err
