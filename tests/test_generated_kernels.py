"""Every generated kernel against direct SymPy evaluation of the derivation (docs/architecture.md, example 6).

The generated functions in ``generated/`` are evaluated at seeded random complex points with mpmath at
30 digits and compared with the derivation's own SymPy expressions (``derivations.model.foundation_image``,
``derivations.system``) evaluated exactly and rounded to 40 digits: every output must match to 25 digits.
The same functions called with numpy complex arrays must agree with the mpmath values to ~1e-12 (one
implementation serves both backends). The partial derivatives of E_chr are also checked against
numerical differentiation of the generated E_chr, which does not involve SymPy at all.

The random inputs are double-precision numbers, converted exactly to mpmath and to SymPy rationals, so
the three backends see the same numbers and any difference is the kernel's own rounding.
"""

from __future__ import annotations

import functools
import importlib
import sys
from pathlib import Path

import mpmath
import numpy as np
import pytest
from derivation_support import require_sympy

sp = require_sympy()

REPO = Path(__file__).resolve().parents[1]
if str(REPO) not in sys.path:  # derivations/ is a top-level folder of the repository, not installed
    sys.path.insert(0, str(REPO))

import moving_bogie.generated as generated  # noqa: E402
from derivations import symbols as s  # noqa: E402
from derivations.foundations import MODELS  # noqa: E402
from derivations.model import foundation_image  # noqa: E402
from derivations.system import SYSTEMS, derivatives, in_q  # noqa: E402

DIGITS = 25  # required agreement of the 30-digit kernels with the 40-digit SymPy reference
NUMPY_RTOL = 1e-12
SEEDS = range(6)


# --- exact conversion of the shared inputs -------------------------------------------------------------


def _to_sympy(x):
    """Exact SymPy number of a float or complex (floats are binary rationals)."""
    if x is None:
        return None
    z = complex(x)
    return sp.Rational(z.real) + sp.I * sp.Rational(z.imag) if isinstance(x, complex) else sp.Rational(z.real)


def _to_mp(x):
    if x is None:
        return None
    return mpmath.mpc(x) if isinstance(x, complex) else mpmath.mpf(x)


def _reference(expr, values: dict):
    """``expr`` at exact rational inputs (dict of symbol -> float/complex), rounded to 40 digits, as mpc."""
    exact = expr.xreplace({sym: _to_sympy(v) for sym, v in values.items() if v is not None})
    leftover = exact.free_symbols
    assert not leftover, f"reference still depends on {sorted(map(str, leftover))}"
    return _rounded(exact)


def _rounded(exact):
    """An exact SymPy number rounded to 40 digits, as mpc."""
    z = sp.N(exact, 40)
    re, im = z.as_real_imag()
    with mpmath.workdps(45):
        return mpmath.mpc(mpmath.mpf(str(sp.N(re, 40))), mpmath.mpf(str(sp.N(im, 40))))


def _assert_digits(values, references, what, digits=DIGITS):
    """Each value matches its reference to ``digits`` significant digits; exact zeros stay exact."""
    assert len(values) == len(references), f"{what}: {len(values)} outputs, expected {len(references)}"
    with mpmath.workdps(45):
        for k, (a, b) in enumerate(zip(values, references)):
            if b == 0:
                assert a == 0, f"{what}[{k}] = {a}, expected exactly 0"
                continue
            err = abs(mpmath.mpc(a) - b) / abs(b)
            assert err <= mpmath.mpf(10) ** (-digits), (
                f"{what}[{k}]: generated {mpmath.nstr(a, 30)} vs SymPy {mpmath.nstr(b, 30)}, "
                f"only {mpmath.nstr(-mpmath.log10(err), 3)} digits"
            )


def _rng(seed):
    return np.random.default_rng(20250121 + seed)


def _complex(rng, scale=1.0):
    return complex(*(scale * rng.uniform(-1, 1, 2)))


def _positive(rng):
    """A positive parameter, log-uniform over two decades around 1 (the paper's dimensionless range)."""
    return float(10 ** rng.uniform(-1, 1))


# --- the derivation's expressions, built once ----------------------------------------------------------


@functools.cache
def _foundation(name):
    image = foundation_image(MODELS[name]())
    return image.N, image.Q


@functools.cache
def _vehicle(name):
    system = SYSTEMS[name]()
    responses = importlib.import_module(f"moving_bogie.generated.vehicle_{name}").RESPONSES
    parts = derivatives(system)
    return {
        "system": system,
        "e_chr": [in_q(system.E_chr, system)],
        "e_chr_partials": [parts["E_q"], parts["E_K0"], parts["E_Kp"], parts["E_Km"]],
        "numerators": [in_q(system.numerators[r], system) for r in responses],
        "shape_weights": [in_q(g, system) for g in system.shape_weights],
    }


