"""Verdict of the finite-beam validation: a fixed, stated tolerance per compared quantity.

The finite beam (Section 3.2) and the closed form (Eqs. (35)-(47)) agree when, for every compared
time series ``X`` (every degree of freedom of the vehicle, under its name in the generated ``DOFS``: the
rail's deflection under each wheel, then each body's bounce and pitch),

    relative_diff_X = max_window |X_finite - X_closed| / max_window |X_closed| <= tol,

with ``tol = 1 %`` by default: a number stated in advance, not derived from either run. The finite
beam's own error is estimated as information only: a second run with twice the time step on the
same beam gives the time-step error of the Newmark average-acceleration rule (second order, so
``|X_h - X_2h| / 3``), which after the static correction of the truncated modes is the dominant
error (``docs/finite_beam.md``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from moving_bogie.validation.finite_beam import FiniteBeamResult

if TYPE_CHECKING:
    from moving_bogie.model.params import DimensionlessParams
    from moving_bogie.response.closed_form import TimeSeries
    from moving_bogie.validation.sleeper_verdict import SleeperCheck

__all__ = [
    "CHECK_KEYS",
    "DEFAULT_TOLERANCE",
    "VERDICT_KEYS",
    "QuantityComparison",
    "ValidationResult",
    "beam_title",
    "compare_series",
    "quantity_labels",
    "series",
]

#: Default tolerance: every quantity within 1 % of its largest value over the window.
DEFAULT_TOLERANCE = 0.01


def quantity_labels(dofs: Sequence[str], units: Mapping[str, str], contacts: int) -> dict[str, str]:
    """A label for every compared quantity, from the vehicle's generated ``DOFS``, ``UNITS`` and ``CONTACTS``.

    The first ``contacts`` degrees of freedom are the rail's deflection under each wheel (contact order,
    rear first); the others are bounces (unit ``m``) and pitches (unit ``rad``) of the vehicle's bodies.
    Each label names the quantity, its dimensionless unit (Eqs. (15)-(17)) and what it is.

    Parameters
    ----------
    dofs : sequence of str
    units : mapping
        DOF name -> ``"m"`` or ``"rad"``.
    contacts : int
    """
    labels: dict[str, str] = {}
    for k, name in enumerate(dofs):
        if k < contacts:
            labels[name] = f"{name} / w_st, rail under wheel {k + 1} of {contacts}"
        elif units.get(name) == "rad":
            labels[name] = f"{name} / (w_st chi), pitch"
        else:
            labels[name] = f"{name} / w_st, bounce"
    return labels


def beam_title(params: Any) -> str:
    """The beam's title from the catalogue, without its equation ("Euler-Bernoulli beam", ...)."""
    model = getattr(params, "model", None)
    if model is None or isinstance(model, str):
        return "beam"
    return model.catalogue.beams[model.beam].split(", Eq")[0]


@dataclass(frozen=True)
class QuantityComparison:
    """One compared time series over the window.

    Attributes
    ----------
    name : str
        The quantity's degree of freedom (``DOFS`` of the vehicle's generated module).
    max_abs_diff : float
        ``max |finite - closed|`` over the window.
    amplitude : float
        ``max |closed|`` over the window (at least the tolerance times the largest value of the quantities
        of the same unit: a response that vanishes by symmetry is judged against the size of its kind).
    relative : float
        ``max_abs_diff / amplitude``: the ``relative_diff`` judged against `tolerance`.
    tolerance : float
        The relative tolerance (default 0.01).
    convergence_diff : float
        ``max |X_h - X_2h|`` over the window (``X_2h``: the same beam, twice the time step);
        NaN without the estimate run.
    error_estimate : float
        ``convergence_diff / 3``: estimated time-step error of the finite beam (information).
    reference_diff : float
        ``max |X_2h - X_closed|`` over the window.
    """

    name: str
    max_abs_diff: float
    amplitude: float
    relative: float
    tolerance: float
    convergence_diff: float = math.nan
    error_estimate: float = math.nan
    reference_diff: float = math.nan

    @property
    def within(self) -> bool:
        """Whether the relative difference is within the tolerance."""
        return bool(self.relative <= self.tolerance)

    def to_dict(self) -> dict[str, Any]:
        return {
            "max_abs_diff": self.max_abs_diff,
            "amplitude": self.amplitude,
            "relative_diff": self.relative,
            "tolerance": self.tolerance,
            "within": self.within,
            "convergence_diff": _json_float(self.convergence_diff),
            "error_estimate": _json_float(self.error_estimate),
            "reference_diff": _json_float(self.reference_diff),
        }


