"""Every symbol of the derivation, declared once.

Physical quantities (SI) are positive reals; the dimensionless groups of Eqs. (15)-(17) and (59) are
positive reals too (zero values are limits that the runtime handles numerically). The transform variables
``p`` (Fourier, Eq. (22)) and ``q`` (Laplace with ``qbar = i q``, Eq. (21)) are complex.
"""

from dataclasses import dataclass

import sympy as sp

# --- physical (SI) ---------------------------------------------------------------------------------------
EI, m, k_f, k_s, c_f = sp.symbols("EI m k_f k_s c_f", positive=True)
M, M_b, J_phys, k_v, c_v = sp.symbols("M M_b J_phys k_v c_v", positive=True)
d_phys, v, P = sp.symbols("d_phys v P", positive=True)
# The car (derivations/vehicles.py): a body on two secondary suspensions over two bogies, per rail.
M_c, J_c_phys, k_sec, c_sec, L_phys = sp.symbols("M_c J_c_phys k_sec c_sec L_phys", positive=True)
# A wheel on a linearised Hertz contact spring (derivations/vehicles.py, hertz_mass).
k_H, c_H = sp.symbols("k_H c_H", positive=True)
GA, r_g = sp.symbols("GA r_g", positive=True)  # Timoshenko: G*Abar and radius of gyration
N_ax = sp.Symbol("N_ax", positive=True)  # axial compressive force in the rail (Metrikine & Dieterman 1997)
# Layered tracks: mass layers (sleepers, ballast) per unit length and their supports. The rail's support
# (the railpads) is k_f, c_f: the reference stiffness of the scaling, named k_1, c_1 on those tracks.
m_2, k_2, c_2, m_3, k_3, c_3 = sp.symbols("m_2 k_2 c_2 m_3 k_3 c_3", positive=True)

# --- scales, Eqs. (15)-(16) ------------------------------------------------------------------------------
chi = (k_f / (4 * EI)) ** sp.Rational(1, 4)
v_ref = (4 * k_f * EI / m**2) ** sp.Rational(1, 4)
w_st = P * chi / (2 * k_f)
omega = sp.sqrt(k_f / m)  # tau = omega * t

# --- dimensionless groups, Eqs. (16)-(17), (59), and the Pasternak group eta_s --------------------------
alpha, eta_f, eta_s = sp.symbols("alpha eta_f eta_s", positive=True)
mu_2, kappa_2, eta_2, mu_3, kappa_3, eta_3 = sp.symbols(
    "mu_2 kappa_2 eta_2 mu_3 kappa_3 eta_3", positive=True
)
eta_M, mu_v, J_b, kappa_v, eta_v, d = sp.symbols("eta_M mu_v J_b kappa_v eta_v d", positive=True)
S, r = sp.symbols("S r", positive=True)
eta_N = sp.Symbol("eta_N", positive=True)
mu_c, J_c, kappa_sec, eta_sec, L_c = sp.symbols("mu_c J_c kappa_sec eta_sec L_c", positive=True)
kappa_H, eta_H = sp.symbols("kappa_H eta_H", positive=True)

#: Physical parameter -> expression through the dimensionless groups (the inverse of Eq. (17)).
#: EI, m, k_f and P stay free: every dimensionless result must be independent of them. Filled by
#: :func:`declare` below, the one place where a dimensionless group, its SI counterpart and their relation
#: are written.
PHYSICAL_IN_DIMENSIONLESS = {}


@dataclass(frozen=True)
class Group:
    """Metadata of one dimensionless group, written once and generated into the runtime.

    ``constraint`` is "positive" (> 0), "nonnegative" (>= 0) or "underdamped" (0 <= x < 1); ``default``
    (exact, or None when required) is used when an input leaves the group out; ``si`` is the SI name of
    the physical parameter it scales (as the user types it), ``unit`` its SI unit. ``damping`` marks a
    viscous damping group: zero on the undamped track whose free waves give the critical velocity.
    """

    symbol: sp.Symbol
    meaning: str
    constraint: str
    equation: str
    default: sp.Rational | None
    physical: sp.Symbol
    si: str
    unit: str
    si_meaning: str
    damping: bool = False


#: name -> Group, in declaration order (the order of parameters in every generated list).
GROUPS = {}

#: SI parameters that set the scales (Eqs. (15)-(16)) and have no dimensionless group: (name, unit, meaning).
SCALE_PARAMETERS = (
    ("EI", "N m^2", "beam bending stiffness"),
    ("m", "kg/m", "beam mass per unit length"),
    ("k_f", "N/m^2", "foundation (Winkler) stiffness"),
    ("P", "N", "constant load on each wheel"),
)


