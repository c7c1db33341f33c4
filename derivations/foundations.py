"""Beam + foundation operators: the one place where the track model is defined.

A track model is a square matrix of constant-coefficient differential operators in fixed physical
coordinates, written as polynomials in the operator symbols ``dx`` (d/dx) and ``dt`` (d/dt). The first
unknown is the beam deflection ``w``; the moving loads enter the first equation only. Any further unknowns
(the cross-section rotation of a Timoshenko beam, a second layer, ...) are eliminated by the derivation.

To add a foundation model, add one function returning its ``TrackModel`` and one entry to ``MODELS``;
``python -m derivations`` then derives its D(p, q) = N/Q and writes ``generated/foundation_<name>.py``.
"""

from dataclasses import dataclass

import sympy as sp

from .symbols import EI, GA, c_f, chi, dt, dx, k_f, k_s, m, r_g, w_st


@dataclass(frozen=True)
class TrackModel:
    """A track operator matrix with the scales that make it dimensionless.

    ``unknown_scales[j]`` converts the j-th dimensionless unknown to SI (w = w_st w~, phi = w_st chi phi~,
    Eqs. (16), (59)); ``row_scales[i]`` multiplies equation i (row 0 as in Eq. (18): 4 / (k_f w_st)).
    ``parameters`` names the dimensionless groups the model adds to alpha, eta_f, eta_s.
    """

    operator: sp.Matrix
    unknown_scales: tuple
    row_scales: tuple
    parameters: tuple


def euler_bernoulli_pasternak() -> TrackModel:
    """Eq. (1) with the Pasternak layer k_s of the text: EI w_xxxx - k_s w_xx + m w_tt + c_f w_t + k_f w."""
    op = sp.Matrix([[EI * dx**4 - k_s * dx**2 + m * dt**2 + c_f * dt + k_f]])
    return TrackModel(op, (w_st,), (4 / (k_f * w_st),), ())


def timoshenko_rayleigh() -> TrackModel:
    """Eqs. (55)-(56), rotary inertia J = m r_g^2, with the same Pasternak layer acting on w.

    Row 1: -GA w_xx + GA phi_x + m w_tt + c_f w_t + k_f w - k_s w_xx = p
    Row 2: -GA w_x + GA phi + m r_g^2 phi_tt - EI phi_xx = 0
    """
    op = sp.Matrix(
        [
            [-GA * dx**2 - k_s * dx**2 + m * dt**2 + c_f * dt + k_f, GA * dx],
            [-GA * dx, GA + m * r_g**2 * dt**2 - EI * dx**2],
        ]
    )
    # Row 2 is scaled like Eq. (61) (4 S phi~ from GA phi); any scale would do, it cancels in Q/N.
    row_scales = (4 / (k_f * w_st), 2 / (sp.sqrt(k_f * EI) * w_st * chi))
    return TrackModel(op, (w_st, w_st * chi), row_scales, ("S", "r"))


#: name -> track model builder. Adding a model here is all the runtime needs (after regenerating).
MODELS = {
    "eb": euler_bernoulli_pasternak,
    "tr": timoshenko_rayleigh,
}
