"""The finite rail on a layered track (docs/layered_tracks.md, "Layered finite rail") against references.

References:
* generated blocks: the SymPy blocks of derivations/modal.py, evaluated by SymPy;
* per-mode blocks: the one-layer formulas (Euler-Bernoulli and Timoshenko-Rayleigh, written by hand from
  Eqs. (1), (55)-(56) in ``one_layer_blocks``) for the generated blocks of the one-layer tracks;
* moving-load symbol: its closed form from the generated N(p, 0)/Q(p, 0) of the moving frame against the
  direct inverse of the fixed-frame block (two different generated expressions);
* block-diagonal Newmark solve: a dense numpy solve;
* time series: the Bromwich integral (``bromwich_line``), a numerical inverse Laplace transform that uses
  neither the finite rail nor the residues (the layered closed form is residues only until its branch-cut
  part lands);
* one-layer limit: the one-layer finite beam with k_f = k_1 (m_2 -> 0, k_2 -> infinity), whose departure is
  O(1/kappa_2 + mu_2) by the model (the layer's compliance 1/(1 + kappa_2) in series with the pads).
"""

from __future__ import annotations

import importlib
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from derivation_support import require_sympy
from test_finite_beam_tr import tr_symbol

from moving_bogie.kernels.bound import bind
from moving_bogie.model.cases import table1_case
from moving_bogie.model.files import load_params_file
from moving_bogie.response.bromwich import bromwich_line
from moving_bogie.validation.finite_beam import simulate_finite_beam
from moving_bogie.validation.modal import ModalBeam
from moving_bogie.validation.newmark import ModeBlocks, woodbury_solve
from moving_bogie.validation.track_modes import ModalTrack

REPO = Path(__file__).resolve().parent.parent
TWO_LAYER = REPO / "examples" / "two-layer.toml"


@pytest.fixture(scope="module")
def two_layer():
    return load_params_file(TWO_LAYER)[0]


@pytest.mark.parametrize(
    "name",
    [
        "eb",
        "tr",
        "eb_axial",
        "eb_two_layer",
        "tr_two_layer",
        "eb_axial_two_layer",
        "eb_three_layer",
        "tr_three_layer",
    ],
)
def test_generated_modal_blocks_equal_the_derivation(name):
    """The generated ``modal_*`` functions against the SymPy blocks of derivations/modal.py (20 digits)."""
    sp = require_sympy()
    if str(REPO) not in sys.path:  # derivations/ is a top-level folder of the repository, not installed
        sys.path.insert(0, str(REPO))
    from derivations.foundations import MODELS
    from derivations.modal import lam, modal_blocks

    module = importlib.import_module(f"moving_bogie.generated.foundation_{name}")
    blocks = modal_blocks(MODELS[name]())
    rng = np.random.default_rng(11)
    values = {arg: float(rng.uniform(0.1, 2.0)) for arg in module.MODAL_ARGUMENTS}
    symbols = {x: values[str(x)] for b in blocks[:3] for e in b for x in e.free_symbols} | {
        lam: values["lam"]
    }
    args = {k: v for k, v in values.items() if k != "lam"}
    for function, block in zip((module.modal_mass, module.modal_damping, module.modal_stiffness), blocks[:3]):
        expected = [float(sp.N(e.subs(symbols), 20)) for e in block]
        np.testing.assert_allclose(
            np.array(function(values["lam"], **args), dtype=float), expected, rtol=1e-14
        )
    assert module.MODAL_PARITY == blocks[3]


def one_layer_blocks(lam, eta_f, eta_s, S=None, r=0.0):
    """Per-mode ``M, C, K`` of the one-layer track by hand (shape ``(len(lam), s, s)``).

    Euler-Bernoulli, Eq. (1) with the shear layer: ``1``, ``2 eta_f``, ``1 + eta_s lam^2 + lam^4/4``.
    Timoshenko-Rayleigh, Eqs. (55)-(56) made dimensionless as Eqs. (60)-(61) in the fixed frame
    (``w = sum q_k sin``, ``phi = sum b_k cos``): ``diag(1, r^2)``, ``diag(2 eta_f, 0)`` and
    ``[[1 + (S + eta_s) lam^2, -S lam], [-S lam, S + lam^2/4]]``.
    """
    n = lam.size
    if S is None:
        return (
            np.ones((n, 1, 1)),
            np.full((n, 1, 1), 2.0 * eta_f),
            (1 + eta_s * lam**2 + lam**4 / 4)[:, None, None],
        )
    m, c, k = np.zeros((n, 2, 2)), np.zeros((n, 2, 2)), np.zeros((n, 2, 2))
    m[:, 0, 0], m[:, 1, 1], c[:, 0, 0] = 1.0, r * r, 2.0 * eta_f
    k[:, 0, 0], k[:, 1, 1] = 1.0 + (S + eta_s) * lam**2, S + 0.25 * lam**2
    k[:, 0, 1] = k[:, 1, 0] = -S * lam
    return m, c, k


