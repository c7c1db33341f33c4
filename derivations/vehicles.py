"""Vehicles declared as data: wheels, rigid bodies and spring-dampers; SymPy assembles their matrices.

A vehicle is

- **wheels** (mass, contact position along the track, constant load), in permanent contact with the rail:
  the deflection of a wheel is the rail's deflection under it; the rear wheel sits at x = 0 and positions
  increase forwards. A wheel of mass 0 is a massless contact point: a wheel mass above it on a contact
  spring-damper (a linearised Hertz spring k_H, c_H) is then a body;
- **rigid bodies** (mass, pitch moment of inertia or none for a body that only bounces, centre position):
  a point at x on a body moves u + (x - x_c) theta (theta > 0 lifts the front);
- **spring-dampers** (stiffness, viscous damping) acting vertically at a position x between a point of one
  wheel or body below and a point of another above.

The assembly is the general one (Lagrange's equations of the quadratic energies): each spring-damper with
extension e = g . x adds k g g^T to the stiffness matrix and c g g^T to the damping matrix, so asymmetric
layouts get their bounce-pitch cross terms. The degrees of freedom are the n wheel deflections first (in
contact order, rear first), then each body's bounce and pitch.

Everything is then made dimensionless as the rest of the derivation (Eqs. (15)-(17)): time tau = omega t,
displacements in units of w_st, rotations in units of w_st chi (so that a point at xi on a body moves
U + (xi - xi_c) Theta with xi = chi x), forces multiplied by chi / (k_f w_st) and moments by
chi^2 / (k_f w_st) (the matrices stay symmetric; the constant load P becomes 2). With
D(q) = -q^2 M + i q C + K (d/dtau -> i q, Eq. (21)) the force that wheel j exerts on the rail is
f_j = 2 - (D x)_j (times i q, as every image in ``system.py``), and the beam rows of Eq. (28) read
pi W_i = 2 sum_j K(xi_i - xi_j, q) f_j.
The characteristic function of a vehicle on n wheels is therefore the determinant of the block matrix

    [[pi I + 2 Kmat D_cc, 2 Kmat D_ci], [D_ic, D_ii]],   Kmat_ij = K(xi_i - xi_j, q)

(c: the wheel rows and columns, i: the internal ones); for the paper's bogie it is -1/2 times Eq. (38)
(``block_characteristic`` below, checked in tests/test_vehicles.py).

Per-rail convention: the paper's beam is one rail and its vehicle is what one rail carries. A car is
declared per rail too (half of the car's mass and inertia, one wheel of each wheelset), as STEM and ROSE do;
a whole vehicle on a beam standing for both rails would double every mass, stiffness and load instead.
"""

from dataclasses import dataclass, field

import sympy as sp

from . import symbols as s

I = sp.I  # noqa: E741


@dataclass(frozen=True)
class Wheel:
    """A wheel in permanent contact: its deflection is the rail's; ``position`` along the track (SI)."""

    name: str
    mass: sp.Expr
    position: sp.Expr
    load: sp.Expr = s.P


@dataclass(frozen=True)
class Body:
    """A rigid body: bounce DOF ``name``, pitch DOF ``pitch`` (None: the body only bounces)."""

    name: str
    mass: sp.Expr
    centre: sp.Expr
    inertia: sp.Expr | None = None
    pitch: str | None = None


@dataclass(frozen=True)
class Link:
    """A vertical spring-damper at ``at`` (SI position) between ``lower`` and ``upper`` (wheels or bodies)."""

    lower: str
    upper: str
    at: sp.Expr
    stiffness: sp.Expr
    damping: sp.Expr = sp.Integer(0)


