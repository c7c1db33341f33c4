"""The generated vehicle modules ``vehicle_<name>.py``.

Each holds a declared vehicle's matrices (``vehicles.py``) and, for the vehicles that ``system.py`` derives
in closed form (the bogie, two masses), E_chr of Eq. (38) with its partial derivatives, residue numerators
and shape weights.
"""

import sympy as sp

from . import symbols as s
from .emit import definition_digest, function_source, module_source
from .system import SYSTEMS, in_q
from .vehicle_degrees import block_degrees
from .vehicles import VEHICLES as DECLARED
from .vehicles import assemble


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
    degrees = block_degrees(matrices)
    fixed = block_degrees(matrices, follow=False)
    if name in SYSTEMS:
        system_parts, system_constants, system_definitions = _system_parts(name)
        for key, block in (("POLYNOMIAL_DEGREES", degrees), ("FIXED_POLYNOMIAL_DEGREES", fixed)):
            closed = dict(system_constants)[key]
            if closed != block:  # two derivations of one fact: the closed form and the block system
                raise AssertionError(f"{name}: {key} {closed} (Eq. (38)) != {block} (block system)")
        parts = system_parts + parts
        constants += system_constants
        definitions += system_definitions
    else:
        constants += [
            ("PARAMETERS", params),
            ("MODEL_PARAMETERS", tuple(g for g in s.GROUPS if g in set(params))),
            ("RESPONSES", matrices.dofs),
            ("POLYNOMIAL_DEGREES", degrees),
            ("FIXED_POLYNOMIAL_DEGREES", fixed),
        ]
    constants += [
        ("CONTACTS", matrices.contacts),
        ("DOFS", matrices.dofs),
        ("UNITS", matrices.units),
        ("MATRIX_ARGUMENTS", params),
        *roles(matrices),
    ]
    title = f"Vehicle '{name}': its matrices, characteristic function, derivatives and residue numerators."
    digest = definition_digest(*definitions)
    return module_source(title, digest, parts, constants)


def _role(entry) -> str | None:
    """The one dimensionless group that a matrix entry is proportional to (None for an entry 0)."""
    groups = sorted(str(x) for x in sp.sympify(entry).free_symbols)
    if not groups:
        return None
    if len(groups) != 1:
        raise AssertionError(f"a role's matrix entry depends on more than one group: {entry}")
    return groups[0]


def roles(matrices) -> list:
    """The groups the stability tools sweep by default, read off the assembled matrices.

    ``WHEEL_MASS``: the group of the first wheel's mass (M[0, 0]; for a massless contact point, the first
    mass on the diagonal: the wheel on its contact spring); ``PRIMARY_STIFFNESS``: that of the stiffness
    acting on the first contact (K[0, 0], the primary suspension or the contact spring; None for a vehicle
    without one).
    """
    masses = [matrices.mass[i, i] for i in range(len(matrices.dofs))]
    return [
        ("WHEEL_MASS", next((_role(x) for x in masses if x != 0), None)),
        ("PRIMARY_STIFFNESS", _role(matrices.stiffness[0, 0])),
    ]


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
    fixed = polynomial_degrees(system, follow=False)
    # The wheel spacing d places the contact points (K(+-d, q)) whatever the vehicle.
    model_params = tuple(g for g in s.GROUPS if g in set(params) | {"d"})
    constants = [
        ("ARGUMENTS", args),
        ("PARAMETERS", params),
        ("MODEL_PARAMETERS", model_params),
        ("RESPONSES", names),
        ("POLYNOMIAL_DEGREES", degrees),
        ("FIXED_POLYNOMIAL_DEGREES", fixed),
    ]
    definitions = [E, *system.atoms.values(), *system.numerators.values()]
    return parts, constants, definitions


def polynomial_degrees(system, follow: bool = True) -> dict:
    """Degree of E_chr in each vehicle parameter at fixed q and K, the alternatives held (Eq. (63)).

    The stability tools sweep a parameter by interpolating E_chr exactly in it. The wheel spacing d is left
    out: it also moves the contact point, so K(+-d, q) depends on it. A group that an alternative sets
    (mu_v = cf1 eta_M) follows its dependencies and is not swept on its own. With ``follow=False`` those
    groups are held fixed instead (mu_v, J_b constant as eta_M changes: a sweep over the wheel mass in SI
    units) and swept like the others.
    """
    E = sp.expand(in_q(system.E_chr, system))
    held = {group: expr for group, expr, _ in s.ALTERNATIVES.values() if group in system.parameters}
    if follow:
        E = sp.expand(E.subs(held))
    else:
        held = {}
    out = {}
    for par in system.parameters:
        if str(par) == "d" or par in held:
            continue
        out[str(par)] = sp.Poly(E, par).degree()
    return out
