"""Every verdict says whether the speed is above the critical velocity of the track.

Reference: v_cr from the dispersion relation of the undamped beam on its foundation, written out here and
minimised with scipy: a free wave e^{i(k x - omega t)} on an Euler-Bernoulli beam on a Winkler foundation
with a Pasternak layer has omega^2 m = EI k^4 + k_s k^2 + k_f, so its phase speed is
c(k) = sqrt((EI k^4 + k_s k^2 + k_f) / m) / k and v_cr = min_k c(k) (in groups alpha_cr = sqrt(1 + eta_s)).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from moving_bogie.cli import main
from moving_bogie.model.cases import table1_case
from moving_bogie.model.files import load_params_file
from moving_bogie.roots.table2 import case_list
from moving_bogie.stability.velocity.supercritical import speed_regime
from moving_bogie.sweep import make_spec
from moving_bogie.sweep.speed import speed_arrays

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "physical_eb.toml"

# The text and --json runs of one file (and --set v=900 on the file of 300 m/s, the file with v = 900) search
# the same roots: once for the module. The tests check what the commands say of the speed and the verdict.
pytestmark = pytest.mark.usefixtures("same_search_once")


def _v_cr(EI, m, k_f, k_s=0.0) -> float:
    """min over k of the phase speed, on a log scale of k around the minimum's order."""
    k0 = (k_f / EI) ** 0.25
    res = minimize_scalar(
        lambda t: (
            np.sqrt((EI * (k0 * np.exp(t)) ** 4 + k_s * (k0 * np.exp(t)) ** 2 + k_f) / m) / (k0 * np.exp(t))
        ),
        bounds=(-3, 3),
        method="bounded",
        options={"xatol": 1e-10},
    )
    return float(res.fun)


def _with_speed(tmp_path, v: str) -> Path:
    text = "\n".join(
        f"v = {v}  # m/s" if line.startswith("v ") else line for line in EXAMPLE.read_text().splitlines()
    )
    path = tmp_path / f"v{v}.toml"
    path.write_text(text + "\n")
    return path


@pytest.mark.parametrize("v, expected", [("900", True), ("300", False)])
def test_frequencies_says_supercritical(v, expected, tmp_path, capsys):
    path = _with_speed(tmp_path, v)
    _, physical = load_params_file(path)
    v_cr = _v_cr(*(float(getattr(physical, k)) for k in ("EI", "m", "k_f")))
    assert 770 < v_cr < 775  # the numbers: v = 900 m/s above v_cr = 772 m/s
    main(["frequencies", "--file", str(path), "--json"])
    data = json.loads(capsys.readouterr().out)
    assert data["supercritical"] is expected and data["verdict"]["supercritical"] is expected
    assert data["v_cr"] == pytest.approx(v_cr, rel=1e-8)
    assert data["speed"]["v"] == pytest.approx(float(v), rel=1e-12)
    assert ("meaning" in data["speed"]) is expected
    main(["frequencies", "--file", str(path)])
    out = capsys.readouterr().out
    assert ("speed: SUPERCRITICAL" in out) is expected and ("speed: subcritical" in out) is not expected
    if expected:
        assert "radiates" in out and "subcritical" in out


def test_alpha_cr_with_a_shear_layer():
    params = table1_case(1).replace(eta_s="0.5", alpha="1.2")
    regime = speed_regime(params)
    # in groups: EI = 1/4, k_f = 1, m = 1 (v_ref = 1, chi = 1), k_s = 2 eta_s sqrt(EI k_f) = eta_s
    assert regime.alpha_cr == pytest.approx(_v_cr(0.25, 1.0, 1.0, 0.5), rel=1e-8)
    assert regime.alpha_cr == pytest.approx(np.sqrt(1.5), rel=1e-12)
    assert not regime.supercritical  # 1.2 < sqrt(1.5)
    assert speed_regime(params.replace(alpha="1.3")).supercritical


def test_sweep_flags_every_point_by_its_own_track():
    spec = make_spec(table1_case(1), {"alpha": "0.9,1.1,1.3", "eta_s": "0,0.5"})
    arrays = speed_arrays(spec)
    alpha_cr = np.array([_v_cr(0.25, 1.0, 1.0, eta_s) for eta_s in (0.0, 0.5)])
    np.testing.assert_allclose(arrays["alpha_cr"], np.broadcast_to(alpha_cr, (3, 2)), rtol=1e-8)
    expected = np.array([0.9, 1.1, 1.3])[:, None] > alpha_cr[None, :]
    np.testing.assert_array_equal(arrays["supercritical"], expected)
    assert expected.any() and not expected.all()


