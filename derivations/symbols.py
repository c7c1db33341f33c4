"""Every symbol of the derivation, declared once.

Physical quantities (SI) are positive reals; the dimensionless groups of Eqs. (15)-(17) and (59) are
positive reals too (zero values are limits that the runtime handles numerically). The transform variables
``p`` (Fourier, Eq. (22)) and ``q`` (Laplace with ``qbar = i q``, Eq. (21)) are complex.
"""

import sympy as sp

# --- physical (SI) ---------------------------------------------------------------------------------------
EI, m, k_f, k_s, c_f = sp.symbols("EI m k_f k_s c_f", positive=True)
M, M_b, J_phys, k_v, c_v = sp.symbols("M M_b J_phys k_v c_v", positive=True)
d_phys, v, P = sp.symbols("d_phys v P", positive=True)
GA, r_g = sp.symbols("GA r_g", positive=True)  # Timoshenko: G*Abar and radius of gyration

# --- scales, Eqs. (15)-(16) ------------------------------------------------------------------------------
chi = (k_f / (4 * EI)) ** sp.Rational(1, 4)
v_ref = (4 * k_f * EI / m**2) ** sp.Rational(1, 4)
w_st = P * chi / (2 * k_f)
omega = sp.sqrt(k_f / m)  # tau = omega * t

# --- dimensionless groups, Eqs. (16)-(17), (59), and the Pasternak group eta_s --------------------------
alpha, eta_f, eta_s = sp.symbols("alpha eta_f eta_s", positive=True)
eta_M, mu_v, J_b, kappa_v, eta_v, d = sp.symbols("eta_M mu_v J_b kappa_v eta_v d", positive=True)
S, r = sp.symbols("S r", positive=True)

#: Physical parameter -> expression through the dimensionless groups (the inverse of Eq. (17)).
#: EI, m, k_f and P stay free: every dimensionless result must be independent of them.
PHYSICAL_IN_DIMENSIONLESS = {
    c_f: 2 * eta_f * sp.sqrt(m * k_f),
    k_s: 2 * eta_s * sp.sqrt(k_f * EI),
    v: alpha * v_ref,
    M: eta_M * m / chi,
    M_b: mu_v * m / chi,
    J_phys: J_b * m / chi**3,
    k_v: kappa_v * k_f / chi,
    c_v: eta_v * 2 * sp.sqrt(m * k_f) / chi,
    d_phys: d / chi,
    GA: 2 * S * sp.sqrt(k_f * EI),
    r_g: r / chi,
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
