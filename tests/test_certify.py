"""Certified induced frequencies (ball arithmetic): enclosures, proven counts and verdicts.

References used here are independent of the ball-arithmetic code: the mpmath Newton polish at 30 digits
(roots/refine/polish.py), the double-pole residue formula for dE/dq (kernels/track.py), the paper's printed
Table 2, polynomials with known roots, and the double-precision argument-principle count.
"""

from __future__ import annotations

import dataclasses
import json
import random
from pathlib import Path

import mpmath
import pytest
from flint import acb, acb_poly, ctx

from moving_bogie.api import induced_frequencies
from moving_bogie.cli import main
from moving_bogie.kernels.bound import bind
from moving_bogie.kernels.characteristic import Characteristic
from moving_bogie.kernels.cut import cut_locus
from moving_bogie.model.cases import table1_case, table2_printed
from moving_bogie.model.files import load_params_file
from moving_bogie.model.params import DimensionlessParams
from moving_bogie.roots.count.contour import Rectangle
from moving_bogie.roots.count.strip import pieces_below_axis
from moving_bogie.roots.proof.balls import BallCharacteristic, isolate_roots, square_ball
from moving_bogie.roots.proof.certify import certify, krawczyk
from moving_bogie.roots.proof.p_balls import _poly, direct_root_balls, horner, point_root_balls
from moving_bogie.roots.proof.proof_tiling import Staircase, proof_tiling
from moving_bogie.roots.proof.strip_proof import strip_region
from moving_bogie.roots.proof.winding import NotProven, _between, proven_count
from moving_bogie.roots.refine.polish import newton
from moving_bogie.roots.table2 import compute_table2, format_table2

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"

#: A window holding the four pairs of Case 1 (Table 2: Re q <= 0.31, |Im q| <= 0.03) and the cut Im q = 0.1.
CASE1_WINDOW = Rectangle(-5e-4, 0.5, -0.1, 0.2)


@pytest.fixture(scope="module")
def case1():
    return induced_frequencies(table1_case(1), window=CASE1_WINDOW, certify=True)


def test_case_1_is_proven_unstable_with_every_root_and_the_count(case1):
    c = case1.certificate
    assert c.all_proven and c.count == case1.count == 4 and c.proven_roots == 4
    assert c.verdict == "unstable"
    # the proven unstable root is Table 2's q = 0.222538 - 0.000130 i
    assert sum(e.below_axis for e in c.roots) == 1


def test_enclosures_contain_the_30_digit_roots_and_the_printed_digits(case1):
    precise = Characteristic(bind(table1_case(1)))
    printed = table2_printed(1)
    for r, e in zip(case1.roots, case1.certificate.roots):
        with mpmath.workdps(30):
            q30, _ = newton(precise, mpmath.mpc(complex(r.q)))  # an independent polish from 16 digits
        assert e.contains(q30)
        assert float(e.radius) <= 1e-25
        pr = min(printed, key=lambda p: abs(complex(r.q) - complex(float(p[0]), float(p[1]))))
        assert e.rounds_to(pr[0], pr[1], 6)


def test_a_wrong_candidate_fails_the_proof(case1):
    bc = BallCharacteristic(bind(table1_case(1)), prec=200)
    q = case1.roots[0].q
    assert krawczyk(bc, q).certified
    assert not krawczyk(bc, q + mpmath.mpf("1e-20")).certified  # the root is outside this ball
    assert not krawczyk(bc, mpmath.mpc("0.25", "0.01")).certified  # no root near
    # the printed digits alone are not a ball of radius 1e-26 around the root
    assert not krawczyk(bc, mpmath.mpc("0.307227", "0.021025")).certified


def test_json_output_has_the_certified_fields(capsys):
    # The small window stops inside the far-field radius: the verdict about every root with Im q < 0 is
    # UNDETERMINED (exit status 1), while the certificate proves the roots and the count inside the window.
    assert main(["frequencies", "--case", "1", "--window", "0.5,0.1", "--certify", "--json"]) == 1
    data = json.loads(capsys.readouterr().out)
    assert data["verdict"]["state"] == "undetermined" and data["verdict"]["reasons"][0].startswith("window:")
    assert all(r["certified"] is True and float(r["radius"]) <= 1e-25 for r in data["roots"])
    assert data["certified"]["all"] is True and data["certified"]["count"] == data["count"] == 4
    assert data["certified"]["verdict"] == "unstable"


