"""Beams and tracks: the one place where the track models are defined.

A track model is a beam (the rail: Euler-Bernoulli or Timoshenko-Rayleigh) on a track (what supports the
rail: one viscoelastic layer with an optional Pasternak shear layer, or the layered tracks of
docs/layered_tracks.md: the rail on railpads over one or two continuous mass layers). Each is a square
matrix of constant-coefficient differential operators in fixed physical coordinates, written as
polynomials in the operator symbols ``dx`` (d/dx) and ``dt`` (d/dt). The first unknown is the rail
deflection ``w``; the moving loads enter the first equation only; every further unknown (the
cross-section rotation of a Timoshenko beam, the deflection of a mass layer, ...) is eliminated by the
derivation.

Every beam runs on every track: adding one ``Track`` to ``TRACKS`` (or one ``Beam`` to ``BEAMS``) and running
``python -m derivations`` generates the kernels of every new combination, with their metadata.
"""

from dataclasses import dataclass

import sympy as sp

from .symbols import (
    EI,
    GA,
    N_ax,
    c_2,
    c_3,
    c_f,
    chi,
    dt,
    dx,
    k_2,
    k_3,
    k_f,
    k_s,
    m,
    m_2,
    m_3,
    r_g,
    w_st,
)


@dataclass(frozen=True)
class TrackModel:
    """A track operator matrix with the scales that make it dimensionless.

    ``unknown_scales[j]`` converts the j-th dimensionless unknown to SI (w = w_st w~, phi = w_st chi phi~,
    Eqs. (16), (59)); ``row_scales[i]`` multiplies equation i (row 0 as in Eq. (18): 4 / (k_f w_st)).
    ``beam`` and ``track`` name the parts; ``description`` says what the model is in one line.
    """

    operator: sp.Matrix
    unknown_scales: tuple
    row_scales: tuple
    beam: str = ""
    track: str = ""
    description: str = ""
    si_names: tuple = ()


@dataclass(frozen=True)
class Beam:
    """The rail's operator on its own unknowns (w first), with their scales; ``title`` for listings."""

    title: str
    operator: sp.Matrix
    unknown_scales: tuple
    row_scales: tuple


@dataclass(frozen=True)
class Track:
    """What supports the rail.

    ``on_rail`` is added to the rail's first equation (the foundation reaction on w); ``layers`` is the
    operator matrix of further unknowns (mass layers), ``coupling[j]`` the operator that couples the rail
    deflection w with layer unknown j (symmetric), ``layer_scales`` the SI scale of each layer unknown and
    its row. ``si_names`` renames SI parameters on this track: symbol -> (SI name, meaning); the
    railpads of a layered track are the reference stiffness k_f of the scaling, named ``k_1`` there.
    """

    title: str
    on_rail: sp.Expr
    layers: sp.ImmutableMatrix = sp.ImmutableMatrix.zeros(0, 0)
    coupling: tuple = ()
    layer_scales: tuple = ()
    si_names: tuple = ()


BEAMS = {
    "eb": Beam(
        "Euler-Bernoulli beam, Eq. (1)", sp.Matrix([[EI * dx**4 + m * dt**2]]), (w_st,), (4 / (k_f * w_st),)
    ),
    # Eqs. (55)-(56), rotary inertia J = m r_g^2. Row 2 is scaled like Eq. (61) (4 S phi~ from GA phi); any
    # scale would do, it cancels in Q/N.
    "tr": Beam(
        "Timoshenko-Rayleigh beam, Eqs. (55)-(56)",
        sp.Matrix([[-GA * dx**2 + m * dt**2, GA * dx], [-GA * dx, GA + m * r_g**2 * dt**2 - EI * dx**2]]),
        (w_st, w_st * chi),
        (4 / (k_f * w_st), 2 / (sp.sqrt(k_f * EI) * w_st * chi)),
    ),
    # Eq. (A1): a compressive axial force N (the thermal force E A alpha_T dT of a continuous welded rail)
    # adds N w_xx to Eq. (1) (A. V. Metrikine and H. A. Dieterman, J. Sound Vib. 201(5), 567-576, 1997).
    "eb_axial": Beam(
        "Euler-Bernoulli beam under an axial compressive force N, Eq. (A1)",
        sp.Matrix([[EI * dx**4 + N_ax * dx**2 + m * dt**2]]),
        (w_st,),
        (4 / (k_f * w_st),),
    ),
}

