"""The search window of :func:`~moving_bogie.roots.frequencies.induced_frequencies`.

:func:`default_window` is the scale of the induced frequencies (natural-frequency estimates);
:func:`far_field_window` widens it to the far-field radius R (:mod:`~moving_bogie.roots.count.far_field`),
beyond which E_chr (Eq. (48)) has no root with Im q < 0, so that the lower half of the window holds every
unstable root.
"""

from __future__ import annotations

from moving_bogie.kernels.bound import BoundModel
from moving_bogie.roots.count.contour import Rectangle
from moving_bogie.roots.count.far_field import FarField, far_field_radius

__all__ = ["default_window", "far_field_window"]


def default_window(bound: BoundModel) -> Rectangle:
    """Default search window: 0 <= Re q <= X, -X <= Im q <= X + eta_f.

    X = max(3, 3 f) where f is the largest natural-frequency estimate of the model: the beam on its
    foundation (q = 1 at rest, Eq. (24) with p = 0) and the vehicle's bodies with the wheels held
    (K_ii v = q^2 M_ii v, the zeros of det D_ii that E_chr approaches when K -> 0; for the bogie its bounce
    sqrt(2 kappa_v / mu_v) and pitch sqrt(kappa_v d^2 / (2 J_b)), the zeros of B2 and B3 of Eq. (37)).
    For large |q| E_chr approaches its leading part (:mod:`~moving_bogie.roots.count.far_field`), which has no
    zeros: every root lies at moderate |q|. The search still checks a window twice as large
    (``check_window``).
    The left edge sits slightly left of Re q = 0 so that a purely imaginary root is inside, not on it.
    :func:`induced_frequencies` widens it to the far-field radius R (:func:`far_field_window`).
    """
    f = bound.floats
    scale = [1.0, *bound.float_system.natural_frequencies()]
    X = max(3.0, 3.0 * max(scale))
    return Rectangle(-1e-3 * X, X, -X, X + f.eta_f)


def far_field_window(bound: BoundModel) -> tuple[Rectangle, FarField]:
    """The window searched by default and the far-field check that justifies it.

    With S = max(X, R), X the scale of :func:`default_window` and R the radius beyond which E_chr has no root
    with Im q < 0 (:func:`~moving_bogie.roots.count.far_field.far_field_radius`): -S/1000 <= Re q <= S,
    -S <= Im q <= S + eta_f. The lower half contains every root with Im q < 0; the upper half (roots that
    decay) is a stated choice, checked against a window twice as large.
    """
    base = default_window(bound)
    far = far_field_radius(bound, base.x1)
    if far.radius is None:
        return base, far
    S = max(base.x1, far.radius)
    return Rectangle(-1e-3 * S, S, -S, S + float(bound.params.eta_f)), far
