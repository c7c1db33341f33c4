"""Vehicle systems: the 4x4 bogie system (30)-(34), the 2x2 system of two moving masses, E_chr and numerators.

Unknowns are i q times the Laplace images: W0 = i q W~(0,q), Wd = i q W~(d,q), U = i q U~, Th = i q Theta~.
The beam rows come from Eq. (28) at xi = 0 and xi = d:
    2 pi W0 = F_rear K0 + F_front K-,      2 pi Wd = F_rear K+ + F_front K0,
with F_rear, F_front the derived load brackets of Eq. (23) (times i q). Beam rows are divided by 2 so the
matrix is the paper's A of Eq. (30). The bar rows are Eqs. (25)-(26) as derived in ``model.py``.

The linear algebra runs on the atoms B1..B4 and K0, K+, K- (Eq. (37)); the B's are substituted afterwards.
For every response X in (W0, Wd, U, Th): X = n_X / E_chr, where E_chr = det(A) / c with a constant c
(c = 1 for both systems: with the beam rows halved as in Eq. (30), det(A) is Eq. (38) itself).
The time response is then the residue sum of Eqs. (36)-(43):
    x(tau) = n_X(0)/E_chr(0) + sum_j n_X(q_j) e^{i q_j tau} / (q_j E_chr'(q_j)).
The deflection at any xi is i q W~(xi, q) = (G_rear K(xi) + G_front K(xi - d)) / (2 pi E_chr),
G = E_chr * F, which are 8 E_chr + E1 and 8 E_chr + E2 of Eqs. (44)-(47).
"""

from dataclasses import dataclass

import sympy as sp

from .model import W0, Th, U, Wd, contact_images, expanded_det
from .symbols import B1, B2, B3, B4, K0, Km, Kp, d, eta_M, q

pi = sp.pi


@dataclass(frozen=True)
class VehicleSystem:
    """A derived vehicle system, everything as SymPy expressions in q, K0, K+, K- and parameters."""

    name: str
    unknowns: tuple  # symbols, i q times the images
    matrix: sp.Matrix  # A of Eq. (30) (beam rows / 2), in atoms
    rhs: sp.Matrix
    det_factor: sp.Expr  # det(A) = det_factor * E_chr
    E_chr: sp.Expr  # in atoms
    numerators: dict  # name -> n_X in atoms
    shape_weights: tuple  # (G_rear, G_front) in atoms
    atoms: dict  # atom -> expression in q and parameters
    parameters: tuple  # parameter symbols, in argument order


def _beam_rows(F_rear, F_front):
    return [W0 - (F_rear * K0 + F_front * Km) / (2 * pi), Wd - (F_rear * Kp + F_front * K0) / (2 * pi)]


def _solve(equations, unknowns):
    """Cramer's rule on the linear system; returns (A, b, det, numerators)."""
    A, b = sp.linear_eq_to_matrix([sp.expand(e * pi) for e in equations], unknowns)
    # Rows were multiplied by pi above (beam rows then read pi W0 - ... as in Eq. (30)); bar rows are
    # rescaled back so that they read exactly as Eqs. (25)-(26).
    for i in range(2, len(unknowns)):
        A[i, :] = A[i, :] / pi
        b[i] = b[i] / pi
    det = expanded_det(A)
    nums = []
    for j in range(len(unknowns)):
        Aj = A.copy()
        Aj[:, j] = b
        nums.append(expanded_det(Aj))
    return A, b, det, nums


def bogie_system() -> VehicleSystem:
    """The bogie of Figure 1b: a rigid bar on two spring-dampers over two wheel masses, Eqs. (23)-(47)."""
    c = contact_images()
    # The load brackets in atoms; model.contact_images derived them with B1..B4 read off its coefficients,
    # and paper.py proves that substituting the atoms back reproduces the derived brackets.
    F_rear = 8 + 4 * B1 * W0 + 2 * B4 * (2 * U - Th * d)
    F_front = 8 + 4 * B1 * Wd + 2 * B4 * (2 * U + Th * d)
    bounce = B2 * U + B4 * (W0 + Wd)
    pitch = B3 * Th + B4 * d * (W0 - Wd)
    atoms = c.B
    _check_atomised([(F_rear, c.F_rear), (F_front, c.F_front), (bounce, c.bounce), (pitch, c.pitch)], atoms)
    unknowns = (W0, Wd, U, Th)
    A, b, det, nums = _solve(_beam_rows(F_rear, F_front) + [bounce, pitch], unknowns)
    factor = sp.Integer(1)  # det(A) of Eq. (30) is E_chr of Eq. (38) itself (proved in paper.py)
    E = sp.expand(det / factor)
    numerators = {name: sp.expand(n / factor) for name, n in zip(("w_rear", "w_front", "u", "theta"), nums)}
    # G = E_chr * F with the unknowns replaced by n_X (X = n_X / E_chr).
    sub = {W0: numerators["w_rear"], Wd: numerators["w_front"], U: numerators["u"], Th: numerators["theta"]}
    G_rear = sp.expand(8 * E + (F_rear - 8).subs(sub))
    G_front = sp.expand(8 * E + (F_front - 8).subs(sub))
    params = tuple(sorted(set().union(*(e.free_symbols for e in atoms.values())) - {q}, key=str))
    return VehicleSystem("bogie", unknowns, A, b, factor, E, numerators, (G_rear, G_front), atoms, params)


def masses_system() -> VehicleSystem:
    """Two moving masses (Figure 1a): the bogie's loads with no suspension, B1 = eta_M q^2."""
    F_rear = 8 + 4 * B1 * W0
    F_front = 8 + 4 * B1 * Wd
    atoms = {B1: eta_M * q**2}
    unknowns = (W0, Wd)
    A, b, det, nums = _solve(_beam_rows(F_rear, F_front), unknowns)
    factor = sp.Integer(1)
    E = sp.expand(det / factor)
    numerators = {name: sp.expand(n / factor) for name, n in zip(("w_rear", "w_front"), nums)}
    sub = {W0: numerators["w_rear"], Wd: numerators["w_front"]}
    G_rear = sp.expand(8 * E + (F_rear - 8).subs(sub))
    G_front = sp.expand(8 * E + (F_front - 8).subs(sub))
    return VehicleSystem("masses", unknowns, A, b, factor, E, numerators, (G_rear, G_front), atoms, (eta_M,))


def _check_atomised(pairs, atoms):
    for atomised, derived in pairs:
        if sp.expand(atomised.subs(atoms) - derived) != 0:
            raise AssertionError(f"atomised form {atomised} differs from the derived {derived}")


def in_q(expr: sp.Expr, system: VehicleSystem) -> sp.Expr:
    """Substitute the atoms B1..B4 by their expressions in q and the parameters."""
    return sp.expand(expr.subs(system.atoms))


def derivatives(system: VehicleSystem) -> dict:
    """dE_chr/dq = E_q + E_K0 K0' + E_K+ K+' + E_K- K-' (Eq. (40)): the partial derivatives, in q."""
    E = in_q(system.E_chr, system)
    return {
        "E_q": sp.expand(sp.diff(E, q)),
        "E_K0": sp.expand(sp.diff(E, K0)),
        "E_Kp": sp.expand(sp.diff(E, Kp)),
        "E_Km": sp.expand(sp.diff(E, Km)),
    }


SYSTEMS = {"bogie": bogie_system, "masses": masses_system}