def declare(
    symbol,
    physical,
    relation,
    *,
    meaning,
    constraint,
    equation,
    unit,
    si_meaning,
    default=None,
    si=None,
    damping=False,
):
    """Declare a dimensionless group: ``physical = relation`` (in the group and EI, m, k_f, P)."""
    if constraint not in ("positive", "nonnegative", "underdamped"):
        raise ValueError(f"{symbol}: unknown constraint {constraint!r}")
    declared = {physical, *PHYSICAL_IN_DIMENSIONLESS}
    if relation.free_symbols & declared or any(
        physical in r.free_symbols for r in PHYSICAL_IN_DIMENSIONLESS.values()
    ):
        # the derivation replaces every declared physical parameter at once (model.to_dimensionless)
        raise ValueError(f"{symbol}: {physical} = {relation} mixes the declared physical parameters")
    PHYSICAL_IN_DIMENSIONLESS[physical] = relation
    GROUPS[str(symbol)] = Group(
        symbol,
        meaning,
        constraint,
        equation,
        None if default is None else sp.Rational(default),
        physical,
        si or str(physical),
        unit,
        si_meaning,
        damping,
    )
    return symbol


declare(
    alpha,
    v,
    alpha * v_ref,
    meaning="velocity ratio v/v_ref",
    constraint="nonnegative",
    equation="(16)",
    unit="m/s",
    si_meaning="velocity of the vehicle",
)
declare(
    eta_f,
    c_f,
    2 * eta_f * sp.sqrt(m * k_f),
    meaning="foundation damping ratio c_f/(2 sqrt(m k_f))",
    constraint="underdamped",
    equation="(17)",
    unit="N s/m^2",
    si_meaning="foundation viscous damping",
    damping=True,
)
declare(
    eta_s,
    k_s,
    2 * eta_s * sp.sqrt(k_f * EI),
    meaning="Pasternak shear layer k_s/(2 sqrt(k_f EI))",
    constraint="nonnegative",
    equation="(17)",
    unit="N",
    si_meaning="foundation shear (Pasternak) stiffness",
    default=0,
)
declare(
    S,
    GA,
    2 * S * sp.sqrt(k_f * EI),
    meaning="Timoshenko shear parameter G Abar/(2 sqrt(k_f EI))",
    constraint="positive",
    equation="(59)",
    unit="N",
    si_meaning="shear stiffness G Abar of the beam",
)
declare(
    r,
    r_g,
    r / chi,
    meaning="radius of gyration r chi",
    constraint="nonnegative",
    equation="(59)",
    unit="m",
    si_meaning="radius of gyration of the cross-section",
)
declare(
    eta_N,
    N_ax,
    2 * eta_N * sp.sqrt(k_f * EI),
    meaning="axial compressive force N/(2 sqrt(k_f EI)); buckles the beam on its foundation at 1 + eta_s",
    constraint="nonnegative",
    equation="(A1)",
    unit="N",
    si_meaning="axial compressive force in the rail (thermal: N = E A alpha_T dT)",
    default=0,
)
declare(
    eta_M,
    M,
    eta_M * m / chi,
    meaning="wheel mass ratio M chi/m",
    constraint="positive",
    equation="(17)",
    unit="kg",
    si_meaning="mass of each wheel",
)
declare(
    d,
    d_phys,
    d / chi,
    meaning="wheel spacing d chi",
    constraint="positive",
    equation="(16)",
    unit="m",
    si_meaning="wheel spacing",
    si="d",
)
declare(
    mu_v,
    M_b,
    mu_v * m / chi,
    meaning="bogie-bar mass ratio M_b chi/m",
    constraint="positive",
    equation="(17)",
    unit="kg",
    si_meaning="bogie-bar mass",
)
declare(
    J_b,
    J_phys,
    J_b * m / chi**3,
    meaning="bogie-bar mass moment of inertia chi^3 J_b/m",
    constraint="positive",
    equation="(17)",
    unit="kg m^2",
    si_meaning="bogie-bar mass moment of inertia",
    si="J_b",
)
declare(
    kappa_v,
    k_v,
    kappa_v * k_f / chi,
    meaning="primary suspension stiffness k_v chi/k_f",
    constraint="positive",
    equation="(17)",
    unit="N/m",
    si_meaning="primary suspension stiffness (each side)",
)
declare(
    eta_v,
    c_v,
    eta_v * 2 * sp.sqrt(m * k_f) / chi,
    meaning="primary suspension damping c_v chi/(2 sqrt(m k_f))",
    constraint="nonnegative",
    equation="(17)",
    unit="N s/m",
    si_meaning="primary suspension damping (each side)",
    damping=True,
)

