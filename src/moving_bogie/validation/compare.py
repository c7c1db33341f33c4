"""Finite-beam validation of the closed-form response, side by side (paper, Section 3.2).

The paper checks every closed-form time series (Figures 5, 9-14, A1-A7) against a long simply
supported beam in 500 sine modes. :func:`validate` does the same: it runs
:func:`~moving_bogie.validation.finite_beam.simulate_finite_beam` (with the static correction of
the truncated modes, :mod:`moving_bogie.validation.corrected`) and
:func:`~moving_bogie.response.closed_form.closed_form_response` on one tau grid and compares the
every response of the vehicle (the rail under each wheel, each body's bounce and pitch) over the window
in which the finite beam stands in for the infinite one (:mod:`moving_bogie.validation.window`).
They agree when every quantity is within a fixed relative tolerance, 1 % of its largest value over
the window by default (:mod:`moving_bogie.validation.verdict`); a second run with twice the time
step estimates the finite beam's own error, as information.

Measured at the defaults (``docs/finite_beam.md``): every one of the 13 cases of Table 1 agrees to
better than 0.2 % on every quantity; without the correction the same runs are off by up to 21 %.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np

from moving_bogie.errors import MovingBogieError
from moving_bogie.kernels.bound import BoundModel
from moving_bogie.validation.finite_beam import FiniteBeamResult, simulate_finite_beam
from moving_bogie.validation.plots import plot_validation
from moving_bogie.validation.vehicle import vehicle_kernels
from moving_bogie.validation.verdict import (
    DEFAULT_TOLERANCE,
    QuantityComparison,
    ValidationResult,
    compare_series,
    quantity_labels,
    series,
)
from moving_bogie.validation.window import (
    DEFAULT_TAU_STEP,
    comparison_window,
    default_tau_max,
    reflection_bound,
    truncation_a_priori,
)

if TYPE_CHECKING:
    from moving_bogie.model.params import DimensionlessParams
    from moving_bogie.response.closed_form import TimeSeries

__all__ = [
    "DEFAULT_TOLERANCE",
    "QuantityComparison",
    "ValidationResult",
    "comparison_window",
    "default_tau_max",
    "plot_validation",
    "reflection_bound",
    "truncation_a_priori",
    "validate",
]


#: Below this ``k_max`` the static correction's quasi-static assumption fails (measured: at
#: ``k_max = 1`` Case 13 diverges, at 2 the correction still gains 2-30; ``docs/finite_beam.md``).
MIN_CORRECTED_WAVENUMBER = 2.0


def _staged(
    progress: Callable[[float], None] | None, start: float, width: float
) -> Callable[[float], None] | None:
    if progress is None:
        return None
    return lambda fraction: progress(start + width * min(max(fraction, 0.0), 1.0))


def _check(params: DimensionlessParams, n_modes: int, tol: float, tau_step: float) -> None:
    vehicle_kernels(params)  # names an unknown vehicle
    if int(n_modes) != n_modes or n_modes < 4:
        raise MovingBogieError(f"n_modes must be an integer of at least 4 (got {n_modes!r})")
    if not (math.isfinite(tol) and 0 < tol < 1):
        raise MovingBogieError(f"tol must be a number between 0 and 1 (got {tol!r})")
    if not (tau_step > 0 and math.isfinite(tau_step)):
        raise MovingBogieError(f"tau_step must be a positive finite number (got {tau_step!r})")


def validate(
    bound: BoundModel,
    *,
    n_modes: int = 500,
    tau_max: float | None = None,
    tau_step: float = DEFAULT_TAU_STEP,
    tol: float = DEFAULT_TOLERANCE,
    static_correction: bool = True,
    estimate: bool = True,
    reflection_level: float = 1e-3,
    progress: Callable[[float], None] | None = None,
) -> ValidationResult:
    """Compare the finite-beam model with the closed-form response (paper, Section 3.2).

    Parameters
    ----------
    bound : BoundModel
        Any beam on any track (the finite rail of :class:`~moving_bogie.validation.modal.ModalBeam`
        reads the model's generated per-mode blocks) under any generated vehicle (that of the
        model; another: ``bound.replace(vehicle=...)``): the finite beam couples its generated
        matrices at its contacts and every degree of freedom is compared with the closed form's
        response of the same name. The comparison is in dimensionless tau and w / w_st (the public
        :func:`moving_bogie.validate` binds, from SI parameters too).
    n_modes : int, optional
        Modes of the finite beam (default 500, as in the paper); at least 4.
    tau_max : float, optional
        End of the run; default :func:`~moving_bogie.validation.window.default_tau_max` (100
        undamped, 200 damped).
    tau_step : float, optional
        Spacing of the common output grid (default 0.05).
    tol : float, optional
        Relative tolerance: the run agrees when ``max |X_finite - X_closed| <= tol max |X_closed|``
        over the window for every quantity (default 0.01).
    static_correction : bool, optional
        Add back the truncated modes' quasi-static response (default True).
    estimate : bool, optional
        Run the finite beam a second time with twice the time step to estimate its error
        (information only; default True).
    reflection_level : float, optional
        Reflection bound that ends the window (default 1e-3, in units of the static deflection).
    progress : callable, optional
        Called with the fraction done.

    Returns
    -------
    ValidationResult

    Raises
    ------
    MovingBogieError
        For an unknown model or beam, too few modes, a bad `tau_max` or `tol`, or when the closed
        form fails (e.g. incomplete induced frequencies).
    """
    _check(bound.params, n_modes, tol, tau_step)
    tau = _tau_grid(bound.params, tau_max, tau_step)
    run = _Runs(bound, tau, int(n_modes), static_correction, estimate, progress)
    finite, reference, closed = run.finite, run.reference, run.closed
    tau_w = comparison_window(bound.params, finite, reflection_level=reflection_level)
    inside = tau <= tau_w * (1 + 1e-12)
    notes = _closed_form_notes(closed, finite, static_correction)
    quantities, labels = _compare_responses(bound, finite, reference, closed, tau, inside, tol, notes)
    if progress is not None:
        progress(1.0)
    return ValidationResult(
        model=bound.params.vehicle,
        params=bound.params,
        tau=tau,
        finite=finite,
        reference=reference,
        closed=closed,
        window=(0.0, tau_w),
        quantities=quantities,
        finite_beam_s=run.finite_s,
        reference_s=run.reference_s,
        closed_form_s=run.closed_s,
        tolerance=tol,
        reflection_level=reflection_level,
        notes=tuple(notes),
        labels=labels,
    )


def _tau_grid(params: DimensionlessParams, tau_max: float | None, tau_step: float) -> np.ndarray:
    """The common output grid 0, ..., tau_max (default :func:`default_tau_max`), spaced about ``tau_step``."""
    tau_max = default_tau_max(params) if tau_max is None else float(tau_max)
    if not (math.isfinite(tau_max) and tau_max > 0):
        raise MovingBogieError(f"tau_max must be a positive finite number (got {tau_max!r})")
    n_out = max(2, math.ceil(tau_max / tau_step - 1e-9)) + 1
    return np.linspace(0.0, tau_max, n_out)


class _Runs:
    """The two models on the common tau grid, each timed: the finite beam, with ``estimate`` again at twice
    its time step (the estimate of its own error), and the closed form."""

    def __init__(
        self,
        bound: BoundModel,
        tau: np.ndarray,
        n_modes: int,
        static_correction: bool,
        estimate: bool,
        progress: Callable[[float], None] | None,
    ) -> None:
        tau_max = float(tau[-1])
        share = (0.55, 0.25) if estimate else (0.8, 0.0)
        start = time.perf_counter()
        self.finite = simulate_finite_beam(
            bound,
            tau_max,
            n_modes=n_modes,
            tau_out=tau,
            static_correction=static_correction,
            progress=_staged(progress, 0.0, share[0]),
        )
        self.finite_s = time.perf_counter() - start
        start = time.perf_counter()
        self.reference: FiniteBeamResult | None = None
        if estimate:
            self.reference = simulate_finite_beam(
                bound,
                tau_max,
                n_modes=n_modes,
                length=self.finite.length,
                entry=self.finite.entry,
                dt=2.0 * self.finite.dt,
                tau_out=tau,
                static_correction=static_correction,
                progress=_staged(progress, share[0], share[1]),
            )
        self.reference_s = time.perf_counter() - start
        from moving_bogie.response.closed_form import closed_form_response

        start = time.perf_counter()
        self.closed = closed_form_response(bound, tau, progress=_staged(progress, 0.8, 0.2))
        self.closed_s = time.perf_counter() - start


def _closed_form_notes(closed: TimeSeries, finite: FiniteBeamResult, static_correction: bool) -> list[str]:
    """What the reader must know about the two sides: the closed form's notes, a left-out branch cut, a
    static correction that cannot be trusted."""
    notes = [f"closed form: {note}" for note in getattr(closed, "notes", ())]
    if any("branch cut skipped" in note for note in getattr(closed, "notes", ())):
        notes.append(
            "the closed form is residues only (its branch-cut part was left out), so it is not the complete "
            "response: differences of the size of that part are expected, largest at early times"
        )
    if static_correction and finite.k_max < MIN_CORRECTED_WAVENUMBER:
        notes.append(
            f"k_max = {finite.k_max:.2f} < {MIN_CORRECTED_WAVENUMBER:g}: the truncated modes are not much "
            "faster than the forcing, so the static correction is unreliable; use more modes"
        )
    return notes


def _compare_responses(
    bound: BoundModel,
    finite: FiniteBeamResult,
    reference: FiniteBeamResult | None,
    closed: TimeSeries,
    tau: np.ndarray,
    inside: np.ndarray,
    tol: float,
    notes: list[str],
) -> tuple[dict[str, QuantityComparison], dict[str, str]]:
    """Every response of the vehicle, under its name in the generated DOFS, compared over the window
    (each relative to the largest value of its kind: deflections, rotations); notes appended."""
    names = {dof: dof for dof in finite.responses}
    quantities: dict[str, QuantityComparison] = {}
    kernels = bound.vehicle
    units = getattr(kernels, "UNITS", {})
    labels = quantity_labels(tuple(names), units, finite.contacts)
    closed_all = {attr: series(closed, attr, tau.size)[inside] for attr in names.values()}
    kinds: dict[str, float] = {}
    for attr, values in closed_all.items():
        if np.all(np.isfinite(values)):
            unit = units.get(attr, attr)
            kinds[unit] = max(kinds.get(unit, 0.0), float(np.max(np.abs(values))))
    for name, attr in names.items():
        closed_x = closed_all[attr]
        if not np.all(np.isfinite(closed_x)):
            notes.append(f"closed form {attr} is not finite everywhere in the window")
        quantities[name] = compare_series(
            name,
            series(finite, attr, tau.size)[inside],
            closed_x,
            tol,
            None if reference is None else series(reference, attr, tau.size)[inside],
            kinds.get(units.get(attr, attr), 0.0),
        )
    return quantities, labels
