"""The Timoshenko-Rayleigh sequence along the real axis located from the large-|q| balance (axis_law.py).

Reference: the same strip searched with no starting points (the argument principle on its tiling, tiles
bisected until each holds one root: roots/frequencies.py), which uses nothing of the balance.
"""

from __future__ import annotations

import numpy as np
import pytest

from moving_bogie.kernels.bound import bind
from moving_bogie.kernels.characteristic import CharacteristicArray
from moving_bogie.model.cases import table1_case
from moving_bogie.response.axis_law import law_applies, law_roots
from moving_bogie.roots.count.contour import Rectangle
from moving_bogie.roots.frequencies import induced_frequencies

STRIP = Rectangle(24.0, 48.0, -1.0, 1.0)  # the first roots of the sequence (Re q = 39.07, 44.27)


@pytest.fixture(scope="module")
def tr():
    return bind(table1_case(7).replace(beam="tr", S=10, r="0.09"))


@pytest.fixture(scope="module")
def searched(tr):
    return induced_frequencies(tr, dps=15, window=STRIP, check_window=False)


def test_the_balance_applies_to_a_bogie_on_a_timoshenko_rayleigh_beam_only(tr):
    assert law_applies(tr)
    assert not law_applies(bind(table1_case(7)))  # Euler-Bernoulli: p-roots grow like sqrt|q|


def test_the_balance_finds_the_roots_of_the_strip_search(tr, searched):
    law = law_roots(CharacteristicArray(tr), STRIP)
    ref = np.array([complex(r.q) for r in searched.roots])
    assert searched.count_ok and ref.size == law.size >= 2
    for z in ref:
        assert np.min(np.abs(law - z)) < 1e-10 * abs(z)


def test_wrong_starting_points_never_lose_a_root(tr, searched):
    # one root shifted off its place and the other missing: a tile whose count disagrees with the points
    # is bisected, one that agrees polishes from the point within the tile; every root is still found
    law = law_roots(CharacteristicArray(tr), STRIP)
    wrong = [law[0] + 0.3]
    result = induced_frequencies(tr, dps=15, window=STRIP, check_window=False, starts=wrong)
    assert result.count_ok and result.count == searched.count
    got = sorted(complex(r.q).real for r in result.roots)
    want = sorted(complex(r.q).real for r in searched.roots)
    np.testing.assert_allclose(got, want, rtol=1e-12)