def _json_float(x: float) -> float | None:
    return None if math.isnan(x) else x


def series(obj: FiniteBeamResult | TimeSeries, attr: str, n: int) -> np.ndarray:
    """``obj.responses[attr]`` as a float array, or NaN of length `n` when it lacks it."""
    value = obj.responses.get(attr)
    return np.full(n, np.nan) if value is None else np.asarray(value, dtype=float)


def compare_series(
    name: str,
    finite: np.ndarray,
    closed: np.ndarray,
    tolerance: float,
    reference: np.ndarray | None = None,
    kind_amplitude: float = 0.0,
) -> QuantityComparison:
    """Compare one quantity over the window (arrays already restricted to it).

    The difference is judged relative to the quantity's largest closed-form value, but never to less than
    `tolerance` times `kind_amplitude` (the largest value of the quantities of the same unit): a response
    that vanishes by symmetry (the pitch of a symmetric car body) is compared with the size of its kind,
    not with its own round-off.

    Parameters
    ----------
    name : str
    finite, closed : ndarray
        The finite-beam run and the closed form.
    tolerance : float
        Relative tolerance.
    reference : ndarray, optional
        The twice-the-step run, for the error estimate.
    kind_amplitude : float, optional
        Largest closed-form value over the quantities of the same unit (default 0: the quantity alone).
    """
    diff = float(np.max(np.abs(finite - closed)))
    amplitude = max(float(np.max(np.abs(closed))), tolerance * kind_amplitude)
    extra: dict[str, float] = {}
    if reference is not None:
        convergence = float(np.max(np.abs(finite - reference)))
        extra = {
            "convergence_diff": convergence,
            "error_estimate": convergence / 3.0,
            "reference_diff": float(np.max(np.abs(reference - closed))),
        }
    return QuantityComparison(
        name=name,
        max_abs_diff=diff,
        amplitude=amplitude,
        relative=diff / amplitude if amplitude > 0 else math.inf,
        tolerance=tolerance,
        **extra,
    )


#: The keys every check's ``to_dict()`` has, with the same meaning on every track (a
#: :class:`ValidationResult`, on sleepers with those of its ``supports``,
#: :class:`~moving_bogie.validation.sleeper_verdict.SleeperCheck`): the model and its parameters, whether
#: it agrees, the tolerance and its rule, each quantity's relative difference and comparison, the wall
#: times and the notes.
VERDICT_KEYS = (
    "model", "beam", "track", "params", "agrees", "tolerance", "tolerance_rule", "relative_diff",
    "quantities", "timings", "notes",
)  # fmt: skip

#: Every key of a continuous track's check (beside ``max_abs_diff_<body DOF>``), a check on supports's too:
#: the values its finite rail has (fit window, length, step), None for the modal beam's alone.
CHECK_KEYS = (
    "model", "beam", "track", "params", "closed_form_branch_cut", "agrees", "tolerance", "tolerance_rule",
    "relative_diff", "labels", "max_abs_diff_rear", "max_abs_diff_front", "error_estimate", "quantities",
    "window", "tau_valid", "reflection_level", "tau_max", "n_modes", "static_correction", "L", "entry",
    "k_max", "dt", "reference_dt", "timings", "notes",
)  # fmt: skip