@dataclass(frozen=True)
class Vehicle:
    """A declared vehicle: its wheels (rear first), bodies and spring-dampers, and a one-line description."""

    description: str
    wheels: tuple
    bodies: tuple = ()
    links: tuple = ()
    extra: dict = field(default_factory=dict)

    @property
    def dofs(self) -> tuple:
        """The DOF names: the wheel deflections in contact order, then each body's bounce and pitch."""
        names = [w.name for w in self.wheels]
        for b in self.bodies:
            names.append(b.name)
            if b.pitch is not None:
                names.append(b.pitch)
        return tuple(names)

    @property
    def rotations(self) -> frozenset:
        return frozenset(b.pitch for b in self.bodies if b.pitch is not None)


@dataclass(frozen=True)
class VehicleMatrices:
    """The assembled dimensionless vehicle: M, C, K (symmetric), contact positions xi_j, static loads."""

    dofs: tuple
    contacts: int
    mass: sp.Matrix
    damping: sp.Matrix
    stiffness: sp.Matrix
    positions: tuple
    loads: tuple
    units: dict
    parameters: tuple  # parameter symbols (dimensionless groups), sorted by name

    def dynamic_stiffness(self, q=s.q) -> sp.Matrix:
        """D(q) = -q^2 M + i q C + K: d/dtau -> i q (Eq. (21))."""
        return (-(q**2) * self.mass + I * q * self.damping + self.stiffness).applyfunc(sp.expand)


def _gradient(vehicle: Vehicle, element: str, x) -> list:
    """The displacement at x of a wheel or body as a row of coefficients on the DOFs (SI)."""
    dofs = vehicle.dofs
    row = [sp.Integer(0)] * len(dofs)
    for w in vehicle.wheels:
        if w.name == element:
            row[dofs.index(w.name)] = sp.Integer(1)
            return row
    for b in vehicle.bodies:
        if b.name == element:
            row[dofs.index(b.name)] = sp.Integer(1)
            if b.pitch is not None:
                row[dofs.index(b.pitch)] = sp.expand(x - b.centre)
            elif sp.expand(x - b.centre) != 0:
                raise ValueError(f"body {b.name} has no pitch DOF but a link acts off its centre at {x}")
            return row
    raise ValueError(f"link to an undeclared wheel or body {element!r}")


def _dimensionless(expr):
    e = sp.expand(sp.powsimp(sp.expand(sp.sympify(expr).xreplace(s.PHYSICAL_IN_DIMENSIONLESS)), force=True))
    leftover = e.free_symbols & {s.EI, s.m, s.k_f, s.P}
    if leftover:
        raise AssertionError(f"vehicle term not dimensionless, depends on {sorted(map(str, leftover))}: {e}")
    return e


def assemble(vehicle: Vehicle) -> VehicleMatrices:
    """Mass, damping and stiffness matrices of a declared vehicle, dimensionless (Eqs. (15)-(17))."""
    dofs = vehicle.dofs
    n = len(dofs)
    Mp, Cp, Kp = sp.zeros(n, n), sp.zeros(n, n), sp.zeros(n, n)
    for w in vehicle.wheels:
        Mp[dofs.index(w.name), dofs.index(w.name)] = w.mass
    for b in vehicle.bodies:
        Mp[dofs.index(b.name), dofs.index(b.name)] = b.mass
        if b.pitch is not None:
            Mp[dofs.index(b.pitch), dofs.index(b.pitch)] = b.inertia
    for link in vehicle.links:
        g = sp.Matrix(_gradient(vehicle, link.upper, link.at)) - sp.Matrix(
            _gradient(vehicle, link.lower, link.at)
        )
        Kp += link.stiffness * g * g.T
        Cp += link.damping * g * g.T
    rotation = vehicle.rotations
    # DOF scales (w_st, or w_st chi for a rotation) and row scales (chi/(k_f w_st) for a force,
    # chi^2/(k_f w_st) for a moment); d/dt = omega d/dtau.
    dof_scale = [s.w_st * s.chi if name in rotation else s.w_st for name in dofs]
    row_scale = [
        s.chi**2 / (s.k_f * s.w_st) if name in rotation else s.chi / (s.k_f * s.w_st) for name in dofs
    ]

    def scaled(A, time_power):
        return sp.Matrix(
            n, n, lambda i, j: _dimensionless(A[i, j] * s.omega**time_power * dof_scale[j] * row_scale[i])
        )

    mass, damping, stiffness = scaled(Mp, 2), scaled(Cp, 1), scaled(Kp, 0)
    positions = tuple(_dimensionless(s.chi * w.position) for w in vehicle.wheels)
    loads = tuple(_dimensionless(w.load * s.chi / (s.k_f * s.w_st)) for w in vehicle.wheels)
    for A in (mass, damping, stiffness):
        if A != A.T:
            raise AssertionError("assembled vehicle matrix is not symmetric")
    units = {name: "rad" if name in rotation else "m" for name in dofs}
    free = set().union(
        *(e.free_symbols for A in (mass, damping, stiffness) for e in A), *(x.free_symbols for x in positions)
    )
    return VehicleMatrices(
        dofs,
        len(vehicle.wheels),
        mass,
        damping,
        stiffness,
        positions,
        loads,
        units,
        tuple(sorted(free, key=str)),
    )


