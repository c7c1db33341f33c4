"""Governing equations: fixed coordinates -> moving coordinates -> dimensionless -> Laplace-Fourier images.

Implements the chain Eqs. (1)-(4) -> (10)-(14) -> (15)-(20) -> (21)-(26) and, for the Timoshenko-Rayleigh
beam, (55)-(56) -> (57)-(58) -> (59)-(61) -> (62). Because every operator has constant coefficients, a
change of coordinates is a substitution of operator symbols and the transforms with homogeneous initial
conditions replace d/dxi by i p and d/dtau by i q.
"""

import functools
from dataclasses import dataclass

import sympy as sp
from sympy.polys.matrices import DomainMatrix
from sympy.polys.polyerrors import CoercionFailed, ExactQuotientFailed

from .symbols import (
    B1,
    B2,
    B3,
    B4,
    EI,
    PHYSICAL_IN_DIMENSIONLESS,
    J_b,
    J_phys,
    M,
    M_b,
    P,
    c_v,
    chi,
    d,
    d_phys,
    dr,
    dt,
    dtau,
    dx,
    dxi,
    eta_M,
    eta_v,
    k_f,
    k_v,
    kappa_v,
    m,
    mu_v,
    omega,
    p,
    q,
    v,
    w_st,
)

I = sp.I  # noqa: E741


def to_moving(op: sp.Expr) -> sp.Expr:
    """Eq. (10): with r = x - v t, d/dx = d/dr and d/dt|_x = d/dt|_r - v d/dr."""
    return sp.expand(op.subs({dx: dr, dt: sp.Symbol("dt_r")}).subs(sp.Symbol("dt_r"), dt - v * dr))


def to_dimensionless(op: sp.Expr, scale: sp.Expr) -> sp.Expr:
    """Eqs. (15)-(17): r = xi/chi, t = tau/omega; the result is multiplied by ``scale`` and every physical
    parameter is replaced by its dimensionless group. EI, m, k_f, P must drop out (checked).

    The replacements are made all at once (``xreplace``): no right-hand side holds a replaced symbol
    (``symbols.declare`` checks it for the groups), so that is the same as one after the other (``subs``).
    """
    op = op.xreplace({dr: chi * dxi, dt: omega * dtau}) * scale
    op = sp.expand(sp.powsimp(sp.expand(op.xreplace(PHYSICAL_IN_DIMENSIONLESS)), force=True))
    leftover = op.free_symbols & {EI, m, k_f, P}
    if leftover:
        raise AssertionError(f"dimensionless operator still depends on {sorted(map(str, leftover))}: {op}")
    return op


def transform(op: sp.Expr) -> sp.Expr:
    """Eqs. (21)-(22) with homogeneous initial conditions: d/dxi -> i p, d/dtau -> i q."""
    return sp.expand(op.subs({dxi: I * p, dtau: I * q}))


@dataclass(frozen=True)
class ContactImages:
    """Laplace images of the loads and bar equations, Eqs. (23), (25), (26), as derived.

    ``F_rear``/``F_front`` are i q times the load amplitudes at xi = 0 and xi = d (the brackets of Eq. (23)
    multiplied by i q), as linear forms in the unknowns' images times i q: ``W0``, ``Wd``, ``U``, ``Th``
    stand for i q W~(0,q), i q W~(d,q), i q U, i q Theta. ``bounce`` and ``pitch`` are Eqs. (25), (26).
    """

    F_rear: sp.Expr
    F_front: sp.Expr
    bounce: sp.Expr
    pitch: sp.Expr
    B: dict  # B1..B4 of Eq. (37) as derived from the coefficients


W0, Wd, U, Th = sp.symbols("W0 Wd U Th")


