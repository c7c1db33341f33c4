"""A verdict for the whole lower half-plane: the far-field radius; UNDETERMINED when anything is missing.

References for Case 1 at alpha = 5: the roots with Im q < 0 of a brute-force scan (local minima of |E_chr|
on a dense grid polished by Newton and mpmath.findroot, ``benchmarks/bench_search_random.py``, no contour
code); Eq. (38) in closed form (``generated/vehicle_bogie.py``) with K(xi, q) by QUADPACK quadrature of
Eq. (29) over real p (``tests/test_track_kernel.py``), independent of the residue kernel.
"""

import json
from fractions import Fraction
from pathlib import Path

import mpmath
import numpy as np
import pytest
from scripts import load_script
from test_track_kernel import quadrature_K

from moving_bogie.api import induced_frequencies
from moving_bogie.cli import main
from moving_bogie.generated import asymptotics, vehicle_bogie
from moving_bogie.kernels.bound import bind
from moving_bogie.kernels.characteristic import CharacteristicArray
from moving_bogie.kernels.track import TrackKernelArray
from moving_bogie.model.cases import table1_case
from moving_bogie.roots.count import far_field
from moving_bogie.roots.count.contour import Rectangle
from moving_bogie.roots.count.far_field import far_field_radius, rho
from moving_bogie.roots.count.outcomes import Reason


def _scan_roots(params, window, n):
    """The brute-force roots with Im q < 0 of ``benchmarks/bench_search_random.py`` (no contour code)."""
    return load_script("benchmarks/bench_search_random.py").scan_roots(params, window, n=n)


@pytest.fixture(scope="module")
def supercritical():
    """Case 1 at alpha = 5 (issue 17): the default window of 3 used to miss two unstable pairs."""
    return induced_frequencies(table1_case(1).replace(alpha=5), dps=20)


def test_supercritical_case1_finds_every_unstable_root_without_a_window(supercritical):
    res = supercritical
    assert res.count_ok and res.verdict.state == "unstable"
    assert len(res.unstable_roots) == 3
    # Reference: the brute-force scan of the window (Re q >= 0; the roots with Re q < 0 are mirrors): the
    # same three roots, the lowest of them the degree of instability (its Im q is -4.16549...).
    scan = _scan_roots(res.params, Rectangle(0.0, res.window.x1, res.window.y0, 0.5), n=(241, 241))
    assert len(scan) == 3
    lowest = min(scan, key=lambda z: z.imag)
    assert float(res.degree_of_instability) == pytest.approx(lowest.imag, abs=1e-9)
    # Reference: the same count in an explicitly given window four times the far-field radius (other contours,
    # no far-field argument): no further root with Im q < 0 anywhere in it.
    R = res.far_field.radius
    big = induced_frequencies(
        res.params, dps=20, window=Rectangle(-4e-3 * R, 4 * R, -4 * R, 0.5), check_window=False
    )
    assert big.count_ok and len(big.unstable_roots) == 3

    def roots(result):
        return sorted((complex(r.q) for r in result.unstable_roots), key=lambda z: (z.real, z.imag))

    assert roots(big) == pytest.approx(roots(res), abs=1e-12)


@pytest.mark.slow
def test_supercritical_case1_most_unstable_root_is_a_zero_of_eq38_by_quadrature(supercritical):
    # Reference: E_chr of Eq. (38) in closed form with K(0), K(d), K(-d) by QUADPACK (independent of the
    # residue kernel). One secant step from the reported root moves it by its distance from the zero of
    # that E_chr (superlinear convergence): below 1e-10, where |E_chr| 1e-5 away is 1e8 times larger.
    res = supercritical
    q = complex(min(res.unstable_roots, key=lambda r: complex(r.q).imag).q)
    params = res.params
    d = float(params.d)
    vehicle = {name: float(getattr(params, name)) for name in vehicle_bogie.PARAMETERS}

    def e_chr(z):
        K0, Kp, Km = (quadrature_K(params, z, xi) for xi in (0.0, d, -d))
        return vehicle_bogie.e_chr(z, K0, Kp, Km, pi=np.pi, **vehicle)

    near = q * (1 + 1e-6)
    E, E_near = e_chr(q), e_chr(near)
    step = E * (q - near) / (E - E_near)
    assert abs(step) < 1e-10
    assert abs(E_near) > 1e6 * abs(E)


