"""Large-|q| behaviour of K and E_chr: what lets the runtime search the lower half-plane completely.

For every model (beam x track, ``foundations.all_models()``) and every vehicle (``system.SYSTEMS``),
generically:

1. **Kernel decay.** The roots p_k(q) of N(p, q) grow like |q|^beta, one beta per edge of the upper
   Newton polygon of N in (deg_p, deg_q): on an edge, w(beta) = max over the monomials p^a q^b of a beta + b
   is attained by two or more of them (dominant balance; p^4 = 4 q^2, beta = 1/2, for Euler-Bernoulli,
   Eq. (24); beta = 1 for Timoshenko-Rayleigh). A root of size |q|^beta has a residue Q/N' of size
   |q|^(w_Q(beta) - w_N(beta) + beta) in Eq. (29), so K(xi, q) = O(|q|^-gamma) with
   gamma = min over the edges of w_N - w_Q - beta (3/2 for Euler-Bernoulli, 1 for Timoshenko-Rayleigh). The
   bound holds for K(+-d, q) too: their residues carry factors e^{i p_k d} of modulus below 1 (upward closure
   for +d, downward for -d).
2. **Leading part of E_chr.** E_chr is a polynomial in q, K0, K+, K- (Eq. (38)); give q^a K0^i K+^j K-^k the
   order a - gamma (i + j + k). The terms of the top order m form E_lead (for the bogie
   4 B1^2 B2 B3 (K0^2 - K+ K-) with the B's of Eq. (37) reduced to their leading powers); every other
   term is smaller by at least |q|^-delta, delta = m - (next order) (1/2 for Euler-Bernoulli, 1 for
   Timoshenko-Rayleigh).
3. **The radius R** (runtime, ``roots/count/far_field.py``): where |E_chr - E_lead| < |E_lead|, E_chr cannot
   vanish
   (a zero of E_chr would give |E_lead| < |E_lead|). The relative size |E_chr - E_lead| / |E_lead| is
   O(|q|^-delta) / |1 - K+ K- / K0^2|; for Euler-Bernoulli the leading residues give
   K+ K- / K0^2 -> (i/2) e^{-2 i sqrt(2q) d}, of modulus <= 1/2 in the lower half-plane, so the ratio
   tends to 0.
   The runtime checks the ratio with a margin on circles |q| = R, 2R, ..., 32R in the lower half-plane.
"""

import functools
from dataclasses import dataclass
from fractions import Fraction

import sympy as sp

from . import symbols as s
from .emit import definition_digest, function_source, module_source
from .model import foundation_image, power_of
from .system import SYSTEMS, in_q


@dataclass(frozen=True)
class KernelDecay:
    """Growth of the p-roots (|p| ~ |q|^beta, one beta per polygon edge) and decay of K (O(|q|^-gamma))."""

    betas: tuple
    gamma: Fraction


def _weight(monomials: set, beta: Fraction) -> Fraction:
    """max over the monomials p^a q^b (exponent pairs (a, b), :func:`_monomials`) of a beta + b."""
    return max(a * beta + b for a, b in monomials)


def _monomials(expr: sp.Expr) -> set:
    """The exponent pairs (a, b) of the monomials p^a q^b with a nonzero coefficient in the expanded
    polynomial ``expr`` (what ``sp.Poly(expr, p, q).monoms()`` lists, read off its terms: an expanded sum
    holds each monomial once)."""
    out = set()
    for term in sp.Add.make_args(expr):
        factors = sp.Mul.make_args(term)
        out.add((sum(power_of(f, s.p) for f in factors), sum(power_of(f, s.q) for f in factors)))
    return out


def kernel_decay(track) -> KernelDecay | None:
    """Newton-polygon slopes beta of N(p, q) and the decay gamma of K(xi, q) for large |q| (Eq. (29)).

    None when K does not decay (gamma <= 0): no far-field expansion is generated for such a model.
    Derived once per image (the kernel module and the asymptotics module both ask).
    """
    return _decay(foundation_image(track))


@functools.cache
def _decay(image) -> KernelDecay | None:
    N, Q = _monomials(image.N), _monomials(image.Q)
    candidates = {Fraction(b1 - b2, a2 - a1) for a1, b1 in N for a2, b2 in N if a2 > a1 and b1 > b2}
    betas = set()
    for beta in candidates:
        weight = _weight(N, beta)
        if len({a for a, b in N if a * beta + b == weight}) >= 2:
            betas.add(beta)
    if not betas:
        return None
    gamma = min(_weight(N, beta) - _weight(Q, beta) - beta for beta in betas)
    return KernelDecay(tuple(sorted(betas)), gamma) if gamma > 0 else None


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


def asymptotics_module(models: dict) -> str:
    """Source of ``generated/asymptotics.py``: gamma per model, E_lead per (vehicle, model).

    ``models`` maps a model name (the ``foundation_<name>`` module) to its TrackModel.
    """
    decays = {name: kernel_decay(model) for name, model in models.items()}
    decays = {name: d for name, d in decays.items() if d is not None}
    parts, order, gap, definitions = [], {}, {}, []
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
            definitions.append(lead.E_lead)
    # Exponents as exact fraction text ("3/2"): the generated modules carry no float literals.
    constants = [
        ("ROOT_GROWTH", {name: tuple(str(b) for b in d.betas) for name, d in decays.items()}),
        ("KERNEL_DECAY", {name: str(d.gamma) for name, d in decays.items()}),
        ("LEADING_ORDER", order),
        ("LEADING_GAP", gap),
    ]
    title = (
        "Large-|q| behaviour (derivations/asymptotics.py): |p_k| ~ |q|^ROOT_GROWTH,\n"
        "K = O(|q|^-KERNEL_DECAY), E_chr = E_lead (1 + O(|q|^-LEADING_GAP)),\n"
        "E_lead = e_chr_leading_<vehicle>_<model>."
    )
    digest = definition_digest(*definitions, *[value for _, value in constants])
    return module_source(title, digest, parts, constants)
