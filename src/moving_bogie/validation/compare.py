"""Finite-beam validation of the closed-form response, side by side (paper, Section 3.2).

The paper checks every closed-form time series (Figures 5, 9-12, 14, A1) against a long simply
supported beam in 500 sine modes. :func:`validate` does the same: it runs
:func:`~moving_bogie.validation.finite_beam.simulate_finite_beam` and
:func:`~moving_bogie.response.closed_form.closed_form_response` on one tau grid and compares the rear-wheel
deflection, the front-wheel deflection, the bar bounce and the bar pitch over the window in which
the finite beam stands in for the infinite one, against a tolerance derived from the finite beam's
own discretization error.

Comparison window
-----------------
The finite beam's ``tau_valid`` ends where the *fastest* wave the modes can carry (group velocity
``c(k_max)``) could be back from a support. That is a hard bound: before ``tau_valid`` there is no
reflection at all. After it, the waves that have had time to return are those with ``p_s(tau) <= p
<= k_max``, where ``p_s(tau)`` is the wavenumber whose round trip to support ``s`` takes ``tau``
(``c(p) - alpha = 2 x0 / tau`` behind the rear wheel, ``c(p) + alpha = 2 (L - x0 - d) / tau`` ahead of
the front wheel). Their share of a wheel's deflection is bounded by the point-load spectrum
``8 / (p^4 + 4)`` of a suddenly applied load (static deflection 1 per wheel): at most
``T(p_s) = (8 / 3 pi) (p_s^-3 - k_max^-3)``. A simply supported end reflects with magnitude 1, and
every free wave decays like ``exp(-eta_f tau)`` (the modal damping ``2 eta_f`` is the same for all
modes). Summing over both supports with both wheels as sources,

    R(tau) = 2 exp(-eta_f tau) [T(p_left(tau)) + T(p_right(tau))]

bounds what the reflections can add at the wheels (ignoring dispersion, which spreads them further).
The window ends at the first ``tau`` where ``R`` exceeds ``reflection_level`` (default 1e-3, the
level the geometry already treats as negligible), or where the front wheel's near field reaches the
right support. Undamped cases keep essentially ``tau_valid``; in damped cases the reflections arrive
damped below 1e-3 and the window covers the run (Case 7, default beam: ``tau_valid`` 98, window 200).

Tolerance
---------
The finite beam's error is dominated by the modal truncation, which misses about ``eps(k_max) = 8 /
(3 pi k_max^3)`` of the static deflection under a wheel (``k_max = N pi / L``; see
``docs/finite_beam.md``), plus the time-step error, ``O(h^2)``. Measured against ``N = 4000``, the
absolute error of the default run is ``C eps(k_max)`` with ``C`` between about 0.6 and 17 depending
on case, quantity and window length: truncation also shifts the induced frequencies slightly, so in
lightly damped cases the error grows with tau (a phase drift). No single ``C`` fits all cases
without being very loose, so the tolerance uses the measured convergence instead: a reference run
with ``2N`` modes on the same beam (``k_max`` doubled) and half the time step. With the truncation
error falling like ``k_max^-3`` and the time error like ``h^2``, the fine run's error is
``e = e_trunc + e_time`` and the reference run's ``e_trunc / 8 + e_time / 4``, so the difference
``D = max_window |X_N - X_ref|`` is ``7/8 e_trunc + 3/4 e_time`` and ``8 D / 7`` estimates ``e``
(exactly for pure truncation, to within a factor 7/6 for pure time error). The tolerance is

    tolerance_X = safety * (8/7) max_window |X_N - X_ref| + floor * max_window |X_closed|,

with ``safety = 2`` (covers the time-error factor 7/6 and any truncation convergence ratio down to
``16/9 = 1.8`` in place of 8; measured ratios ``k_max = 4 -> 8`` are 6-9) and ``floor = 1e-4`` (far
above the closed form's and the output interpolation's error). A halved run (``N/2``) would be
cheaper but at ``N = 500`` it has ``k_max = 2``, before the asymptotic regime (measured ratios 3-17).
``eps(k_max)`` itself is reported as ``truncation_a_priori``. The closed form is also compared with
the reference run (``reference_diff``), which should be about 8 times closer.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from moving_bogie.errors import MovingBogieError
from moving_bogie.validation.finite_beam import FiniteBeamResult, simulate_finite_beam
from moving_bogie.validation.geometry import group_velocity, near_field_decay_rate

__all__ = [
    "QUANTITIES",
    "QuantityComparison",
    "ValidationResult",
    "comparison_window",
    "default_tau_max",
    "plot_validation",
    "reflection_bound",
    "truncation_a_priori",
    "validate",
]

#: Compared time series: name -> (attribute of the time series, label).
QUANTITIES: dict[str, tuple[str, str]] = {
    "rear": ("w_rear", "beam deflection at the rear wheel"),
    "front": ("w_front", "beam deflection at the front wheel"),
    "u": ("u", "bar bounce u"),
    "theta": ("theta", "bar pitch theta"),
}

#: Default end of the run: undamped cases stop near the strict reflection-free window of the
#: 500-mode beam (``tau_valid`` ~ 98, because ``L`` is capped at ``500 pi / 4``); damped ones, whose
#: reflections return damped below 1e-3, run twice as long.
DEFAULT_TAU_MAX_UNDAMPED = 100.0
DEFAULT_TAU_MAX_DAMPED = 200.0

#: Output spacing of the common tau grid (the response's periods are 12 or longer; the finite
#: beam's Hermite interpolation and the closed form are both exact to far below the tolerance there).
DEFAULT_TAU_STEP = 0.05


def default_tau_max(params: Any) -> float:
    """Default end of a validation run: 200 with foundation damping, 100 without (see module notes)."""
    return DEFAULT_TAU_MAX_DAMPED if float(params.eta_f) > 0 else DEFAULT_TAU_MAX_UNDAMPED


def truncation_a_priori(k_max: float) -> float:
    """Share ``8 / (3 pi k_max^3)`` of a point load's static deflection missed by modes up to `k_max`.

    The static deflection spectrum of a point load is ``8 / (p^4 + 4)`` (normalised to deflection
    1); its tail beyond ``k_max`` integrates to at most this.
    """
    return 8.0 / (3.0 * math.pi * k_max**3)


def _tail(p: np.ndarray, k_max: float) -> np.ndarray:
    """Spectral share of a point load's deflection between `p` and `k_max` (bound ``8/(3 pi p^3)`` tail)."""
    with np.errstate(divide="ignore"):
        share = (8.0 / (3.0 * math.pi)) * (np.power(p, -3.0) - k_max**-3.0)
    return np.clip(share, 0.0, 1.0)


