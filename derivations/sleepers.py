"""A rail on discrete supports every l (docs/sleepers.md): the beam symbol, the support and the lattice sum.

Every declared beam (``foundations.BEAMS``) may lie on discrete supports every ``l``, with the paper's
continuous foundation (``k_f``, ``c_f``) beside them, either of which may be zero. Two support elements,
each per support and per rail:

- ``sleepers``: a spring-dashpot ``k_sup``, ``c_sup``;
- ``sleepers-two-layer``: a railpad ``k_pad``, ``c_pad`` over a sleeper mass ``m_sl`` on the ballast
  ``k_bal``, ``c_bal``.

The scaling is the paper's (Eqs. (15)-(17)) with the smeared support stiffness ``k_e`` in the place of
``k_f``: ``k_e = k_sup / l`` (``k_pad / l`` on the two-layer support), chi = (k_e / (4 EI))^(1/4),
omega_e = sqrt(k_e / m), v_ref = (4 k_e EI / m^2)^(1/4). The frequency w = omega / omega_e, the wavenumber
p = k / chi, the bay lam = l chi. The groups of the supports are per unit length of rail (a support's
constant over l), so ``l -> 0`` with them held fixed is the continuous track of the same name: the paper's
one-layer track (``eta_f`` = eta_sup, k_f = k_e) and the two-layer track (k_1 = k_pad / l, m_2 = m_sl / l,
...).

Generated (``generated/sleepers.py``), for every beam:

- ``n_coeffs_<beam>(w, ...)``, ``q_coeffs_<beam>(w, ...)``: G~(p, w) = k_e G0 = Q~ / N~, the inverse of the
  beam symbol (beam operator + continuous foundation, d/dx -> -i k, d/dt -> i omega), as polynomials in
  p^2 (every beam is even in p), highest power first;
- ``moving_n_coeffs_<beam>(q, alpha, ...)``, ``moving_q_coeffs_<beam>``: the same at w = q + alpha p (the
  frequency a wavenumber p of a load moving at v sees, omega = Omega + k v), as polynomials in p, for the
  free-rail receptance by residues;

for every support, ``support_<track>(w, ...)`` = z = (Z_s / l) / k_e; and the exact scaling of every group
from SI. The lattice sum S~(p, w) = sum_j G~(p + j K, w), K = 2 pi / lam, is the closed form
sum over the roots r of N~ of (lam / 2) cot(lam (p - r) / 2) Res(G~, r) (Res = Q~(r) / dN~/dp(r)):
:func:`lattice_sum_check` proves it numerically against the direct sum.
"""

from __future__ import annotations

import sympy as sp

from . import symbols as s
from .emit import SCALING_PRINTER, definition_digest, function_source, module_source
from .foundations import BEAMS

#: Symbols of this module: the smeared stiffness, the bay and the support elements (SI), and the groups.
k_e, l_bay = sp.symbols("k_e l", positive=True)
k_sup, c_sup = sp.symbols("k_sup c_sup", positive=True)
k_pad, c_pad, m_sl, k_bal, c_bal = sp.symbols("k_pad c_pad m_sl k_bal c_bal", positive=True)
lam, eta_sup, kappa_f, eta_f = sp.symbols("lam eta_sup kappa_f eta_f", positive=True)
mu_sl, kappa_bal, eta_pad, eta_bal = sp.symbols("mu_sl kappa_bal eta_pad eta_bal", positive=True)
w, p, q, alpha = sp.symbols("w p q alpha")

chi_e = (k_e / (4 * s.EI)) ** sp.Rational(1, 4)
omega_e = sp.sqrt(k_e / s.m)
v_ref_e = (4 * k_e * s.EI / s.m**2) ** sp.Rational(1, 4)

#: track -> (title, SI reference stiffness k_e, the track of the same name that l -> 0 gives).
TRACKS = {
    "sleepers": (
        "rail on discrete spring-dashpot supports (k_sup, c_sup) every l, optional continuous k_f, c_f",
        k_sup / l_bay,
        "one-layer",
    ),
    "sleepers-two-layer": (
        "rail on discrete railpads (k_pad, c_pad) over sleepers m_sl on ballast (k_bal, c_bal) every l,"
        " optional continuous k_f, c_f",
        k_pad / l_bay,
        "two-layer",
    ),
}

