"""Critical velocity of a constant moving force, Eqs. (65)-(66), from the dispersion relation of any track.

A constant force moving at alpha excites a steady wave of wavenumber p wherever N(p, 0) = 0 has a real
root on the undamped track (every damping group zero; q = 0 in the moving frame). Because every track
operator has constant coefficients, N(p, q; alpha) = N(p, q - alpha p; 0): the free waves of the track at
rest have the frequencies +-Omega_j(p) (the roots in q of N(p, q; 0), the dispersion branches j = 1, 2, ...
counted from below), and the force resonates with branch j where alpha = c_j(p) = Omega_j(p) / p, the
phase speed. The resonance velocity is where the load's line Omega = alpha p is tangent to a branch: a
*local* minimum of c_j(p), where N(p, 0) has a real double root in p, so (p_cr, alpha_cr) solves
N = dN/dp = 0.

On the paper's one-layer track there is one branch and its minimum is Eq. (65) (Euler-Bernoulli with a
Pasternak layer, alpha_cr = sqrt(1 + eta_s) at p^2 = 2) or Eq. (66) (Timoshenko-Rayleigh); those closed
forms are the paper's formulas for its two beams and live in ``paper/critical_velocity_formulas.py``, which
a caller passes as ``formula`` to compare with. On a layered
track (docs/layered_tracks.md) the lowest branch is bounded (the mass layer's own vibration) unless a
shear layer stiffens it, so c_1(p) -> 0 as p grows: the global infimum of the phase speed is 0 and is no
critical velocity. The critical velocity is the smallest local minimum over all branches; every local
minimum is reported with its branch, and a branch without one is named.

Every local minimum is bracketed on a grid of p in double precision, polished with mpmath's Newton on the
2x2 system at ``dps`` digits and confirmed at ``dps + 15``.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from fractions import Fraction
from types import ModuleType
from typing import Any

import mpmath
import numpy as np

from moving_bogie.errors import MovingBogieError, ParameterError
from moving_bogie.kernels.bound import BoundModel
from moving_bogie.kernels.polynomial import derivative_coefficients, horner
from moving_bogie.kernels.polyroots import companion_roots
from moving_bogie.model.catalogue import Model, get_model
from moving_bogie.model.exact import fraction_to_mpf, nonnegative, positive
from moving_bogie.model.values import ModelValues
from moving_bogie.stability.velocity.critical_result import CriticalVelocity, PhaseSpeedMinimum
from moving_bogie.typing import FloatArray, Mpf

__all__ = [
    "CriticalVelocity",
    "PhaseSpeedMinimum",
    "critical_velocity",
    "dispersion_branches",
    "phase_speed",
]


#: What the critical velocity is computed from: a model, parameters (their model and track groups), a bound
#: model, or None (the paper's model).
Source = Model | ModelValues | BoundModel | None


def _track(source: Source, groups: Mapping[str, Any]) -> tuple[Model, dict[str, Fraction]]:
    """The model and the values of its foundation's groups (None: the paper's, a Model, or parameters)."""
    if isinstance(source, BoundModel):
        source = source.params
    if source is None:
        model = get_model()
    elif isinstance(source, Model):
        model = source
    elif hasattr(source, "model") and hasattr(source, "values"):
        model = source.model
        groups = {**source.values(), **{k: v for k, v in groups.items() if v is not None}}
    else:
        raise ParameterError("model", f"expected a Model or parameters (got {source!r})")
    if getattr(model, "periodic", False):
        raise ParameterError(
            "track",
            f"{model.name} is a track on periodic supports: its critical velocity is that of its smeared "
            "track, critical_velocity(moving_bogie.smeared_track(physical).to_dimensionless()) "
            "(docs/sleepers.md), which `moving-bogie critical-velocity --file F` prints with the "
            "pinned-pinned and sleeper-passing frequencies",
        )
    module = model.foundation
    damping = set(getattr(module, "DAMPING", ()))
    specs = model.catalogue.specs
    values: dict[str, Fraction] = {}
    for name in module.ARGUMENTS[1:]:
        if name == "alpha" or name in damping:
            continue
        spec = specs[name]
        value = groups.get(name)
        if value is None:
            if spec.default is None:
                raise ParameterError(
                    name, f"the critical velocity of {model.beam}/{model.track} needs {name} ({spec.meaning})"
                )
            value = spec.default
        check = positive if spec.constraint == "positive" else nonnegative
        values[name] = check(name, value)
    return model, values


def _arguments(
    module: ModuleType, values: Mapping[str, Fraction], convert: Callable[[Fraction], Any]
) -> dict[str, Any]:
    """Keyword arguments of the generated functions on the undamped track (alpha given separately)."""
    out = {name: convert(values[name]) for name in values}
    for name in getattr(module, "DAMPING", ()):
        out[name] = 0
    return out


def dispersion_branches(source: Source = None, p: Any = None, **groups: Any) -> FloatArray:
    """Frequencies Omega_j(p) >= 0 of free waves on the undamped track at rest, ascending, shape (n, J).

    They are the roots in q of N(p, q) at alpha = 0 (they come in pairs +-Omega). ``source`` is a
    :class:`Model`, parameters or a bound model (None: the paper's model); ``groups`` the track's groups.
    """
    model, values = _track(source, groups)
    module = model.foundation
    args = _arguments(module, values, float) | {"alpha": 0.0}
    p = np.atleast_1d(np.asarray(p, dtype=float))
    rows = np.stack(
        [np.broadcast_to(np.asarray(c, dtype=complex), p.shape) for c in module.n_coeffs_in_q(p, **args)],
        axis=-1,
    )
    # the rows whose leading coefficient is nonzero in one batched call; the others, of lower degree
    # there, one by one. Undamped: the roots are real pairs +-Omega_j, the upper half of the sorted real
    # parts; the array is as wide as the widest row.
    n = rows.shape[1] - 1
    branches = np.full((len(p), n - n // 2), np.nan)
    full = rows[:, 0] != 0
    branches[full] = np.sort(companion_roots(rows[full]).real, axis=1)[:, n // 2 :]
    width = branches.shape[1] if full.any() else 0
    for k in np.flatnonzero(~full):
        roots = np.sort(np.roots(np.trim_zeros(rows[k], "f")).real)
        branches[k, : len(roots) - len(roots) // 2] = roots[len(roots) // 2 :]
        width = max(width, len(roots) - len(roots) // 2)
    return branches[:, :width]


def phase_speed(
    source: Source = None, p: Any = None, *, alpha_max: float = np.inf, **groups: Any
) -> FloatArray:
    """Phase speed c(p) of the lowest branch that has a real phase speed, vectorised in p.

    The smallest alpha > 0 with N(p, 0; alpha) = 0, i.e. min_j Omega_j(p)/p; inf where none is at most
    ``alpha_max``. For all branches use :func:`dispersion_branches`.
    """
    p = np.atleast_1d(np.asarray(p, dtype=float))
    speeds = dispersion_branches(source, p, **groups) / p[:, None]
    speeds = np.where(np.isfinite(speeds) & (speeds <= alpha_max), speeds, np.inf)
    return speeds.min(axis=1)


def _n_values(module: ModuleType, args: Mapping[str, Any], p: Any, alpha: Any) -> tuple[Any, Any]:
    """N(p, 0; alpha) and dN/dp on the undamped track (mpmath or numpy arguments)."""
    cs = list(module.n_coeffs(0, alpha=alpha, **args))
    return horner(cs, p), horner(derivative_coefficients(cs), p)


def _polish(
    module: ModuleType, values: Mapping[str, Fraction], p0: float, a0: float, digits: int
) -> tuple[Mpf, Mpf]:
    """Newton on N(p, 0; alpha) = dN/dp = 0 at `digits` digits from the grid minimum (p0, a0)."""
    with mpmath.workdps(digits):
        args = _arguments(module, values, fraction_to_mpf)

        def system(p: Mpf, a: Mpf) -> tuple[Mpf, Mpf]:
            N, dN = _n_values(module, args, p, a)
            return mpmath.re(N), mpmath.re(dN)

        # start slightly off the grid minimum: findroot can stop at once on a start that is exact to
        # double precision in alpha but not in p
        start = (mpmath.mpf(p0) * (1 + mpmath.mpf(1e-6)), mpmath.mpf(a0) * (1 + mpmath.mpf(1e-6)))
        p, a = mpmath.findroot(system, start, tol=mpmath.mpf(10) ** (-2 * digits))
        return abs(p), +a


def _confirmed_digits(lo: tuple[Mpf, Mpf], hi: tuple[Mpf, Mpf], dps: int) -> int:
    with mpmath.workdps(dps + 15):
        err = max(abs(h - low) / abs(low) for low, h in zip(lo, hi))
        return dps if err == 0 else max(0, min(dps, int(-mpmath.log10(2 * err))))


def _phase_speed_minima(
    module: ModuleType,
    values: Mapping[str, Fraction],
    ps: FloatArray,
    speeds: FloatArray,
    dps: int,
    name: str,
) -> tuple[list[PhaseSpeedMinimum], list[int]]:
    """The local minima of the phase speed c_j(p) of every branch j, bracketed on the grid ``ps`` and
    polished at ``dps`` (digits confirmed at ``dps + 15``), and the branches (from 1) without one.

    Raises
    ------
    MovingBogieError
        Where a branch's phase speed falls to 0 (the track ``name`` is unstable at rest), or where Newton
        does not converge on a minimum.
    """
    found: list[PhaseSpeedMinimum] = []
    without: list[int] = []
    for j in range(speeds.shape[1]):
        c = speeds[:, j]
        inner = np.flatnonzero((c[1:-1] < c[:-2]) & (c[1:-1] <= c[2:]) & np.isfinite(c[1:-1])) + 1
        if inner.size == 0:
            without.append(j + 1)
        for k in inner:
            where = f"branch {j + 1} near p = {ps[k]:.4g} (phase speed {c[k]:.3g} on the grid)"
            if not c[k] > 1e-9 * np.nanmax(np.abs(c)):  # a static wave: nothing to polish
                raise MovingBogieError(
                    f"critical velocity of {name}: the phase speed of {where} falls to 0: the track is "
                    "unstable at rest (for example a rail buckled by its axial force)"
                )
            try:
                lo = _polish(module, values, ps[k], c[k], dps)
                hi = _polish(module, values, ps[k], c[k], dps + 15)
            except ValueError as error:  # mpmath.findroot: no convergence from the grid minimum
                raise MovingBogieError(
                    f"critical velocity of {name}: Newton did not converge on the phase-speed minimum of "
                    f"{where}; a phase speed that falls to 0 means the track is unstable at rest (for "
                    f"example a rail buckled by its axial force) ({str(error).splitlines()[0]})"
                ) from None
            digits = _confirmed_digits(lo, hi, dps)
            found.append(PhaseSpeedMinimum(j + 1, lo[1], lo[0], float(c[k]), float(ps[k]), digits))
    return found, without


def critical_velocity(
    source: Source = None,
    *,
    eta_s: object = None,
    S: object = None,
    r: object = None,
    groups: Mapping[str, object] | None = None,
    dps: int = 30,
    p_max: float = 20.0,
    samples: int = 4001,
    formula: Callable[[Model, dict[str, Mpf]], tuple[str, Mpf] | None] | None = None,
) -> CriticalVelocity:
    """Critical velocity of a constant moving force on any track: Eqs. (65)-(66) generalised.

    Parameters
    ----------
    source : Model, DimensionlessParams or BoundModel, optional
        A model (``get_model(beam=...)``), or parameters whose model and track groups are used (vehicle
        groups are ignored); default the paper's model.
    eta_s, S, r : number, optional
        Groups of the paper's tracks, by keyword (override those of `source`).
    groups : dict, optional
        Any further groups of the track (``{"mu_2": ..., "kappa_2": ...}`` on a layered track).
    dps : int
        Working precision of the polished minima; digits are confirmed at ``dps + 15``.
    p_max, samples : float, int
        Grid of wavenumbers 0 < p <= p_max on which the local minima of each c_j(p) are bracketed.
    formula : callable, optional
        ``formula(model, groups)`` -> ``(name, alpha_cr)`` or None: a closed form to compare with (groups
        as mpf at ``dps``), e.g. :func:`moving_bogie.paper.critical_velocity_formulas.paper_formula`.

    Raises
    ------
    ParameterError
        For a missing or invalid group (the message names it).
    MovingBogieError
        If no branch has a local minimum of its phase speed in the scanned range.
    """
    given = dict(groups or {}) | {k: v for k, v in (("eta_s", eta_s), ("S", S), ("r", r)) if v is not None}
    model, values = _track(source, given)
    module = model.foundation
    ps = np.linspace(p_max / samples, p_max, samples)
    speeds = dispersion_branches(model, ps, **values) / ps[:, None]
    branches = speeds.shape[1]
    found, without = _phase_speed_minima(module, values, ps, speeds, dps, f"{model.beam}/{model.track}")
    if not found:
        raise MovingBogieError(
            f"no local minimum of the phase speed on 0 < p <= {p_max} for {model.beam}/{model.track}: "
            "no critical velocity (a larger p_max may find one)"
        )
    found.sort(key=lambda m: m.alpha)
    best = found[0]
    lowest = speeds[:, 0]
    unattained = float(lowest[-1]) if lowest[-1] < lowest[-2] else None
    closed = None
    if formula is not None:
        with mpmath.workdps(dps):
            closed = formula(model, {k: fraction_to_mpf(v) for k, v in values.items()})
    name, closed_value = closed if closed is not None else (None, None)
    return CriticalVelocity(
        model=f"{model.beam}/{model.track}",
        groups={k: float(v) for k, v in values.items()},
        alpha_cr=best.alpha,
        p_cr=best.p,
        branch=best.branch,
        minima=tuple(found),
        branches=branches,
        without_minimum=tuple(without),
        unattained=unattained,
        formula=closed_value,
        formula_name=name,
        digits=best.digits,
        p_max=p_max,
    )