def block_characteristic(matrices: VehicleMatrices, kernel) -> sp.Expr:
    """det [[pi I + 2 Kmat D_cc, 2 Kmat D_ci], [D_ic, D_ii]] with Kmat_ij = kernel(xi_i - xi_j)."""
    n = matrices.contacts
    total = len(matrices.dofs)
    D = matrices.dynamic_stiffness()
    Kmat = sp.Matrix(n, n, lambda i, j: kernel(sp.expand(matrices.positions[i] - matrices.positions[j])))
    A = sp.zeros(total, total)
    A[:n, :] = 2 * Kmat * D[:n, :]
    A[:n, :n] += sp.pi * sp.eye(n)
    A[n:, :] = D[n:, :]
    return sp.expand(A.det(method="berkowitz"))


# --- the vehicles ------------------------------------------------------------------------------------------

P = s.P
x_rear, x_front = sp.Integer(0), s.d_phys


def moving_mass() -> Vehicle:
    """One wheel: the classical moving mass M under the constant load P."""
    return Vehicle(moving_mass.__doc__.splitlines()[0], (Wheel("w", s.M, x_rear),))


def oscillator() -> Vehicle:
    """One wheel under a sprung mass: a spring-damper (k_v, c_v) over the wheel mass M."""
    return Vehicle(
        oscillator.__doc__.splitlines()[0],
        (Wheel("w", s.M, x_rear),),
        (Body("u", s.M_b, x_rear),),
        (Link("w", "u", x_rear, s.k_v, s.c_v),),
    )


def two_masses() -> Vehicle:
    """Two moving masses (Figure 1a): the bogie's loads with no suspension, B1 = eta_M q^2."""
    return Vehicle(
        two_masses.__doc__.splitlines()[0], (Wheel("w_rear", s.M, x_rear), Wheel("w_front", s.M, x_front))
    )


def bogie() -> Vehicle:
    """The bogie of Figure 1b: a rigid bar on two spring-dampers over two wheel masses, Eqs. (23)-(47)."""
    return Vehicle(
        bogie.__doc__.splitlines()[0],
        (Wheel("w_rear", s.M, x_rear), Wheel("w_front", s.M, x_front)),
        (Body("u", s.M_b, s.d_phys / 2, s.J_phys, "theta"),),
        (
            Link("w_rear", "u", x_rear, s.k_v, s.c_v),
            Link("w_front", "u", x_front, s.k_v, s.c_v),
        ),
    )


