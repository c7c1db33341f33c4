"""Critical stiffness of the primary suspension (Section 3.8, Figure 16).

For each velocity alpha, the suspension stiffness kappa_v is swept over (0, kappa_max]: the values where
the number of unstable induced frequencies changes are the crossings of the D-decomposition in kappa_v
(:mod:`d_decomposition`; E_chr is quadratic in kappa_v), and the number on each interval between them comes
from the argument principle (:func:`~moving_bogie.stability.maps.column.stability_column`) at its midpoint.
As a
cross-check, the D-decomposition's own count (rule of hatching from one reference count) is compared with
the argument principle on a grid of kappa_v. The critical stiffnesses are the kappa_v where the bogie
passes from stable to unstable; the result lists every stable/unstable interval as well.

On an undamped or near-undamped foundation (eta_f <
:data:`~moving_bogie.stability.maps.undamped.NEAR_UNDAMPED`)
the D-decomposition degenerates (real induced frequencies fill whole kappa_v intervals, :mod:`undamped`):
the intervals then come from root counts on a grid of ``check_points`` values of kappa_v, every change
bisected to ``tol``; ``intervals`` are the counts at eta_f = 0 exactly (K on the cut from below) when
eta_f = 0, and the limit eta_f -> 0+ (real roots that small foundation damping destabilises counted as
unstable) when 0 < eta_f < NEAR_UNDAMPED; ``limit_intervals`` always hold the limit.

The function is general: any beam and track, and any vehicle with a primary suspension kappa_v (two
masses have none). The paper's Figure 16 uses the data of its ref. [48] (Verichev & Metrikine 2002), which
the paper does not give in full; ``figure16_params`` in :mod:`moving_bogie.paper.stability_figures` is the
documented stand-in used by the package's Figure 16.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from typing import TYPE_CHECKING, TypeAlias

import numpy as np

from moving_bogie.errors import ParameterError
from moving_bogie.kernels.bound import BoundModel
from moving_bogie.kernels.sweep_characteristic import SweepCharacteristic
from moving_bogie.stability.maps.column import stability_column
from moving_bogie.stability.maps.undamped import (
    CONVENTION,
    Boundary,
    UndampedColumn,
    UndampedCounter,
    boundaries,
    parameter_grid,
    regime,
    uncertain_warning,
)
from moving_bogie.stability.stiffness.d_decomposition import d_decomposition

if TYPE_CHECKING:
    from moving_bogie.model.params import DimensionlessParams

__all__ = ["CriticalStiffness", "critical_stiffness"]

#: The kappa_v intervals at one alpha: ``(kappa_low, kappa_high, unstable_count)``, ascending.
Intervals: TypeAlias = tuple[tuple[float, float, int], ...]


@dataclass(frozen=True)
class CriticalStiffness:
    """Stable and unstable kappa_v intervals at each alpha.

    Attributes
    ----------
    alphas : ndarray
    intervals : tuple
        Per alpha, a tuple of ``(kappa_low, kappa_high, unstable_count)`` covering (0, kappa_max].
    critical : tuple
        Per alpha, the kappa_v values (sorted) where the count changes between 0 and > 0.
    mismatches : int
        Grid points where the D-decomposition count and the argument-principle count disagree (0 expected;
        0 and not computed on an undamped or near-undamped foundation, where there is no D-decomposition).
    """

    params: DimensionlessParams
    alphas: np.ndarray
    kappa_max: float
    intervals: tuple[Intervals, ...]
    critical: tuple[tuple[float, ...], ...]
    mismatches: int
    warnings: tuple[str, ...] = field(default=())
    method: str = "D-decomposition in kappa_v, counts by the argument principle"
    limit_intervals: tuple[Intervals, ...] | None = None  # undamped regimes: counts in the limit eta_f -> 0+

    @property
    def regime(self) -> str:
        """ "damped", "undamped" (eta_f = 0) or "near-undamped" (see :func:`~.undamped.regime`)."""
        return regime(self.params.eta_f)

    def lowest_critical(self) -> np.ndarray:
        """Per alpha: the smallest kappa_v in (0, kappa_max] at which the bogie is unstable (nan if none)."""
        out = []
        for ivs in self.intervals:
            lows = [lo for lo, hi, n in ivs if n > 0]
            out.append(min(lows) if lows else np.nan)
        return np.array(out)

    def to_dict(self) -> dict:
        return {
            "params": self.params.to_dict(),
            "kappa_max": self.kappa_max,
            "alphas": [
                {
                    "alpha": float(a),
                    "critical_kappa_v": [float(k) for k in crit],
                    "intervals": [
                        {"kappa_low": lo, "kappa_high": hi, "unstable": int(n)} for lo, hi, n in ivs
                    ],
                }
                for a, crit, ivs in zip(self.alphas, self.critical, self.intervals)
            ],
            "mismatches": self.mismatches,
            "warnings": list(self.warnings),
            "regime": self.regime,
            "method": self.method,
            **(
                {}
                if self.limit_intervals is None
                else {
                    "convention": CONVENTION,
                    "limit_intervals": [
                        [{"kappa_low": lo, "kappa_high": hi, "unstable": int(n)} for lo, hi, n in ivs]
                        for ivs in self.limit_intervals
                    ],
                }
            ),
        }


def critical_stiffness(
    bound: BoundModel,
    alphas: Sequence[float],
    *,
    kappa_max: float = 1.0,
    q_max: float = 1.5,
    samples: int = 4000,
    check_points: int = 40,
    tol: float = 1e-6,
    progress: Callable[[float], None] | None = None,
) -> CriticalStiffness:
    """Critical primary-suspension stiffness kappa_v of the bogie as a function of alpha (Figure 16).

    Parameters
    ----------
    bound : BoundModel
        Bogie and track (kappa_v and alpha of its parameters are ignored). eta_f = 0 and
        0 < eta_f < NEAR_UNDAMPED are handled as the module text says.
    alphas : sequence of float
    kappa_max : float
        Upper end of the kappa_v range.
    q_max, samples : float, int
        Sampling of the real q-axis by the D-decomposition.
    check_points : int
        kappa_v grid on which the argument-principle count is computed: the first point is the reference
        of the D-decomposition count, all are compared with it. Undamped regimes: the grid of the counts
        (a change between two grid values is found; two changes within one grid step can be missed).
    tol : float
        Undamped regimes: bisection tolerance of each change, relative to ``kappa_max``.
    progress : callable, optional
    """
    params = bound.params
    alpha_grid = np.asarray(alphas, dtype=float)
    stiffness = primary_stiffness(bound)
    if regime(params.eta_f) != "damped":
        return _undamped(bound, stiffness, alpha_grid, kappa_max, check_points, tol, progress)
    sweep = SweepCharacteristic(bound, stiffness)
    kappas = np.linspace(kappa_max / check_points, kappa_max, check_points)
    intervals: list[Intervals] = []
    critical: list[tuple[float, ...]] = []
    warnings: list[str] = []
    mismatches = 0
    for k, a in enumerate(alpha_grid):
        dd = d_decomposition(
            bound.replace(alpha=Fraction(str(a))),
            a,
            parameter=stiffness,
            theta_max=kappa_max,
            q_max=q_max,
            samples=samples,
        )
        col = stability_column(sweep, a, kappas)
        ref = int(col.count[0])
        predicted = dd.counts(kappas, kappas[0], ref)
        ok = ~col.uncertain
        bad = int(np.sum(predicted[ok] != col.count[ok]))
        if bad:
            warnings.append(f"alpha={a:g}: D-decomposition and argument principle disagree at {bad} point(s)")
        mismatches += bad
        edges = sorted({0.0, kappa_max, *(c.theta for c in dd.crossings)})
        pairs = [(lo, hi) for lo, hi in zip(edges[:-1], edges[1:]) if hi - lo > 1e-9 * kappa_max]
        mids = stability_column(sweep, a, np.array([0.5 * (lo + hi) for lo, hi in pairs]))
        ivs: list[tuple[float, float, int]] = []
        for (lo, hi), n in zip(pairs, mids.count):
            if ivs and ivs[-1][2] == n:  # a touching pair of crossings: merge
                ivs[-1] = (ivs[-1][0], float(hi), int(n))
            else:
                ivs.append((float(lo), float(hi), int(n)))
        intervals.append(tuple(ivs))
        critical.append(_critical(tuple(ivs)))
        if progress is not None:
            progress((k + 1) / len(alpha_grid))
    return CriticalStiffness(
        params, alpha_grid, float(kappa_max), tuple(intervals), tuple(critical), mismatches, tuple(warnings)
    )


def _intervals(bounds: list[Boundary], column: UndampedColumn, kind: str, kappa_max: float) -> Intervals:
    """(low, high, count) intervals over [first grid value, kappa_max] from the boundaries of one kind."""
    counts = getattr(column, kind)
    edges = [float(column.thetas[0])] + [b.theta for b in bounds if b.kind == kind] + [float(kappa_max)]
    ns = [int(counts[0])] + [b.count_above for b in bounds if b.kind == kind]
    return tuple((float(lo), float(hi), n) for lo, hi, n in zip(edges[:-1], edges[1:], ns))


def _critical(ivs: Intervals) -> tuple[float, ...]:
    """The kappa_v values where the count changes between 0 and > 0 (the ends of the stable intervals)."""
    return tuple(hi for (lo, hi, n), (_, _, m) in zip(ivs[:-1], ivs[1:]) if (n == 0) != (m == 0))


def primary_stiffness(bound: BoundModel) -> str:
    """The vehicle's primary-suspension stiffness group (``Model.primary_stiffness``: kappa_v).

    Raises
    ------
    ParameterError
        For a vehicle without a primary suspension (two masses), naming the vehicle.
    """
    name = bound.model.primary_stiffness
    if name is None:
        raise ParameterError(
            "vehicle", f"vehicle {bound.model.vehicle!r} has no primary suspension: no critical stiffness"
        )
    return name


def _undamped(
    bound: BoundModel,
    stiffness: str,
    alphas: np.ndarray,
    kappa_max: float,
    check_points: int,
    tol: float,
    progress: Callable[[float], None] | None,
) -> CriticalStiffness:
    """Counts on a kappa_v grid and bisection (:mod:`undamped`), exact at eta_f = 0 and in the limit."""
    params = bound.params
    margin = 100 * float(params.eta_f)
    counter = UndampedCounter(bound, stiffness, margin=margin)
    unsure: dict[float, int] = {}
    grid = parameter_grid(kappa_max, check_points)
    kind = "undamped" if regime(params.eta_f) == "undamped" else "limit"
    intervals: list[Intervals] = []
    limits: list[Intervals] = []
    critical: list[tuple[float, ...]] = []
    warnings: list[str] = []

    for k, a in enumerate(alphas):
        bounds, column, unsure[float(a)] = boundaries(counter, float(a), grid, tol=tol * kappa_max)
        ivs = _intervals(bounds, column, kind, kappa_max)
        intervals.append(ivs)
        limits.append(_intervals(bounds, column, "limit", kappa_max))
        critical.append(_critical(ivs))
        if progress is not None:
            progress((k + 1) / len(alphas))
    warnings += uncertain_warning("", unsure, margin)
    what = (
        "at eta_f = 0"
        if kind == "undamped"
        else f"in the limit eta_f -> 0+ (eta_f = {float(params.eta_f):g})"
    )
    method = (
        f"{'undamped' if kind == 'undamped' else 'near-undamped'} foundation: unstable counts {what} on "
        f"{check_points} kappa_v values (argument principle, K on the cut from below; real roots in the gap "
        f"counted unstable in the limit when small foundation damping destabilises them), every change "
        f"bisected to {tol * kappa_max:.2g}; the D-decomposition degenerates there"
    )
    return CriticalStiffness(
        params,
        alphas,
        float(kappa_max),
        tuple(intervals),
        tuple(critical),
        0,
        tuple(warnings),
        method,
        tuple(limits),
    )