def reflection_bound(
    tau: np.ndarray,
    *,
    length: float,
    entry: float,
    d: float,
    alpha: float,
    eta_f: float,
    eta_s: float,
    k_max: float,
) -> np.ndarray:
    """Upper bound ``R(tau)`` of what waves reflected at the supports add to a wheel's deflection.

    See the module docstring: zero until the fastest modelled wave can be back (``tau_valid``),
    then ``2 exp(-eta_f tau) [T(p_left) + T(p_right)]`` with ``T`` the spectral share of the
    wavenumbers that have had time to return.
    """
    tau = np.asarray(tau, dtype=float)
    p = np.linspace(0.0, k_max, 4001)
    c = np.asarray(group_velocity(p, eta_s))  # increasing in p
    bound = np.zeros_like(tau)
    gap_right = length - entry - d
    for distance, relative in ((entry, c - alpha), (gap_right, c + alpha)):
        ok = relative > 0
        if not ok.any():
            continue
        # Round-trip time of wavenumber p, decreasing in p; the smallest p back by tau is p_s(tau).
        with np.errstate(divide="ignore"):
            trip = 2.0 * distance / relative[ok]
        p_ok = p[ok]
        arrived = tau >= trip[-1]
        p_s = np.interp(tau[arrived], trip[::-1], p_ok[::-1])
        bound[arrived] += 2.0 * _tail(p_s, k_max)
    return bound * np.exp(-eta_f * tau)


