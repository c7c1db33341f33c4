"""Induced frequencies and stability maps on layered tracks (kernels/cut.py, roots/, stability/maps/map.py).

References:
- the roots of the two-layer example against a dense scan of |E_chr| on a grid below the cut (local minima
  refined by mpmath.findroot) and a discrete argument principle on the scan's boundary (numpy angles of E
  sampled densely, no contour code of the package);
- the ends of the cut at alpha = 0 against the roots of the layer's own row Q(q) = 1 + kappa_2 - mu_2 q^2
  + 2 i (eta_f + eta_2) q (the leading coefficient of N in p there, docs/layered_tracks.md);
- polynomial roots against numpy.roots, one polynomial at a time;
- the stability map's verdicts against ``induced_frequencies`` (its own full count) at a few cells.
"""

from __future__ import annotations

from pathlib import Path

import mpmath
import numpy as np
import pytest

from moving_bogie.api import induced_frequencies, stability_map
from moving_bogie.cli import main
from moving_bogie.kernels.bound import bind
from moving_bogie.kernels.characteristic import Characteristic, CharacteristicArray
from moving_bogie.kernels.cut import cut_locus
from moving_bogie.kernels.polyroots import inverse_distances, poly_roots
from moving_bogie.model.cases import table1_case
from moving_bogie.model.files import load_params_file
from moving_bogie.roots.count.contour import Rectangle
from moving_bogie.stability.maps.column import exact

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def _cut_q(params, ps: np.ndarray) -> np.ndarray:
    """The q of the cut of K at each real p of ``ps``: the roots of N(p, .), p after p, as numpy.roots finds
    them (the eigenvalues of the companion matrix numpy.roots builds), in one batched eigvals call."""
    track = bind(params).foundation_model
    args = track.float_arguments(params)
    coeffs = np.array([track.module.n_coeffs_in_q(p, **args) for p in ps], dtype=complex)
    assert np.all(coeffs[:, 0] != 0) and np.all(coeffs[:, -1] != 0)  # numpy.roots would strip zeros
    n = coeffs.shape[1] - 1
    companion = np.zeros((len(ps), n, n), dtype=complex)
    companion[:, 1:, :-1] = np.eye(n - 1)
    companion[:, 0, :] = -coeffs[:, 1:] / coeffs[:, :1]
    return np.linalg.eigvals(companion).ravel()


@pytest.fixture(scope="module")
def two_layer():
    return load_params_file(EXAMPLES / "two-layer.toml")[0]


def _scan_roots(params, x0, x1, y0, y1, n=(1501, 181)):
    """Roots of E_chr in the rectangle: local minima of |E| on a grid, refined by mpmath.findroot."""
    fast = CharacteristicArray(bind(params))
    xs, ys = np.linspace(x0, x1, n[0]), np.linspace(y0, y1, n[1])
    Z = xs[None, :] + 1j * ys[:, None]
    A = np.abs(fast(Z.ravel())).reshape(Z.shape)
    inner = A[1:-1, 1:-1]
    is_min = np.ones(inner.shape, dtype=bool)
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            if dy or dx:
                is_min &= inner <= A[1 + dy : A.shape[0] - 1 + dy, 1 + dx : A.shape[1] - 1 + dx]
    precise = Characteristic(bind(params))
    roots = []
    with mpmath.workdps(20):
        for j, i in zip(*np.nonzero(is_min)):
            try:
                q = complex(
                    mpmath.findroot(lambda z: precise.value_and_derivative(z)[0], complex(Z[j + 1, i + 1]))
                )
            except (ValueError, ZeroDivisionError):
                continue
            if x0 < q.real < x1 and y0 < q.imag < y1 and all(abs(q - r) > 1e-8 for r in roots):
                roots.append(q)
    return roots, fast


def _boundary_count(fast, x0, x1, y0, y1, n=20000):
    corners = [complex(x0, y0), complex(x1, y0), complex(x1, y1), complex(x0, y1), complex(x0, y0)]
    z = np.concatenate(
        [a + (b - a) * np.linspace(0, 1, n, endpoint=False) for a, b in zip(corners, corners[1:])]
    )
    w = fast(np.append(z, z[0]))
    return int(round(np.sum(np.angle(w[1:] / w[:-1])) / (2 * np.pi)))


@pytest.mark.slow
def test_two_layer_roots_match_a_dense_scan(two_layer):
    """Every root below the cut (Im q < 0.06; the cut's lowest point is at Im q = 0.0708, checked here by
    numpy.roots of N(p, .) on a p-grid) is found by the search, and no other."""
    track_q = _cut_q(two_layer, np.linspace(-40, 40, 4001))
    assert track_q[np.abs(track_q.real) < 3].imag.min() > 0.07
    box = (0.0, 1.5, -0.3, 0.06)
    scan, fast = _scan_roots(two_layer, *box)
    assert _boundary_count(fast, *box) == len(scan) == 4
    result = induced_frequencies(two_layer, dps=20)
    assert result.count_ok and result.verdict.state == "stable"
    found = [complex(r.q) for r in result.roots if box[2] < float(mpmath.im(r.q)) < box[3]]
    assert len(found) == len(scan)
    for q in scan:
        assert min(abs(q - f) for f in found) < 1e-12
    assert all(r.side == "below" for r in result.roots)
    # the sliver left out around the cut stays thin (the boxes at the folds opening to the left)
    assert max(u.height for u in result.unsearched) < 1e-3


