"""The first samples of a rectangle's boundary on the shared lattice (roots/count/lattice.py) and E_chr
evaluated once per point (CharacteristicArray with ``remember``): never coarser than the sampling rule,
shared along common lines, and the same counts and values as without them."""

import numpy as np
import pytest

from moving_bogie.kernels.bound import bind
from moving_bogie.kernels.characteristic import CharacteristicArray
from moving_bogie.model.cases import table1_case
from moving_bogie.roots.count.contour import Rectangle, initial_samples, winding_number, winding_numbers
from moving_bogie.roots.count.lattice import STEP, lattice_boundary

RECTS = [
    Rectangle(-0.003, 3.0, -3.0, 3.1),
    Rectangle(0.13088299091439032, 0.26476598182878064, -0.0525, 0.09999999999999998),
    Rectangle(0.2, 0.2 + 3e-7, -0.1, -0.1 + 1e-7),
    Rectangle(-1.0, 2.0, 0.5, 0.5004),
]


@pytest.mark.parametrize("rect", RECTS)
def test_no_segment_is_longer_than_the_sampling_rule_allows(rect):
    z = lattice_boundary(rect.x0, rect.x1, rect.y0, rect.y1)
    assert z is not None and z[0] == z[-1]
    size = max(rect.width, rect.height)
    corners = {complex(rect.x0, rect.y0), complex(rect.x1, rect.y0), complex(rect.x1, rect.y1)}
    assert corners <= set(z.tolist())
    seg = np.abs(np.diff(z))
    assert np.all(np.diff(z).real * np.diff(z).imag == 0)  # along the edges only
    assert np.all(seg <= min(size / 64, STEP) * (1 + 1e-12))
    # every edge has at least 8 segments
    assert np.sum(z.imag[:-1] == rect.y0) >= 8 and np.sum(z.real[:-1] == rect.x1) >= 8
    # and the samples go round counter-clockwise: the signed area is the rectangle's
    area = 0.5 * np.sum(z.real[:-1] * z.imag[1:] - z.real[1:] * z.imag[:-1])
    assert area == pytest.approx(rect.width * rect.height, rel=1e-9)


def test_halves_share_the_split_line_and_inherit_the_outer_samples():
    rect = Rectangle(-0.003, 3.0, -3.0, 3.1)
    z, _ = initial_samples(rect)
    lo, hi = rect.split(0.5)
    a, _ = initial_samples(lo)
    b, _ = initial_samples(hi)
    line = {w for w in a.tolist() if w.imag == lo.y1}
    assert line == {w for w in b.tolist() if w.imag == hi.y0}
    assert set(z.tolist()) <= set(a.tolist()) | set(b.tolist())  # the parent's samples, all reused


def test_far_from_the_origin_the_growing_sampling_is_kept():
    far = Rectangle(0.0, 40.0, -40.0, 0.1)
    assert lattice_boundary(far.x0, far.x1, far.y0, far.y1) is None
    z, _ = initial_samples(far)
    assert z.size < 4 * 80 / STEP / 4  # coarser than STEP far out


@pytest.mark.parametrize("case", [1, 7])
def test_counts_on_the_lattice_agree_with_uniform_sampling(case):
    """The independent reference: the rectangle sampled uniformly at a step finer than either rule."""
    fast = CharacteristicArray(bind(table1_case(case)))
    rects = [
        Rectangle(-0.003, 0.6, -0.5, 0.09),
        Rectangle(0.1, 0.35, -0.05, 0.05),
        Rectangle(0.5, 3.0, -3, -0.5),
    ]
    counted = winding_numbers(fast, rects)
    for rect, n in zip(rects, counted):
        assert n == winding_number(fast, rect, spacing=STEP / 4)


def test_remembered_values_are_the_values_and_count_once():
    bound = bind(table1_case(3))
    plain, remembering = CharacteristicArray(bound), CharacteristicArray(bound, remember=2.0)
    rng = np.random.default_rng(5)
    q = rng.uniform(-1.4, 1.4, 300) + 1j * rng.uniform(-1.4, 1.4, 300)
    q[[10, 250]] = [3.0 - 0.5j, -2.5 + 1j]  # beyond the radius: evaluated each time, not kept
    first = remembering(q[:200])
    assert remembering.evaluations == 200
    again = remembering(q.reshape(3, 100))  # 199 near points seen, 99 new; both far ones evaluated
    assert remembering.evaluations == 200 + 99 + 2
    assert again.shape == (3, 100)
    reference = plain(q)
    assert np.allclose(first, reference[:200], rtol=1e-13, atol=0)
    assert np.allclose(again.ravel(), reference, rtol=1e-13, atol=0)
    near = np.abs(q[:200]) <= 2.0
    assert np.array_equal(again.ravel()[:200][near], first[near])  # the values kept, to the bit
    # a point repeated within one batch, and a zero of either sign (equal as complex numbers, as they were
    # as a dict's keys), is evaluated once; the repeats get its value
    fresh = np.array([0.3 + 0.2j, 0.4 - 0.1j, 0.3 + 0.2j, complex(-0.0, 0.7), complex(0.0, 0.7)])
    before = remembering.evaluations
    values = remembering(fresh)
    assert remembering.evaluations == before + 3
    assert values[0] == values[2] and values[3] == values[4]
    assert np.allclose(values, plain(fresh), rtol=1e-13, atol=0)
