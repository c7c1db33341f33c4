"""The window search of a track whose receptance is a quadrature (roots/quadrature_window.py), on a track
whose roots are known another way.

Reference: the continuous track's own search (roots/frequencies.py: residues, the cut traced, the far
field, digits confirmed at higher precision) on Table 1's case 1, a bogie at alpha = 0.8 with eta_f = 0.1:
its cut of K lies above the real axis, so the window Im q <= 0 searched through the track's receptance
alone (no cut, no kernel by residues in the search) holds the same growing roots. And the winding number
of the same characteristic function on every cell of a 4 x 4 grid over the window (a brute-force count
that places each root in its cell, with no use of the search's bisection or moments).
"""

from __future__ import annotations

import mpmath
import numpy as np

from moving_bogie import table1_case
from moving_bogie.api import bind, induced_frequencies
from moving_bogie.roots.count.contour import Rectangle, winding_number
from moving_bogie.roots.quadrature_search import window_frequencies
from moving_bogie.roots.quadrature_window import QuadratureCharacteristic, window_radius
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


def test_count_and_roots_against_the_winding_number_on_a_grid():
    bound = bind(table1_case(1))
    radius, far = window_radius(bound)
    result = window_frequencies(bound, radius=radius, far_field=far)
    w = result.window
    xs, ys = np.linspace(w.x0, w.x1, 5), np.linspace(w.y0, w.y1, 5)
    cells = [Rectangle(xs[i], xs[i + 1], ys[j], ys[j + 1]) for i in range(4) for j in range(4)]
    E = QuadratureCharacteristic(bound)
    counts = [winding_number(E, c, spacing=min(c.width, c.height) / 16, max_points=20_000) for c in cells]
    assert sum(counts) == result.count == len(result.roots)
    for root in result.roots:
        q = complex(root.q)
        assert any(n >= 1 and c.contains(q) for c, n in zip(cells, counts, strict=True))


def test_a_count_on_values_within_their_error_of_zero_is_not_a_verdict(monkeypatch):
    """The same search with the receptance's stated error raised to a tenth of its largest entry: the
    samples of the window's edge near the growing root no longer hold |E_chr| above twice delta E, so the
    count does not stand and the verdict is UNDETERMINED (reason QUADRATURE), never UNSTABLE or STABLE."""
    import dataclasses

    from moving_bogie.kernels.continuous_track import ContinuousTrack
    from moving_bogie.roots.count.outcomes import Reason
    from moving_bogie.roots.verdict import UNDETERMINED

    exact = ContinuousTrack.receptance

    def coarse(self, q, *args, **kwargs):
        rec = exact(self, q, *args, **kwargs)
        return dataclasses.replace(rec, error=0.1 * float(np.abs(rec.matrix).max()))

    monkeypatch.setattr(ContinuousTrack, "receptance", coarse)
    bound = bind(table1_case(1))
    radius, far = window_radius(bound)
    result = window_frequencies(bound, radius=radius, far_field=far)
    assert result.verdict.state == UNDETERMINED
    assert any(n.reason == Reason.QUADRATURE and "count rests" in n.text for n in result.notes)
