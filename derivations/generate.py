"""What ``python -m derivations`` writes: the generated kernels and the proof table.

Into src/moving_bogie/generated/:
foundation_<name>.py  coefficients (highest power first) of N(p, q), dN/dq, Q(p, q), dQ/dq in p
vehicle_<name>.py     E_chr, its partial derivatives, residue numerators and shape weights
__init__.py           the lists of models and the inputs hash
and docs/proofs.md: derived == printed, equation by equation (paper.py)
"""

from pathlib import Path

import sympy as sp

from . import symbols as s
from .asymptotics import asymptotics_module
from .emit import function_source, inputs_digest, module_source
from .foundations import MODELS
from .model import foundation_image
from .paper import all_proofs
from .system import SYSTEMS

HERE = Path(__file__).resolve().parent
#: Where the kernels go, relative to the repository root: inside the package, so the source tree imports.
GENERATED = Path("src/moving_bogie/generated")

FOUNDATION_ARGS = ("q", "alpha", "eta_f", "eta_s", "S", "r")


def _coeffs(expr, degree):
    poly = sp.Poly(expr, s.p)
    if poly.degree() > degree:
        raise AssertionError(f"degree {poly.degree()} in p exceeds {degree}")
    coeffs = [sp.expand(poly.coeff_monomial(s.p**k)) for k in range(degree, -1, -1)]
    return coeffs


def foundation_module(name, digest):
    model = MODELS[name]()
    image = foundation_image(model)
    # Groups a model adds beyond the common ones (TrackModel.parameters) become further arguments.
    args = FOUNDATION_ARGS + tuple(x for x in model.parameters if x not in FOUNDATION_ARGS)
    deg_n = sp.Poly(image.N, s.p).degree()
    deg_q = sp.Poly(image.Q, s.p).degree()
    n = _coeffs(image.N, deg_n)
    qq = _coeffs(image.Q, deg_q)
    deg_nq = sp.Poly(image.N, s.q).degree()
    n_in_q = [sp.expand(sp.Poly(image.N, s.q).coeff_monomial(s.q**k)) for k in range(deg_nq, -1, -1)]
    cut_args = ("p",) + args[1:]
    parts = [
        function_source("n_coeffs", args, n, "Coefficients of N(p, q) in p, highest power first."),
        function_source(
            "n_coeffs_in_q",
            cut_args,
            n_in_q,
            "Coefficients of N(p, q) in q, highest first: for real p its roots trace the cut of K.",
        ),
        function_source("n_coeffs_dq", args, [sp.diff(c, s.q) for c in n], "Coefficients of dN/dq in p."),
        function_source("q_coeffs", args, qq, "Coefficients of Q(p, q) in p, highest power first."),
        function_source("q_coeffs_dq", args, [sp.diff(c, s.q) for c in qq], "Coefficients of dQ/dq in p."),
    ]
    summary = (MODELS[name].__doc__ or name).strip().splitlines()[0]
    title = (
        f"Track model '{name}': D(p, q) = N(p, q) / Q(p, q) of {summary}\n\n"
        "K(xi, q) = integral over real p of exp(i p xi) Q / N dp (Eq. (29))."
    )
    constants = [
        ("ARGUMENTS", args),
        ("MODEL_PARAMETERS", tuple(model.parameters)),
        ("DEGREE_N", deg_n),
        ("DEGREE_Q", deg_q),
        ("DEGREE_N_IN_Q", deg_nq),
    ]
    return module_source(title, digest, parts, constants)


def vehicle_module(name, digest):
    system = SYSTEMS[name]()
    params = tuple(str(x) for x in system.parameters)
    args = ("q", "K0", "Kp", "Km", *params, "pi")
    atoms = sorted(system.atoms.items(), key=lambda kv: str(kv[0]))
    datoms = [(sp.Symbol(f"d{a}"), sp.diff(e, s.q)) for a, e in atoms]
    E = system.E_chr
    parts = [
        function_source(
            "e_chr", args, [E], "E_chr(q), Eq. (38) (two masses: its 2x2 analogue).", atoms, scalar=True
        )
    ]
    # dE/dq with K fixed, by the chain rule through the atoms; then the K partials.
    E_q = sum((sp.diff(E, a) * da for (a, _), (da, _) in zip(atoms, datoms)), sp.Integer(0))
    grads = [sp.expand(E_q), sp.diff(E, s.K0), sp.diff(E, s.Kp), sp.diff(E, s.Km)]
    parts.append(
        function_source(
            "e_chr_partials",
            args,
            grads,
            "(dE/dq at fixed K, dE/dK0, dE/dK+, dE/dK-): dE_chr/dq of Eq. (40) by the chain rule.",
            atoms + datoms,
        )
    )
    names = tuple(system.numerators)
    parts.append(
        function_source(
            "numerators",
            args,
            [system.numerators[k] for k in names],
            "Residue numerators n_X of Eqs. (36), (41)-(43): x(tau) = sum res(n_X e^{i q tau} / (q E_chr)).",
            atoms,
        )
    )
    parts.append(
        function_source(
            "shape_weights",
            args,
            list(system.shape_weights),
            "(G_rear, G_front) = (8 E_chr + E1, 8 E_chr + E2) of Eqs. (44)-(47), Eqs. (45)-(46) as derived.",
            atoms,
        )
    )
    title = f"Vehicle '{name}': characteristic function, its derivatives and residue numerators."
    constants = [("ARGUMENTS", args), ("PARAMETERS", params), ("RESPONSES", names)]
    return module_source(title, digest, parts, constants)


def proofs_markdown(digest):
    lines = [
        "# Derived versus printed formulas",
        "",
        "Written by `python -m derivations` (do not edit); the explanations are in [errata.md](errata.md).",
        f"Inputs hash: `{digest}`",
        "",
        "| equation | statement | status | evidence |",
        "|---|---|---|---|",
    ]
    for pr in all_proofs():
        evidence = pr.evidence.replace("|", "\\|").replace("*", "\\*")
        lines.append(f"| {pr.equation} | {pr.statement} | {pr.status} | {evidence} |")
    return "\n".join(lines) + "\n"


def outputs(root: Path) -> dict:
    """Map of path -> text of every generated file."""
    digest = inputs_digest(HERE)
    files = {}
    for name in MODELS:
        files[root / GENERATED / f"foundation_{name}.py"] = foundation_module(name, digest)
    for name in SYSTEMS:
        files[root / GENERATED / f"vehicle_{name}.py"] = vehicle_module(name, digest)
    init = module_source(
        "Generated kernels of moving-bogie (the committed output of derivations/).",
        digest,
        [],
        [("FOUNDATIONS", tuple(MODELS)), ("VEHICLES", tuple(SYSTEMS)), ("INPUTS_HASH", digest)],
    )
    files[root / GENERATED / "__init__.py"] = init
    files[root / GENERATED / "asymptotics.py"] = asymptotics_module(digest, module_source, function_source)
    files[root / "docs" / "proofs.md"] = proofs_markdown(digest)
    return files