def _foundation_module(name):
    return importlib.import_module(f"moving_bogie.generated.foundation_{name}")


def _vehicle_module(name):
    return importlib.import_module(f"moving_bogie.generated.vehicle_{name}")


def _exact_polys(name, point) -> tuple:
    """N and Q of the derivation with the point's groups substituted exactly (``_to_sympy``): polynomials
    in (p, q) over the Gaussian rationals. Exact arithmetic commutes with taking coefficients and with
    d/dq, so each coefficient (or derivative) read from these at the point is exactly the derivation's own
    coefficient evaluated there; a Poly over every group of a layered track would take seconds to build.
    """
    groups = {getattr(s, k): _to_sympy(v) for k, v in point.items() if k not in ("p", "q") and v is not None}
    polys = []
    for expr in _foundation(name):
        exact = expr.xreplace(groups)
        leftover = exact.free_symbols - {s.p, s.q}
        assert not leftover, f"{name}: N or Q still depends on {sorted(map(str, leftover))}"
        polys.append(sp.Poly(exact, s.p, s.q))
    return tuple(polys)


def _coeffs(poly, degree):
    """Coefficients of ``poly``, highest power first, padded to ``degree``."""
    c = poly.all_coeffs()
    assert len(c) <= degree + 1
    return [sp.Integer(0)] * (degree + 1 - len(c)) + c


def _polyval(coeffs, x):
    acc = 0
    for c in coeffs:
        acc = acc * x + c
    return acc


# --- the lists agree ---------------------------------------------------------------------------------------


def test_generated_lists_match_the_derivation():
    assert generated.FOUNDATIONS == tuple(MODELS)
    assert set(SYSTEMS) <= set(generated.VEHICLES)
    for name in SYSTEMS:
        module = _vehicle_module(name)
        system = _vehicle(name)["system"]
        assert module.PARAMETERS == tuple(str(x) for x in system.parameters)
        assert module.ARGUMENTS == ("q", "K0", "Kp", "Km", *module.PARAMETERS, "pi")
        assert module.RESPONSES == tuple(system.numerators)


# --- foundations -------------------------------------------------------------------------------------------


def _foundation_point(name, seed, *, derived=True):
    """q complex, parameters positive; parameters the model does not use are None (as the runtime passes).

    ``derived=False``: every parameter gets its value (the same random numbers), with no SymPy derivation of
    the model to tell which are used; a parameter the generated functions do not use changes none of their
    outputs, so a comparison of two backends of those functions is the same at either point."""
    rng = _rng(seed)
    if derived:
        N, Q = _foundation(name)
        used = {str(x) for x in (N.free_symbols | Q.free_symbols)}
    else:
        used = set(_foundation_module(name).ARGUMENTS[1:])
    point = {"q": _complex(rng), "p": _complex(rng, 2.0)}
    for par in _foundation_module(name).ARGUMENTS[1:]:
        value = _positive(rng)
        if par == "eta_f":
            value = float(rng.uniform(0, 0.9))  # under-damped foundation, as the runtime requires
        point[par] = value if par in used else None
    return point


#: (foundation, seed) of every comparison. The layered tracks' kernels against SymPy are the longest
#: comparisons (exact evaluation of large expressions at 40 digits): they run in the full suite only, at
#: one random point each (two polynomials that agree at a random complex point are equal but for a set of
#: measure zero; every coefficient is compared there, to DIGITS digits). The one-layer kernels stay in the
#: quick subset at all six points.
FOUNDATION_CASES = [
    pytest.param(name, seed, marks=pytest.mark.slow, id=f"{name}-{seed}")
    if "layer" in name
    else pytest.param(name, seed, id=f"{name}-{seed}")
    for name in generated.FOUNDATIONS
    for seed in (SEEDS[:1] if "layer" in name else SEEDS)
]


