"""Modal blocks of a track model on a simply supported finite length: the finite-rail validation's equations.

The finite-beam validation (paper, Section 3.2, Eqs. (49)-(54)) expands the rail in sine modes. On any track
of ``foundations.py`` every unknown of the track operator is expanded in the mode shape that the simply
supported ends allow: the deflections (the rail's ``w``, every mass layer's) in ``sin(lambda x)``, the rail's
cross-section rotation of a Timoshenko-Rayleigh beam in ``cos(lambda x)`` (so ``w = phi_x = 0`` at the ends).
Because the operators have constant coefficients and no layer has bending stiffness, mode ``lambda`` of one
unknown couples only with mode ``lambda`` of the others: per mode a block

    M(lambda) y'' + C(lambda) y' + K(lambda) y = (load on the rail row),

with ``y`` the mode's amplitudes of every unknown (rail deflection first). It is the fixed-frame operator
matrix made dimensionless (Eqs. (15)-(18), (59); ``x = chi x_phys``, ``tau = t sqrt(k_f/m)``), with
``d/dtau`` read off as the time derivative and ``d/dx`` applied to the mode shapes: ``d/dx -> i lambda``
between unknowns of the same parity (``d^2/dx^2 sin = -lambda^2 sin``) and ``d/dx -> i lambda`` times
``i^(parity_j - parity_i)`` from a ``cos`` unknown ``j`` to a ``sin`` row ``i`` or back (``d/dx cos =
-lambda sin``, ``d/dx sin = lambda cos``). The parity of each unknown follows from the operator: odd powers of
``d/dx`` between two unknowns flip it. Galerkin projection on the same shape (each of norm ``L/2``), and every
row divided by the scale of the load on the rail row, the rail row's coefficient of ``d^2/dtau^2`` at
``lambda = 0`` (4, Eq. (18)), so the rail mode has unit translational mass and the moving loads enter the
rail row as ``(2/L) sum_j F_j sin(lambda x_j)`` whatever the beam (a rotary inertia stays in the block).
The blocks come out symmetric (checked): the models are self-adjoint.
"""

import sympy as sp

from .model import to_dimensionless
from .symbols import dr, dt, dtau, dx, dxi

#: The mode's wavenumber lambda = n pi / L (dimensionless).
lam = sp.Symbol("lam", positive=True)


def parities(operator: sp.Matrix) -> tuple:
    """0 (sine mode) or 1 (cosine mode) per unknown: the rail deflection is a sine, and an entry with odd
    powers of d/dx flips the parity between its row's and column's unknowns (mixed powers are refused)."""
    n = operator.shape[0]
    parity = {0: 0}
    changed = True
    while changed:
        changed = False
        for i in range(n):
            for j in range(n):
                entry = sp.expand(operator[i, j])
                if i == j or entry == 0 or (i in parity) == (j in parity):
                    continue
                powers = {sp.degree(term, dx) % 2 for term in sp.Add.make_args(entry)}
                if len(powers) != 1:
                    raise ValueError(f"entry ({i}, {j}) mixes odd and even powers of d/dx: {entry}")
                known, other = (i, j) if i in parity else (j, i)
                parity[other] = parity[known] ^ powers.pop()
                changed = True
    if len(parity) != n:
        raise ValueError("an unknown is not coupled to the rail: its mode shape is undetermined")
    return tuple(parity[k] for k in range(n))


def modal_blocks(track) -> tuple:
    """(M, C, K, parity): the per-mode mass, damping and stiffness matrices (SymPy, in ``lam``, groups).

    ``track`` is a ``TrackModel`` of ``foundations.compose``. Each matrix is ``n x n`` with ``n`` the number
    of unknowns (rail first); see the module docstring for the conventions.
    """
    operator = track.operator
    n = operator.shape[0]
    parity = parities(operator)
    entries = sp.zeros(n, n)
    for i in range(n):
        for j in range(n):
            scale = track.row_scales[i] * track.unknown_scales[j]
            # fixed frame (x read as r, no motion); Eqs. (15)-(17): d/dr -> chi d/dxi, d/dt -> omega d/dtau
            image = to_dimensionless(operator[i, j].subs(dx, dr), scale)
            image = sp.expand(image.subs(dxi, sp.I * lam) * sp.I ** (parity[j] - parity[i]))
            entries[i, j] = image
    # The scale of the load on the rail row (4, Eq. (18)): the rail row's d^2/dtau^2 coefficient of the mode
    # lam = 0 (a beam with rotary inertia adds lam-dependent mass above it, which stays in the block).
    unit = sp.Poly(entries[0, 0], dtau).coeff_monomial(dtau**2).subs(lam, 0)
    if unit.free_symbols or unit == 0:
        raise AssertionError(f"the rail row's mass at lam = 0 is not a nonzero constant: {unit}")
    blocks = []
    for order in (2, 1, 0):
        block = sp.zeros(n, n)
        for i in range(n):
            for j in range(n):
                block[i, j] = sp.expand(sp.Poly(entries[i, j], dtau).coeff_monomial(dtau**order) / unit)
        if block != block.T:
            raise AssertionError(f"modal block of d^{order}/dtau^{order} is not symmetric: {block}")
        if any(sp.im(e) != 0 for e in block):
            raise AssertionError(f"modal block of d^{order}/dtau^{order} is not real: {block}")
        blocks.append(block)
    if dt in set().union(*(e.free_symbols for e in entries)):
        raise AssertionError("d/dt left in the modal blocks")
    return (*blocks, parity)
