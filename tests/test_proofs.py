"""The paper's printed formulas against the derivation: ``derivations.paper.all_proofs()``.

Every proof is either "equal" (printed == derived, symbolically) or a recorded "erratum" that
``docs/errata.md`` explains. The expected outcome of every proof is listed here, so a regression that turns
an "equal" into an "erratum" (or a new, unreviewed proof) fails. ``docs/proofs.md`` is the generated table
of the same proofs; that it is current is checked by ``tests/test_derivations_current.py``.

A few errata are also re-derived here from the derivation's building blocks, independently of paper.py,
and the printed matrix of Eqs. (30)-(34) is compared entry by entry with the derived one.
"""

from __future__ import annotations

import functools
import sys
from collections import Counter
from pathlib import Path

import pytest
from derivation_support import require_sympy

sp = require_sympy()

REPO = Path(__file__).resolve().parents[1]
if str(REPO) not in sys.path:  # derivations/ is a top-level folder of the repository, not installed
    sys.path.insert(0, str(REPO))

from derivations import symbols as s  # noqa: E402
from derivations.foundations import euler_bernoulli_pasternak  # noqa: E402
from derivations.model import foundation_image  # noqa: E402
from derivations.paper import _printed_bogie_atoms, all_proofs  # noqa: E402
from derivations.system import bogie_system, in_q, masses_system  # noqa: E402

ERRATA = REPO / "docs" / "errata.md"

#: (equation, statement) of every proof expected to show printed == derived.
EXPECTED_EQUAL = {
    ("(24)", "D(p,q) of the Euler-Bernoulli beam (eta_s = 0)"),
    ("(37)", "B1 of Eq. (37)"),
    ("(37)", "B2 of Eq. (37)"),
    ("(37)", "B3 of Eq. (37)"),
    ("(37)", "B4 of Eq. (37)"),
    ("(23)", "load bracket at the rear wheel (times i q)"),
    ("(25)", "bounce equation of the bar"),
    ("(26)", "pitch equation of the bar"),
    ("(30)-(34), (38)", "det(A) = E_chr"),
    ("(36), (39), (40)", "numerator of the w_rear residue sum"),
    ("(41)", "numerator of the w_front residue sum"),
    ("(42)", "numerator of the u residue sum"),
    ("(43)", "numerator of the theta residue sum"),
    ("Fig. 1a", "E_chr of two moving masses, B1 = eta_M q^2"),
    ("(60)-(62)", "D = N/Q of the Timoshenko-Rayleigh beam, reading w_rr as w_tautau"),
    ("(61)-(62)", "image of the cross-section rotation, Phi/W"),
    ("(65)", "alpha_cr^2 of the Euler-Bernoulli beam with Pasternak term"),
}

#: (equation, statement) of every proof expected to record an erratum of the print.
EXPECTED_ERRATUM = {
    ("(18), (24)", "Pasternak term omitted from the dimensionless equation and from D"),
    ("(18)", "damping coefficient of w_tau in the dimensionless beam equation"),
    ("(14)", "moment equilibrium of the bogie bar (twice Eq. (4))"),
    ("(45)", "E1 of the deflection shape"),
    ("(46)", "E2 of the deflection shape"),
    ("(60)", "inertia term of the Timoshenko-Rayleigh beam equation"),
}


@functools.cache
def _proofs():
    return tuple(all_proofs())


def _by_key():
    return {(p.equation, p.statement): p for p in _proofs()}


def test_every_proof_is_equal_or_an_erratum():
    bad = [p for p in _proofs() if p.status not in ("equal", "erratum")]
    assert not bad, bad


def test_proofs_are_unique():
    counts = Counter((p.equation, p.statement) for p in _proofs())
    assert all(n == 1 for n in counts.values()), [k for k, n in counts.items() if n > 1]


def test_expected_equal_results_hold():
    """A regression that turns one of these into an erratum (or drops it) fails here."""
    proofs = _by_key()
    missing = sorted(EXPECTED_EQUAL - set(proofs))
    assert not missing, f"proofs no longer produced: {missing}"
    regressed = {k: proofs[k].evidence for k in sorted(EXPECTED_EQUAL) if proofs[k].status != "equal"}
    assert not regressed, f"printed != derived for formulas that used to agree: {regressed}"
    for key in EXPECTED_EQUAL:
        assert proofs[key].evidence == "printed - derived = 0", key


def test_expected_errata_are_recorded_and_no_proof_is_unreviewed():
    proofs = _by_key()
    missing = sorted(EXPECTED_ERRATUM - set(proofs))
    assert not missing, f"errata no longer produced: {missing}"
    changed = sorted(k for k in EXPECTED_ERRATUM if proofs[k].status != "erratum")
    assert not changed, f"expected errata now read 'equal' (update docs/errata.md and this test): {changed}"
    unreviewed = sorted(set(proofs) - EXPECTED_EQUAL - EXPECTED_ERRATUM)
    assert not unreviewed, (
        f"new proofs {unreviewed}: add them to EXPECTED_EQUAL or EXPECTED_ERRATUM (errata: docs/errata.md)"
    )


def test_every_erratum_is_explained_in_errata_md():
    text = ERRATA.read_text()
    assert text.startswith("# Errata of the paper")
    labels = sorted({p.equation for p in _proofs() if p.status == "erratum"})
    unexplained = [label for label in labels if label not in text]
    assert not unexplained, f"errata without an explanation in docs/errata.md: {unexplained}"