def test_ball_derivative_contains_the_double_pole_formula():
    # dE/dq from the series in balls.py against the double-pole residues of kernels/track.py
    params = table1_case(6)
    bc = BallCharacteristic(bind(params), prec=128)
    precise = Characteristic(bind(params))
    for q in (0.3 + 0.05j, 0.1 - 0.2j, 1.5 + 0.2j):
        Eb, dEb = bc.value_and_derivative(q)
        with mpmath.workdps(30), ctx.workprec(128):
            E, dE = precise.value_and_derivative(mpmath.mpc(q))
            # the balls evaluate Eq. (38), the block determinant is -1/2 times it (tests/test_vehicles.py)
            E, dE = -2 * E, -2 * dE
            E, dE = (acb(mpmath.nstr(v.real, 30), mpmath.nstr(v.imag, 30)) for v in (E, dE))
            # the balls reach the 30-digit reference values (up to their relative 1e-25 accuracy)
            assert (Eb - E).abs_lower() < 1e-25 * max(1, E.abs_upper())
            assert (dEb - dE).abs_lower() < 1e-25 * max(1, dE.abs_upper())
            assert Eb.rad() < 1e-20 and dEb.rad() < 1e-20
        # over a ball, the enclosure holds the values at its corners
        ball = square_ball(q, 1e-4)
        Ew = bc.value(ball)
        for corner in (1 + 1j, 1 - 1j, -1 + 1j, -1 - 1j):
            with mpmath.workdps(30):
                Ec = -2 * precise(mpmath.mpc(q + 1e-4 * corner))
            assert Ew.contains(acb(complex(Ec)))


@pytest.mark.parametrize("method", ["direct", "discs"])
def test_both_p_root_methods_enclose_the_point_values(method):
    """Each method of p-root balls over a q-ball (p_balls.py, p_discs.py) gives E_chr balls that hold the
    30-digit mpmath values at points of the ball (kernels/characteristic.py, an independent residue sum)."""
    params = table1_case(6)
    bc = BallCharacteristic(bind(params), prec=128, p_roots=method)
    assert bc.direct == (method == "direct")
    precise = Characteristic(bind(params))
    for q in (0.3 + 0.05j, 1.5 + 0.2j):
        ball = square_ball(q, 1e-6)
        upper, lower = bc.p_roots(ball)
        assert len(upper) + len(lower) == 4
        Ew = bc.value(ball)
        for z in (q, q + 9e-7 * (1 + 1j), q + 9e-7 * (1 - 1j), q - 9e-7):
            with mpmath.workdps(30):
                Ec = -2 * precise(mpmath.mpc(z))
            assert Ew.contains(acb(complex(Ec)))
        assert Ew.rad() < 1e-2 * Ew.abs_upper()  # a usable enclosure, not the whole plane


def test_p_root_method_is_checked():
    with pytest.raises(ValueError, match="p_roots"):
        BallCharacteristic(bind(table1_case(1)), p_roots="fast")


def test_isolated_p_roots_contain_known_roots():
    roots = [complex(1.5, 0.25), complex(-0.5, 1), complex(-1, -0.75), complex(2, -0.5)]
    with ctx.workprec(128):
        coeffs = list(reversed(acb_poly.from_roots([acb(z) for z in roots]).coeffs()))
        balls = isolate_roots(coeffs, 2.0**-120)
        assert len(balls) == 4
        for z in roots:
            assert sum(b.contains(acb(z)) for b in balls) == 1
        assert max(float(b.rad()) for b in balls) < 1e-30