def contact_images() -> ContactImages:
    """Derive the moving-load terms of Eq. (12) and the bar equations (13)-(14) in transformed form.

    In moving coordinates the contact points are fixed at r = 0 and r = d, so w_01(t) = w(0, t) and its
    total time derivatives are plain d/dt (this is the content of Eqs. (5)-(6) after Eq. (10)).
    Physical time derivatives become omega * i q after the Laplace transform; displacements are
    w = w_st w~, u = w_st u~, theta = w_st chi theta~ (Eq. (16)); delta(r) = chi delta(xi).
    """
    s = omega * I * q  # d/dt in the Laplace image
    w1, w2, u, th = sp.symbols("w1 w2 u th")  # physical images (per unit of 1/(i q) for the step load)
    load_step = P  # P is a step load: its image is P/(i q); we work with i q times every image
    f1 = load_step - M * s**2 * w1 - k_v * (w1 - u + th * d_phys / 2) - c_v * s * (w1 - u + th * d_phys / 2)
    f2 = load_step - M * s**2 * w2 - k_v * (w2 - u - th * d_phys / 2) - c_v * s * (w2 - u - th * d_phys / 2)
    bounce = M_b * s**2 * u - k_v * (w1 + w2 - 2 * u) - c_v * s * (w1 + w2 - 2 * u)
    pitch = J_phys * s**2 * th + (k_v + c_v * s) * (w1 - w2 + th * d_phys) * d_phys / 2
    dimensionless = {w1: w_st * W0, w2: w_st * Wd, u: w_st * U, th: w_st * chi * Th}
    # delta(r) = chi delta(xi); the beam equation is scaled by 4 / (k_f w_st) (Eq. (18)).
    load_scale = chi * 4 / (k_f * w_st)

    def clean(e, scale):
        e = (e.xreplace(dimensionless) * scale).xreplace(PHYSICAL_IN_DIMENSIONLESS)
        return sp.expand(sp.powsimp(sp.expand(e), force=True))

    F_rear = clean(f1, load_scale)
    F_front = clean(f2, load_scale)
    bounce_d = clean(bounce, chi / (k_f * w_st))  # Eq. (13) -> (19): multiply by chi/(k_f w_st)
    pitch_d = clean(pitch, 2 * chi**2 / (k_f * w_st))  # Eq. (14) -> (20): multiply by 2 chi^2/(k_f w_st)
    for e in (F_rear, F_front, bounce_d, pitch_d):
        if e.free_symbols & {EI, m, k_f, P}:
            raise AssertionError(f"contact equation not dimensionless: {e}")
    # Read B1..B4 of Eq. (37) off the derived coefficients (the sign conventions of the paper).
    B = {
        B1: sp.expand(F_rear.coeff(W0) / 4),  # F = 8 + 4 B1 W0 + ...
        B4: sp.expand(F_rear.coeff(U) / 4),  # ... + 2 B4 (2 U - Th d)
        B2: sp.expand(-bounce_d.coeff(U)),  # Eq. (25): (mu_v q^2 - 2 B4) U + ...
        B3: sp.expand(pitch_d.coeff(Th)),  # Eq. (26): (-2 J_b q^2 + B4 d^2) Theta + ...
    }
    return ContactImages(F_rear, F_front, sp.expand(-bounce_d), pitch_d, B)


def printed_B() -> dict:
    """B1..B4 as printed in Eq. (37), for the proof in ``paper.py``."""
    return {
        B1: eta_M * q**2 - kappa_v - 2 * I * q * eta_v,
        B2: mu_v * q**2 - 2 * kappa_v - 4 * I * q * eta_v,
        B3: -2 * J_b * q**2 + kappa_v * d**2 + 2 * I * q * eta_v * d**2,
        B4: kappa_v + 2 * I * q * eta_v,
    }


@dataclass(frozen=True)
class FoundationImage:
    """The transformed track operator: W~(p, q) = (load image) * Q / N, i.e. D(p, q) = N / Q (Eq. (24)).

    ``N`` and ``Q`` are polynomials in p whose coefficients are polynomials in q and the dimensionless
    groups. They are normalised so that Q(0, 0) = 1 where Q(0, 0) is a monomial in the groups (a sum, as on
    the layered tracks, is kept: dividing by it would make every coefficient a rational function; K = Q/N
    does not depend on the normalisation); for the Euler-Bernoulli beam Q = 1 and N = D of Eq. (24)
    (plus the Pasternak term). For Timoshenko-Rayleigh N is the quartic of Section 3.3, Q comes from Eq. (62).
    """

    N: sp.Expr
    Q: sp.Expr


def foundation_image(track) -> FoundationImage:
    """Eliminate every unknown but w from a track operator matrix (fixed physical coordinates).

    Rows are moved to moving coordinates (Eq. (10)), made dimensionless (Eqs. (15)-(18), (59)) and
    transformed (Eqs. (21)-(22)). The first row is scaled like Eq. (18); other rows' scale cancels in Q/N.
    By Cramer's rule the image of w for a load on row 1 is load * cofactor_00 / det.

    The image depends only on the operator and the scales, so it is derived once per process for each
    (the generated kernel module and the asymptotics both need it).
    """
    return _image(sp.ImmutableMatrix(track.operator), tuple(track.row_scales), tuple(track.unknown_scales))


#: Coefficient domains in which a determinant is exact polynomial arithmetic (Gaussian integers or
#: rationals, and polynomial rings over them).
_EXACT = (sp.ZZ, sp.QQ, sp.ZZ_I, sp.QQ_I)


