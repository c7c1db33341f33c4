"""Critical velocity of a constant force: Eqs. (65)-(66) against the minimum phase speed of free waves."""

import json

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


def test_cli_json(capsys):
    from moving_bogie.cli import main

    assert main(["critical-velocity", "--beam", "tr", "--S", "10", "--r", "0.09", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
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


def _two_layer_phase_speeds(p, eta_N, mu_2, kappa_2):
    """Reference phase speeds omega_j(p) / p of the free waves of a compressed rail on two layers, ascending
    in j, shape (len(p), 2): the undamped equations (L1) of docs/layered_tracks.md with the axial force of
    Eq. (A1), in their groups (rail row divided by k_1, x by chi, t by sqrt(m / k_1)), as the generalised
    eigenproblem K(p) v = omega^2 M v with
    K = [[p^4/4 - eta_N p^2 + 1, -1], [-1, 1 + kappa_2]] and M = diag(1, mu_2). Written from the equations,
    not from the generated kernels."""
    import numpy as np

    K = np.zeros((len(p), 2, 2))
    K[:, 0, 0] = p**4 / 4 - eta_N * p**2 + 1
    K[:, 0, 1] = K[:, 1, 0] = -1 / np.sqrt(mu_2)  # M^(-1/2) K M^(-1/2): symmetric, same eigenvalues
    K[:, 1, 1] = (1 + kappa_2) / mu_2
    return np.sqrt(np.linalg.eigvalsh(K)) / p[:, None]


def test_the_critical_velocity_is_the_slowest_minimum_not_the_first_in_p():
    """A compressed rail (eta_N = 0.8) on pads over a heavy layer (mu_2 = 100): the phase speed of each of
    the two branches has a local minimum, and the slower one lies at the larger wavenumber (branch 1, alpha
    0.128 at p 1.472; branch 2, alpha 0.462 at p 1.434). alpha_cr is the smallest local minimum in alpha:
    ordering the minima by p would report branch 2's. Reference: a dense scan of the phase speeds of the
    model's equations over 0 < p <= 20 (:func:`_two_layer_phase_speeds`)."""
    import numpy as np

    groups = {"eta_N": 0.8, "mu_2": 100.0, "kappa_2": 5.0}
    ps = np.linspace(1e-4, 20.0, 200_000)
    speeds = _two_layer_phase_speeds(ps, **groups)
    reference = []  # (alpha, p, branch) of every local minimum on the scan
    for j in range(speeds.shape[1]):
        c = speeds[:, j]
        for k in np.flatnonzero((c[1:-1] < c[:-2]) & (c[1:-1] < c[2:])) + 1:
            reference.append((float(c[k]), float(ps[k]), j + 1))
    assert len(reference) == 2
    slowest = min(reference)
    assert slowest[1] > min(p for _, p, _ in reference)  # the set tells the two orders apart

    res = critical_velocity(get_model(beam="eb_axial", track="two-layer"), groups=groups)
    assert float(res.alpha_cr) == pytest.approx(slowest[0], rel=1e-8)
    assert float(res.p_cr) == pytest.approx(slowest[1], abs=2e-4)
    assert res.branch == slowest[2]
    found = [(float(m.alpha), float(m.p), m.branch) for m in res.minima]  # ascending in alpha
    assert [b for _, _, b in found] == [b for _, _, b in sorted(reference)]
    for (a, p, _), (a_ref, p_ref, _) in zip(found, sorted(reference)):
        assert a == pytest.approx(a_ref, rel=1e-8) and p == pytest.approx(p_ref, abs=2e-4)