@dataclass(frozen=True)
class ValidationResult:
    """Finite beam against closed form on one tau grid (:func:`moving_bogie.validation.compare.validate`);
    on supports the finite rail against Floquet (:mod:`~moving_bogie.validation.on_supports`): ``supports``
    holds what it adds, ``finite`` and ``closed`` are None, ``quantities`` the compared rate and frequency
    or steady force (amplitude: the Floquet value), ``closed_form_s`` the Floquet side's wall time.

    Attributes
    ----------
    model : str
        The vehicle compared (its name in the catalogue).
    params : DimensionlessParams
        The parameters compared.
    tau : ndarray
        The common output grid.
    finite : FiniteBeamResult or None
        The finite-beam run (None on periodic supports: ``supports.free``, ``supports.loaded``).
    reference : FiniteBeamResult or None
        The same beam with twice the time step (error estimate), None when not run.
    closed : TimeSeries or None
        The closed form's :class:`~moving_bogie.response.closed_form.TimeSeries` (None on periodic
        supports).
    window : tuple of float
        ``(0, tau_w)``, the comparison window.
    quantities : dict of str to QuantityComparison
        Every degree of freedom of the vehicle by its ``DOFS`` name (wheels first, in contact order).
    finite_beam_s, reference_s, closed_form_s : float
        Wall times of the finite-beam run, the estimate run and the closed form (frequency search
        included).
    tolerance : float
        Relative tolerance of the verdict.
    reflection_level : float
        Reflection bound that ends the window.
    notes : tuple of str
    labels : dict of str to str
        A label per quantity (:func:`quantity_labels`).
    supports : SleeperCheck or None
        On periodic supports, the finite rail's runs and fits and the Floquet side (None on a continuous
        track).
    """

    model: str
    params: DimensionlessParams
    tau: np.ndarray
    finite: FiniteBeamResult | None
    reference: FiniteBeamResult | None
    closed: TimeSeries | None
    window: tuple[float, float]
    quantities: dict[str, QuantityComparison]
    finite_beam_s: float
    reference_s: float
    closed_form_s: float
    tolerance: float
    reflection_level: float
    notes: tuple[str, ...] = field(default=())
    labels: dict[str, str] = field(default_factory=dict)
    supports: SleeperCheck | None = None

    @property
    def finite_beam(self) -> FiniteBeamResult:
        """The finite-beam run of a continuous track's check (a ValueError on periodic supports)."""
        if self.finite is None:
            raise ValueError(f"{self.model}: the check on supports has no finite-beam modal run")
        return self.finite

    @property
    def closed_form(self) -> TimeSeries:
        """The closed form of a continuous track's check (a ValueError on periodic supports)."""
        if self.closed is None:
            raise ValueError(f"{self.model}: the check on supports compares no closed form")
        return self.closed

    @property
    def max_abs_diff_rear(self) -> float:
        """Difference under the rear wheel (the first contact, at xi = 0) over the window."""
        return self.quantities[self._wheels[0]].max_abs_diff

    @property
    def max_abs_diff_front(self) -> float:
        """Difference under the front wheel (the last contact) over the window."""
        return self.quantities[self._wheels[-1]].max_abs_diff

    @property
    def _wheels(self) -> list[str]:
        return list(self.quantities)[: max(1, int(getattr(self.finite, "contacts", 1)))]

    @property
    def relative_diff(self) -> dict[str, float]:
        """``max |diff| / max |closed|`` over the window, per quantity."""
        return {k: q.relative for k, q in self.quantities.items()}

    @property
    def tau_valid(self) -> float:
        """The finite beam's strict reflection-free window (fastest modelled wave; NaN on supports)."""
        return math.nan if self.finite is None else self.finite.tau_valid

    @property
    def agrees(self) -> bool:
        """Some quantity compared, and every one within the tolerance."""
        return bool(self.quantities) and all(q.within for q in self.quantities.values())

    @property
    def ratio(self) -> float:
        """``finite_beam_s / closed_form_s``: how many times slower the finite beam is."""
        return self.finite_beam_s / self.closed_form_s if self.closed_form_s > 0 else math.inf

    def _repr_html_(self) -> str:
        """Jupyter: whether the finite beam agrees first, then every quantity's relative difference."""
        from moving_bogie.html_repr import html_table

        if self.supports is not None:
            return self.supports._repr_html_()
        verdict = "AGREES" if self.agrees else "DISAGREES"
        rows = [
            ("model", self.model),
            ("window", f"tau {self.window[0]:.6g}..{self.window[1]:.6g}"),
            ("tolerance", f"{self.tolerance:g} of max |closed form|"),
            ("wall times [s]", f"finite beam {self.finite_beam_s:.3g}, closed form {self.closed_form_s:.3g}"),
        ]
        items = [
            (self.labels.get(k, k), f"{q.relative:.3g}", "yes" if q.within else "no")
            for k, q in self.quantities.items()
        ]
        header = ("quantity", "max |difference| / max |closed form|", "within")
        return html_table(
            "finite beam against closed form", verdict, rows, reasons=list(self.notes), items=(header, items)
        )

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary (no time series); on supports :meth:`_on_supports`."""
        if self.supports is not None:
            return self._on_supports(self.supports)
        params = self.params.to_dict() if hasattr(self.params, "to_dict") else None
        q = self.quantities
        finite = self.finite_beam
        return {
            "model": self.model,
            "beam": getattr(self.params, "beam", None),
            "track": getattr(self.params, "track", "one-layer"),
            "params": params,
            "closed_form_branch_cut": bool(getattr(self.closed, "branch_cut", False)),
            "agrees": self.agrees,
            "tolerance": self.tolerance,
            "tolerance_rule": (
                f"max|X_finite - X_closed| <= {self.tolerance:g} max|X_closed| over the window, "
                "for every quantity (max|X_closed| at least tol times the largest quantity of the same unit)"
            ),
            "relative_diff": self.relative_diff,
            "labels": dict(self.labels),
            "max_abs_diff_rear": self.max_abs_diff_rear,
            "max_abs_diff_front": self.max_abs_diff_front,
            **{f"max_abs_diff_{name}": q[name].max_abs_diff for name in list(q)[len(self._wheels) :]},
            "error_estimate": {k: _json_float(v.error_estimate) for k, v in q.items()},
            "quantities": {k: v.to_dict() for k, v in q.items()},
            "window": list(self.window),
            "tau_valid": finite.tau_valid,
            "reflection_level": self.reflection_level,
            "tau_max": float(self.tau[-1]),
            "n_modes": finite.n_modes,
            "static_correction": finite.static_correction,
            "L": finite.length,
            "entry": finite.entry,
            "k_max": finite.k_max,
            "dt": finite.dt,
            "reference_dt": None if self.reference is None else self.reference.dt,
            "timings": {
                "finite_beam_s": self.finite_beam_s,
                "finite_beam_stepping_s": finite.elapsed_s,
                "reference_run_s": self.reference_s,
                "closed_form_s": self.closed_form_s,
                "ratio_finite_to_closed": self.ratio,
            },
            "notes": list(self.notes),
        }

    def _on_supports(self, check: SleeperCheck) -> dict[str, Any]:
        """:data:`CHECK_KEYS` (None where the modal finite beam's alone), then :meth:`SleeperCheck.to_dict`'s
        keys; each quantity with the keys of both."""
        own = check.to_dict()
        shared = dict.fromkeys(CHECK_KEYS) | {
            "closed_form_branch_cut": False,
            "labels": {name: name for name in self.quantities},
            "error_estimate": dict.fromkeys(self.quantities),
            "window": list(self.window),
            "tau_max": float(self.tau[-1]),
            "L": check.rail.length,
            "dt": check.free.dt,
        }
        quantities = {name: q.to_dict() | own["quantities"][name] for name, q in self.quantities.items()}
        return shared | own | {"quantities": quantities}
