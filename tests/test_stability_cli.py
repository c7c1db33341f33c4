"""The stability subcommands: JSON shapes, files written, one-line errors."""

import json

import numpy as np

from moving_bogie.cli import main


def _run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_instability_lines_json(capsys, tmp_path):
    code, out, _ = _run(
        capsys,
        "instability-lines",
        "--model",
        "masses",
        "--d",
        "1.5",
        "--eta-f",
        "0.1",
        "--alpha-min",
        "0.5",
        "--json",
        "--verify",
        "--plot",
        str(tmp_path / "lines.png"),
    )
    assert code == 0 and (tmp_path / "lines.png").stat().st_size > 0
    data = json.loads(out)
    assert data["model"] == "masses" and data["branches"]
    assert data["eta_M_max"] == 200.0 and "theta_max" not in data  # named as the option --eta-M-max
    branch = data["branches"][0]
    assert branch["d"] == 1.5 and branch["unstable_side"] in ("above", "below", "mixed")
    assert set(branch["points"][0]) == {"alpha", "eta_M", "q", "unstable_above"}
    v = branch["verified"]  # induced_frequencies on both sides of the middle point
    assert v["count_above"] - v["count_below"] == (1 if branch["unstable_side"] == "above" else -1)


def test_stability_map_writes_npz_and_plot(capsys, tmp_path):
    code, out, _ = _run(
        capsys,
        "stability-map",
        "--case",
        "1",
        "--n",
        "8",
        "--workers",
        "1",
        "--alpha-min",
        "0.7",
        "--json",
        "--npz",
        str(tmp_path / "m.npz"),
        "--plot",
        str(tmp_path / "m.png"),
    )
    assert code == 0
    summary = json.loads(out)
    assert summary["alpha_range"][2] == 8
    assert summary["eta_M_range"][2] == 8 and "theta_range" not in summary  # named as the option --eta-M-max
    arrays = np.load(tmp_path / "m.npz")
    assert arrays["degree"].shape == (8, 8) and np.all(arrays["degree"] <= 0)
    assert (tmp_path / "m.png").stat().st_size > 0


def test_critical_stiffness_json(capsys):
    code, out, _ = _run(
        capsys,
        "critical-stiffness",
        "--case",
        "5",
        "--alpha-min",
        "0.7",
        "--alpha-max",
        "0.7",
        "--alphas",
        "1",
        "--kappa-max",
        "0.6",
        "--json",
    )
    assert code == 0
    data = json.loads(out)
    assert data["mismatches"] == 0 and data["alphas"][0]["critical_kappa_v"]


def test_negative_foundation_damping_is_a_one_line_error(capsys):
    code, _, err = _run(capsys, "instability-lines", "--eta-f", "-0.1")
    assert code == 2 and err.count("\n") == 1 and "eta" in err


def test_figure_subcommand_lists_the_figures(capsys):
    import pytest

    with pytest.raises(SystemExit):
        main(["stability-figure", "--help"])
    out = capsys.readouterr().out
    assert "{2,3,4,7,8,16}" in out