#: group -> (SI name, unit, SI meaning, SI in terms of the group (k_e, EI, m, l), constraint, default).
_COMMON = {
    "lam": ("l", "m", "distance between the supports (sleeper bay)", lam / chi_e, "positive", None),
    "alpha": ("v", "m/s", "velocity of the vehicle", alpha * v_ref_e, "nonnegative", None),
    "kappa_f": ("k_f", "N/m^2", "continuous foundation stiffness", kappa_f * k_e, "nonnegative", 0),
    "eta_f": (
        "c_f",
        "N s/m^2",
        "continuous viscous damping",
        2 * eta_f * sp.sqrt(s.m * k_e),
        "nonnegative",
        0,
    ),
}
_SUPPORT = {
    "sleepers": {
        "eta_sup": (
            "c_sup",
            "N s/m",
            "viscous damping of one support",
            2 * eta_sup * sp.sqrt(s.m * k_e) * l_bay,
            "nonnegative",
            0,
        ),
    },
    "sleepers-two-layer": {
        "eta_pad": (
            "c_pad",
            "N s/m",
            "railpad damping",
            2 * eta_pad * sp.sqrt(s.m * k_e) * l_bay,
            "nonnegative",
            0,
        ),
        "mu_sl": ("m_sl", "kg", "sleeper mass per rail", mu_sl * s.m * l_bay, "positive", None),
        "kappa_bal": (
            "k_bal",
            "N/m",
            "ballast stiffness per rail",
            kappa_bal * k_e * l_bay,
            "positive",
            None,
        ),
        "eta_bal": (
            "c_bal",
            "N s/m",
            "ballast damping per rail",
            2 * eta_bal * sp.sqrt(s.m * k_e) * l_bay,
            "nonnegative",
            0,
        ),
    },
}
#: the SI name of the reference stiffness of each track (k_e = that / l)
REFERENCE = {
    "sleepers": ("k_sup", "N/m", "stiffness of one support"),
    "sleepers-two-layer": ("k_pad", "N/m", "railpad stiffness"),
}


def support_stiffness(track: str) -> sp.Expr:
    """z(w) = (Z_s(omega) / l) / k_e, the dimensionless dynamic stiffness of the supports per unit length."""
    if track == "sleepers":
        return 1 + 2 * sp.I * eta_sup * w
    pad = 1 + 2 * sp.I * eta_pad * w
    sleeper = kappa_bal + 2 * sp.I * eta_bal * w - mu_sl * w**2
    return pad * sleeper / (pad + sleeper)


def _beam_groups(beam: str) -> tuple:
    """The paper's groups of the rail itself (S, r, eta_N), read with k_e in the place of k_f."""
    op = BEAMS[beam].operator
    physical = {x for x in op.free_symbols} - {s.dx, s.dt, s.EI, s.m}
    return tuple(g for g in s.GROUPS.values() if g.physical in physical)


def beam_symbol(beam: str) -> tuple[sp.Expr, sp.Expr]:
    """(N~, Q~): k_e G0(k, omega) = Q~ / N~ in p = k / chi, w = omega / omega_e (e^{i omega t - i k x}).

    G0 is the rail's response to a unit force at x = 0 (first unknown, first equation): the (0, 0) entry of
    the inverse of the operator matrix with d/dx -> -i k, d/dt -> i omega, plus the continuous foundation.
    """
    op = sp.Matrix(BEAMS[beam].operator)
    op[0, 0] += s.k_f + s.c_f * s.dt
    op = op.subs({s.dx: -sp.I * p * chi_e, s.dt: sp.I * w * omega_e})
    groups = {
        g.physical: s.PHYSICAL_IN_DIMENSIONLESS[g.physical].subs(s.k_f, k_e) for g in _beam_groups(beam)
    }
    op = op.subs({s.k_f: kappa_f * k_e, s.c_f: 2 * eta_f * sp.sqrt(s.m * k_e)}).subs(groups)
    g0 = k_e * op.adjugate()[0, 0] / op.det()
    num, den = sp.fraction(sp.cancel(sp.together(sp.expand(g0))))
    lead = sp.Poly(den, p).LC()
    num, den = sp.expand(num / lead), sp.expand(den / lead)
    if {s.EI, s.m, k_e} & (num.free_symbols | den.free_symbols):
        raise ValueError(f"{beam}: the symbol is not dimensionless: {den}")
    if sp.expand(den.subs(p, -p) - den) != 0 or sp.expand(num.subs(p, -p) - num) != 0:
        raise ValueError(f"{beam}: the symbol is not even in p")
    return den, num


