"""What ``python -m derivations`` writes: the generated kernels, their metadata and the proof table.

Into src/moving_bogie/generated/:
foundation_<name>.py  coefficients (highest power first) of N(p, q), dN/dq, Q(p, q), dQ/dq in p; the
                      model's beam, track, parameters and degrees; the per-mode mass, damping and stiffness
                      blocks of the simply supported finite rail (validation)
vehicle_<name>.py     the declared vehicle (derivations/vehicles.py): contacts, DOFs, units, M, C, K, contact
                      positions, static loads; for bogie and masses also E_chr, its partial derivatives,
                      residue numerators and shape weights
parameters.py         every dimensionless group: meaning, constraint, default, equation, SI name and unit,
                      the exact SI <-> dimensionless scaling, the scales of Eqs. (15)-(16), Eq. (63)
__init__.py           the catalogue: beams, tracks, vehicles and which module holds each combination
and docs/proofs.md: derived == printed, equation by equation (paper.py).
"""

import re
from pathlib import Path

import sympy as sp

from . import symbols as s
from .asymptotics import asymptotics_module, kernel_decay
from .emit import SCALING_PRINTER, definition_digest, function_source, module_source
from .foundations import BEAMS, TRACKS, all_models
from .modal import modal_blocks
from .model import foundation_image
from .paper import all_proofs
from .system import SYSTEMS, in_q
from .vehicles import VEHICLES as DECLARED
from .vehicles import assemble

HERE = Path(__file__).resolve().parent
#: Where the kernels go, relative to the repository root: inside the package, so the source tree imports.
GENERATED = Path("src/moving_bogie/generated")
GENERATOR = "python -m derivations"


def _coeffs(expr, var):
    """(degree, coefficients highest first) of ``expr`` as a polynomial in ``var`` (one Poly built)."""
    poly = sp.Poly(expr, var)
    degree = poly.degree()
    return degree, [sp.expand(poly.coeff_monomial(var**k)) for k in range(degree, -1, -1)]


def _groups_in(*exprs) -> tuple:
    """Names of the declared groups the expressions depend on, in declaration order; others are refused."""
    names = {str(x) for e in exprs for x in e.free_symbols} - {"p", "q", "K0", "Kp", "Km", "pi"}
    unknown = names - set(s.GROUPS)
    if unknown:
        raise ValueError(f"undeclared dimensionless groups {sorted(unknown)}: declare them in symbols.py")
    return tuple(name for name in s.GROUPS if name in names)


def foundation_module(name, model):
    image = foundation_image(model)
    params = _groups_in(image.N, image.Q)
    args = ("q", *params)
    deg_n, n = _coeffs(image.N, s.p)
    deg_q, qq = _coeffs(image.Q, s.p)
    deg_nq, n_in_q = _coeffs(image.N, s.q)
    cut_args = ("p", *params)
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
    mass, damping, stiffness, parity = modal_blocks(model)
    modal_params = tuple(
        g for g in s.GROUPS if g in {str(x) for e in (*mass, *damping, *stiffness) for x in e.free_symbols}
    )
    modal_args = ("lam", *modal_params)
    for label, block in (("mass", mass), ("damping", damping), ("stiffness", stiffness)):
        parts.append(
            function_source(
                f"modal_{label}",
                modal_args,
                list(block),
                f"Finite rail (validation): {label} matrix of the sine mode of wavenumber lam, row-major.",
            )
        )
    title = (
        f"Track model '{name}': D(p, q) = N(p, q) / Q(p, q) of the {model.description}\n\n"
        "K(xi, q) = integral over real p of exp(i p xi) Q / N dp (Eq. (29))."
    )
    si_names, scale_parameters, overrides = _track_si_names(model)
    decay = kernel_decay(model)
    constants = [
        ("BEAM", model.beam),
        ("TRACK", model.track),
        ("DESCRIPTION", model.description),
        ("ARGUMENTS", args),
        ("MODEL_PARAMETERS", params),
        ("DEGREE_N", deg_n),
        ("DEGREE_Q", deg_q),
        ("DEGREE_N_IN_Q", deg_nq),
        ("DAMPING", tuple(name for name in params if s.GROUPS[name].damping)),
        ("SCALE_PARAMETERS", scale_parameters),
        ("SI_NAMES", si_names),
        ("GROUP_OVERRIDES", overrides),
        ("MODAL_ARGUMENTS", modal_args),
        ("MODAL_PARITY", parity),
        ("KERNEL_DECAY", None if decay is None else str(decay.gamma)),
    ]
    digest = definition_digest(
        model.operator, *model.unknown_scales, *model.row_scales, model.description, model.si_names
    )
    return module_source(title, digest, parts, constants)


