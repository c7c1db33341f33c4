"""What ``python -m derivations`` writes: the generated kernels, their metadata and the proof table.

Into src/moving_bogie/generated/:
foundation_<name>.py  coefficients (highest power first) of N(p, q), dN/dq, Q(p, q), dQ/dq in p; the
                      model's beam, track, parameters and degrees; where the cut of K is a half-line, its
                      Im q and the radicand R(p) (cut_line.py); the per-mode mass, damping and stiffness
                      blocks of the simply supported finite rail (validation)
vehicle_<name>.py     the declared vehicle (derivations/vehicles.py): contacts, DOFs, units, M, C, K, contact
                      positions, static loads; for bogie and masses also E_chr, its partial derivatives,
                      residue numerators and shape weights
parameters.py         every dimensionless group: meaning, constraint, default, equation, SI name and unit,
                      the exact SI <-> dimensionless scaling, the scales of Eqs. (15)-(16), Eq. (63)
__init__.py           the catalogue: beams, tracks, vehicles and which module holds each combination; each
                      rigid-contact vehicle's variant on Hertz contact springs and the groups that select it
and docs/proofs.md: derived == printed, equation by equation (paper.py).
"""

import re
from pathlib import Path

import sympy as sp

from . import symbols as s
from .asymptotics import asymptotics_module, kernel_decay
from .cut_line import cut_line
from .emit import SCALING_PRINTER, definition_digest, function_source, module_source
from .foundations import BEAMS, TRACKS, all_models
from .modal import modal_blocks
from .model import coefficients, derivative, foundation_image
from .paper import all_proofs
from .sleepers import TRACKS as SLEEPER_TRACKS
from .sleepers import sleepers_module
from .soil import soil_module
from .vehicle_modules import vehicle_module
from .vehicles import CONTACT_SPRING_GROUPS, CONTACT_SPRINGS
from .vehicles import VEHICLES as DECLARED

HERE = Path(__file__).resolve().parent
#: Where the kernels go, relative to the repository root: inside the package, so the source tree imports.
GENERATED = Path("src/moving_bogie/generated")
GENERATOR = "python -m derivations"


def _coeffs(expr, var):
    """(degree, coefficients highest first) of ``expr`` as a polynomial in ``var`` (``coefficients``)."""
    degree, coeffs = coefficients(expr, var)
    return degree, list(coeffs)


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
        function_source("n_coeffs_dq", args, [derivative(c, s.q) for c in n], "Coefficients of dN/dq in p."),
        function_source("q_coeffs", args, qq, "Coefficients of Q(p, q) in p, highest power first."),
        function_source("q_coeffs_dq", args, [derivative(c, s.q) for c in qq], "Coefficients of dQ/dq in p."),
    ]
    line = cut_line(model)
    if line is not None:
        parts += [
            function_source(
                "cut_line_im",
                params,
                [line.im],
                "Im q on the cut of K, a half-line: q = alpha p + i cut_line_im +- sqrt(R(p))/2 for real p.",
                scalar=True,
            ),
            function_source(
                "cut_line_radicand",
                params,
                _coeffs(line.radicand, s.p)[1],
                "Coefficients of R(p) in p, highest first (the cut: Re q = alpha p +- sqrt(R(p))/2).",
            ),
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


def selectable() -> tuple:
    """The names ``--only`` accepts: every beam, track and vehicle of the catalogue."""
    return (*BEAMS, *TRACKS, *SLEEPER_TRACKS, "soil", *DECLARED)


def outputs(root: Path, only=None) -> dict:
    """Map of path -> text of every generated file, or with ``only`` (names of beams, tracks, vehicles) of
    the kernel modules of those (every model on a named beam or track, each named vehicle) and the files
    that index the whole catalogue (``__init__.py``, ``asymptotics.py``, ``parameters.py``), which are
    always derived in full. The other kernel modules and ``docs/proofs.md`` are left out: that is for a
    copy whose only change is the addition of the named beams, tracks or vehicles.
    """
    files = {}
    models = {name: build() for name, build in all_models().items()}
    for name, model in models.items():
        if only is None or model.beam in only or model.track in only:
            files[root / GENERATED / f"foundation_{name}.py"] = foundation_module(name, model)
    for name in DECLARED:
        if only is None or name in only:
            files[root / GENERATED / f"vehicle_{name}.py"] = vehicle_module(name)
    files[root / GENERATED / "parameters.py"] = parameters_module()
    catalogue = [
        ("BEAMS", {name: beam.title for name, beam in BEAMS.items()}),
        ("TRACKS", {name: track.title for name, track in TRACKS.items()}),
        ("VEHICLES", {name: DECLARED[name]().description for name in DECLARED}),
        ("DECLARED_VEHICLES", {name: DECLARED[name]().description for name in DECLARED}),
        ("CONTACT_SPRINGS", CONTACT_SPRINGS),
        ("CONTACT_SPRING_GROUPS", CONTACT_SPRING_GROUPS),
        ("MODULES", {(m.beam, m.track): f"foundation_{name}" for name, m in models.items()}),
        ("FOUNDATIONS", tuple(models)),
    ]
    digest = definition_digest(*[value for _, value in catalogue])
    init = module_source("Generated kernels of moving-bogie: the catalogue of models.", digest, [], catalogue)
    files[root / GENERATED / "__init__.py"] = init
    files[root / GENERATED / "asymptotics.py"] = asymptotics_module(models)
    if only is None or only & {"sleepers", "sleepers-two-layer"}:
        files[root / GENERATED / "sleepers.py"] = sleepers_module()
    if only is None or "soil" in only:
        files[root / GENERATED / "soil_layer.py"] = soil_module()
    if only is None:
        files[root / "docs" / "proofs.md"] = proofs_markdown()
    return files