def _in_p2(expr: sp.Expr) -> list:
    """Coefficients of an even polynomial in p as a polynomial in p^2, highest power first."""
    t = sp.Symbol("t")
    poly = sp.Poly(sp.expand(expr).subs(p**2, t), t) if expr.has(p) else sp.Poly(expr, t)
    return [sp.expand(c) for c in poly.all_coeffs()]


def _in_p(expr: sp.Expr) -> list:
    return [sp.expand(c) for c in sp.Poly(sp.expand(expr), p).all_coeffs()]


def _names(*exprs) -> tuple:
    found = {str(x) for e in exprs for x in e.free_symbols} - {"w", "p", "q"}
    order = list(dict.fromkeys(["alpha", "kappa_f", "eta_f", *(str(g.symbol) for g in s.GROUPS.values())]))
    unknown = found - set(order)
    if unknown:
        raise ValueError(f"undeclared groups {sorted(unknown)}")
    return tuple(n for n in order if n in found)


def beam_parts(beam: str) -> tuple[list, dict]:
    """The generated functions of one beam and its metadata (groups, degrees)."""
    den, num = beam_symbol(beam)
    groups = _names(den, num)
    args = ("w", *groups)
    moving = {w: q + alpha * p}
    m_den, m_num = sp.expand(den.subs(moving)), sp.expand(num.subs(moving))
    m_args = ("q", "alpha", *(g for g in groups if g != "alpha"))
    parts = [
        function_source(f"n_coeffs_{beam}", args, _in_p2(den), "N~(p, w) in p^2, highest power first."),
        function_source(f"q_coeffs_{beam}", args, _in_p2(num), "Q~(p, w) in p^2, highest power first."),
        function_source(
            f"moving_n_coeffs_{beam}", m_args, _in_p(m_den), "N~(p, q + alpha p) in p, highest power first."
        ),
        function_source(
            f"moving_q_coeffs_{beam}", m_args, _in_p(m_num), "Q~(p, q + alpha p) in p, highest power first."
        ),
    ]
    meta = {"groups": groups, "moving_groups": m_args[2:], "degree_p2": len(_in_p2(den)) - 1}
    return parts, meta


def group_table(track: str, beam_groups: tuple) -> dict:
    """name -> metadata of every group of ``track`` (support groups, then the common and the beam's)."""
    table = {}
    for name, (si, unit, meaning, _rel, constraint, default) in {**_SUPPORT[track], **_COMMON}.items():
        table[name] = {
            "si": si,
            "unit": unit,
            "si_meaning": meaning,
            "constraint": constraint,
            "default": default,
        }
    for g in beam_groups:
        table[str(g.symbol)] = {
            "si": g.si,
            "unit": g.unit,
            "si_meaning": g.si_meaning,
            "constraint": g.constraint,
            "default": None if g.default is None else str(g.default),
        }
    return table


def scaling_parts(track: str) -> list:
    """Exact group-from-SI functions of one track: k_e = reference / l, the relations solved for the group."""
    ref_name = REFERENCE[track][0]
    ref = sp.Symbol(ref_name, positive=True)
    parts = []
    relations = {**_SUPPORT[track], **_COMMON}
    tag = track.replace("-", "_")
    for name, (si, _unit, _meaning, relation, _c, _d) in relations.items():
        (group,) = [x for x in relation.free_symbols if str(x) == name]
        si_symbol = sp.Symbol(si, positive=True)
        (inverse,) = sp.solve(sp.Eq(si_symbol, relation), group)
        expr = sp.powsimp(inverse.subs(k_e, ref / l_bay), force=True)
        args = ("sqrt", *sorted({str(x) for x in expr.free_symbols}))
        parts.append(
            function_source(
                f"dimensionless_{tag}_{name}",
                args,
                [expr],
                f"{name} from SI on {track}.",
                scalar=True,
                printer=SCALING_PRINTER,
            )
        )
    scales = [x.subs(k_e, ref / l_bay) for x in (chi_e, v_ref_e, 1 / omega_e, ref / l_bay)]
    parts.append(
        function_source(
            f"scales_{tag}",
            ("sqrt", "EI", "m", ref_name, "l"),
            scales,
            "(chi [1/m], v_ref [m/s], t_scale [s], k_e [N/m^2]): Omega = w / t_scale, reference k_f = k_e.",
            printer=SCALING_PRINTER,
        )
    )
    return parts


