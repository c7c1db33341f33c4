"""Layered tracks (docs/layered_tracks.md): the generated two- and three-layer models, their scaling, their
one-layer limit and their critical velocity, each against an independent reference.

References:
* K(xi, q): QUADPACK quadrature of Eq. (29) over real p (``test_track_kernel.quadrature_module_K``);
* one-layer limit: the paper's track with k_f = k_1, c_f = c_1 (Table 2 Case 7 computed with the one-layer
  quartic kernel), approached as m_2 -> 0 and k_2 -> infinity at the rate the model predicts;
* critical velocity: a direct scan, independent of the dispersion branches, of the real p-roots of
  N(p, 0; alpha) (numpy roots of the generated polynomial in p) across each reported minimum;
* scaling: the SI -> dimensionless -> SI round trip with the track's own SI names.
"""

from __future__ import annotations

import json
from fractions import Fraction
from pathlib import Path

import mpmath
import numpy as np
import pytest
from test_track_kernel import quadrature_module_K

from moving_bogie.errors import ParameterError
from moving_bogie.kernels.bound import bind
from moving_bogie.kernels.characteristic import Characteristic
from moving_bogie.kernels.track import TrackKernel
from moving_bogie.model.cases import table1_case
from moving_bogie.model.catalogue import get_model
from moving_bogie.model.files import load_params_file
from moving_bogie.model.physical import PhysicalParams
from moving_bogie.paper.critical_velocity_formulas import paper_formula
from moving_bogie.roots.refine.polish import newton
from moving_bogie.stability.velocity.critical_velocity import critical_velocity, dispersion_branches

REPO = Path(__file__).resolve().parent.parent
EXAMPLES = ("two-layer", "three-layer")


def test_generated_layered_models_have_the_degrees_of_the_derivation():
    """Two layers: N of degree 6, Q of 2 in p (docs/layered_tracks.md); three layers: 8 and 4."""
    two, three = get_model("eb", "two-layer"), get_model("eb", "three-layer")
    assert (two.degrees["N_in_p"], two.degrees["Q_in_p"]) == (6, 2)
    assert (three.degrees["N_in_p"], three.degrees["Q_in_p"]) == (8, 4)
    assert set(two.parameters) - set(get_model("eb").parameters) == {"mu_2", "kappa_2", "eta_2"}
    assert two.scale_parameters.keys() == {"EI", "m", "k_1", "P"}
    assert two.specs["eta_f"].si == "c_1" and get_model("eb").specs["eta_f"].si == "c_f"
    assert two.damping == ("eta_f", "eta_v", "eta_2")


@pytest.mark.parametrize("track", EXAMPLES)
def test_example_files_scale_with_k1_and_round_trip(track):
    """chi = (k_1/(4 EI))^(1/4) (Eq. (15) with k_1 for k_f); SI -> groups -> SI gives the file back."""
    params, physical = load_params_file(REPO / "examples" / f"{track}.toml")
    assert params.track == track and physical.k_1 == 300_000_000
    chi = physical.scales().chi
    assert chi == pytest.approx((3.0e8 / (4 * 6.42e6)) ** 0.25, rel=1e-14)
    assert params.kappa_2 == physical.k_2 / physical.k_1  # exact: a ratio of the file's decimals
    back = PhysicalParams.from_dimensionless(
        params, EI=physical.EI, m=physical.m, k_1=physical.k_1, P=physical.P
    )
    for name, value in physical.values().items():
        assert float(getattr(back, name)) == pytest.approx(float(value), rel=1e-15, abs=1e-300), name
    with pytest.raises(ParameterError) as info:
        PhysicalParams(track=track, **{k: v for k, v in physical.values().items() if k != "k_1"}, k_f=3)
    assert info.value.parameter in ("k_f", "k_1")