@pytest.mark.parametrize("start", ["near", "far", "twice"])
def test_point_root_balls_from_given_approximations_hold_the_known_roots(start):
    """The Smith discs at a point after Newton steps from given approximations (near ones, as the roots at a
    neighbouring point; far or repeated ones, which fall back to Arb's root finder) each hold exactly one
    of the known roots, and are about as narrow as those of :func:`isolate_roots`."""
    roots = [complex(1.5, 0.25), complex(-0.5, 1), complex(-1, -0.75), complex(2, -0.5)]
    starts = {
        "near": [z + complex(1e-3, -2e-3) for z in roots],
        "far": [complex(10 * k, 1) for k in range(4)],
        "twice": [roots[0]] * 2 + roots[2:],
    }[start]
    with ctx.workprec(128):
        coeffs = list(reversed(acb_poly.from_roots([acb(z) for z in roots]).coeffs()))
        balls = point_root_balls(coeffs, 2.0**-120, [acb(z) for z in starts])
        reference = isolate_roots(coeffs, 2.0**-120)
        assert len(balls) == 4
        for z in roots:
            assert sum(b.contains(acb(z)) for b in balls) == 1
        assert max(float(b.rad()) for b in balls) < max(1e-30, 4 * max(float(b.rad()) for b in reference))


def test_arb_polynomial_gives_the_balls_of_horner():
    """N's coefficients over a q-ball evaluated by Arb's acb_poly (p_balls.py) and by Horner's scheme in
    Python, on wide and exact points: the same balls, bit for bit."""
    bc = BallCharacteristic(bind(table1_case(2)), prec=96)
    rng = random.Random(3)
    with ctx.workprec(96):
        for _ in range(20):
            q = square_ball(complex(rng.uniform(0.1, 3), rng.uniform(-1, 1)), rng.choice([0.0, 1e-4]))
            coeffs = [acb(c) for c in bc.foundation.n_coeffs(q, **bc.foundation_args)]
            p = square_ball(complex(rng.uniform(-5, 5), rng.uniform(-5, 5)), rng.choice([0.0, 1e-3]))
            a, b = horner(coeffs, p), _poly(coeffs)(p)
            assert (a.real.mid(), a.real.rad(), a.imag.mid(), a.imag.rad()) == (
                b.real.mid(),
                b.real.rad(),
                b.imag.mid(),
                b.imag.rad(),
            )


def test_proven_count_around_a_root_and_next_to_it(case1):
    bc = BallCharacteristic(bind(table1_case(1)), prec=96)
    q = complex(case1.roots[0].q)
    around = Rectangle(q.real - 0.01, q.real + 0.01, q.imag - 0.01, q.imag + 0.01)
    beside = Rectangle(q.real + 0.005, q.real + 0.03, q.imag - 0.01, q.imag + 0.01)
    assert proven_count(bc, around).count == 1
    assert proven_count(bc, beside).count == 0
    through = Rectangle(q.real, q.real + 0.01, q.imag - 0.01, q.imag + 0.01)  # the root on its edge
    with pytest.raises(NotProven):
        proven_count(bc, through, min_length=1e-6)


@pytest.mark.slow
def test_proven_count_equals_the_numerical_one_on_random_parameter_sets():
    rng = random.Random(16)
    for _ in range(2):
        params = DimensionlessParams.from_coefficients(
            eta_f=rng.choice(["0.02", "0.05", "0.1"]),
            eta_M=rng.randint(10, 50),
            d=f"{rng.uniform(0.8, 3):.2f}",
            cf1=f"{rng.uniform(1, 2.5):.2f}",
            cf2=f"{rng.uniform(0.01, 0.1):.3f}",
            kappa_v=f"{rng.uniform(0.02, 0.4):.3f}",
            eta_v=rng.choice(["0", "0.05"]),
            alpha=f"{rng.uniform(0.2, 0.9):.2f}",
        )
        window = Rectangle(-1e-3, 1.0, -0.3, 0.3 + float(params.eta_f))
        result = induced_frequencies(params, dps=20, extra_dps=10, window=window, check_window=False)
        assert result.count >= 1  # the window holds roots: the comparison below is not vacuous
        c = certify(result)
        assert c.count == result.count, (params, c.problems)
        assert c.all_proven, (params, c.problems)
        assert c.verdict == ("stable" if result.stable else "unstable"), (params, c.reason)


