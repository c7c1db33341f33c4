"""Critical velocity of a constant force: Eqs. (65)-(66) against the minimum phase speed of free waves."""

import json
import subprocess
import sys

import mpmath
import pytest

from moving_bogie.model.catalogue import get_model
from moving_bogie.paper.critical_velocity_formulas import formula_tr, paper_formula
from moving_bogie.stability.velocity.critical_velocity import critical_velocity, phase_speed


@pytest.mark.parametrize("eta_s", ["0", "0.3", "2"])
def test_euler_bernoulli_equals_eq65(eta_s):
    """Eq. (65): alpha_cr = sqrt(1 + eta_s), found numerically from the dispersion minimum (p_cr = sqrt 2)."""
    res = critical_velocity(get_model(beam="eb"), eta_s=eta_s, formula=paper_formula)
    with mpmath.workdps(30):
        assert abs(res.alpha_cr - mpmath.sqrt(1 + mpmath.mpf(eta_s))) < mpmath.mpf(10) ** -25
        assert abs(res.p_cr - mpmath.sqrt(2)) < mpmath.mpf(10) ** -25
    assert res.agrees and res.digits >= 25


@pytest.mark.parametrize(
    ("S", "r", "value"), [("100", "0.03", "0.997855232629651"), ("10", "0.09", "0.979847522056015")]
)
def test_timoshenko_rayleigh_equals_eq66(S, r, value):
    """Eq. (66) as printed is right; Section 3.6 quotes 0.993 and 0.980: the first is an erratum (0.998)."""
    res = critical_velocity(get_model(beam="tr"), S=S, r=r, formula=paper_formula)
    assert res.agrees
    assert mpmath.nstr(res.alpha_cr, 15) == value
    with mpmath.workdps(30):
        assert abs(formula_tr(S, r) - res.alpha_cr) < mpmath.mpf(10) ** -25


def test_phase_speed_minimum_brackets_the_critical_velocity():
    import numpy as np

    ps = np.linspace(0.5, 3, 501)
    c = phase_speed(get_model(beam="tr"), ps, S=10.0, r=0.09)
    assert float(c.min()) == pytest.approx(0.97984752205601499, abs=1e-5)  # grid minimum
    assert np.all(c >= 0.979847522056015 - 1e-12)


def test_cli_json():
    out = subprocess.run(
        [
            sys.executable,
            "-m",
            "moving_bogie",
            "critical-velocity",
            "--beam",
            "tr",
            "--S",
            "10",
            "--r",
            "0.09",
            "--json",
        ],
        capture_output=True,
        text=True,
        check=True,
    )
    data = json.loads(out.stdout)
    assert data["alpha_cr"].startswith("0.979847522056") and data["alpha_cr_formula"].startswith(
        "0.979847522056"
    )
    assert data["method"]


def test_a_track_unstable_at_rest_is_one_clear_error(capsys):
    """A compressed rail on a soft three-layer track: the lowest branch's phase speed falls to 0 (the rail
    buckles: its N(p, 0; alpha = 0) has a real root p, seen on the grid), so there is no critical velocity to
    polish. The command says so in one line and exits 2 (no traceback)."""
    import numpy as np

    from moving_bogie.cli import main

    groups = {"eta_s": 0.1, "mu_2": 2.2, "kappa_2": 0.15, "mu_3": 3.9, "kappa_3": 0.56, "eta_N": 0.68}
    model = get_model(beam="eb_axial", track="three-layer")
    speeds = phase_speed(model, np.linspace(0.3, 0.5, 201), **groups)
    assert float(np.nanmin(speeds)) < 1e-6  # the grid itself sees the phase speed reach 0 (lowest branch)
    options = [f"--{name.replace('_', '-')}={value}" for name, value in groups.items()]
    code = main(["critical-velocity", "--beam", "eb_axial", "--track", "three-layer", *options])
    err = capsys.readouterr().err
    assert code == 2 and "Traceback" not in err
    assert len(err.strip().splitlines()) == 1 and "unstable at rest" in err