def test_derived_kernel_decay_matches_the_residues():
    # Euler-Bernoulli: p^4 = 4 q^2 at leading order (Eq. (24)); the two upper roots -sqrt(2q), i sqrt(2q) give
    # |K0| = pi / (4 |q|^(3/2)) by hand. The derivation says gamma = 3/2 (and 1 for Timoshenko-Rayleigh).
    assert asymptotics.KERNEL_DECAY["eb"] == "3/2" and asymptotics.KERNEL_DECAY["tr"] == "1"
    q = 1e6 * np.exp(1j * np.linspace(-3.0, -0.14, 9))
    K0 = TrackKernelArray(bind(table1_case(1)))(q, [0.0]).K[0]
    assert np.abs(K0) * np.abs(q) ** 1.5 == pytest.approx(np.pi / 4, rel=2e-3)
    tr = table1_case(1).replace(beam="tr", S=100, r="0.03")
    K_tr = [
        np.abs(TrackKernelArray(bind(tr))(np.array([R * np.exp(-1j)]), [0.0]).K[0]) * R for R in (1e4, 1e5)
    ]
    assert K_tr[1] == pytest.approx(K_tr[0], rel=0.05)  # |K0| |q| tends to a constant: gamma = 1


def test_relative_remainder_decays_as_derived():
    # rho = |E - E_lead| / |E_lead| = O(|q|^-delta), delta = 1/2 for the bogie on an EB beam: away from the
    # real axis, 16 times the radius divides rho by about 4.
    assert asymptotics.LEADING_GAP[("bogie", "eb")] == "1/2"
    p = table1_case(7)
    r1, r2 = (float(rho(bind(p), np.array([R * np.exp(-1.2j)]))[0]) for R in (1e3, 1.6e4))
    assert r1 / r2 == pytest.approx(4, rel=0.15)


@pytest.mark.parametrize(
    ("case", "changes"),
    [
        (5, {"alpha": "2.5"}),
        (13, {"kappa_v": "3", "alpha": "0.3"}),
        pytest.param(7, {"alpha": "3", "eta_M": "5"}, marks=pytest.mark.slow),  # the longest of the three
    ],
)
def test_far_field_radius_is_confirmed_by_a_larger_window(case, changes):
    p = table1_case(case).replace(**changes)
    res = induced_frequencies(p, dps=20)
    assert res.verdict.determined, res.verdict.reasons
    R = res.far_field.radius
    # Reference: argument-principle count in a window three times the radius, lower half-plane only.
    lower = induced_frequencies(
        p, dps=20, window=Rectangle(-3e-3 * R, 3 * R, -3 * R, -1e-6), check_window=False
    )
    assert lower.count == sum(1 for r in res.roots if mpmath.im(r.q) < -1e-6)


def test_window_inside_the_radius_is_undetermined(capsys):
    res = induced_frequencies(table1_case(1).replace(alpha=5), dps=20, window=Rectangle(-0.003, 3, -3, 3.1))
    assert res.verdict.state == "undetermined"
    assert [note.reason for note in res.verdict.reasons] == [Reason.WINDOW]  # WindowIncomplete, and only it
    assert res.to_dict()["verdict"]["reasons"][0].startswith("window: it stops at Re q = 3,")
    assert res.to_dict()["stable"] is None