@pytest.mark.slow
def test_table2_certified_row_encloses_the_printed_case_5():
    table = compute_table2(cases=(5,), certify=True)
    row = table.to_dict()["cases"][0]
    # Case 5 of Table 2 (paper): four pairs, q = 0.206528 - 0.000472 i unstable, all six decimals enclosed
    assert row["certified"]["all"] and row["certified"]["count"] == 4
    assert row["certified"]["verdict"] == "unstable"
    assert row["certified"]["printed_enclosed"] == [True] * 4
    assert all(r["certified"] and r["radius"] == "1e-26" for r in row["roots"])
    assert "proven: 4/4 roots, count 4, verdict unstable, printed digits enclosed" in format_table2(table)


@pytest.mark.slow
def test_a_missing_root_is_caught_by_the_proven_count(case1):
    # drop the stable root 0.307 + 0.021 i from the numerical result: the proof must notice
    incomplete = dataclasses.replace(case1, roots=case1.roots[1:], certificate=None)
    c = certify(incomplete)
    assert not c.all_proven and c.count == 4
    assert any("root(s) proven" in p and "enclosure(s) inside" in p for p in c.problems)
    assert c.verdict == "unstable"  # still proven: an unstable root needs no count
    stable_only = dataclasses.replace(case1, roots=(case1.roots[0],), certificate=None)
    assert certify(stable_only).verdict == "not proven"


def _shoelace(corners) -> float:
    return 0.5 * sum((a.conjugate() * b).imag for a, b in zip(corners, corners[1:] + corners[:1]))


def test_staircases_bound_exactly_their_rectangles():
    # The proof counts once around a base rectangle and the columns on it. The boundary must run
    # counterclockwise around exactly those rectangles: its signed area (shoelace) equals their total area,
    # its corners are corners of the members (exact floats, no rounded copies), and the staircases with
    # the other regions and the unsearched strip still cover the window.
    params = load_params_file(EXAMPLES / "two-layer.toml")[0]
    window = Rectangle(-3e-3, 3.0, -3.0, 3.2)
    cut = cut_locus(bind(params), window.x0, window.x1)
    tiling = proof_tiling(window, cut, margin=1e-3, gap_height=0.1 * 6.2)
    stairs = [r for r in tiling.regions if isinstance(r, Staircase)]
    assert len(stairs) == 2 and all(len(s.rects) > 40 for s in stairs)
    for s in stairs:
        corners = list(s.corners)
        assert _shoelace(corners) == pytest.approx(sum(r.width * r.height for r in s.rects), rel=1e-12)
        member_corners = {complex(x, y) for r in s.rects for x in (r.x0, r.x1) for y in (r.y0, r.y1)}
        assert set(corners) <= member_corners
    others = [r for r in tiling.regions if not isinstance(r, Staircase)]
    pieces = [r for s in stairs for r in s.rects] + others
    total = sum(r.width * r.height for r in pieces + list(tiling.unsearched))
    assert total == pytest.approx(window.width * window.height, rel=1e-12)


@pytest.mark.slow
def test_two_layer_example_is_proven_stable():
    # The proof on a layered track (degree 6 in p: two roots |p| ~ 60 from the sleeper layer) against the
    # numerical search's count (itself checked against a dense scan in tests/test_layered_search.py).
    result = induced_frequencies(load_params_file(EXAMPLES / "two-layer.toml")[0], certify=True)
    c = result.certificate
    assert c.all_proven and not c.problems, c.problems
    assert c.count == result.count == 4 and c.proven_roots == 4
    assert c.verdict == "stable"


def _covers_exactly(region: Staircase) -> None:
    """The boundary runs counterclockwise around exactly the members: signed area (shoelace) equal to their
    total area, corners among the members' corners (exact floats)."""
    corners = list(region.corners)
    assert _shoelace(corners) == pytest.approx(sum(r.width * r.height for r in region.rects), rel=1e-12)
    member_corners = {complex(x, y) for r in region.rects for x in (r.x0, r.x1) for y in (r.y0, r.y1)}
    assert set(corners) <= member_corners