def test_e1_e2_correction_is_verified():
    """Eqs. (45)-(46): the printed B3 (before the square bracket and first inside it) read as B4 gives the
    derived shape weights; paper.py records whether that correction reproduces the derivation exactly."""
    proofs = _by_key()
    for key in (("(45)", "E1 of the deflection shape"), ("(46)", "E2 of the deflection shape")):
        evidence = proofs[key].evidence
        assert evidence.endswith("makes the printed formula equal to the derived one: verified."), evidence


# --- errata re-derived from the building blocks, independently of paper.py ---------------------------------


def test_pasternak_term_is_the_only_difference_from_the_printed_d():
    """(18), (24): derived D - printed D = 4 eta_s p^2; this eta_s gives Eq. (65), alpha_cr^2 = 1 + eta_s."""
    p, q, alpha, eta_f, eta_s = s.p, s.q, s.alpha, s.eta_f, s.eta_s
    printed = p**4 - 4 * p**2 * alpha**2 - 4 * q**2 + 8 * alpha * p * q
    printed += 8 * sp.I * eta_f * (q - alpha * p) + 4
    derived = foundation_image(euler_bernoulli_pasternak()).N
    assert sp.expand(derived - printed - 4 * eta_s * p**2) == 0
    # Undamped, q = 0: D = 0 has a real double root in p exactly at alpha^2 = 1 + eta_s (p^2 = 2).
    d0 = derived.subs({q: 0, eta_f: 0, alpha: sp.sqrt(1 + eta_s)})
    assert sp.expand(d0 - (p**2 - 2) ** 2) == 0


def test_eq14_with_the_lever_arm_is_twice_eq4():
    """(14): 2 J theta'' + k_v (...) d + c_v (...)' d = 2 x Eq. (4); the print lacks the first d."""
    th, w1, w2, dt = sp.symbols("theta w1 w2 dt")
    J, k_v, c_v, d = s.J_phys, s.k_v, s.c_v, s.d_phys
    eq4 = J * dt**2 * th + k_v * (w1 - w2 + th * d) * d / 2 + c_v * dt * (w1 - w2 + th * d) * d / 2
    corrected14 = 2 * J * dt**2 * th + k_v * (w1 - w2 + th * d) * d + c_v * dt * (w1 - w2 + th * d) * d
    printed14 = 2 * J * dt**2 * th + k_v * (w1 - w2 + th * d) + c_v * dt * (w1 - w2 + th * d) * d
    assert sp.expand(corrected14 - 2 * eq4) == 0
    assert sp.factor(printed14 - 2 * eq4) == sp.factor(k_v * (1 - d) * (w1 - w2 + th * d))


def test_printed_system_matrix_30_34_is_the_derived_one():
    """Eqs. (30)-(34) entry by entry (the proof "(30)-(34), (38)" compares only the determinant)."""
    q, d, K0, Kp, Km, pi, iu = s.q, s.d, s.K0, s.Kp, s.Km, sp.pi, sp.I
    eta_M, kappa_v, eta_v, mu_v, J_b = s.eta_M, s.kappa_v, s.eta_v, s.mu_v, s.J_b
    b1 = eta_M * q**2 - kappa_v - 2 * eta_v * iu * q
    b4 = kappa_v + 2 * eta_v * iu * q
    printed = sp.Matrix(
        [
            [pi - 2 * b1 * K0, -2 * b1 * Km, -2 * b4 * K0 - 2 * b4 * Km, b4 * K0 * d - b4 * Km * d],
            [-2 * b1 * Kp, pi - 2 * b1 * K0, -2 * b4 * Kp - 2 * b4 * K0, b4 * Kp * d - b4 * K0 * d],
            [b4, b4, mu_v * q**2 - 2 * kappa_v - 4 * eta_v * iu * q, 0],
            [
                kappa_v * d + 2 * eta_v * iu * q * d,
                -kappa_v * d - 2 * eta_v * iu * q * d,
                0,
                -2 * J_b * q**2 + kappa_v * d**2 + 2 * eta_v * iu * q * d**2,
            ],
        ]
    )
    # Right-hand side of (30) times i q (the unknowns are i q times the images): 4 eta_p (K0 + K-), ...
    printed_rhs = sp.Matrix([4 * (K0 + Km), 4 * (Kp + K0), 0, 0])
    system = bogie_system()
    derived = system.matrix.applyfunc(lambda e: in_q(e, system))
    assert (printed - derived).applyfunc(sp.expand) == sp.zeros(4, 4)
    assert (printed_rhs - system.rhs).applyfunc(sp.expand) == sp.zeros(4, 1)


@pytest.mark.parametrize("build", [bogie_system, masses_system], ids=["bogie", "masses"])
def test_shape_weights_pass_through_the_wheels(build):
    """Eqs. (44), (47) at xi = 0 and xi = d must give the contact deflections of Eqs. (36)/(39) and (41):
    G_rear K0 + G_front K- = 2 pi n_rear and G_rear K+ + G_front K0 = 2 pi n_front, identically in q."""
    system = build()
    g_rear, g_front = system.shape_weights
    n_rear, n_front = system.numerators["w_rear"], system.numerators["w_front"]
    K0, Kp, Km = s.K0, s.Kp, s.Km
    assert sp.expand(g_rear * K0 + g_front * Km - 2 * sp.pi * n_rear) == 0
    assert sp.expand(g_rear * Kp + g_front * K0 - 2 * sp.pi * n_front) == 0


def test_printed_e1_e2_do_not_pass_through_the_wheels():
    """Eqs. (45)-(46) as printed: the deflection shape (44) misses the rear wheel (the erratum matters)."""
    E, nums, E1, E2 = _printed_bogie_atoms()
    miss = sp.expand((8 * E + E1) * s.K0 + (8 * E + E2) * s.Km - 2 * sp.pi * nums["w_rear"])
    assert miss != 0