@pytest.mark.slow
def test_table2_says_every_case_is_subcritical(capsys, compute_once):
    # Both outputs (JSON, then text) of the command are judged on one computation of Table 2: the second
    # command is handed the same table (the speed regimes are computed by each command from it).
    from moving_bogie.roots import table2

    tables = compute_once(table2, "compute_table2")
    main(["table2", "--json"])
    data = json.loads(capsys.readouterr().out)
    for case in data["cases"]:
        alpha = float(case["params"]["alpha"])
        assert case["supercritical"] is False and alpha < case["alpha_cr"]
        if case["params"]["beam"] == "eb":  # Eq. (65) with the shear layer eta_s
            assert case["alpha_cr"] == pytest.approx(np.sqrt(1 + float(case["params"]["eta_s"])), rel=1e-12)
    main(["table2"])
    text = capsys.readouterr().out
    assert "speed: every case subcritical" in text
    # The summary names the unstable cases of the computed verdicts (Cases 1, 5, 12, 13 in the paper).
    unstable = [case["case"] for case in data["cases"] if case["verdict"]["state"] == "unstable"]
    assert unstable and f"verdicts: {len(unstable)} unstable ({case_list(unstable)}: " in text
    assert len(tables) == 1


def test_set_changes_an_si_parameter_of_the_file(capsys):
    """``--set v=900`` on the file of v = 300 m/s is the file with v = 900 (the test above writes it out)."""
    assert main(["frequencies", "--file", str(EXAMPLE), "--set", "v=900", "--json"]) in (0, 1)
    data = json.loads(capsys.readouterr().out)
    assert data["supercritical"] is True and data["speed"]["v"] == pytest.approx(900, rel=1e-12)
    _, physical = load_params_file(EXAMPLE)
    EI, m, k_f = (float(getattr(physical, k)) for k in ("EI", "m", "k_f"))
    assert float(data["params"]["alpha"]) == pytest.approx(900 / (4 * k_f * EI / m**2) ** 0.25, rel=1e-15)


@pytest.mark.parametrize(
    "args, message",
    [
        (["--case", "1", "--set", "v=900"], "--set needs a [physical] parameter file"),
        (["--file", str(EXAMPLE), "--set", "vv=900"], "unknown SI parameter 'vv'"),
        (["--file", str(EXAMPLE), "--set", "v=fast"], "expected NAME=NUMBER"),
        (["--file", str(EXAMPLE), "--set", "c_f=1e9"], "c_f = 1000000000 N s/m^2 gives eta_f"),
    ],
)
def test_set_refuses_bad_input(args, message, capsys):
    assert main(["frequencies", *args, "--json"]) == 2
    error = json.loads(capsys.readouterr().out)
    assert message in error["error"] and error["option"] == "--set"


def test_undetermined_critical_velocity_is_said_not_guessed(monkeypatch):
    from moving_bogie.errors import MovingBogieError
    from moving_bogie.stability.velocity import critical_velocity as module

    def fails(*args, **kwargs):
        raise MovingBogieError("no branch has a local minimum of its phase speed")

    monkeypatch.setattr(module, "critical_velocity", fails)
    regime = speed_regime(table1_case(1).replace(eta_s="0.123"))  # a track not seen before in this process
    assert regime.alpha_cr is None and regime.supercritical is None
    assert regime.line().startswith("speed: UNDETERMINED") and "no branch" in regime.line()
    assert regime.to_dict()["supercritical"] is None


def test_params_says_the_speed_regime(capsys):
    assert main(["params", "--file", str(EXAMPLE), "--set", "v=900", "--json"]) == 0
    speed = json.loads(capsys.readouterr().out)["speed"]
    assert speed["supercritical"] is True and speed["v"] == pytest.approx(900, rel=1e-12)
    assert main(["params", "--case", "1"]) == 0
    assert (
        capsys.readouterr().out.rstrip().splitlines()[-1] == "speed: subcritical, alpha = 0.8, alpha_cr = 1"
    )
