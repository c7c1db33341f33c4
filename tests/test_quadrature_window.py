"""The window search of a track whose receptance is a quadrature (roots/quadrature_window.py), on a track
whose roots are known another way.

Reference: the continuous track's own search (roots/frequencies.py: residues, the cut traced, the far
field, digits confirmed at higher precision) on Table 1's case 1, a bogie at alpha = 0.8 with eta_f = 0.1:
its cut of K lies above the real axis, so the window Im q <= 0 searched through the track's receptance
alone (no cut, no kernel by residues in the search) holds the same growing roots.
"""

from __future__ import annotations

import mpmath

from moving_bogie import table1_case
from moving_bogie.api import bind, induced_frequencies
from moving_bogie.roots.quadrature_window import window_frequencies, window_radius
from moving_bogie.roots.verdict import UNSTABLE


def test_window_search_through_the_receptance_finds_the_continuous_tracks_growing_roots():
    bound = bind(table1_case(1))
    reference = induced_frequencies(bound)
    growing = [complex(r.q) for r in reference.roots if mpmath.im(r.q) < 0]
    radius, far = window_radius(bound)
    result = window_frequencies(bound, radius=radius, far_field=far)
    assert result.verdict.state == reference.verdict.state == UNSTABLE
    assert result.count == len(result.roots) == len(growing) == 1
    q = complex(result.roots[0].q)
    # to the digits each search confirms: the reference's are 30, this one's its decimals
    assert abs(q - growing[0]) <= 10.0 ** -result.roots[0].decimals
    assert result.roots[0].decimals >= 8