@pytest.mark.parametrize("q", [0.3 + 0.02j, 0.9 - 0.3j, 0.05 + 1.5j])
def test_three_layer_K_against_quadrature(q):
    """K(xi, q) of the degree-8 three-layer track by residues, against quadrature of Eq. (29)."""
    params = table1_case(1).replace(
        track="three-layer", mu_2="0.8", kappa_2="1.5", eta_2="0.3", mu_3="2", kappa_3="0.7", eta_3="0.2"
    )
    module = params.model.foundation
    args = {name: float(getattr(params, name)) for name in module.ARGUMENTS[1:]}
    d = float(params.d)
    with mpmath.workdps(30):
        kv = TrackKernel(bind(params))(mpmath.mpc(q), [0, d, -d])
    assert len(kv.roots) == 8
    for k, xi in enumerate((0.0, d, -d)):
        ref = quadrature_module_K(module, args, q, xi)
        assert abs(complex(kv.K[k]) - ref) < 1e-9 * max(1, abs(ref)), (xi, kv.K[k], ref)


def test_one_layer_limit_is_table2_case7():
    """m_2 -> 0 and k_2 -> infinity (mu_2 = t, kappa_2 = 1/t) give the one-layer track with k_f = k_1.

    Each induced frequency of Case 7 (the one-layer model, quartic kernel) is followed by Newton on the
    two-layer characteristic function (degree-6 kernel) as t decreases; the distance falls like t (the
    first-order term of the layer's compliance), so halving t halves it, and the extrapolation
    2 q(t/2) - q(t) lands within O(t^2) of the one-layer root (Case 7's row of Table 2 is not in the
    packaged data; its one-layer roots are those `moving-bogie table2` prints).
    """
    from moving_bogie.api import induced_frequencies

    base = table1_case(7)
    ones = induced_frequencies(base, dps=20)
    assert ones.count_ok and ones.roots
    for root in ones.roots:
        q1 = mpmath.mpc(root.q)
        found = {}
        for t in ("1e-3", "5e-4"):
            params = base.replace(track="two-layer", mu_2=t, kappa_2=1 / Fraction(t), eta_2=0)
            with mpmath.workdps(25):
                found[t] = newton(Characteristic(bind(params)), q1)[0]
        d1, d2 = abs(found["1e-3"] - q1), abs(found["5e-4"] - q1)
        assert 1e-6 < d1 < 1e-1  # the layer is felt at first order ...
        assert d2 / d1 == pytest.approx(0.5, abs=0.05)  # ... and the distance is O(t)
        # the remainder is O(t^2): relative to the first-order distance d1 it is O(t), t = 1e-3
        assert abs(2 * found["5e-4"] - found["1e-3"] - q1) < 10 * 1e-3 * d1


def _real_p_roots(module, args, alpha, window):
    """Real roots of N(p, 0; alpha) in p inside window = (p_lo, p_hi): numpy roots of the polynomial."""
    coeffs = np.array([complex(c) for c in module.n_coeffs(0, alpha=alpha, **args)])
    roots = np.roots(np.trim_zeros(coeffs, "f"))
    scale = max(1.0, float(np.abs(roots).max()))
    real = roots[np.abs(roots.imag) < 1e-7 * scale].real
    return np.sort(real[(real > window[0]) & (real < window[1])])


@pytest.mark.slow
@pytest.mark.parametrize("track", EXAMPLES)
def test_critical_velocity_of_the_examples_against_a_direct_scan(track):
    """At each local minimum the load's line touches a branch: just below alpha the two real roots p near
    p_cr are absent, just above they are present (a direct scan of N(p, 0; alpha) in p)."""
    params, _ = load_params_file(REPO / "examples" / f"{track}.toml")
    res = critical_velocity(params)
    assert res.digits >= 28 and res.minima
    assert res.branch == res.branches  # the rail's branch on these tracks
    assert 1 in res.without_minimum and res.unattained is not None
    module = params.model.foundation
    args = {k: float(v) for k, v in res.groups.items()} | {name: 0.0 for name in module.DAMPING}
    for m in res.minima:
        a, p = float(m.alpha), float(m.p)
        window = (p - 0.3, p + 0.3)
        below = _real_p_roots(module, args, a * (1 - 1e-6), window)
        above = _real_p_roots(module, args, a * (1 + 1e-6), window)
        assert below.size + 2 == above.size, (below, above)
        assert np.all(np.abs(above - p) < 0.01)
        # and the scan of the branches' phase speed on a finer grid never goes below the minimum near p
        ps = np.linspace(p - 0.2, p + 0.2, 4001)
        c = dispersion_branches(params, ps)[:, m.branch - 1] / ps
        assert c.min() >= a * (1 - 1e-12) and c.min() <= a * (1 + 1e-6)