def car() -> Vehicle:
    """A car per rail: a body on two secondary suspensions, two bogies, four wheels (Zhai & Sun 1994)."""
    L, d = s.L_phys, s.d_phys
    wheels = tuple(Wheel(f"w_{j + 1}", s.M, x) for j, x in enumerate((0, d, L, L + d)))
    bodies = (
        Body("u_b1", s.M_b, d / 2, s.J_phys, "theta_b1"),
        Body("u_b2", s.M_b, L + d / 2, s.J_phys, "theta_b2"),
        Body("u_c", s.M_c, (L + d) / 2, s.J_c_phys, "theta_c"),
    )
    links = (
        Link("w_1", "u_b1", 0, s.k_v, s.c_v),
        Link("w_2", "u_b1", d, s.k_v, s.c_v),
        Link("w_3", "u_b2", L, s.k_v, s.c_v),
        Link("w_4", "u_b2", L + d, s.k_v, s.c_v),
        Link("u_b1", "u_c", d / 2, s.k_sec, s.c_sec),
        Link("u_b2", "u_c", L + d / 2, s.k_sec, s.c_sec),
    )
    return Vehicle(car.__doc__.splitlines()[0], wheels, bodies, links)


def _contact_name(wheel: str) -> str:
    """The contact point under a wheel: ``w`` -> ``c``, ``w_rear`` -> ``c_rear``, ``w_1`` -> ``c_1``."""
    return "c" + wheel[1:] if wheel.startswith("w") else f"c_{wheel}"


def on_contact_springs(vehicle: Vehicle) -> Vehicle:
    """The vehicle with each wheel on its own linearised Hertz contact spring-damper (k_H, c_H).

    Every wheel becomes a massless contact point (a wheel of mass 0, same position and load: its deflection
    is the rail's) and, above it, a body of the wheel's mass and name, bouncing only, linked to it by
    (k_H, c_H). The vehicle's own spring-dampers keep acting on that body. The load P acts at the contact:
    the static compression P / k_H of each contact spring, a constant offset of its wheel, is left out of
    the wheel's displacement; it changes no frequency and no contact force. As k_H -> infinity each contact
    spring locks and the vehicle is the rigid-contact one (tests/test_hertz.py).
    """
    contacts = tuple(Wheel(_contact_name(w.name), sp.Integer(0), w.position, w.load) for w in vehicle.wheels)
    wheels = tuple(Body(w.name, w.mass, w.position) for w in vehicle.wheels)
    springs = tuple(Link(c.name, w.name, w.position, s.k_H, s.c_H) for c, w in zip(contacts, vehicle.wheels))
    description = f"{vehicle.description.rstrip('.')}; each wheel on a Hertz contact spring (k_H, c_H)."
    return Vehicle(description, contacts, wheels + vehicle.bodies, springs + vehicle.links)


def hertz_mass() -> Vehicle:
    """One wheel on a Hertz spring: the wheel mass M on a linearised contact spring (k_H, c_H), load P.

    The rigid-contact ``mass`` on its contact spring (:func:`on_contact_springs`): the contact point is a
    wheel of mass 0 (its deflection is the rail's), the wheel mass a body above it.
    """
    declared = on_contact_springs(moving_mass())
    return Vehicle(hertz_mass.__doc__.splitlines()[0], declared.wheels, declared.bodies, declared.links)


#: The rigid-contact vehicles, name -> declaration.
RIGID = {
    "mass": moving_mass,
    "oscillator": oscillator,
    "masses": two_masses,
    "bogie": bogie,
    "car": car,
}

#: Each rigid-contact vehicle -> the name of its variant on Hertz contact springs (``hertz_mass`` for
#: ``mass``); a parameter file that sets the contact spring (k_H, c_H) selects the variant.
CONTACT_SPRINGS = {name: f"hertz_{name}" for name in RIGID}


def _variant(name: str):
    def build() -> Vehicle:
        return on_contact_springs(RIGID[name]())

    return build


#: name -> declaration. A new vehicle is one more entry of ``RIGID`` (docs/adding_a_model.md); its variant
#: on contact springs follows.
VEHICLES = {
    **RIGID,
    "hertz_mass": hertz_mass,
    **{CONTACT_SPRINGS[name]: _variant(name) for name in RIGID if name != "mass"},
}

#: The groups of the contact spring: a parameter file that sets one selects the contact-spring variant.
CONTACT_SPRING_GROUPS = (str(s.kappa_H), str(s.eta_H))
