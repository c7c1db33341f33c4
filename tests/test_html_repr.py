"""Results shown as HTML tables in Jupyter: the verdict comes first, every text is escaped."""

from __future__ import annotations

import numpy as np
import pytest

from moving_bogie import induced_frequencies, table1_case
from moving_bogie.api import stability_map
from moving_bogie.html_repr import html_table


def test_the_verdict_comes_before_every_row():
    html = html_table("result", "STABLE", [("a", 1), ("b", 2)], items=(("x",), [(3,)]))
    assert html.index("STABLE") < html.index("<table>")
    assert html.index("<th style='text-align:left'>a</th>") < html.index(">b<")


def test_every_text_is_escaped():
    html = html_table("<script>x</script>", "UNSTABLE & more", [("<b>", "a<b")], reasons=["<i>"])
    assert "<script>" not in html and "&lt;script&gt;" in html
    assert "UNSTABLE &amp; more" in html and "a&lt;b" in html and "<li>&lt;i&gt;</li>" in html
    assert html.count("<b>") == 1  # the title's own bold, no other


def test_frequency_result_shows_its_verdict_first_and_its_roots():
    """Case 1 is unstable (Table 2 of the paper); its roots' printed digits appear in the table."""
    res = induced_frequencies(table1_case(1), dps=15)
    html = res._repr_html_()
    assert html.index(res.verdict.state.upper()) < html.index("<table>")
    assert res.verdict.state.upper() == "UNSTABLE"
    for root in res.roots:
        assert root.re_text in html and root.im_text in html


def test_stability_map_shows_its_verdict_first():
    smap = stability_map(table1_case(1), alphas=np.array([0.5, 0.9]), thetas=np.array([50.0]), workers=1)
    html = smap._repr_html_()
    unstable = int((smap.count > 0).sum())
    assert unstable == 1  # alpha = 0.9 lies beyond Case 1's boundary near alpha = 0.72, alpha = 0.5 before it
    assert html.index(f"UNSTABLE in {unstable} of 2 cells") < html.index("<table>")


@pytest.mark.slow
def test_sleeper_results_show_their_verdict_first():
    """A rail on sleepers: the steady response (its mean contact force is the static load P of the file,
    (S17) at n = 0) and a one-column map show themselves as the continuous tracks' results do."""
    from pathlib import Path

    import moving_bogie as mb

    examples = Path(__file__).resolve().parent.parent / "examples"
    _, physical = mb.load_parameters(examples / "sleepers_zones.toml")
    series = mb.sleeper_series(physical, points=33, free=False)
    html = series._repr_html_()
    assert html.index("NOT SEARCHED") < html.index("<table>") and f"{float(physical.P):.6g}" in html
    smap = mb.sleeper_map(physical, [88.0], [1500.0, 1750.0], verify=0, workers=1)
    html = smap._repr_html_()
    unstable = int((smap.count > 0).sum())
    verdict = f"UNSTABLE in {unstable} of 2 cells" if unstable else "STABLE in every cell"
    assert html.index(verdict) < html.index("<table>")