def test_lowest_branch_without_shear_is_bounded_and_gains_a_minimum_with_shear():
    """Without k_s the sleeper branch tends to sqrt((1 + kappa_2)/mu_2) (the layer on its springs): its
    phase speed falls to 0; a shear layer on the ballast gives it a tangency (docs/layered_tracks.md)."""
    params, _ = load_params_file(REPO / "examples" / "two-layer.toml")
    far = dispersion_branches(params, [1e3])[0, 0]
    assert far == pytest.approx(float(np.sqrt(float((1 + params.kappa_2) / params.mu_2))), rel=1e-3)
    sheared = critical_velocity(params.replace(eta_s=1))
    assert sheared.branch == 1 and sheared.alpha_cr < 1


def test_critical_velocity_keeps_eqs_65_66_on_the_one_layer_track():
    assert critical_velocity(get_model(beam="eb"), eta_s="0.3", formula=paper_formula).agrees
    tr = critical_velocity(get_model(beam="tr"), S="10", r="0.09", formula=paper_formula)
    assert tr.agrees and mpmath.nstr(tr.alpha_cr, 15) == "0.979847522056015"


def test_cli_critical_velocity_of_a_layered_file_in_si(monkeypatch, capsys):
    from moving_bogie.cli import main

    monkeypatch.chdir(REPO)
    assert main(["critical-velocity", "--file", "examples/two-layer.toml", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["model"] == "eb/two-layer" and data["branch"] == 2 and data["branches"] == 2
    assert data["branches_without_minimum"] == [1] and "note" in data
    assert float(data["v_cr"]) == pytest.approx(float(data["alpha_cr"]) * 1207.3821610999894, rel=1e-9)


def test_critical_velocity_tends_to_eq65_in_the_one_layer_limit():
    """mu_2 = t, kappa_2 = 1/t: alpha_cr -> 1 (Eq. (65) with eta_s = 0, k_f = k_1) at the rate O(t)."""
    gaps = []
    for t in ("1e-3", "5e-4"):
        model = get_model("eb", "two-layer")
        res = critical_velocity(model, groups={"mu_2": t, "kappa_2": 1 / Fraction(t)})
        gaps.append(abs(float(res.alpha_cr) - 1))
        assert res.branch == 1  # the rail: the stiff light layer's branch lies far above
    assert 0 < gaps[0] < 1e-2 and gaps[1] / gaps[0] == pytest.approx(0.5, abs=0.05)


@pytest.mark.parametrize("track", EXAMPLES)
def test_layered_K_at_alpha_zero_where_the_degree_of_N_drops(track):
    """At alpha = 0 the leading coefficient of N in p vanishes (one root at infinity): the vectorised
    kernel of the instability lines and maps must drop that root, not return nan or zero. Reference:
    quadrature of Eq. (29) at alpha = 0 (independent of the roots)."""
    from moving_bogie.kernels.sweep_characteristic import SweepCharacteristic

    groups = dict(mu_2="4", kappa_2="0.5", eta_2="0.2")
    if track == "three-layer":
        groups |= dict(mu_3="2", kappa_3="0.7", eta_3="0.2")
    params = table1_case(7).replace(track=track, alpha=0, **groups)
    module = params.model.foundation
    args = {name: float(getattr(params, name)) for name in module.ARGUMENTS[1:]}
    sweep = SweepCharacteristic(bind(params), "eta_M")
    qs = np.array([0.3 + 0.02j, 0.9 - 0.3j, 1.7 + 0.1j])
    with np.errstate(all="raise"):
        K, _, _ = sweep.kernel(qs, np.zeros(qs.size))
    d = float(params.d)
    for k, xi in enumerate((0.0, d, -d)):
        for j, q in enumerate(qs):
            ref = quadrature_module_K(module, args, q, xi)
            assert abs(K[k][j] - ref) < 1e-8 * max(1, abs(ref)), (xi, q, K[k][j], ref)