def sleepers_module() -> str:
    """The text of ``generated/sleepers.py``."""
    parts, beams = [], {}
    for beam in BEAMS:
        beam_funcs, meta = beam_parts(beam)
        parts += beam_funcs
        beams[beam] = meta
    tracks, params = {}, {}
    for track, (title, _ref, limit) in TRACKS.items():
        z = support_stiffness(track)
        z_args = ("w", *sorted(str(x) for x in z.free_symbols if str(x) != "w"))
        z_num, z_den = sp.fraction(sp.cancel(sp.together(z)))
        parts.append(
            function_source(
                f"support_polynomials_{track.replace('-', '_')}",
                z_args[1:],
                [sp.Tuple(*sp.Poly(z_num, w).all_coeffs()), sp.Tuple(*sp.Poly(z_den, w).all_coeffs())],
                f"(numerator, denominator) of z(w) on {track} as polynomials in w, highest power first.",
            )
        )
        parts.append(
            function_source(
                f"support_{track.replace('-', '_')}",
                z_args,
                [z],
                f"z(w) = (Z_s / l) / k_e on {track}.",
                scalar=True,
            )
        )
        parts += scaling_parts(track)
        tracks[track] = {
            "description": title,
            "support_arguments": z_args[1:],
            "limit": limit,
            "reference": REFERENCE[track],
        }
        params[track] = {b: group_table(track, _beam_groups(b)) for b in BEAMS}
    constants = [
        ("TRACKS", tracks),
        ("BEAMS", beams),
        ("PARAMETERS", params),
    ]
    digest = definition_digest(
        *[BEAMS[b].operator for b in BEAMS],
        *[support_stiffness(t) for t in TRACKS],
        repr(_COMMON),
        repr(_SUPPORT),
    )
    title = (
        "A rail on discrete supports every l (docs/sleepers.md): beam symbols, supports, scaling.\n\n"
        "k_e G0(k, omega) = Q~/N~ in p = k/chi, w = omega/omega_e; z = (Z_s/l)/k_e; the lattice sum\n"
        "S~(p, w) = sum_j Q~/N~(p + j K, w) = sum over the roots r of N~ of\n"
        "(lam/2) cot(lam (p - r)/2) Q~(r)/N~'(r)."
    )
    return module_source(title, digest, parts, constants)


def lattice_sum_check(beam: str = "eb", *, terms: int = 4000) -> float:
    """Largest relative difference between the closed-form lattice sum and the direct sum at test points."""
    den, num = beam_symbol(beam)
    values = {
        sp.Symbol(n, positive=True): sp.Rational(v)
        for n, v in (("kappa_f", "1/5"), ("eta_f", "1/10"), ("S", 50), ("r", "1/20"), ("eta_N", "1/4"))
    }
    worst = 0.0
    for pw, ww, lv in ((0.3, 0.7 - 0.2j, 0.9), (1.7, 1.3 + 0.05j, 0.5)):
        nn = sp.lambdify(p, den.subs(values).subs(w, ww), "mpmath")
        qq = sp.lambdify(p, num.subs(values).subs(w, ww), "mpmath")
        dn = sp.lambdify(p, sp.diff(den, p).subs(values).subs(w, ww), "mpmath")
        import mpmath

        K = 2 * mpmath.pi / lv
        direct = mpmath.nsum(
            lambda j, qq=qq, nn=nn, pw=pw, K=K: qq(pw + j * K) / nn(pw + j * K), [-mpmath.inf, mpmath.inf]
        )
        roots = mpmath.polyroots(
            [complex(c) for c in _in_p(den.subs(values).subs(w, ww))], maxsteps=200, extraprec=60
        )
        closed = sum(lv / 2 * mpmath.cot(lv * (pw - rr) / 2) * qq(rr) / dn(rr) for rr in roots)
        worst = max(worst, float(abs(closed - direct) / abs(direct)))
    del terms
    return worst