def _track_si_names(model):
    """The SI names on this track: (catalogue name -> track name, scale parameters, group overrides).

    A layered track names the reference stiffness k_f and its damping c_f ``k_1``, ``c_1``; the scale
    parameters and every group whose SI name or meaning mentions them are renamed accordingly (the
    scaling itself is the same expression, with k_1 in the place of k_f).
    """
    renames = {str(symbol): name for symbol, (name, _) in model.si_names}
    meanings = {str(symbol): meaning for symbol, (_, meaning) in model.si_names}

    def rename(text):
        return re.sub(r"\b\w+\b", lambda m: renames.get(m.group(0), m.group(0)), text)

    scale_parameters = {
        renames.get(name, name): {"unit": unit, "meaning": meanings.get(name, meaning)}
        for name, unit, meaning in s.SCALE_PARAMETERS
    }
    overrides = {}
    for name, g in s.GROUPS.items():
        changed = {}
        if str(g.physical) in renames:
            changed = {"si": renames[str(g.physical)], "si_meaning": meanings[str(g.physical)]}
        if rename(g.meaning) != g.meaning:
            changed["meaning"] = rename(g.meaning)
        if changed:
            overrides[name] = changed
    return renames, scale_parameters, overrides


def matrix_parts(matrices) -> list:
    """The shared vehicle interface: contact positions, static loads and the M, C, K matrices."""
    args = tuple(str(x) for x in matrices.parameters)
    n = len(matrices.dofs)
    parts = [
        function_source(
            "contact_positions",
            args,
            list(matrices.positions),
            "Dimensionless contact positions xi_j = chi x_j of the wheels, rear wheel at 0 (Eq. (16)).",
        ),
        function_source(
            "static_loads",
            args,
            list(matrices.loads),
            "Constant wheel loads in units of k_f w_st / chi (2 for the load P of Eq. (16)).",
        ),
    ]
    for label, matrix, what in (
        ("mass", matrices.mass, "M"),
        ("damping", matrices.damping, "C"),
        ("stiffness", matrices.stiffness, "K"),
    ):
        parts.append(
            function_source(
                f"{label}_matrix",
                args,
                list(matrix),
                f"{what} of the vehicle (DOFS order, symmetric); f_j = static_j - (M x'' + C x' + K x)_j.",
                columns=n,
            )
        )
    return parts


def vehicle_module(name):
    declared = DECLARED[name]()
    matrices = assemble(declared)
    params = tuple(str(x) for x in matrices.parameters)
    parts = matrix_parts(matrices)
    constants = [("DESCRIPTION", declared.description)]
    definitions = [
        matrices.mass,
        matrices.damping,
        matrices.stiffness,
        *matrices.positions,
        *matrices.loads,
        declared.description,
    ]
    if name in SYSTEMS:
        system_parts, system_constants, system_definitions = _system_parts(name)
        parts = system_parts + parts
        constants += system_constants
        definitions += system_definitions
    else:
        constants += [
            ("PARAMETERS", params),
            ("MODEL_PARAMETERS", tuple(g for g in s.GROUPS if g in set(params))),
            ("RESPONSES", matrices.dofs),
        ]
    constants += [
        ("CONTACTS", matrices.contacts),
        ("DOFS", matrices.dofs),
        ("UNITS", matrices.units),
        ("MATRIX_ARGUMENTS", params),
    ]
    title = f"Vehicle '{name}': its matrices, characteristic function, derivatives and residue numerators."
    digest = definition_digest(*definitions)
    return module_source(title, digest, parts, constants)


def _system_parts(name):
    """E_chr of Eq. (38) and its companions for a vehicle that ``system.py`` derives in closed form."""
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
    degrees = polynomial_degrees(system)
    # The wheel spacing d places the contact points (K(+-d, q)) whatever the vehicle.
    model_params = tuple(g for g in s.GROUPS if g in set(params) | {"d"})
    constants = [
        ("ARGUMENTS", args),
        ("PARAMETERS", params),
        ("MODEL_PARAMETERS", model_params),
        ("RESPONSES", names),
        ("POLYNOMIAL_DEGREES", degrees),
    ]
    definitions = [E, *system.atoms.values(), *system.numerators.values()]
    return parts, constants, definitions


def polynomial_degrees(system) -> dict:
    """Degree of E_chr in each vehicle parameter at fixed q and K, the alternatives held (Eq. (63)).

    The stability tools sweep a parameter by interpolating E_chr exactly in it. The wheel spacing d is left
    out: it also moves the contact point, so K(+-d, q) depends on it. A group that an alternative sets
    (mu_v = cf1 eta_M) follows its dependencies and is not swept on its own.
    """
    E = sp.expand(in_q(system.E_chr, system))
    held = {group: expr for group, expr, _ in s.ALTERNATIVES.values() if group in system.parameters}
    E = sp.expand(E.subs(held))
    out = {}
    for par in system.parameters:
        if str(par) == "d" or par in held:
            continue
        out[str(par)] = sp.Poly(E, par).degree()
    return out


def _physical_args(expr) -> tuple:
    return tuple(sorted({str(x) for x in expr.free_symbols}))


