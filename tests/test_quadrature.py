"""The quadrature shared by the branch-cut integrals (Eq. (35)): block sums over uniform times against the
direct exponentials and an extended-precision sum, and the adapted panels against the halving rule."""

from __future__ import annotations

import numpy as np
import pytest

from moving_bogie.response import quadrature as quad


def _extended_sum(ts: np.ndarray, q: np.ndarray, G: np.ndarray) -> np.ndarray:
    """sum_n G_n e^{i q_n t} with the phases in long double (an independent reference)."""
    L = np.longdouble
    x = np.multiply.outer(ts.astype(L), q.real.astype(L))
    decay = np.exp(-np.multiply.outer(ts.astype(L), q.imag.astype(L)))
    re, im = np.cos(x) * decay, np.sin(x) * decay
    Gr, Gi = G.real.astype(L), G.imag.astype(L)
    return ((re @ Gr - im @ Gi) + 1j * (re @ Gi + im @ Gr)).astype(complex)


@pytest.mark.parametrize(
    "ts",
    [
        np.linspace(0.0, 40.0, 2001)[801:1601],  # a band of the time series, (16, 32]
        np.linspace(0.0, 40.0, 2001)[:26],  # the first band, from t = 0
        np.linspace(3.0, 7.1, 137),
    ],
)
@pytest.mark.parametrize("curved", [True, False])
def test_uniform_times_match_the_direct_sum(ts: np.ndarray, curved: bool, monkeypatch) -> None:
    rng = np.random.default_rng(7)
    n = 1000
    eta = 0.3
    q = rng.uniform(0.0, 383.0, n) + 1j * (rng.uniform(0.01, 2.0, n) if curved else eta)
    G = rng.normal(size=(n, 4)) + 1j * rng.normal(size=(n, 4))

    def weighted(idx: np.ndarray, w: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return q[idx], G[idx] * w[:, None]

    args = (ts, np.arange(n), np.ones(n), weighted, 4, 383.0, None if curved else eta)
    assert quad.uniform_step(ts) is not None
    blocks = quad.fourier_sum(*args)
    monkeypatch.setattr(quad, "uniform_step", lambda ts: None)
    direct = quad.fourier_sum(*args)
    reference = _extended_sum(ts, q, G)
    scale = np.abs(G).sum()
    assert np.abs(direct - reference).max() <= 1e-15 * scale
    assert np.abs(blocks - reference).max() <= 1e-15 * scale
    assert np.abs(blocks - direct).max() <= 1e-15 * scale


def test_uniform_step_only_for_uniform_times() -> None:
    ts = np.linspace(2.0, 4.0, 101)
    assert quad.uniform_step(ts) == pytest.approx(0.02, rel=1e-14)
    bent = ts.copy()
    bent[50] += 1e-12
    assert quad.uniform_step(bent) is None
    assert quad.uniform_step(ts[:8]) is None  # few times: the direct sum
    assert quad.uniform_step(np.full(40, 3.0)) is None


def _halving_edges(start: np.ndarray, f, tol: float, max_splits: int = 40) -> np.ndarray:
    """The halving rule of adapt_panels evaluated plainly: every pass integrates each open panel and
    its two halves afresh."""

    def integral(a: np.ndarray, b: np.ndarray) -> np.ndarray:
        nodes, weights = quad.gauss_panels(a, b)
        return (f(nodes) * weights[:, None]).reshape(a.size, quad.GL_X.size, -1).sum(axis=1)

    lo, hi, edges = start[:-1], start[1:], [start]
    for _ in range(max_splits):
        if lo.size == 0:
            break
        mid = 0.5 * (lo + hi)
        bad = np.abs(integral(lo, hi) - integral(lo, mid) - integral(mid, hi)).max(axis=-1) > tol
        edges.append(mid[bad])
        lo, hi = np.concatenate([lo[bad], mid[bad]]), np.concatenate([mid[bad], hi[bad]])
    return np.unique(np.concatenate(edges))


def test_adapted_panels_follow_the_halving_rule_and_keep_their_values() -> None:
    def f(x: np.ndarray) -> np.ndarray:  # a narrow peak, and a column that does not enter the test
        return np.stack([1.0 / (1e-6 + (x - 0.3) ** 2), np.cos(3 * x), 1e9 * np.sin(x)], axis=-1)

    start = np.linspace(-1.0, 2.0, 7)
    edges, values = quad.adapt_panels_with_values(start, f, 1e-10, checked=2)
    assert np.array_equal(edges, _halving_edges(start, lambda x: f(x)[:, :2], 1e-10))
    assert edges.size > start.size + 8  # the peak was resolved
    nodes = quad.gauss_panels(edges[:-1], edges[1:])[0]
    assert np.array_equal(values, f(nodes))
    assert np.array_equal(quad.adapt_panels(start, lambda x: f(x)[:, :2], 1e-10), edges)


def test_undivided_panels_keep_their_nodes() -> None:
    edges = np.array([-0.7, -0.1, 0.0, 1e-3, 0.3, 2.9])
    nodes, weights = quad.subdivide(edges, np.array([1, 3, 1, 2, 1]))
    whole = quad.gauss_panels(edges[:-1], edges[1:])[0].reshape(-1, quad.GL_X.size)
    parts = nodes.reshape(-1, quad.GL_X.size)
    for k, row in zip((0, 4, 7), (0, 2, 4)):
        assert np.array_equal(parts[k], whole[row])
    assert weights.sum() == pytest.approx(edges[-1] - edges[0], rel=1e-15)
