"""``compare-tracks``: instability lines of one vehicle on a layered track and on the one-layer track.

Reference: the one-layer limit of the two-layer track (m_2 -> 0, k_2 -> infinity; docs/layered_tracks.md):
there both panels must show the same lines and critical velocity, computed through different kernels
(degree 6 in p against the quartic), so the command pairs the tracks with the same k_f = k_1 scaling.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from moving_bogie.cli import main


def _panel_data(ax):
    """(alpha_cr, [(alpha, eta_M) arrays of every drawn line]) read back from one panel's artists."""
    vertical = [ln for ln in ax.get_lines() if len(set(ln.get_xdata())) == 1 and ln.get_linestyle() == ":"]
    assert len(vertical) == 1, "one dotted critical-velocity line per panel"
    curves = [
        (np.asarray(ln.get_xdata(), float), np.asarray(ln.get_ydata(), float))
        for ln in ax.get_lines()
        if ln not in vertical and len(ln.get_xdata()) > 1
    ]
    return float(vertical[0].get_xdata()[0]), curves


@pytest.mark.slow
def test_one_layer_limit_gives_the_same_lines_on_both_panels(capsys, tmp_path, monkeypatch):
    import moving_bogie.stability.figures.track_comparison as comparison

    drawn = []
    original = comparison.figure_track_comparison

    def keep(c, *args, **kwargs):
        drawn.append(original(c, *args, **kwargs))
        return drawn[-1]

    monkeypatch.setattr(comparison, "figure_track_comparison", keep)
    figure = tmp_path / "compare.png"
    argv = "compare-tracks --track two-layer --mu-2 1e-5 --kappa-2 1e5 --eta-2 0 --d 1.5 --quick --json"
    assert main([*argv.split(), "--plot", str(figure)]) == 0
    data = json.loads(capsys.readouterr().out)
    one, two = data["tracks"]
    assert (one["track"], two["track"]) == ("one-layer", "two-layer")
    # mu_2 = 1e-5 moves v_cr by O(mu_2) (test_layered.py measures the rate)
    assert abs(one["alpha_cr"] - two["alpha_cr"]) < 1e-3
    low1, low2 = one["lowest_subcritical"][0], two["lowest_subcritical"][0]
    assert abs(low1["eta_M"] - low2["eta_M"]) < 1e-2 * low1["eta_M"]
    assert abs(low1["alpha"] - low2["alpha"]) < 1e-2
    # The figure by content: each panel draws its track's critical velocity and lines whose lowest
    # subcritical point is the one reported in the JSON; the written file is that figure.
    assert figure.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    (fig,) = drawn
    panels = [ax for ax in fig.axes if ax.get_lines()]
    assert len(panels) == 2
    for ax, track in zip(panels, (one, two)):
        alpha_cr, curves = _panel_data(ax)
        assert alpha_cr == pytest.approx(track["alpha_cr"], rel=1e-12)
        assert curves, f"no instability line drawn for {track['track']}"
        points = np.concatenate([np.column_stack(c) for c in curves])
        below = points[points[:, 0] < alpha_cr]
        lowest = below[below[:, 1].argmin()]
        assert lowest[0] == pytest.approx(track["lowest_subcritical"][0]["alpha"], abs=1e-9)
        assert lowest[1] == pytest.approx(track["lowest_subcritical"][0]["eta_M"], abs=1e-9)


def test_a_one_layer_track_is_refused_naming_the_option(capsys):
    assert main(["compare-tracks", "--d", "1.5"]) == 2
    assert "--track" in capsys.readouterr().err