def comparison_window(params: Any, finite: FiniteBeamResult, *, reflection_level: float = 1e-3) -> float:
    """End of the window ``[0, tau_w]`` in which the finite beam stands in for the infinite one.

    The first ``tau`` at which :func:`reflection_bound` exceeds `reflection_level`, or at which the
    front wheel's near field (decay ``exp(-gamma xi)``, margin ``ln(1000) / gamma``) reaches the
    right support, capped at the end of the run; never shorter than ``finite.tau_valid``.
    """
    alpha, eta_f, d = float(params.alpha), float(params.eta_f), float(params.d)
    eta_s = float(getattr(params, "eta_s", 0.0))
    tau = finite.tau
    tau_end = float(tau[-1])
    bound = reflection_bound(
        tau,
        length=finite.length,
        entry=finite.entry,
        d=d,
        alpha=alpha,
        eta_f=eta_f,
        eta_s=eta_s,
        k_max=finite.k_max,
    )
    over = np.nonzero(bound > reflection_level)[0]
    end = tau_end if over.size == 0 else float(tau[max(over[0] - 1, 0)])
    gamma = near_field_decay_rate(alpha, eta_f, eta_s)
    if gamma > 0 and alpha > 0:
        margin = math.log(1e3) / gamma
        end = min(end, (finite.length - finite.entry - d - margin) / alpha)
    return float(min(max(end, min(finite.tau_valid, tau_end)), tau_end))


@dataclass(frozen=True)
class QuantityComparison:
    """One compared time series over the window.

    Attributes
    ----------
    name : str
        "rear", "front", "u" or "theta".
    max_abs_diff : float
        ``max |finite - closed|`` over the window.
    amplitude : float
        ``max |closed|`` over the window.
    relative : float
        ``max_abs_diff / amplitude``.
    convergence_diff : float
        ``max |X_N - X_ref|`` over the window (the measured convergence; ``X_ref``: 2N modes, h/2).
    error_estimate : float
        ``8/7 convergence_diff``: estimated error of the N-mode run.
    tolerance : float
        ``safety * error_estimate + floor * amplitude``.
    reference_diff : float
        ``max |X_ref - X_closed|`` over the window: the closed form against the reference run.
    """

    name: str
    max_abs_diff: float
    amplitude: float
    relative: float
    convergence_diff: float
    error_estimate: float
    tolerance: float
    reference_diff: float

    @property
    def within(self) -> bool:
        """Whether the difference is within the tolerance."""
        return bool(self.max_abs_diff <= self.tolerance)

    def to_dict(self) -> dict[str, Any]:
        return {
            "max_abs_diff": self.max_abs_diff,
            "amplitude": self.amplitude,
            "relative": self.relative,
            "convergence_diff": self.convergence_diff,
            "error_estimate": self.error_estimate,
            "tolerance": self.tolerance,
            "within": self.within,
            "reference_diff": self.reference_diff,
        }