@pytest.mark.parametrize(("name", "seed"), FOUNDATION_CASES)
def test_foundation_kernels_match_sympy(name, seed):
    module = _foundation_module(name)
    point = _foundation_point(name, seed)
    n_pq, q_pq = _exact_polys(name, point)
    # degrees at the random point: those of N and Q unless a leading coefficient (a nonzero polynomial in
    # the groups) vanishes there, a set of measure zero
    deg_n, deg_q, deg_nq = n_pq.degree(s.p), q_pq.degree(s.p), n_pq.degree(s.q)
    assert (module.DEGREE_N, module.DEGREE_Q, module.DEGREE_N_IN_Q) == (deg_n, deg_q, deg_nq)
    pars = {k: point[k] for k in module.ARGUMENTS[1:]}
    q_at, p_at = _to_sympy(point["q"]), _to_sympy(point["p"])

    def in_p_at_q(poly, degree):
        return [_rounded(c) for c in _coeffs(poly.eval(s.q, q_at), degree)]

    references = {
        "n_coeffs": in_p_at_q(n_pq, deg_n),
        "n_coeffs_dq": in_p_at_q(n_pq.diff(s.q), deg_n),
        "q_coeffs": in_p_at_q(q_pq, deg_q),
        "q_coeffs_dq": in_p_at_q(q_pq.diff(s.q), deg_q),
        "n_coeffs_in_q": [_rounded(c) for c in _coeffs(n_pq.eval(s.p, p_at), deg_nq)],
    }
    with mpmath.workdps(30):
        mp_pars = {k: _to_mp(v) for k, v in pars.items()}
        q, p = _to_mp(point["q"]), _to_mp(point["p"])
        values = {f: getattr(module, f)(q, **mp_pars) for f in references if f != "n_coeffs_in_q"}
        values["n_coeffs_in_q"] = module.n_coeffs_in_q(p, **mp_pars)
        # The polynomials themselves, at the random p (in p) and q (in q): checks the ordering of powers.
        polys = [
            _polyval(values["n_coeffs"], p),
            _polyval(values["q_coeffs"], p),
            _polyval(values["n_coeffs_dq"], p),
            _polyval(values["q_coeffs_dq"], p),
            _polyval(values["n_coeffs_in_q"], q),
        ]
    for f, ref in references.items():
        _assert_digits(values[f], ref, f"{name}.{f} (seed {seed})")
    at = {s.p: p_at, s.q: q_at}
    poly_refs = [_rounded(e.eval(at)) for e in (n_pq, q_pq, n_pq.diff(s.q), q_pq.diff(s.q))]
    poly_refs.append(poly_refs[0])  # N from its coefficients in q, at the same (p, q): the same exact value
    _assert_digits(polys, poly_refs, f"{name}: N, Q, N_q, Q_q, N from coefficients (seed {seed})")


@pytest.mark.parametrize("name", generated.FOUNDATIONS)
def test_foundation_kernels_numpy_agree_with_mpmath(name):
    module = _foundation_module(name)
    rng = _rng(99)
    # numpy against mpmath, both the generated functions: no SymPy (deriving a layered track takes seconds)
    base = _foundation_point(name, 99, derived=False)
    pars = {k: base[k] for k in module.ARGUMENTS[1:]}
    q = rng.uniform(-1, 1, 16) + 1j * rng.uniform(-1, 1, 16)
    p_real = rng.uniform(-3, 3, 16)  # the runtime traces the cut locus at real p
    for f in ("n_coeffs", "n_coeffs_dq", "q_coeffs", "q_coeffs_dq", "n_coeffs_in_q"):
        x = p_real if f == "n_coeffs_in_q" else q
        out = getattr(module, f)(x, **pars)
        arrays = [np.broadcast_to(np.asarray(c, dtype=complex), x.shape) for c in out]
        with mpmath.workdps(30):
            mp_pars = {k: _to_mp(v) for k, v in pars.items()}
            refs = [getattr(module, f)(_to_mp(xj.item()), **mp_pars) for xj in x]
        _assert_numpy_close(arrays, refs, f"{name}.{f}")


def _assert_numpy_close(arrays, refs, what):
    for k, arr in enumerate(arrays):
        ref = np.array([complex(r[k]) for r in refs])
        err = np.abs(arr - ref)
        bound = NUMPY_RTOL * np.abs(ref)
        bad = err > bound
        worst = float(np.max(err / np.maximum(np.abs(ref), 1e-300)))
        assert not bad.any(), f"{what}[{k}]: numpy differs from mpmath by {worst:.2e} relative"


# --- vehicles ----------------------------------------------------------------------------------------------


def _vehicle_point(name, seed):
    rng = _rng(seed)
    point = {"q": _complex(rng), "K0": _complex(rng, 2.0), "Kp": _complex(rng, 2.0), "Km": _complex(rng, 2.0)}
    for par in _vehicle_module(name).PARAMETERS:
        point[par] = _positive(rng)
    return point


def _mp_vehicle_args(point):
    return {k: _to_mp(v) for k, v in point.items()} | {"pi": mpmath.mp.pi}


VEHICLE_FUNCTIONS = ("e_chr", "e_chr_partials", "numerators", "shape_weights")


@pytest.mark.parametrize("seed", SEEDS)
@pytest.mark.parametrize("name", tuple(SYSTEMS))
def test_vehicle_kernels_match_sympy(name, seed):
    module = _vehicle_module(name)
    exprs = _vehicle(name)
    point = _vehicle_point(name, seed)
    # The derivation's parameter symbols carry assumptions (positive=True): map them by name.
    symbols = {str(x): x for x in exprs["system"].parameters}
    symbols |= {k: getattr(s, k) for k in ("q", "K0", "Kp", "Km")}
    subs = {symbols[k]: v for k, v in point.items()}
    with mpmath.workdps(30):
        args = _mp_vehicle_args(point)
        values = {f: getattr(module, f)(**args) for f in VEHICLE_FUNCTIONS}
    values["e_chr"] = [values["e_chr"]]
    for f in VEHICLE_FUNCTIONS:
        refs = [_reference(e, subs) for e in exprs[f]]
        _assert_digits(values[f], refs, f"{name}.{f} (seed {seed})")