TRACKS = {
    "one-layer": Track(
        "Winkler foundation with viscous damping and a Pasternak shear layer: k_f w + c_f w_t - k_s w_xx",
        k_f + c_f * dt - k_s * dx**2,
    ),
}

#: The railpads (k_1, c_1) are the reference stiffness and damping of the scaling on a layered track.
_PADS = k_f + c_f * dt
_LAYERED_NAMES = (
    (k_f, ("k_1", "railpad stiffness per unit length (reference stiffness of the scaling)")),
    (c_f, ("c_1", "railpad viscous damping per unit length")),
)
#: Pasternak shear k_s acts on the lowest mass layer (the ballast/subgrade surface).
TRACKS["two-layer"] = Track(
    "rail on railpads (k_1, c_1) over a mass layer m_2 (sleepers) on the support (k_2, c_2, shear k_s)",
    _PADS,
    sp.ImmutableMatrix([[m_2 * dt**2 + _PADS + k_2 + c_2 * dt - k_s * dx**2]]),
    (-_PADS,),
    ((w_st, 4 / (k_f * w_st)),),
    _LAYERED_NAMES,
)
TRACKS["three-layer"] = Track(
    "rail on railpads (k_1, c_1) over mass layers m_2 (sleepers) and m_3 (ballast), tied by (k_2, c_2),"
    " on the support (k_3, c_3, shear k_s)",
    _PADS,
    sp.ImmutableMatrix(
        [
            [m_2 * dt**2 + _PADS + k_2 + c_2 * dt, -(k_2 + c_2 * dt)],
            [-(k_2 + c_2 * dt), m_3 * dt**2 + k_2 + c_2 * dt + k_3 + c_3 * dt - k_s * dx**2],
        ]
    ),
    (-_PADS, sp.Integer(0)),
    ((w_st, 4 / (k_f * w_st)), (w_st, 4 / (k_f * w_st))),
    _LAYERED_NAMES,
)


def compose(beam: str, track: str) -> TrackModel:
    """The operator matrix of ``beam`` on ``track``: the rail block, the layer block and their coupling."""
    b, t = BEAMS[beam], TRACKS[track]
    nb, nl = b.operator.shape[0], t.layers.shape[0]
    op = sp.zeros(nb + nl, nb + nl)
    op[:nb, :nb] = b.operator
    op[0, 0] += t.on_rail
    for j in range(nl):
        op[0, nb + j] = op[nb + j, 0] = t.coupling[j]
        for i in range(nl):
            op[nb + i, nb + j] = t.layers[i, j]
    unknowns = tuple(b.unknown_scales) + tuple(s for s, _ in t.layer_scales)
    rows = tuple(b.row_scales) + tuple(r for _, r in t.layer_scales)
    return TrackModel(op, unknowns, rows, beam, track, f"{b.title} on a {track} track: {t.title}", t.si_names)


def model_name(beam: str, track: str) -> str:
    """Name of the generated kernel module's model: the beam alone on the paper's one-layer track."""
    return beam if track == "one-layer" else f"{beam}_{track.replace('-', '_')}"


def euler_bernoulli_pasternak() -> TrackModel:
    """Eq. (1) with the Pasternak layer k_s of the text: EI w_xxxx - k_s w_xx + m w_tt + c_f w_t + k_f w."""
    return compose("eb", "one-layer")


def timoshenko_rayleigh() -> TrackModel:
    """Eqs. (55)-(56) with the same foundation and Pasternak layer acting on w."""
    return compose("tr", "one-layer")


def _builder(beam, track):
    def build() -> TrackModel:
        return compose(beam, track)

    build.__doc__ = f"{BEAMS[beam].title} on the {track} track."
    return build


def all_models() -> dict:
    """model name -> builder, for every beam on every track (read at call time, so additions count)."""
    return {model_name(b, t): _builder(b, t) for t in TRACKS for b in BEAMS}


#: name -> track model builder, as of import time (``all_models()`` sees later additions too).
MODELS = all_models()
