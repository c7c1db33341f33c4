"""Large-|q| behaviour of K and E_chr: what lets the runtime search the lower half-plane completely.

For every track model (``foundations.MODELS``) and every vehicle (``system.SYSTEMS``), generically:

1. **Kernel decay.** The roots p_k(q) of N(p, q) grow like |q|^beta, where beta is the slope of the single
   upper edge of the Newton polygon of N in (deg_p, deg_q): every monomial p^a q^b has a beta + b <= w_N with
   equality at p^deg and at the pure power of q (dominant balance; e.g. p^4 = 4 q^2, beta = 1/2, for
   Euler-Bernoulli, Eq. (24)). Substituting p = q^beta P in Eq. (29),
   K(xi, q) = integral of e^{i p xi} Q/N dp = O(|q|^(w_Q - w_N + beta)) = O(|q|^-gamma),
   gamma = w_N - w_Q - beta (3/2 for Euler-Bernoulli, 1 for Timoshenko-Rayleigh). This holds for K(0, q)
   and bounds K(+-d, q) too: the residue sum of K(+-d) is that of K(0) with factors e^{i p_k d} of modulus
   below 1 (upward closure for +d, downward for -d).
2. **Leading part of E_chr.** E_chr is a polynomial in q, K0, K+, K- (Eq. (38)); give q^a K0^i K+^j K-^k the
   order a - gamma (i + j + k). The terms of the top order m form E_lead (for the bogie
   4 B1^2 B2 B3 (K0^2 - K+ K-) with the B's of Eq. (37) reduced to their leading powers); every other
   term is smaller by at least |q|^-delta, delta = m - (next order) (1/2 for Euler-Bernoulli, 1 for
   Timoshenko-Rayleigh).
3. **The radius R** (runtime, ``roots/far_field.py``): where |E_chr - E_lead| < |E_lead|, E_chr cannot vanish
   (a zero of E_chr would give |E_lead| < |E_lead|). The relative size |E_chr - E_lead| / |E_lead| is
   O(|q|^-delta) / |1 - K+ K- / K0^2|; for Euler-Bernoulli the leading residues give
   K+ K- / K0^2 -> (i/2) e^{-2 i sqrt(2q) d}, of modulus <= 1/2 in the lower half-plane, so the ratio
   tends to 0.
   The runtime checks the ratio with a margin on circles |q| = R, 2R, ..., 32R in the lower half-plane.
"""

from dataclasses import dataclass
from fractions import Fraction

import sympy as sp

from . import symbols as s
from .foundations import MODELS
from .model import foundation_image
from .system import SYSTEMS, in_q


@dataclass(frozen=True)
class KernelDecay:
    """Growth of the p-roots (|p| ~ |q|^beta) and decay of K (|K| = O(|q|^-gamma)) of one track model."""

    beta: Fraction
    gamma: Fraction


def _weights(poly: sp.Poly, beta: Fraction) -> list:
    """Order a beta + b of every monomial p^a q^b of ``poly`` (a Poly in p, q)."""
    return [a * beta + b for a, b in poly.monoms()]


def kernel_decay(track) -> KernelDecay:
    """Newton-polygon slope beta of N(p, q) and the decay gamma of K(xi, q) for large |q| (Eq. (29))."""
    image = foundation_image(track)
    N = sp.Poly(image.N, s.p, s.q)
    Q = sp.Poly(image.Q, s.p, s.q)
    a_top = N.degree(s.p)
    b_top = max(b for a, b in N.monoms() if a == a_top)
    b_zero = max(b for a, b in N.monoms() if a == 0)
    beta = Fraction(b_zero - b_top, a_top)
    w_N = max(_weights(N, beta))
    if w_N != b_zero or w_N != a_top * beta + b_top:
        raise AssertionError(
            "N(p, q) has a Newton polygon with several upper edges: p-roots of several sizes"
        )
    gamma = w_N - max(_weights(Q, beta)) - beta
    if gamma <= 0:
        raise AssertionError(f"K does not decay for large |q| (gamma = {gamma})")
    return KernelDecay(beta, gamma)


@dataclass(frozen=True)
class LeadingPart:
    """E_lead (in q, K0, K+, K- and the vehicle parameters), its order m and the gap delta to the rest."""

    E_lead: sp.Expr
    order: Fraction
    decay: Fraction


def leading_part(system, gamma: Fraction) -> LeadingPart:
    """Top-order terms of E_chr when q^a K^c counts as |q|^(a - gamma c) (K = O(|q|^-gamma))."""
    E = in_q(system.E_chr, system)
    kernels = (s.K0, s.Kp, s.Km)
    poly = sp.Poly(E, s.q, *kernels)
    orders = {}
    for monom, coeff in poly.terms():
        a, *c = monom
        order = a - gamma * sum(c)
        term = coeff * s.q**a * sp.Mul(*(k**e for k, e in zip(kernels, c)))
        orders.setdefault(order, []).append(term)
    ranked = sorted(orders, reverse=True)
    m = ranked[0]
    return LeadingPart(sp.expand(sp.Add(*orders[m])), m, m - ranked[1])


def asymptotics_module(digest, module_source, function_source) -> str:
    """Source of ``generated/asymptotics.py``: gamma per track, E_lead per (vehicle, track)."""
    decays = {name: kernel_decay(MODELS[name]()) for name in MODELS}
    parts, order, gap = [], {}, {}
    for vname in SYSTEMS:
        system = SYSTEMS[vname]()
        args = ("q", "K0", "Kp", "Km", *(str(x) for x in system.parameters), "pi")
        for tname, decay in decays.items():
            lead = leading_part(system, decay.gamma)
            fname = f"e_chr_leading_{vname}_{tname}"
            doc = (
                f"Leading part of E_chr ({vname} on '{tname}') for large |q|: order |q|^{lead.order}, "
                f"the rest smaller by |q|^-{lead.decay}."
            )
            parts.append(function_source(fname, args, [lead.E_lead], doc, scalar=True))
            order[(vname, tname)] = str(lead.order)
            gap[(vname, tname)] = str(lead.decay)
    # Exponents as exact fraction text ("3/2"): the generated modules carry no float literals.
    constants = [
        ("ROOT_GROWTH", {name: str(d.beta) for name, d in decays.items()}),
        ("KERNEL_DECAY", {name: str(d.gamma) for name, d in decays.items()}),
        ("LEADING_ORDER", order),
        ("LEADING_GAP", gap),
    ]
    title = (
        "Large-|q| behaviour (derivations/asymptotics.py): |p_k| ~ |q|^ROOT_GROWTH,\n"
        "K = O(|q|^-KERNEL_DECAY), "
        "E_chr = E_lead (1 + O(|q|^-LEADING_GAP)) with E_lead = e_chr_leading_<vehicle>_<track>."
    )
    return module_source(title, digest, parts, constants)