def parameters_module():
    """Metadata of every group and the exact scaling, Eqs. (15)-(17), (59), (63)."""
    table, parts = {}, []
    si_symbols = {g.si: g.physical for g in s.GROUPS.values()}
    scale_symbols = {name: getattr(s, name) for name, _, _ in s.SCALE_PARAMETERS}
    rename = {g.physical: sp.Symbol(g.si) for g in s.GROUPS.values()}
    for name, g in s.GROUPS.items():
        # physical = relation(group)  <=>  group = inverse(physical): both exact, from the one relation.
        relation = s.PHYSICAL_IN_DIMENSIONLESS[g.physical]
        (inverse,) = sp.solve(sp.Eq(g.physical, relation), g.symbol)
        to_si = sp.powsimp(relation, force=True)
        to_dimensionless = sp.powsimp(inverse.subs(rename), force=True)
        si_args = ("sqrt", *_physical_args(to_dimensionless))
        dl_args = ("sqrt", *_physical_args(to_si))
        parts.append(
            function_source(
                f"dimensionless_{name}",
                si_args,
                [to_dimensionless],
                f"{name} from SI, Eq. {g.equation}.",
                scalar=True,
                printer=SCALING_PRINTER,
            )
        )
        parts.append(
            function_source(
                f"physical_{name}",
                dl_args,
                [to_si],
                f"SI {g.si} [{g.unit}] from {name}, Eq. {g.equation}.",
                scalar=True,
                printer=SCALING_PRINTER,
            )
        )
        table[name] = {
            "meaning": g.meaning,
            "constraint": g.constraint,
            "equation": g.equation,
            "default": None if g.default is None else str(g.default),
            "si": g.si,
            "unit": g.unit,
            "si_meaning": g.si_meaning,
            "damping": g.damping,
        }
    alternatives = {}
    for alt, (group, expr, meaning) in s.ALTERNATIVES.items():
        alt_symbol = sp.Symbol(alt, positive=True)
        args = tuple(x for x in s.GROUPS if sp.Symbol(x, positive=True) in expr.free_symbols)
        (alt_of_group,) = sp.solve(sp.Eq(group, expr), alt_symbol)
        alternatives[alt] = {"sets": str(group), "depends": args, "meaning": meaning}
        parts.append(
            function_source(f"set_by_{alt}", (alt, *args), [expr], f"{group} from {alt}.", scalar=True)
        )
        parts.append(
            function_source(
                f"alternative_{alt}",
                tuple(sorted({str(x) for x in alt_of_group.free_symbols})),
                [alt_of_group],
                f"{alt} from the groups: {meaning}.",
                scalar=True,
            )
        )
    parts.append(
        function_source(
            "scales",
            ("sqrt", "EI", "m", "k_f", "P"),
            [s.chi, s.v_ref, s.w_st, 1 / s.omega],
            "(chi [1/m], v_ref [m/s], w_st [m], t_scale [s]) of Eqs. (15)-(16); tau = t / t_scale.",
            printer=SCALING_PRINTER,
        )
    )
    del si_symbols, scale_symbols
    constants = [
        ("PARAMETERS", table),
        ("SCALE_PARAMETERS", {name: {"unit": u, "meaning": mng} for name, u, mng in s.SCALE_PARAMETERS}),
        ("ALTERNATIVES", alternatives),
    ]
    digest = definition_digest(
        *[(k, s.PHYSICAL_IN_DIMENSIONLESS[g.physical], repr(g)) for k, g in s.GROUPS.items()]
    )
    title = (
        "Dimensionless groups: meaning, range, SI counterpart, exact scaling (Eqs. (15)-(17), (59), (63))."
    )
    return module_source(title, digest, parts, constants)


def proofs_markdown():
    lines = [
        "# Derived versus printed formulas",
        "",
        "Written by `python -m derivations` (do not edit); the explanations are in [errata.md](errata.md).",
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
    files = {}
    models = {name: build() for name, build in all_models().items()}
    for name, model in models.items():
        files[root / GENERATED / f"foundation_{name}.py"] = foundation_module(name, model)
    for name in DECLARED:
        files[root / GENERATED / f"vehicle_{name}.py"] = vehicle_module(name)
    files[root / GENERATED / "parameters.py"] = parameters_module()
    catalogue = [
        ("BEAMS", {name: beam.title for name, beam in BEAMS.items()}),
        ("TRACKS", {name: track.title for name, track in TRACKS.items()}),
        ("VEHICLES", {name: DECLARED[name]().description for name in DECLARED}),
        ("DECLARED_VEHICLES", {name: DECLARED[name]().description for name in DECLARED}),
        ("MODULES", {(m.beam, m.track): f"foundation_{name}" for name, m in models.items()}),
        ("FOUNDATIONS", tuple(models)),
    ]
    digest = definition_digest(*[value for _, value in catalogue])
    init = module_source("Generated kernels of moving-bogie: the catalogue of models.", digest, [], catalogue)
    files[root / GENERATED / "__init__.py"] = init
    files[root / GENERATED / "asymptotics.py"] = asymptotics_module(models)
    files[root / "docs" / "proofs.md"] = proofs_markdown()
    return files