def test_window_but_the_strip_along_a_flat_cut_is_one_region():
    # Table 2's windows: the region below the band, the one above, the gap left of the cut and the columns
    # are counted as one region around the strip, which reaches the window's right edge; with the strip
    # they cover the window.
    window = Rectangle(-3e-3, 3.0, -3.0, 3.1)
    for case in (1, 5, 12):
        cut = cut_locus(bind(table1_case(case)), window.x0, window.x1)
        tiling = proof_tiling(window, cut, margin=1e-3, gap_height=0.1 * 6.1)
        assert len(tiling.regions) == 1 and isinstance(tiling.regions[0], Staircase)
        region = tiling.regions[0]
        _covers_exactly(region)
        assert region.width == window.width and region.height == window.height
        total = sum(r.width * r.height for r in list(region.rects) + list(tiling.unsearched))
        assert total == pytest.approx(window.width * window.height, rel=1e-12)


def test_strip_below_the_axis_is_one_region_around_the_notch():
    # The pieces of the strip below a cut on the real axis (columns to Im q = 0, the notch column under a
    # branch point to -NOTCH) are counted on the boundary of their union.
    pieces = pieces_below_axis(Rectangle(0.6, 3.0, -1e-3, 0.0), [0.8, 1.7])
    (region,) = strip_region(pieces)
    _covers_exactly(region)
    area = sum(r.width * r.height for r in pieces)
    assert _shoelace(list(region.corners)) == pytest.approx(area, rel=1e-12)
    assert len(region.corners) == 12  # the rectangle with two notches in its top edge


@pytest.mark.parametrize("start", ["end", "far"])
def test_direct_p_root_balls_from_given_approximations_hold_the_roots(start):
    """Over a q-ball, the Krawczyk balls started from given approximations (the roots at the ball's end, as
    a boundary segment gives them, or far ones, which fall back to the Smith discs at the centre) each hold
    exactly one root of N(p, q) at points of the ball (mpmath's polyroots at 30 digits), as those without."""
    bound = bind(table1_case(2))
    bc = BallCharacteristic(bound, prec=96)
    f, args = bc.foundation, bc.foundation_args
    a, b = 0.62 - 1e-4j, 0.6203 - 1e-4j
    with ctx.workprec(96):
        ball = acb(a).union(acb(b))
        at_end = [z.mid() for z in direct_root_balls(f, args, acb(a), bc.tol, 96)]
        approx = at_end if start == "end" else [acb(10 * k, 1) for k in range(4)]
        given = direct_root_balls(f, args, ball, bc.tol, 96, approx)
        plain = direct_root_balls(f, args, ball, bc.tol, 96)
        for q in (a, b, 0.5 * (a + b)):
            coeffs = [complex(acb(c).mid()) for c in f.n_coeffs(acb(q), **args)]
            with mpmath.workdps(30):
                roots = mpmath.polyroots(coeffs, maxsteps=200, extraprec=200)
            for balls in (given, plain):
                assert len(balls) == 4
                for p in roots:
                    inside = [
                        g.contains(acb(mpmath.nstr(p.real, 30), mpmath.nstr(p.imag, 30))) for g in balls
                    ]
                    assert sum(inside) == 1
        assert max(float(g.rad()) for g in given) < 2 * max(float(g.rad()) for g in plain)


def test_a_segment_is_split_only_at_a_point_between_its_ends():
    """The halves of a boundary segment (winding.py) cover it only when m lies on it between a and b."""
    assert _between(0.25 - 1j, 0.5 - 1j, 0.75 - 1j) and _between(2 + 0.5j, 2 + 0.25j, 2 + 0j)
    assert not _between(0.25 - 1j, 0.8 - 1j, 0.75 - 1j)
    assert not _between(0.25 - 1j, 0.5 - 1.0000001j, 0.75 - 1j)
    assert not _between(0j, 0.5 + 0.5j, 1 + 1j)