@pytest.mark.slow
def test_three_layer_frequencies_finish_with_a_certified_count():
    params = load_params_file(EXAMPLES / "three-layer.toml")[0]
    result = induced_frequencies(params, dps=15)
    assert result.count_ok, result.warnings
    assert result.verdict.determined, result.verdict.reasons
    assert result.count == len(result.roots) == 4
    assert max(u.height for u in result.unsearched) < 1e-3


def test_cut_at_alpha_zero_ends_at_the_layer_resonance(two_layer):
    """At alpha = 0 the mass layer's curves stay bounded: the cut ends where Q(q) = 0 (N loses its p^6 and
    p^5 terms; its p^4 coefficient is Q)."""
    params = two_layer.replace(alpha=0)
    cut = cut_locus(bind(params), -3.0, 3.0)
    f = params.as_float()
    q_inf = np.roots([-f.mu_2, 2j * (f.eta_f + f.eta_2), 1 + f.kappa_2])
    ends = [fold.q for fold in cut.folds if fold.end]
    assert ends
    for q in ends:
        assert min(abs(q - q_inf)) < 1e-8
    for q in q_inf:
        assert min(abs(q - e) for e in ends) < 1e-8


def test_poly_roots_drop_vanishing_leading_coefficients_and_agree_with_numpy():
    rng = np.random.default_rng(12)
    c = rng.normal(size=(300, 7)) + 1j * rng.normal(size=(300, 7))
    c[::3, 0] = 0  # degree 5 there
    c[::9, 1] = 0  # and degree 4 where both vanish
    roots = poly_roots(c)
    for row, r in zip(c, roots):
        ref = np.sort_complex(np.roots(row))  # numpy.roots strips leading zeros itself
        got = np.sort_complex(r[np.isfinite(r)])
        assert got.size == ref.size and np.allclose(got, ref, rtol=1e-10, atol=1e-12)


@pytest.mark.parametrize("deg", [1, 2, 3, 4, 6, 7, 8, 13])
def test_inverse_distances_of_aberth_agree_with_the_matrix_of_distances(deg):
    """Aberth's repulsion sum_{j != i} 1 / (z_i - z_j) column by column against the (n, deg, deg) matrix of
    the distances, its diagonal left out, summed along its rows; values spread over 16 decades."""
    rng = np.random.default_rng(deg)
    z = (rng.normal(size=(500, deg)) + 1j * rng.normal(size=(500, deg))) * 10.0 ** rng.integers(
        -8, 8, (500, deg)
    )
    diff = z[:, :, None] - z[:, None, :]
    diff[:, np.eye(deg, dtype=bool)] = np.inf  # 1 / inf = 0: no term of its own
    reference = (1.0 / diff).sum(axis=-1)
    got = inverse_distances(z)
    assert np.allclose(got, reference, rtol=1e-13, atol=0)


@pytest.mark.slow
def test_small_two_layer_map_agrees_with_frequencies(two_layer):
    alphas = np.linspace(0.0, 1.2, 12)
    thetas = np.linspace(1.0, 200.0, 12)
    smap = stability_map(two_layer, alphas=alphas, thetas=thetas, workers=1)
    assert not smap.uncertain.any()
    assert not smap.count[:, 0].any()  # alpha = 0: the column runs (no nan from the roots at infinity)
    for j, i in ((4, 6), (4, 8)):  # one unstable and one stable cell (see the map)
        res = induced_frequencies(two_layer.replace(alpha=exact(alphas[i]), eta_M=exact(thetas[j])), dps=15)
        assert res.count_ok and res.verdict.determined
        assert smap.count[j, i] == len(res.unstable_roots)
    assert smap.count[4, 6] == 1 and smap.count[4, 8] == 0


def test_stability_map_cli_on_a_layered_file(capsys):
    file = str(EXAMPLES / "two-layer.toml")
    assert main(["stability-map", "--file", file, "--n", "4", "--workers", "1", "--json"]) == 0
    assert '"uncertain_cells": 0' in capsys.readouterr().out
    assert main(["stability-map", "--track", "two-layer", "--n", "4", "--workers", "1"]) == 2
    assert "--mu-2" in capsys.readouterr().err
    ok = ["--track", "two-layer", "--mu-2", "4", "--kappa-2", "0.5", "--eta-2", "0.4"]
    assert main(["stability-map", *ok, "--n", "3", "--workers", "1", "--json"]) == 0


@pytest.mark.slow
def test_side_between_two_cut_curves():
    """Timoshenko-Rayleigh Case 7 (S = 10, r = 0.09) has roots near the real axis beyond sqrt(S)/r inside
    the lens between two cut curves; the reference is numpy.roots of N(p, .) on a dense p-grid: at the
    root's Re q the cut passes both below and above it."""
    params = table1_case(7).replace(beam="tr", S=10, r="0.09")
    window = Rectangle(-0.01, 60.0, -1.0, 1.0)
    result = induced_frequencies(params, dps=15, window=window, check_window=False)
    assert result.count_ok, result.warnings
    cut = _cut_q(params, np.linspace(-25, 20, 90001))
    far = [r for r in result.roots if float(mpmath.re(r.q)) > 35]
    assert far
    for r in far:
        q = complex(r.q)
        near = cut[np.abs(cut.real - q.real) < 2e-3]
        assert near.imag.min() < q.imag < near.imag.max()
        assert r.side == "between"