@pytest.mark.parametrize("name", tuple(SYSTEMS))
def test_e_chr_partials_are_the_derivatives_of_e_chr(name):
    """dE/dq at fixed K and dE/dK0, dE/dK+, dE/dK- of Eq. (40), by numerical differentiation (no SymPy)."""
    module = _vehicle_module(name)
    for seed in SEEDS[:3]:
        point = _vehicle_point(name, seed)
        with mpmath.workdps(30):
            args = _mp_vehicle_args(point)
            partials = module.e_chr_partials(**args)
            numeric = []
            for var in ("q", "K0", "Kp", "Km"):

                def f(z, var=var, args=args):
                    return module.e_chr(**(args | {var: z}))

                numeric.append(mpmath.diff(f, args[var]))
        # mpmath.diff works at raised precision; agreement to 25 digits as for SymPy.
        with mpmath.workdps(40):
            _assert_digits(partials, [mpmath.mpc(x) for x in numeric], f"{name}.e_chr_partials (seed {seed})")


@pytest.mark.parametrize("name", tuple(SYSTEMS))
def test_vehicle_kernels_numpy_agree_with_mpmath(name):
    module = _vehicle_module(name)
    rng = _rng(77)
    n = 16
    pars = {k: _positive(rng) for k in module.PARAMETERS}
    arrays_in = {k: rng.uniform(-1, 1, n) + 1j * rng.uniform(-1, 1, n) for k in ("q", "K0", "Kp", "Km")}
    arrays_in["q"] = arrays_in["q"] * 0.5
    for f in VEHICLE_FUNCTIONS:
        out = getattr(module, f)(**arrays_in, **pars, pi=np.pi)
        out = [out] if f == "e_chr" else list(out)
        arrays = [np.broadcast_to(np.asarray(c, dtype=complex), (n,)) for c in out]
        refs = []
        with mpmath.workdps(30):
            for j in range(n):
                point = {k: complex(v[j]) for k, v in arrays_in.items()} | pars
                r = getattr(module, f)(**_mp_vehicle_args(point))
                refs.append([r] if f == "e_chr" else list(r))
        _assert_numpy_close(arrays, refs, f"{name}.{f}")


# --- declared vehicles: the shared matrix interface ------------------------------------------------------

MATRIX_FUNCTIONS = ("contact_positions", "static_loads", "mass_matrix", "damping_matrix", "stiffness_matrix")


@functools.cache
def _declared(name):
    from derivations.vehicles import VEHICLES, assemble

    return assemble(VEHICLES[name]())


def test_declared_vehicles_are_generated():
    from derivations.vehicles import VEHICLES

    assert tuple(generated.DECLARED_VEHICLES) == tuple(VEHICLES)
    for name in VEHICLES:
        module = _vehicle_module(name)
        matrices = _declared(name)
        assert module.DOFS == matrices.dofs
        assert module.CONTACTS == matrices.contacts
        assert module.MATRIX_ARGUMENTS == tuple(str(x) for x in matrices.parameters)
        assert set(module.UNITS) == set(module.DOFS)


@pytest.mark.parametrize("seed", SEEDS[:3])
@pytest.mark.parametrize("name", tuple(generated.DECLARED_VEHICLES))
def test_vehicle_matrices_match_sympy(name, seed):
    """Generated contact positions, loads and M, C, K at random parameters against the SymPy assembly."""
    module = _vehicle_module(name)
    matrices = _declared(name)
    rng = _rng(seed)
    point = {par: _positive(rng) for par in module.MATRIX_ARGUMENTS}
    subs = {sym: point[str(sym)] for sym in matrices.parameters}
    exprs = {
        "contact_positions": list(matrices.positions),
        "static_loads": list(matrices.loads),
        "mass_matrix": list(matrices.mass),
        "damping_matrix": list(matrices.damping),
        "stiffness_matrix": list(matrices.stiffness),
    }
    with mpmath.workdps(30):
        args = {k: _to_mp(v) for k, v in point.items()}
        for f in MATRIX_FUNCTIONS:
            out = getattr(module, f)(**args)
            flat = [x for row in out for x in row] if f.endswith("matrix") else list(out)
            if f.endswith("matrix"):
                assert all(len(row) == len(module.DOFS) for row in out) and len(out) == len(module.DOFS)
            _assert_digits(flat, [_reference(e, subs) for e in exprs[f]], f"{name}.{f} (seed {seed})")