@dataclass(frozen=True)
class ValidationResult:
    """Finite beam against closed form on one tau grid (see :func:`validate`).

    Attributes
    ----------
    model : str
        "bogie" or "masses".
    params : Any
        The parameters compared.
    tau : ndarray
        The common output grid.
    finite : FiniteBeamResult
        The N-mode finite-beam run.
    reference : FiniteBeamResult
        The ``2N``-mode, half-time-step run on the same beam (error estimate).
    closed : Any
        The closed form's :class:`~moving_bogie.response.closed_form.TimeSeries`.
    window : tuple of float
        ``(0, tau_w)``, the comparison window.
    quantities : dict of str to QuantityComparison
        "rear", "front" and, for the bogie, "u" and "theta".
    finite_beam_s, reference_s, closed_form_s : float
        Wall times of the N-mode run, the reference run, and the closed form (frequency search
        included).
    safety, floor, reflection_level : float
        The tolerance and window settings used.
    """

    model: str
    params: Any
    tau: np.ndarray
    finite: FiniteBeamResult
    reference: FiniteBeamResult
    closed: Any
    window: tuple[float, float]
    quantities: dict[str, QuantityComparison]
    finite_beam_s: float
    reference_s: float
    closed_form_s: float
    safety: float
    floor: float
    reflection_level: float
    notes: tuple[str, ...] = field(default=())

    def _diff(self, name: str) -> float | None:
        q = self.quantities.get(name)
        return None if q is None else q.max_abs_diff

    @property
    def max_abs_diff_rear(self) -> float:
        """``max |w_rear finite - w_rear closed|`` over the window."""
        return self.quantities["rear"].max_abs_diff

    @property
    def max_abs_diff_front(self) -> float:
        """``max |w_front finite - w_front closed|`` over the window."""
        return self.quantities["front"].max_abs_diff

    @property
    def max_abs_diff_u(self) -> float | None:
        """Bar bounce difference over the window (None for the two masses)."""
        return self._diff("u")

    @property
    def max_abs_diff_theta(self) -> float | None:
        """Bar pitch difference over the window (None for the two masses)."""
        return self._diff("theta")

    @property
    def tau_valid(self) -> float:
        """The finite beam's strict reflection-free window (fastest modelled wave)."""
        return self.finite.tau_valid

    @property
    def agrees(self) -> bool:
        """Every compared quantity within its tolerance."""
        return all(q.within for q in self.quantities.values())

    @property
    def ratio(self) -> float:
        """``finite_beam_s / closed_form_s``: how many times slower the finite beam is."""
        return self.finite_beam_s / self.closed_form_s if self.closed_form_s > 0 else math.inf

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary (no time series)."""
        params = self.params.to_dict() if hasattr(self.params, "to_dict") else None
        q = self.quantities
        return {
            "model": self.model,
            "params": params,
            "agrees": self.agrees,
            "max_abs_diff_rear": self.max_abs_diff_rear,
            "max_abs_diff_front": self.max_abs_diff_front,
            "max_abs_diff_u": self.max_abs_diff_u,
            "max_abs_diff_theta": self.max_abs_diff_theta,
            "relative_diff": {k: v.relative for k, v in q.items()},
            "tolerance": {k: v.tolerance for k, v in q.items()},
            "tolerance_rule": (
                f"{self.safety:g} * (8/7) max|X_N - X_(2N, dt/2)| + {self.floor:g} max|X_closed| "
                "over the window (truncation ~ k_max^-3, time step ~ dt^2)"
            ),
            "reference_diff": {k: v.reference_diff for k, v in q.items()},
            "quantities": {k: v.to_dict() for k, v in q.items()},
            "window": list(self.window),
            "tau_valid": self.finite.tau_valid,
            "reflection_level": self.reflection_level,
            "tau_max": float(self.tau[-1]),
            "n_modes": self.finite.n_modes,
            "L": self.finite.length,
            "entry": self.finite.entry,
            "k_max": self.finite.k_max,
            "dt": self.finite.dt,
            "reference_n_modes": self.reference.n_modes,
            "reference_dt": self.reference.dt,
            "truncation_a_priori": truncation_a_priori(self.finite.k_max),
            "timings": {
                "finite_beam_s": self.finite_beam_s,
                "finite_beam_stepping_s": self.finite.elapsed_s,
                "reference_run_s": self.reference_s,
                "closed_form_s": self.closed_form_s,
                "ratio_finite_to_closed": self.ratio,
            },
            "notes": list(self.notes),
        }


def _series(obj: Any, attr: str, n: int) -> np.ndarray:
    value = getattr(obj, attr, None)
    return np.full(n, np.nan) if value is None else np.asarray(value, dtype=float)


def _staged(progress: Callable[[float], None] | None, start: float, width: float):
    if progress is None:
        return None
    return lambda fraction: progress(start + width * min(max(fraction, 0.0), 1.0))


def validate(
    params: Any,
    *,
    model: str | None = None,
    n_modes: int = 500,
    tau_max: float | None = None,
    tau_step: float = DEFAULT_TAU_STEP,
    safety: float = 2.0,
    floor: float = 1e-4,
    reflection_level: float = 1e-3,
    progress: Callable[[float], None] | None = None,
) -> ValidationResult:
    """Compare the finite-beam model with the closed-form response (paper, Section 3.2).

    Runs :func:`~moving_bogie.validation.finite_beam.simulate_finite_beam` with `n_modes` modes (default beam
    length and entry), a second time with ``2 n_modes`` modes and half the time step on the same
    beam (the error estimate), and :func:`~moving_bogie.response.closed_form.closed_form_response` on the same
    grid, then compares them over :func:`comparison_window`.

    Parameters
    ----------
    params : DimensionlessParams or PhysicalParams
        Euler-Bernoulli beam only (the finite beam does not model Timoshenko-Rayleigh). Physical
        parameters are converted; the comparison is always in dimensionless tau and w / w_st.
    model : {"bogie", "masses"}, optional
        The bogie of Fig. 1b or the two masses of Fig. 1a.
    n_modes : int, optional
        Modes of the finite beam (default 500, as in the paper); at least 4.
    tau_max : float, optional
        End of the run; default :func:`default_tau_max` (100 undamped, 200 damped).
    tau_step : float, optional
        Spacing of the common output grid (default 0.05).
    safety, floor : float, optional
        Tolerance ``safety * (8/7) max|X_N - X_ref| + floor * max|X_closed|`` (defaults 2, 1e-4);
        see the module docstring.
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
        For an unknown model, too few modes, a bad `tau_max`, the Timoshenko-Rayleigh beam, or
        when the closed form fails (e.g. incomplete induced frequencies).
    """
    model = model or params.vehicle
    from moving_bogie.model.physical import PhysicalParams
    from moving_bogie.response.closed_form import closed_form_response

    if isinstance(params, PhysicalParams):
        params = params.to_dimensionless()  # the comparison runs in dimensionless tau
    if model not in ("bogie", "masses"):
        raise MovingBogieError(f"model must be 'bogie' or 'masses' (got {model!r})")
    if int(n_modes) != n_modes or n_modes < 4:
        raise MovingBogieError(f"n_modes must be an integer of at least 4 (got {n_modes!r})")
    n_modes = int(n_modes)
    if getattr(params, "beam", "eb") != "eb":
        raise MovingBogieError(
            f"finite-beam validation is implemented for the Euler-Bernoulli beam only (beam='eb'), "
            f"got beam={params.beam!r}"
        )
    tau_max = default_tau_max(params) if tau_max is None else float(tau_max)
    if not (math.isfinite(tau_max) and tau_max > 0):
        raise MovingBogieError(f"tau_max must be a positive finite number (got {tau_max!r})")
    if not (tau_step > 0 and math.isfinite(tau_step)):
        raise MovingBogieError(f"tau_step must be a positive finite number (got {tau_step!r})")
    n_out = max(2, math.ceil(tau_max / tau_step - 1e-9)) + 1
    tau = np.linspace(0.0, tau_max, n_out)

    start = time.perf_counter()
    finite = simulate_finite_beam(
        params, tau_max, model=model, n_modes=n_modes, tau_out=tau, progress=_staged(progress, 0.0, 0.2)
    )
    finite_s = time.perf_counter() - start

    start = time.perf_counter()
    reference = simulate_finite_beam(
        params,
        tau_max,
        model=model,
        n_modes=2 * n_modes,
        length=finite.length,
        entry=finite.entry,
        dt=0.5 * finite.dt,
        tau_out=tau,
        progress=_staged(progress, 0.2, 0.6),
    )
    reference_s = time.perf_counter() - start

    start = time.perf_counter()
    closed = closed_form_response(params, tau, model=model, progress=_staged(progress, 0.8, 0.2))
    closed_s = time.perf_counter() - start

    tau_w = comparison_window(params, finite, reflection_level=reflection_level)
    inside = tau <= tau_w * (1 + 1e-12)
    names = ("rear", "front", "u", "theta") if model == "bogie" else ("rear", "front")
    quantities = {}
    notes = []
    for name in names:
        attr = QUANTITIES[name][0]
        fine_x = _series(finite, attr, tau.size)[inside]
        reference_x = _series(reference, attr, tau.size)[inside]
        closed_x = _series(closed, attr, tau.size)[inside]
        if not np.all(np.isfinite(closed_x)):
            notes.append(f"closed form {attr} is not finite everywhere in the window")
        diff = float(np.max(np.abs(fine_x - closed_x)))
        amplitude = float(np.max(np.abs(closed_x)))
        convergence = float(np.max(np.abs(fine_x - reference_x)))
        estimate = convergence * 8.0 / 7.0
        quantities[name] = QuantityComparison(
            name=name,
            max_abs_diff=diff,
            amplitude=amplitude,
            relative=diff / amplitude if amplitude > 0 else math.inf,
            convergence_diff=convergence,
            error_estimate=estimate,
            tolerance=safety * estimate + floor * amplitude,
            reference_diff=float(np.max(np.abs(reference_x - closed_x))),
        )
    if progress is not None:
        progress(1.0)
    return ValidationResult(
        model=model,
        params=params,
        tau=tau,
        finite=finite,
        reference=reference,
        closed=closed,
        window=(0.0, tau_w),
        quantities=quantities,
        finite_beam_s=finite_s,
        reference_s=reference_s,
        closed_form_s=closed_s,
        safety=safety,
        floor=floor,
        reflection_level=reflection_level,
        notes=tuple(notes),
    )


def plot_validation(result: ValidationResult, path: Any = None, *, title: str | None = None):
    """Paper-style figure (Figures 5, 9-12, 14, A1): finite beam solid, closed form dashed.

    Three stacked panels for the bogie, (a) beam deflection at the rear wheel, (b) bar bounce,
    (c) bar pitch; one panel (rear-wheel deflection) for the two masses. The comparison window's
    end is marked by a dotted line, the time after it shaded; the strict reflection-free
    ``tau_valid`` by a thin dotted grey line when it is earlier. Builds a bare
    :class:`matplotlib.figure.Figure` (no pyplot, no GUI backend).

    Parameters
    ----------
    result : ValidationResult
    path : path-like, optional
        Save the figure there (PNG, PDF, SVG by extension).
    title : str, optional
        First line of the figure title (default "bogie: finite beam (solid) vs closed form
        (dashed)"); a second line gives modes, beam, window and verdict.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from matplotlib.figure import Figure

    panels = ("rear", "u", "theta") if result.model == "bogie" else ("rear",)
    labels = {
        "rear": r"$\tilde w(0,\tau)$ rear wheel",
        "u": r"$\tilde u$ bar bounce",
        "theta": r"$\tilde\theta$ bar pitch",
    }
    fig = Figure(figsize=(7.5, 2.3 * len(panels) + 0.9), layout="constrained")
    axes = fig.subplots(len(panels), 1, sharex=True, squeeze=False)[:, 0]
    tau = result.tau
    tau_w = result.window[1]
    for letter, (ax, name) in zip("abc", zip(axes, panels)):
        attr = QUANTITIES[name][0]
        ax.plot(
            tau,
            _series(result.finite, attr, tau.size),
            "-",
            color="C0",
            lw=1.2,
            label=f"finite beam, {result.finite.n_modes} modes",
        )
        ax.plot(
            tau,
            _series(result.closed, attr, tau.size),
            "--",
            color="C3",
            lw=1.2,
            label="closed form (infinite beam)",
        )
        if tau_w < tau[-1]:
            ax.axvspan(tau_w, tau[-1], color="0.88", zorder=0, label="after the window")
        ax.axvline(tau_w, color="k", ls=":", lw=1.0, label="window end")
        if result.finite.tau_valid < tau_w:
            ax.axvline(
                result.finite.tau_valid,
                color="0.55",
                ls=(0, (1, 3)),
                lw=0.9,
                label="strict reflection-free end",
            )
        q = result.quantities[name]
        ax.set_ylabel(labels[name])
        ax.set_title(
            f"({letter})  max |difference| in the window {q.max_abs_diff:.2g}, tolerance {q.tolerance:.2g}",
            loc="left",
            fontsize=8,
        )
        ax.margins(x=0)
    axes[-1].set_xlabel(r"$\tau$")
    fig.legend(
        *axes[0].get_legend_handles_labels(), loc="outside lower center", fontsize=8, ncol=3, frameon=False
    )
    verdict = "agree" if result.agrees else "DISAGREE"
    if title is None:
        vehicle = "bogie" if result.model == "bogie" else "two masses"
        title = f"{vehicle}: finite beam (solid) vs closed form (dashed)"
    fig.suptitle(
        f"{title}\n{result.finite.n_modes} modes, "
        f"L = {result.finite.length:.1f}, k_max = {result.finite.k_max:.2f}; window [0, {tau_w:.1f}], "
        f"tau_valid = {result.finite.tau_valid:.1f}: {verdict}",
        fontsize=9,
    )
    if path is not None:
        fig.savefig(path, dpi=150)
    return fig
