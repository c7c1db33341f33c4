"""A beam added in derivations/ only: regenerated in a scratch copy and analysed with no edit of the runtime.

The scratch beam is the Rayleigh beam (Euler-Bernoulli with the rotary inertia m r_g^2 of its cross-section,
the existing group r = r_g chi of Eq. (59)): EI w_xxxx - m r_g^2 w_xxtt + m w_tt on the paper's track. Made
dimensionless by hand like Eq. (18) (the rotary term times 4 / (k_f w_st) gives 4 r^2) and carried to the
moving frame (d/dxi -> i p, d/dtau -> i q, s = q - alpha p):

    N(p, q) = p^4 + 4 eta_s p^2 - 4 s^2 - 4 r^2 p^2 s^2 + 8 i eta_f s + 4.

References, independent of the generated code they check: K(0, q) by adaptive quadrature of 1 / N over real p
(mpmath.quad); the finite beam (the scratch model's generated modal blocks, Newmark) against the closed form
(the scratch model's residues and branch cut), at the tolerance of the paper's beams.
"""

from __future__ import annotations

import mpmath
import pytest
from derivation_support import regenerated_copy, require_sympy

from moving_bogie import DimensionlessParams, table1_case
from moving_bogie.api import validate
from moving_bogie.kernels.bound import bind
from moving_bogie.kernels.track import TrackKernel
from moving_bogie.model.catalogue import Model, load_catalogue

require_sympy()

FOUNDATIONS = """
BEAMS["rayleigh"] = Beam(
    "Rayleigh beam: Euler-Bernoulli with rotary inertia m r_g^2",
    sp.Matrix([[EI * dx**4 - m * r_g**2 * dx**2 * dt**2 + m * dt**2]]),
    (w_st,),
    (4 / (k_f * w_st),),
)
"""


@pytest.fixture(scope="module")
def scratch(tmp_path_factory):
    """A copy of the source tree with the new beam, regenerated (``--only rayleigh``)."""
    return regenerated_copy(
        tmp_path_factory.mktemp("beam"), {"foundations.py": FOUNDATIONS}, only=("rayleigh",)
    )


def _params(scratch) -> DimensionlessParams:
    model = Model("rayleigh", "one-layer", "bogie", load_catalogue(scratch / "src/moving_bogie/generated"))
    return DimensionlessParams(model=model, **table1_case(7).values(), r="0.09")


@pytest.mark.slow
def test_kernel_against_quadrature(scratch):
    params = _params(scratch)
    f = params.as_float()
    q = mpmath.mpc("0.3", "-0.2")

    def n_by_hand(p):
        s = q - f.alpha * p
        return p**4 + 4 * f.eta_s * p**2 - 4 * s**2 - 4 * f.r**2 * p**2 * s**2 + 8j * f.eta_f * s + 4

    with mpmath.workdps(30):
        got = TrackKernel(bind(params))(q, [0]).K[0]
        breaks = [-mpmath.inf, *mpmath.linspace(-20, 20, 81), mpmath.inf]
        quadrature = mpmath.quad(lambda p: 1 / n_by_hand(p), breaks)
        assert abs(got - quadrature) < 1e-12 * abs(quadrature)


@pytest.mark.slow
def test_finite_beam_agrees_with_the_closed_form(scratch):
    result = validate(_params(scratch), tau_max=40.0, estimate=False)
    assert result.agrees and max(result.relative_diff.values()) < 2e-3, result.relative_diff