def test_a_count_mismatch_is_its_own_reason(monkeypatch):
    """A root the search loses (locate returns one cell fewer, as if Newton's method had not found it) makes
    the count disagree: the result says CountMismatch, the verdict is UNDETERMINED for that reason alone,
    and the printed warning is rendered from it."""
    from moving_bogie.roots import frequencies

    complete = induced_frequencies(table1_case(1), dps=20)
    assert complete.count_ok and complete.verdict.determined and complete.count > 0
    located = frequencies.locate

    def loses_one(fast, rect, n, newton_cell):
        cells, missing = located(fast, rect, n, newton_cell)
        return cells[1:], missing

    monkeypatch.setattr(frequencies, "locate", loses_one)
    res = induced_frequencies(table1_case(1), dps=20)
    assert res.found < res.count == complete.count and not res.count_ok
    assert [note.reason for note in res.verdict.reasons] == [Reason.COUNT]
    assert [note.reason for note in res.notes] == [Reason.COUNT]
    assert res.warnings[0] == (
        f"count: the argument principle counts {res.count} root(s) with Re q >= 0, {res.found} were found "
        "and confirmed"
    )


def test_roots_left_unlocated_are_typed_and_counted_against_the_verdict(monkeypatch):
    """Roots counted in a cell but not located come back as an Unlocated with its LOCATE note; a cell that
    reaches below the axis (where a missing root may be unstable) makes the verdict UNDETERMINED, with
    CountMismatch as its reason (a cell wholly in Im q > 0 would not: its roots decay)."""
    from moving_bogie.roots import frequencies
    from moving_bogie.roots.count.outcomes import Note, Unlocated

    located = frequencies.locate

    def gives_up_below(fast, rect, n, newton_cell):
        if rect.y0 <= 0:
            return [], Unlocated(rect, n, Note(Reason.LOCATE, f"gave up on {rect}"))
        return located(fast, rect, n, newton_cell)

    monkeypatch.setattr(frequencies, "locate", gives_up_below)
    res = induced_frequencies(table1_case(1), dps=20)
    assert res.unlocated and res.found < res.count and all(u.cell.y0 <= 0 for u in res.unlocated)
    assert sum(u.missing for u in res.unlocated) == res.count - res.found
    assert Reason.LOCATE in [note.reason for note in res.notes]
    assert [note.reason for note in res.verdict.reasons] == [Reason.COUNT]


def test_undamped_sliver_is_undetermined_when_the_strip_is_not_counted(monkeypatch):
    """Case 2 (eta_f = 0): without the count of the strip below the cut (roots/count/strip.py, which decides
    it:
    tests/test_undamped_verdict.py), the sliver reaching below the axis leaves the verdict UNDETERMINED."""
    from moving_bogie.roots import frequencies

    monkeypatch.setattr(frequencies, "strip_below_cut", lambda *args, **kwargs: None)
    res = induced_frequencies(table1_case(2), dps=20)
    assert res.count_ok and res.verdict.state == "undetermined"
    assert [note.reason for note in res.verdict.reasons] == [Reason.SLIVER]


def test_missing_expansion_is_undetermined(monkeypatch):
    module = bind(table1_case(7)).foundation
    monkeypatch.setattr(module, "KERNEL_DECAY", None)
    far = far_field_radius(bind(table1_case(7)), 3.0)
    assert far.radius is None and "no far-field expansion" in far.reason
    assert far.to_dict()["rho"] is None  # valid JSON
    other = table1_case(7).replace(beam="tr", S=10, r="0.09")
    assert far_field.kernel_decay(bind(other)) == 1  # the other tracks are untouched


@pytest.mark.parametrize("vehicle", ["bogie", "masses"])
@pytest.mark.parametrize("track", ["eb", "tr", "eb_two_layer", "tr_three_layer"])
def test_block_leading_gap_is_the_derived_one(vehicle, track):
    """delta = min(2 - gamma, 1) of the block system against the symbolic expansion of Eq. (38)."""
    gamma = Fraction(asymptotics.KERNEL_DECAY[track])
    assert far_field.leading_gap(gamma) == Fraction(asymptotics.LEADING_GAP[(vehicle, track)])