declare(
    L_c,
    L_phys,
    L_c / chi,
    meaning="distance between the bogie centres L_c chi",
    constraint="positive",
    equation="(16)",
    unit="m",
    si_meaning="distance between the bogie centres of a car",
    si="L_c",
)
declare(
    mu_c,
    M_c,
    mu_c * m / chi,
    meaning="car-body mass ratio M_c chi/m",
    constraint="positive",
    equation="(17)",
    unit="kg",
    si_meaning="car-body mass (per rail)",
)
declare(
    J_c,
    J_c_phys,
    J_c * m / chi**3,
    meaning="car-body mass moment of inertia chi^3 J_c/m",
    constraint="positive",
    equation="(17)",
    unit="kg m^2",
    si_meaning="car-body pitch moment of inertia (per rail)",
    si="J_c",
)
declare(
    kappa_sec,
    k_sec,
    kappa_sec * k_f / chi,
    meaning="secondary suspension stiffness k_sec chi/k_f",
    constraint="positive",
    equation="(17)",
    unit="N/m",
    si_meaning="secondary suspension stiffness (each bogie)",
)
declare(
    eta_sec,
    c_sec,
    eta_sec * 2 * sp.sqrt(m * k_f) / chi,
    meaning="secondary suspension damping c_sec chi/(2 sqrt(m k_f))",
    constraint="nonnegative",
    equation="(17)",
    unit="N s/m",
    si_meaning="secondary suspension damping (each bogie)",
    damping=True,
)
declare(
    kappa_H,
    k_H,
    kappa_H * k_f / chi,
    meaning="linearised Hertz contact stiffness k_H chi/k_f",
    constraint="positive",
    equation="(17)",
    unit="N/m",
    si_meaning="linearised Hertz contact stiffness between wheel and rail",
)
declare(
    eta_H,
    c_H,
    eta_H * 2 * sp.sqrt(m * k_f) / chi,
    meaning="contact damping c_H chi/(2 sqrt(m k_f))",
    constraint="nonnegative",
    equation="(17)",
    unit="N s/m",
    si_meaning="viscous damping of the contact between wheel and rail",
    default=0,
    damping=True,
)


# --- layered tracks (docs/layered_tracks.md): every mass layer scaled by the rail's m, every stiffness
# by the railpads' k_1 (= k_f, the reference stiffness), every damping like c_f.
def _declare_layer(j, mu, kappa, eta, mass, stiffness, damping, what):
    """The groups of mass layer j: its mass, the stiffness and damping of the support under it."""
    declare(
        mu,
        mass,
        mu * m,
        meaning=f"mass ratio m_{j}/m of the {what}",
        constraint="positive",
        equation="(L3)",
        unit="kg/m",
        si_meaning=f"mass per unit length of the {what}",
    )
    declare(
        kappa,
        stiffness,
        kappa * k_f,
        meaning=f"stiffness ratio k_{j}/k_1 of the support under the {what}",
        constraint="positive",
        equation="(L3)",
        unit="N/m^2",
        si_meaning=f"stiffness per unit length of the support under the {what}",
    )
    declare(
        eta,
        damping,
        2 * eta * sp.sqrt(m * k_f),
        meaning=f"damping ratio c_{j}/(2 sqrt(m k_1)) of the support under the {what}",
        constraint="nonnegative",
        equation="(L3)",
        unit="N s/m^2",
        si_meaning=f"viscous damping per unit length of the support under the {what}",
        damping=True,
    )


_declare_layer(2, mu_2, kappa_2, eta_2, m_2, k_2, c_2, "first mass layer (sleepers)")
_declare_layer(3, mu_3, kappa_3, eta_3, m_3, k_3, c_3, "second mass layer (ballast)")

#: Alternative inputs (Table 1, Eq. (63)): name -> (the group it sets, its expression, meaning). Giving the
#: alternative sets the group; when a group the expression depends on changes, the alternative is kept.
cf1, cf2 = sp.symbols("cf1 cf2", positive=True)
ALTERNATIVES = {
    "cf1": (mu_v, cf1 * eta_M, "bar-to-wheel mass coefficient mu_v/eta_M = M_b/M, Eq. (63)"),
    "cf2": (J_b, cf2 * eta_M * d**2, "bar inertia coefficient J_b/(eta_M d^2), Eq. (63)"),
}

# --- transform variables and operator symbols ------------------------------------------------------------
p = sp.Symbol("p")  # Fourier variable of xi, Eq. (22)
q = sp.Symbol("q")  # Laplace variable, qbar = i q, Eq. (21)
dx, dt = sp.symbols("dx dt")  # d/dx, d/dt in fixed physical coordinates (constant-coefficient operators)
dr = sp.Symbol("dr")  # d/dr in moving physical coordinates r = x - v t
dxi, dtau = sp.symbols("dxi dtau")  # d/dxi, d/dtau in moving dimensionless coordinates

# --- kernel values and auxiliary atoms of the vehicle system, Eq. (37) -----------------------------------
K0, Kp, Km = sp.symbols("K0 Kp Km")  # K(0,q), K(d,q), K(-d,q)
B1, B2, B3, B4 = sp.symbols("B1 B2 B3 B4")
