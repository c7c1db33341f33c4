"""The stability subcommands: JSON shapes, files written (figures read back by content), one-line errors."""

import json

import numpy as np
import pytest

import moving_bogie.cli.lines_cmd as lines_cmd
from moving_bogie.cli import main


@pytest.fixture
def saved_figures(monkeypatch):
    """The figures the line and map commands save, kept so that a test reads their data back."""
    figures = []
    original = lines_cmd.save_figure

    def keep(fig, path, *args, **kwargs):
        figures.append(fig)
        return original(fig, path, *args, **kwargs)

    monkeypatch.setattr(lines_cmd, "save_figure", keep)
    return figures


def _run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


@pytest.mark.slow
def test_instability_lines_json(capsys, tmp_path, saved_figures):
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
    assert code == 0 and (tmp_path / "lines.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    data = json.loads(out)
    # the figure by content: its lines are the branches of the JSON, point by point
    (fig,) = saved_figures
    drawn = [np.column_stack(ln.get_data()).astype(float) for ax in fig.axes for ln in ax.get_lines()]
    drawn = [d for d in drawn if len(d) > 1 and len(set(d[:, 0])) > 1]
    reported = [np.array([[pt["alpha"], pt["eta_M"]] for pt in b["points"]]) for b in data["branches"]]
    assert len(drawn) == len(reported)
    for d, r in zip(drawn, reported):
        np.testing.assert_allclose(d, r, rtol=1e-12)
    assert data["model"] == "masses" and data["branches"]
    assert data["eta_M_max"] == 200.0 and "theta_max" not in data  # named as the option --eta-M-max
    branch = data["branches"][0]
    assert branch["d"] == 1.5 and branch["unstable_side"] in ("above", "below", "mixed")
    assert set(branch["points"][0]) == {"alpha", "eta_M", "q", "unstable_above"}
    v = branch["verified"]  # induced_frequencies on both sides of the middle point
    assert v["count_above"] - v["count_below"] == (1 if branch["unstable_side"] == "above" else -1)


def test_stability_map_writes_npz_and_plot(capsys, tmp_path, saved_figures):
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
    assert (tmp_path / "m.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    # the figure by content: the unstable cells are coloured by their growth rate -degree (the margin of an
    # unstable cell is its degree, min Im q), the other cells are blank in that mesh
    from matplotlib.collections import QuadMesh

    (fig,) = saved_figures
    (ax,) = [ax for ax in fig.axes if ax.get_xlabel() == r"$\alpha$"]  # not the colour bars
    meshes = [c for c in ax.collections if isinstance(c, QuadMesh) and c.colorbar is not None]
    (mesh,) = [c for c in meshes if "growth" in c.colorbar.ax.get_ylabel()]
    degree = arrays["degree"]
    unstable = (degree < 0) & ~arrays["uncertain"]
    assert unstable.any() and not unstable.all()  # both kinds of cell on the map
    shown = np.ma.getdata(mesh.get_array()).reshape(degree.shape)
    blank = np.ma.getmaskarray(mesh.get_array()).reshape(degree.shape) | np.isnan(shown)
    np.testing.assert_array_equal(blank, ~unstable)
    np.testing.assert_allclose(shown[unstable], -degree[unstable], rtol=1e-12)


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
