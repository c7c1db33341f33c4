"""The car (four contacts, ten DOFs) certified in ball arithmetic: every root, the count and the verdict.

References independent of the ball code: the mpmath Newton polish at 30 digits from each root's double
value (roots/refine/polish.py, the block system condensed to its wheels), and the double-precision argument
principle on a circle around each close pair (the car's two bogies interact only through the rail, so their
roots come in pairs 2e-10, 1e-7 and 3e-7 apart).
"""

from __future__ import annotations

from pathlib import Path

import mpmath
import numpy as np
import pytest

from moving_bogie.api import induced_frequencies
from moving_bogie.kernels.bound import bind
from moving_bogie.kernels.characteristic import Characteristic, CharacteristicArray
from moving_bogie.model.files import load_params_file
from moving_bogie.roots.count.contour import Rectangle
from moving_bogie.roots.proof.balls import BallCharacteristic
from moving_bogie.roots.proof.certify import certify, krawczyk
from moving_bogie.roots.proof.winding import proven_count
from moving_bogie.roots.refine.polish import newton

CAR = Path(__file__).resolve().parent.parent / "examples" / "car.toml"


@pytest.fixture(scope="module")
def car():
    params = load_params_file(CAR)[0]
    result = induced_frequencies(params)
    return params, result, certify(result)


def close_pairs(result, gap=1e-6):
    qs = [r.q for r in result.roots]
    return [(a, b) for i, a in enumerate(qs) for b in qs[i + 1 :] if abs(a - b) < gap]


@pytest.mark.slow
def test_the_car_is_proven_stable_with_every_root_and_the_count(car):
    _, result, cert = car
    assert cert.all_proven and cert.proven_roots == len(result.roots) == 11
    assert cert.count == result.count == 11
    assert cert.verdict == "stable" and not cert.problems


@pytest.mark.slow
def test_each_member_of_a_close_pair_has_its_own_enclosure(car):
    params, result, cert = car
    pairs = close_pairs(result)
    assert len(pairs) >= 2 and min(abs(a - b) for a, b in pairs) < 1e-9
    precise = Characteristic(bind(params))
    for r, e in zip(result.roots, cert.roots):
        with mpmath.workdps(30):
            q30, _ = newton(precise, mpmath.mpc(complex(r.q)))  # an independent polish from 16 digits
        assert e.contains(q30)
    enclosure = {id(r.q): e for r, e in zip(result.roots, cert.roots)}
    for a, b in pairs:
        ea, eb = enclosure[id(a)], enclosure[id(b)]
        assert not ea.ball.overlaps(eb.ball)
        assert ea.contains(a) and eb.contains(b) and not ea.contains(b) and not eb.contains(a)


@pytest.mark.slow
def test_a_wrong_candidate_fails_and_a_close_pair_counts_two(car):
    params, result, _ = car
    bc = BallCharacteristic(bind(params), prec=200)
    a, b = min(close_pairs(result), key=lambda ab: abs(ab[0] - ab[1]))  # 2e-10 apart
    assert krawczyk(bc, a).certified and krawczyk(bc, b).certified
    assert not krawczyk(bc, a + mpmath.mpf("1e-20")).certified  # the root is outside this ball
    assert not krawczyk(bc, (a + b) / 2).certified  # between the two members: no root within 1e-26
    # a square around the pair, far from the other roots: proven to hold both (and the numerical count agrees)
    centre, half = complex((a + b) / 2), 1e-6
    box = Rectangle(centre.real - half, centre.real + half, centre.imag - half, centre.imag + half)
    assert proven_count(BallCharacteristic(bind(params), prec=96), box).count == 2
    E = CharacteristicArray(bind(params))
    t = np.linspace(0, 2 * np.pi, 2000, endpoint=False)
    values = E(centre + half * np.exp(1j * t))
    assert round(np.sum(np.angle(np.roll(values, -1) / values)) / (2 * np.pi)) == 2
