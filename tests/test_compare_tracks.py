"""``compare-tracks``: instability lines of one vehicle on a layered track and on the one-layer track.

Reference: the one-layer limit of the two-layer track (m_2 -> 0, k_2 -> infinity; docs/layered_tracks.md):
there both panels must show the same lines and critical velocity, computed through different kernels
(degree 6 in p against the quartic), so the command pairs the tracks with the same k_f = k_1 scaling.
"""

from __future__ import annotations

import json

from moving_bogie.cli import main


def test_one_layer_limit_gives_the_same_lines_on_both_panels(capsys, tmp_path):
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
    assert figure.stat().st_size > 10_000


def test_a_one_layer_track_is_refused_naming_the_option(capsys):
    assert main(["compare-tracks", "--d", "1.5"]) == 2
    assert "--track" in capsys.readouterr().err