def test_block_leading_part_is_the_derived_one():
    """E_lead of the block system is -1/2 times the generated symbolic E_lead of Eq. (38)."""
    p = table1_case(7)
    E = CharacteristicArray(bind(p))
    q = np.array([40 - 30j, -200 - 5j, 1e3 * np.exp(-2j)])
    kv = E.kernel_values(q)
    block = far_field.e_lead(E.system, q, kv.K)
    args = {name: getattr(p.as_float(), name) for name in E.module.PARAMETERS} | {"pi": np.pi}
    index = E.system.index  # offset xi_i - xi_j: K(0), K(d) = K(xi_1 - xi_0), K(-d) = K(xi_0 - xi_1)
    K0, Kp, Km = kv.K[index[0][0]], kv.K[index[1][0]], kv.K[index[0][1]]
    derived = asymptotics.e_chr_leading_bogie_eb(q, K0, Kp, Km, **args)
    np.testing.assert_allclose(block, -derived / 2, rtol=1e-10)


def test_cli_verdict_line_exit_status_and_stderr(capsys, monkeypatch, supercritical):
    # The text and the --json run below print the same search (same case, alpha, dps and window) as the
    # module's fixture: it runs once and all print it; the run with --window 3,3 is a search of its own.
    # (Two searches in all: a command that searched other parameters would make a third.)
    from moving_bogie.roots import frequencies

    searches, search = {}, frequencies.induced_frequencies
    searches[(supercritical.params, 20, repr(None), False)] = supercritical

    def once(bound, *, dps, window, progress=None, certify=False):
        key = (bound.params, dps, repr(window), certify)
        if key not in searches:
            searches[key] = search(bound, dps=dps, window=window, progress=progress, certify=certify)
        return searches[key]

    monkeypatch.setattr(frequencies, "induced_frequencies", once)
    assert main(["frequencies", "--case", "1", "--alpha", "5", "--dps", "20"]) == 0
    out = capsys.readouterr()
    assert "verdict: UNSTABLE, 3 unstable pair(s); degree of instability -4.16549" in out.out
    assert out.err == ""
    assert main(["frequencies", "--case", "1", "--alpha", "5", "--dps", "20", "--window", "3,3"]) == 1
    out = capsys.readouterr()
    (verdict,) = [line for line in out.out.splitlines() if line.startswith("verdict:")]
    assert verdict.startswith("verdict: UNDETERMINED: ") and "STABLE" not in verdict.replace(
        "UNDETERMINED", ""
    )
    assert "moving-bogie: warning: window:" in out.err and "WARNING" not in out.out
    assert main(["frequencies", "--case", "1", "--alpha", "5", "--dps", "20", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["count_ok"] and data["verdict"]["state"] == "unstable" and data["verdict"]["reasons"] == []
    # alpha = 5 is above the EB critical velocity sqrt(1 + eta_s) (Eq. (66)): the verdict says so
    eta_s = float(table1_case(1).eta_s)
    assert data["verdict"]["supercritical"] is True
    assert data["verdict"]["alpha_cr"] == pytest.approx((1 + eta_s) ** 0.5, rel=1e-9)
    assert data["degree_of_instability"] == "-4.16549" and data["far_field"]["radius"] == 12.0
    assert len(searches) == 2


@pytest.mark.parametrize(
    "source",
    ["case 7", "case 1, tr", "two-layer.toml", "car.toml"],
)
def test_far_field_samples_mirror(source):
    """The far-field check samples only Re q >= 0: rho(-conj q) = rho(q) (E_chr and E_lead have real
    coefficients). Checked against rho evaluated directly at the mirror points of the samples, for the
    bogie on both beams, a layered track and the car."""
    from moving_bogie.model.files import load_params_file

    examples = Path(__file__).resolve().parent.parent / "examples"
    if source.endswith(".toml"):
        params = load_params_file(examples / source)[0]
    else:
        params = table1_case(7) if source == "case 7" else table1_case(1).replace(beam="tr", S=10, r="0.09")
    bound = bind(params)
    q = far_field.sample_points(3.0)
    assert np.all(q.real >= 0) and np.all(q.imag < 0)
    q = q[:: max(1, q.size // 2000)]  # about 2000 of them: circles, rays and the imaginary axis alike
    here, there = rho(bound, q), rho(bound, -np.conj(q))
    assert np.all(np.isfinite(here))
    np.testing.assert_allclose(there, here, rtol=1e-8, atol=1e-14)
