"""The layered elastic half-space under a track (docs/soil.md): the wave basis of one soil layer.

Plane strain in the vertical plane of the wavenumber k (the vertical surface flexibility of the
half-space is axisymmetric, so the P-SV problem with k = sqrt(k1^2 + k2^2) gives it), fields
``exp(i (omega t - k x))``, depth z positive downwards, Lame constants lambda, mu (complex under
Kelvin-Voigt damping). A wave ``v exp(-gamma zeta)`` has the depth coordinate zeta = z (down-going,
sigma = +1) or zeta = h - z (up-going, sigma = -1), so d/dz -> -sigma gamma; gamma = p for P waves,
gamma = s for S waves, p^2 = k^2 - k_p^2, s^2 = k^2 - k_s^2 (k_p = omega / c_p, k_s = omega / c_s).

- P wave (grad of a potential): u = (-i k, -sigma p);
- S wave (curl of a potential): u = (sigma s, -i k);
- traction on a horizontal plane: t_x = mu (du_x/dz - i k u_z),
  t_z = -i k lambda u_x + (lambda + 2 mu) du_z/dz.

As omega / (c k) -> 0 the two waves coincide (v_S -> i sigma v_P, s -> p): the potential basis
degenerates and a stiffness matrix built on it loses digits like (omega / (c k))^2. The basis used here
stays regular: f1 = v_P e^{-p zeta} and the divided difference f2 = (v_S e^{-s zeta} - i sigma v_P
e^{-p zeta}) / (s - p), written as

    f2 = A e^{-s zeta} + i sigma v_P E(zeta),   E(zeta) = (e^{-s zeta} - e^{-p zeta}) / (s - p),

with A = (v_S - i sigma v_P) / (s - p) (and likewise for the tractions). A vanishes to first order in the
small quantities ds = s - k, dp = p - k; written as ds A_s + dp A_p, A = r_s A_s + r_p A_p with the ratios
r_s = ds / (s - p), r_p = dp / (s - p), which the runtime forms without cancellation (ds = -k_s^2 / (s + k),
dp = -k_p^2 / (p + k), s - p = (k_p^2 - k_s^2) / (s + p), and k_p^2 / k_s^2 = mu / (lambda + 2 mu) at every
frequency). At omega = 0 this is the static (Jordan) basis e^{-k z}, z e^{-k z}: one form for every frequency.

Generated (``generated/soil_layer.py``): ``layer_basis(k, ds, dp, rs, rp, lam, mu)``, the coefficients of
the basis functions in (u_x, u_z, t_x, t_z) for down- and up-going waves; :func:`basis_check` proves that
every basis function solves Navier's equations and that the regular form equals the divided difference.
"""

from __future__ import annotations

import sympy as sp

from .emit import definition_digest, function_source, module_source

k, ds, dp, rs, rp = sp.symbols("k ds dp rs rp")
lam, mu = sp.symbols("lam mu")
#: The four components of a basis function, in the order the generated tuple gives them.
COMPONENTS = ("u_x", "u_z", "t_x", "t_z")
DIRECTIONS = {"down": 1, "up": -1}


def wave(kind: str, sigma: int, gamma: sp.Expr) -> sp.Matrix:
    """(u_x, u_z, t_x, t_z) of the wave ``kind`` (P or S) of vertical wavenumber gamma, direction sigma."""
    u = sp.Matrix([-sp.I * k, -sigma * gamma]) if kind == "P" else sp.Matrix([sigma * gamma, -sp.I * k])
    dz = -sigma * gamma
    t_x = mu * (dz * u[0] - sp.I * k * u[1])
    t_z = -sp.I * k * lam * u[0] + (lam + 2 * mu) * dz * u[1]
    return sp.Matrix([u[0], u[1], t_x, t_z])


def regular_basis(sigma: int) -> tuple[sp.Matrix, sp.Matrix, sp.Matrix]:
    """(a1, a2, a3): f1 = a1 e^{-p zeta}; f2 = a2 e^{-s zeta} + a3 E(zeta), in k, ds, dp, rs, rp, lam, mu."""
    p, s = k + dp, k + ds
    c = sp.I * sigma
    a1 = wave("P", sigma, p)
    numerator = (wave("S", sigma, s) - c * a1).applyfunc(sp.expand)
    a2 = []
    for entry in numerator:
        if entry.subs({ds: 0, dp: 0}) != 0:
            raise ValueError("the S and P waves do not coincide at omega = 0")
        rest = sp.expand(entry.subs(ds, 0))
        part_s = sp.cancel((entry - rest) / ds)
        part_p = sp.cancel(rest / dp)
        a2.append(sp.expand(rs * part_s + rp * part_p))
    return a1, sp.Matrix(a2), c * a1


def basis_check() -> None:
    """Each basis function solves Navier's equations; the regular a2 equals the divided difference.

    Checked with k_p^2 = rho omega^2 / (lambda + 2 mu), k_s^2 = rho omega^2 / mu, at exact rational points.
    """
    rho_w2, kk = sp.Rational(7, 3), sp.Rational(5, 2)
    values = {lam: sp.Rational(3, 2), mu: sp.Rational(4, 5), k: kk}
    p = sp.sqrt(kk**2 - rho_w2 / (values[lam] + 2 * values[mu]))
    s = sp.sqrt(kk**2 - rho_w2 / values[mu])
    for sigma in DIRECTIONS.values():
        for kind, gamma in (("P", p), ("S", s)):
            u = wave(kind, sigma, gamma).subs(values)
            dz, dx = -sigma * gamma, -sp.I * kk
            lam_, mu_ = values[lam], values[mu]
            div = dx * u[0] + dz * u[1]
            lap = dx**2 + dz**2
            for i, d in enumerate((dx, dz)):
                residual = (lam_ + mu_) * d * div + mu_ * lap * u[i] + rho_w2 * u[i]
                if sp.simplify(residual) != 0:
                    raise ValueError(f"{kind} wave (sigma={sigma}) fails Navier's equation {i}")
        a1, a2, _ = regular_basis(sigma)
        small = {ds: s - kk, dp: p - kk, rs: (s - kk) / (s - p), rp: (p - kk) / (s - p)}
        direct = (wave("S", sigma, s) - sp.I * sigma * wave("P", sigma, p)) / (s - p)
        if any(sp.simplify(e) != 0 for e in (a2.subs(values | small) - direct.subs(values))):
            raise ValueError(f"regular basis (sigma={sigma}) differs from the divided difference")


def soil_module() -> str:
    """The text of ``generated/soil_layer.py``."""
    basis_check()
    outputs = []
    for sigma in DIRECTIONS.values():
        for a in regular_basis(sigma):
            outputs += list(a)
    doc = (
        "(a1, a2, a3) of the down-going then the up-going waves, each (u_x, u_z, t_x, t_z): "
        "f1 = a1 e^{-p zeta}, f2 = a2 e^{-s zeta} + a3 E(zeta) (derivations/soil.py)."
    )
    body = function_source("layer_basis", ("k", "ds", "dp", "rs", "rp", "lam", "mu"), outputs, doc)
    constants = [("COMPONENTS", COMPONENTS), ("DIRECTIONS", DIRECTIONS)]
    digest = definition_digest(*outputs, *[value for _, value in constants])
    return module_source(
        "The wave basis of a soil layer (P-SV, regular as omega -> 0): see derivations/soil.py.",
        digest,
        [body],
        constants,
    )