@pytest.mark.parametrize("beam", ["eb", "tr"])
def test_generated_blocks_equal_the_one_layer_formulas(beam):
    params = table1_case(7).replace(eta_s="0.3")
    if beam == "tr":
        params = params.replace(beam="tr", S=10, r="0.09")
    f = params.as_float()
    shear, radius = (f.S, f.r) if beam == "tr" else (None, 0.0)
    track = ModalTrack.of(params)
    lam = np.arange(1, 41) * np.pi / 120.0
    for got, by_hand in zip(track.blocks(lam), one_layer_blocks(lam, f.eta_f, f.eta_s, shear, radius)):
        np.testing.assert_allclose(got, by_hand, rtol=1e-14, atol=1e-12)
    assert ModalBeam(120.0, 40, track).n_dof == 40 * (2 if beam == "tr" else 1)
    lam = np.linspace(0.05, 6.0, 17)
    np.testing.assert_allclose(
        track.symbol(lam), tr_symbol(lam, f.alpha, f.eta_f, f.eta_s, shear, radius), rtol=1e-12
    )


@pytest.mark.parametrize("track", ["two-layer", "three-layer"])
def test_moving_load_symbol_closed_form_equals_the_block_inverse(track):
    extra = {"mu_2": "0.8", "kappa_2": "1.5", "eta_2": "0.3"}
    if track == "three-layer":
        extra |= {"mu_3": "2", "kappa_3": "0.7", "eta_3": "0.2"}
    params = table1_case(7).replace(track=track, eta_s="0.2", **extra)
    modal = ModalTrack.of(params)
    assert modal.size == (2 if track == "two-layer" else 3)
    p = np.linspace(0.01, 8.0, 41)
    np.testing.assert_allclose(modal.symbol(p), modal.block_symbol(p), rtol=1e-11)


def test_block_diagonal_woodbury_solve_equals_dense():
    rng = np.random.default_rng(5)
    n_blocks, s, r = 7, 3, 4
    n = n_blocks * s + 2
    index = np.arange(n_blocks)[:, None] + n_blocks * np.arange(s)[None, :]
    off = rng.standard_normal((n_blocks, s, s)) * 0.2
    off = off + np.swapaxes(off, 1, 2)
    off[:, np.arange(s), np.arange(s)] = 0.0
    blocks = ModeBlocks(index, off, off, off)
    diag = 2.0 + rng.random(n)
    ut, vt = rng.standard_normal((r, n)) * 0.3, rng.standard_normal((r, n)) * 0.3
    rhs = rng.standard_normal(n)
    x = woodbury_solve(diag, ut, vt, rhs, blocks, off)
    dense = np.diag(diag) + blocks.dense(off, n) + ut.T @ vt
    np.testing.assert_allclose(dense @ x, rhs, atol=1e-12)


def test_two_layer_finite_rail_agrees_with_the_bromwich_integral(two_layer):
    """Target of the one-layer validation: within 0.2 % of each quantity's largest value."""
    taus = np.array([5.0, 10.0, 15.0, 20.0, 30.0, 40.0])
    finite = simulate_finite_beam(two_layer, 40.0, n_modes=200, tau_out=taus)
    inside = taus <= finite.tau_valid  # before any reflection can reach the wheels
    assert inside.sum() >= 5
    taus = taus[inside]
    reference = bromwich_line(bind(two_layer), taus, a=0.05)
    for name in ("w_rear", "w_front", "u", "theta"):
        x, ref = getattr(finite, name)[inside], reference[name]
        assert np.max(np.abs(x - ref)) <= 2e-3 * np.max(np.abs(ref)), name


# slow: the fast subset checks the one-layer limit on the generated blocks
# (test_generated_blocks_equal_the_one_layer_formulas) and the two-layer rail against Bromwich
@pytest.mark.slow
def test_one_layer_limit_of_the_layered_finite_rail():
    """m_2 -> 0, k_2 -> infinity: the two-layer rail tends to the one-layer beam with k_f = k_1, c_f = c_1."""
    base = table1_case(7)
    one = simulate_finite_beam(base, 30.0, n_modes=120, tau_out=np.linspace(0.0, 30.0, 61))
    departures = []
    for kappa in (100, 1000):
        layered = base.replace(track="two-layer", mu_2=f"{1 / kappa}", kappa_2=kappa, eta_2=0)
        two = simulate_finite_beam(
            layered, 30.0, n_modes=120, length=one.length, entry=one.entry, dt=one.dt, tau_out=one.tau
        )
        departures.append(max(np.max(np.abs(two.w_rear - one.w_rear)), np.max(np.abs(two.u - one.u))))
    scale = np.max(np.abs(one.w_rear))
    # O(1/kappa_2 + mu_2): within a few times 2/kappa_2, and falling about tenfold with kappa_2
    assert departures[0] <= 5 * (2 / 100) * scale
    assert departures[1] <= 5 * (2 / 1000) * scale
    assert departures[1] < 0.2 * departures[0]


@pytest.mark.slow
def test_cli_validate_runs_on_a_layered_track():
    cmd = [sys.executable, "-m", "moving_bogie", "validate", "--file", str(TWO_LAYER), "--modes", "60"]
    cmd += ["--tmax", "10", "--no-estimate", "--json"]
    run = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    # the closed form includes the layered branch-cut part (response/cut_pieces.py), so the two independent
    # models must agree within the command's default tolerance (1 %); residues alone were 1-3.6 % off
    assert run.returncode == 0, run.stderr
    data = json.loads(run.stdout)
    assert set(data["relative_diff"]) == {"w_rear", "w_front", "u", "theta"}
    assert data["track"] == "two-layer" and data["closed_form_branch_cut"] is True
    assert max(data["relative_diff"].values()) < 0.01