def expanded_det(matrix: sp.Matrix, divisor: sp.Expr = sp.S.One) -> sp.Expr:
    """``sp.expand(det(matrix) / divisor)`` for a matrix of polynomials (Berkowitz, division-free).

    Computed in the polynomial ring of the entries (``DomainMatrix``), divided there when ``divisor``
    divides it, and converted to an expression once: the same polynomial as
    ``sp.expand(matrix.det(method="berkowitz") / divisor)`` without expanding products of large
    expressions. Entries outside a polynomial ring over the Gaussian rationals take that path.
    """
    dm = DomainMatrix.from_Matrix(matrix)
    domain = dm.domain
    if domain not in _EXACT and not (domain.is_PolynomialRing and domain.domain in _EXACT):
        return sp.expand(matrix.det(method="berkowitz") / divisor)
    det = dm.charpoly()[-1]  # det(x I - A) at x = 0: (-1)^n det A
    det = -det if matrix.shape[0] % 2 else det
    try:
        return sp.expand(domain.to_sympy(domain.exquo(det, domain.from_sympy(divisor))))
    except (CoercionFailed, ExactQuotientFailed):
        return sp.expand(domain.to_sympy(det) / divisor)


@functools.cache
def _entry_image(entry: sp.Expr, scale: sp.Expr) -> sp.Expr:
    """One operator entry moved (Eq. (10)), made dimensionless (Eqs. (15)-(18)) and transformed (Eqs. (21)-
    (22)); derived once per process: the beam's and the layers' entries recur in every model built on them."""
    return transform(to_dimensionless(to_moving(entry), scale))


@functools.cache
def _image(operator, row_scales, unknown_scales) -> FoundationImage:
    n = operator.shape[0]
    transformed = sp.zeros(n, n)
    for i in range(n):
        for j in range(n):
            scale = row_scales[i] * unknown_scales[j]
            transformed[i, j] = _entry_image(operator[i, j], scale)
    cof = expanded_det(transformed[1:, 1:]) if n > 1 else sp.Integer(1)
    norm = cof.subs({p: 0, q: 0})
    if norm == 0:
        raise AssertionError("cofactor vanishes at p = q = 0: cannot normalise Q")
    if norm.is_Add:
        # divide by the integer content only: the coefficients stay polynomials in the groups
        norm = sp.Poly(norm, *sorted(norm.free_symbols, key=str)).content() if norm.free_symbols else norm
    return FoundationImage(N=expanded_det(transformed, norm), Q=sp.expand(cof / norm))


def power_of(factor: sp.Expr, var: sp.Symbol) -> int:
    """k when ``factor`` is var**k (k a positive integer), 0 when it is free of ``var``; else ValueError."""
    if factor == var:
        return 1
    if factor.is_Pow and factor.base == var and factor.exp.is_Integer and factor.exp > 0:
        return int(factor.exp)
    if factor.has(var):
        raise ValueError(f"{factor} is not a power of {var}: expand the polynomial first")
    return 0


def terms_by_power(expr: sp.Expr, var: sp.Symbol) -> dict:
    """``{k: [t_1, t_2, ...]}``: an expanded polynomial in ``var`` read term by term, expr = sum of
    var**k t_i. An expanded sum holds each monomial once, so a k that occurs has a nonzero coefficient."""
    out: dict = {}
    for term in sp.Add.make_args(expr):
        k, rest = 0, []
        for factor in sp.Mul.make_args(term):
            j = power_of(factor, var)
            k += j
            if not j:
                rest.append(factor)
        out.setdefault(k, []).append(sp.Mul(*rest))
    return out


@functools.cache
def coefficients(expr: sp.Expr, var: sp.Symbol) -> tuple:
    """(degree, coefficients highest first, each expanded) of ``expr`` as a polynomial in ``var``.

    What ``sp.Poly(expr, var)`` gives coefficient by coefficient, read off the expanded sum directly: a
    Poly over the other symbols of a layered track's N(p, q) costs seconds. Asked for again by the kernel
    module and the cut line (Eq. (24)), so derived once per process.
    """
    terms = terms_by_power(sp.expand(expr), var)
    degree = max(terms)
    # the terms of an expanded sum are expanded monomials: their sum is expanded as it is built
    return degree, tuple(sp.Add(*terms.get(k, ())) for k in range(degree, -1, -1))


def derivative(expr: sp.Expr, var: sp.Symbol) -> sp.Expr:
    """d/d``var`` of an expanded polynomial, term by term (``sp.diff`` of each monomial: k var**(k-1) t)."""
    return sp.Add(
        *[k * var ** (k - 1) * t for k, terms in terms_by_power(expr, var).items() if k for t in terms]
    )
