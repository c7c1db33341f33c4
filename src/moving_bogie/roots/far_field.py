"""A radius R beyond which E_chr has no root in the lower half-plane (the far field of Eq. (48)).

``derivations/asymptotics.py`` derives, for every track and vehicle, the leading part E_lead of E_chr for
large |q| (``generated/asymptotics.py``): with K = O(|q|^-gamma) (Eq. (29)),
E_chr = E_lead + (terms smaller by |q|^-delta). Wherever

    rho(q) = |E_chr(q) - E_lead(q)| / |E_lead(q)| < 1,

E_chr cannot vanish (E_chr = 0 would give |E_lead| < |E_lead|). :func:`far_field_radius` looks for the
smallest R = R0 2^k at which rho <= 1/2 (a margin of 2) at every sample of the lower half-plane beyond R that
it checks: the half circles |q| = R, 2R, 4R, ..., 32R (angles clustered towards the real axis, where the
factors e^{i p_k d} of K(+-d) stop decaying), the two rays just below the real axis from R to 32R and seven
rays in between. Beyond
32R the derived decay rho = O(|q|^-delta) / |1 - K+ K- / K0^2| takes over (for Euler-Bernoulli the derivation
shows |K+ K- / K0^2| <= 1/2 asymptotically). The check is numerical, with that margin: it is what makes
"stable" a statement about every root with Im q < 0, and when it fails the verdict says UNDETERMINED.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from moving_bogie.errors import MovingBogieError
from moving_bogie.generated import asymptotics
from moving_bogie.kernels.characteristic import CharacteristicArray
from moving_bogie.kernels.track import foundation_module

#: rho must stay below this on every sample (1 would be enough for no root; 1/2 leaves a margin of 2).
MARGIN = 0.5
#: The samples reach out to this multiple of R (half circles at R, 2R, ..., OUTER R).
OUTER = 32
#: Doublings of R tried before giving up.
MAX_DOUBLINGS = 12


@dataclass(frozen=True)
class FarField:
    """Outcome of the far-field check: ``radius`` R (None when none could be justified), the largest rho."""

    radius: float | None
    rho: float
    start: float
    reason: str = ""

    def to_dict(self) -> dict:
        rho = self.rho if np.isfinite(self.rho) else None
        return {"radius": self.radius, "rho": rho, "margin": MARGIN, "reason": self.reason or None}


def model_name(params) -> str:
    """Name of the generated foundation module of ``params`` (``foundation_<name>``): its key here."""
    return foundation_module(params).__name__.rsplit(".", 1)[-1].removeprefix("foundation_")


def leading_part(model: str, beam: str):
    """The generated E_lead of ``model`` (vehicle) on ``beam`` (a :func:`model_name`) and the gap delta.

    Raises
    ------
    MovingBogieError
        When ``generated/asymptotics.py`` has no expansion for this pair (a model generated elsewhere).
    """
    name = f"e_chr_leading_{model}_{beam}"
    try:
        return getattr(asymptotics, name), Fraction(asymptotics.LEADING_GAP[(model, beam)])
    except (AttributeError, KeyError):
        message = f"no generated far-field expansion for {model} on {beam!r}: run python -m derivations"
        raise MovingBogieError(message) from None


def sample_points(
    radius: float, outer: int = OUTER, per_circle: int = 1200, per_ray: int = 4000, inner_rays: int = 7
):
    """q samples of {|q| >= radius, Im q < 0} up to ``outer * radius``: half circles and rays.

    The two rays just below the real axis carry ``per_ray`` points (there the factors e^{i p_k d} of K(+-d)
    oscillate without decaying); ``inner_rays`` rays in between carry a quarter as many.
    """
    t = np.linspace(0.0, 1.0, per_circle)
    theta = -np.pi * (0.5 - 0.5 * np.cos(np.pi * t))  # clustered at 0 and -pi
    theta = np.clip(theta, -np.pi + 1e-7, -1e-7)
    circles = [radius * 2.0**k * np.exp(1j * theta) for k in range(int(np.log2(outer)) + 1)]
    r = np.linspace(radius, outer * radius, per_ray)
    below = -1e-7 * r * 1j
    angles = -np.pi * np.arange(1, inner_rays + 1) / (inner_rays + 1)
    inner = np.outer(np.linspace(radius, outer * radius, per_ray // 4), np.exp(1j * angles)).ravel()
    return np.concatenate(circles + [r + below, -r + below, inner])


def rho(params, model: str, q) -> np.ndarray:
    """|E_chr - E_lead| / |E_lead| at the points ``q`` (double precision)."""
    E = CharacteristicArray(params, model)
    lead, _ = leading_part(model, model_name(params))
    q = np.asarray(q, dtype=complex)
    kv = E.kernel(q, [0.0, E.d, -E.d])
    with np.errstate(all="ignore"):
        full = E.module.e_chr(q, *kv.K, **E.args)
        main = lead(q, *kv.K, **E.args)
        out = np.abs(full - main) / np.abs(main)
    return np.where(np.isfinite(out), out, np.inf)


def far_field_radius(params, model: str, start: float) -> FarField:
    """Smallest R = start 2^k (k <= MAX_DOUBLINGS) with rho <= MARGIN on every sample beyond R.

    Parameters
    ----------
    params : DimensionlessParams
    model : {"bogie", "masses"}
    start : float
        First radius tried (the default window's scale).
    """
    radius = float(start)
    worst = np.inf
    try:
        leading_part(model, model_name(params))
    except MovingBogieError as exc:
        return FarField(None, worst, float(start), str(exc))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        for _ in range(MAX_DOUBLINGS + 1):
            values = rho(params, model, sample_points(radius))
            worst = float(np.max(values))
            if worst <= MARGIN:
                return FarField(radius, worst, float(start))
            radius *= 2.0
    reason = (
        f"no radius up to {radius / 2:.3g} keeps |E_chr - E_lead| / |E_lead| <= {MARGIN} "
        f"(largest {worst:.3g}): roots with Im q < 0 far out cannot be excluded"
    )
    return FarField(None, worst, float(start), reason)
