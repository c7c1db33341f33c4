"""The legends of the map figures list only what is drawn, and a panel with nothing unstable says so.

The maps here are built by hand (the figure is under test, not the D-decomposition): a sleeper map with no
crossing (stable everywhere), and one with a zone between two crossings of one column.
"""

from __future__ import annotations

import numpy as np

from moving_bogie.stability.figures.sleeper_map_figure import sleeper_map_figure
from moving_bogie.stability.maps.d_lines import DColumn, DCrossing
from moving_bogie.stability.maps.sleeper_map import SleeperMap

V, M = np.array([20.0, 40.0, 60.0]), np.array([500.0, 1000.0, 1500.0])


def _map(crossings: dict[int, tuple[DCrossing, ...]]) -> SleeperMap:
    """A 3 x 3 map in SI with v_ref = 100 m/s and the mass unit 1000 kg; column i has ``crossings[i]``."""
    columns = tuple(
        DColumn(
            alpha=v / 100.0,
            Omega0=1.0,
            crossings=crossings.get(i, ()),
            harmonics=2,
            samples=10,
            evaluations=1,
        )
        for i, v in enumerate(V)
    )
    count = np.stack([col.counts(M / 1000.0) for col in columns], axis=1)
    return SleeperMap("mass", V, M, 100.0, 1000.0, 1.0, columns, count)


def _legend(fig) -> list[str]:
    return [t.get_text() for t in fig.axes[0].get_legend().get_texts()]


def _texts(ax) -> list[str]:
    return [t.get_text() for t in ax.texts]


def test_a_stable_sleeper_map_says_so_and_lists_no_unstable_symbol():
    smap = _map({})
    fig = sleeper_map_figure(smap, operating=(40.0, 600.0))
    assert _legend(fig) == ["the file's (v, M)"]
    assert _texts(fig.axes[0]) == ["stable on the whole grid"]


def test_an_unstable_zone_is_drawn_and_listed():
    # column 1 (v = 40 m/s): the count rises at M = 800 kg and falls at 1200 kg: the cell at 1000 kg unstable
    up, down = (
        DCrossing(q=0.5, eta_M=0.8, change=1, moved=0.0),
        DCrossing(q=0.5, eta_M=1.2, change=-1, moved=0.0),
    )
    smap = _map({1: (up, down)})
    assert smap.count.sum() == 1 and smap.count[1, 1] == 1
    fig = sleeper_map_figure(smap)
    assert _legend(fig) == [
        "unstable cell of the grid",
        "unstable between the D-lines (one column wide)",
        "D-line: count +1 as M grows",
        "D-line: count -1 as M grows",
    ]
    assert _texts(fig.axes[0]) == []


def test_a_sleeper_map_with_margins_is_coloured_by_them():
    """With ``margin`` (stability-map --margin) the cells are coloured as the continuous map's: the stable
    ones by their decay rate (a colour bar, the smallest decay rate marked and named), the unstable one by
    its growth rate (no zone bar over it); no count cells, and the panel is not called blank."""
    from dataclasses import replace

    up, down = (
        DCrossing(q=0.5, eta_M=0.8, change=1, moved=0.0),
        DCrossing(q=0.5, eta_M=1.2, change=-1, moved=0.0),
    )
    smap = _map({1: (up, down)})
    margin = np.full(smap.count.shape, 2.0)
    margin[0, 0] = 0.25  # the least-damped stable cell
    margin[1, 1] = -3.0  # the unstable cell grows at 3 1/s
    with_margin = replace(smap, margin=margin, margin_bound=np.zeros(margin.shape, dtype=bool))
    fig = sleeper_map_figure(with_margin)
    legend = _legend(fig)
    assert "smallest decay rate 0.25 1/s" in legend and "unstable cell of the grid" not in legend
    assert not any("between the D-lines" in t for t in legend)  # the growth colour is not hidden
    labels = [ax.get_ylabel() for ax in fig.axes[1:]]  # the colour bars
    assert any("decay rate" in t for t in labels) and any("growth rate" in t for t in labels), labels
    assert _texts(fig.axes[0]) == []
    assert with_margin.min_decay_rate == 0.25 and smap.min_decay_rate is None
