"""Closed-form vibrations: time series at the contact points and deflection shapes, Eqs. (35)-(47).

    x(tau) = steady part (Eq. (39)) + unsteady harmonic part (residues at every induced frequency,
             Eqs. (36), (40)-(43)) + branch-cut part I_bc (Eq. (35))

for x every degree of freedom of the vehicle (its generated ``DOFS``: the rail's deflection under each
wheel, w(xi_j, tau), then the bodies' bounce and pitch), and for the beam deflection w(xi, tau) at any xi
(Eqs. (44)-(47)). Coefficients are evaluated once at the precision
of the roots (:mod:`residues`); time series are vectorised numpy sums whose cost does not grow with tau.
The branch-cut part (:mod:`branch_cut`) is a numerical integral along the cut; it matters at early times
(it makes the homogeneous initial conditions hold exactly) and decays like e^{-eta_f tau} (algebraically,
about tau^-3/2, when eta_f = 0).

``branch_cut="auto"`` (the default) includes I_bc at the times where it can matter
(:mod:`~moving_bogie.response.cut_policy`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike

from moving_bogie.errors import ParameterError
from moving_bogie.kernels.bound import BoundModel
from moving_bogie.model.physical import Scales
from moving_bogie.response.axis_sequence import axis_roots
from moving_bogie.response.cut_policy import branch_cut_extent, branch_cut_mode, branch_cut_or_note, s_min_for
from moving_bogie.response.deflection import deflection_shape, deflection_shape_details
from moving_bogie.response.residues import ResidueExpansion, frequencies_for, residue_expansion

if TYPE_CHECKING:
    import pandas
    import xarray

    from moving_bogie.response.axis_sequence import AxisSequence
    from moving_bogie.response.bay_response import BayResponse
    from moving_bogie.response.branch_cut import BranchCut
    from moving_bogie.response.cut_integral import CurveBranchCut
    from moving_bogie.roots.frequencies import FrequencyResult

__all__ = [
    "SERIES_KEYS",
    "TimeSeries",
    "branch_cut_extent",
    "closed_form_response",
    "deflection_shape",
    "deflection_shape_details",
]

#: The keys every time series' ``to_dict()`` has, with the same meaning on every track (a
#: :class:`TimeSeries` on sleepers adds its ``bay``'s): the times, the units by kind, the rail's
#: deflection under each wheel (and the bodies' motion) by DOF name, its steady part, the units of each
#: response, the notes.
SERIES_KEYS = ("tau", "units", "responses", "steady", "response_units", "notes")

DIMENSIONLESS_UNITS = {"tau": "1", "w": "w_st", "u": "w_st", "theta": "w_st chi", "xi": "1"}
SI_UNITS = {"tau": "s", "w": "m", "u": "m", "theta": "rad", "xi": "m"}


@dataclass(frozen=True)
class TimeSeries:
    """The closed-form response at the times ``tau``, every degree of freedom of the vehicle by its name.

    Attributes
    ----------
    tau : ndarray
        Dimensionless times (seconds if physical parameters were given, see ``units``).
    responses : dict
        Every response of the vehicle by its DOF name (``DOFS`` of its generated module: the rail under
        each wheel, then the bodies' bounce and pitch), e.g. ``w_rear``, ``w_front``, ``u``, ``theta`` for
        the paper's bogie. ``series[name]`` is ``series.responses[name]``.
    steady : dict
        DOF name -> its steady part, Eq. (39).
    response_units : dict
        DOF name -> unit of that response (``w_st``, ``w_st chi`` or SI ``m``, ``rad``).
    branch_cut : bool
        Whether I_bc was included at some of the times.
    branch_cut_until : float
        I_bc is included for tau <= this (0: nowhere, inf: everywhere), in the units of ``tau``.
    frequencies : FrequencyResult or None
        The induced frequencies whose residues were summed; on periodic supports the roots of the strip
        (the free vibrations; None when not searched).
    model : str
    units : dict
        Units by kind of quantity: time ``tau``, rail deflection ``w``, body displacement ``u``, body
        rotation ``theta``, coordinate ``xi``; dimensionless (w_st, w_st chi) or SI (s, m, rad).
    notes : tuple of str
        What the computation decided (e.g. up to which time the branch cut was included).
    contacts : int
        How many of the responses, the first ones, are the rail under a wheel (``CONTACTS``).
    bay : BayResponse or None
        On periodic supports (:func:`~moving_bogie.response.sleeper_series.sleeper_series`), what they add:
        the contact forces over the bays, the bay, Omega_0, the harmonics, the free vibrations in rad/s;
        None on a continuous track.
    """

    tau: np.ndarray
    responses: dict[str, np.ndarray]
    steady: dict[str, float]
    response_units: dict[str, str]
    branch_cut: bool
    frequencies: FrequencyResult | None
    model: str | None = None
    branch_cut_until: float = 0.0
    units: dict[str, str] = field(default_factory=lambda: dict(DIMENSIONLESS_UNITS))
    notes: tuple[str, ...] = ()
    contacts: int = 1
    bay: BayResponse | None = None

    @property
    def complete(self) -> bool:
        """Whether the series is the whole answer: on periodic supports, the steady response converged in
        the harmonics and the free vibrations' verdict is not UNDETERMINED (a closed form is only made from
        a complete frequency search)."""
        return self.bay is None or self.bay.complete

    @property
    def warnings(self) -> tuple[str, ...]:
        """What leaves the answer short (:attr:`complete`): on periodic supports, a steady response not
        converged and the strip search's notes; none on a continuous track (its notes say what was
        decided)."""
        return () if self.bay is None else self.bay.warnings

    @property
    def names(self) -> tuple[str, ...]:
        """The responses' DOF names, the wheels first (``DOFS`` order)."""
        return tuple(self.responses)

    def __getitem__(self, name: str) -> np.ndarray:
        """The response of the DOF ``name`` (``series["w_rear"]``)."""
        try:
            return self.responses[name]
        except KeyError:
            known = ", ".join(self.responses)
            raise KeyError(f"{name!r}: no such response of {self.model}; known: {known}") from None

    def _repr_html_(self) -> str:
        """Jupyter: the verdict of the frequencies summed first, then the times, steady parts and notes (on
        periodic supports, the free vibrations' verdict, then the steady response over the bay per wheel
        and the roots)."""
        from moving_bogie.html_repr import html_table

        if self.bay is not None:
            return self.bay._repr_html_()
        from moving_bogie.presentation import quantity_text

        state = getattr(getattr(self.frequencies, "verdict", None), "state", "frequencies not judged")
        verdict = f"{state.upper()} (the induced frequencies summed)"
        unit = self.units.get("tau", "")
        rows = [
            ("model", self.model),
            (
                "times",
                f"{len(self.tau)} from {quantity_text(self.tau[0], unit)} "
                f"to {quantity_text(self.tau[-1], unit)}",
            ),
            (
                "branch cut included up to",
                quantity_text(self.branch_cut_until, unit) if self.branch_cut else "nowhere",
            ),
        ]
        rows += [
            (f"steady {k}", quantity_text(v, self.response_units.get(k, ""), 10))
            for k, v in self.steady.items()
        ]
        return html_table("closed-form time series", verdict, rows, reasons=list(self.notes))

    def to_xarray(self) -> xarray.Dataset:
        """The series as an xarray Dataset over time, each response with its CF ``units`` attribute
        (``t`` [s], m and rad for SI parameters): :func:`moving_bogie.export.series_dataset`."""
        from moving_bogie.export import series_dataset

        return series_dataset(self)

    def to_dataframe(self) -> pandas.DataFrame:
        """The series as a pandas DataFrame indexed by time, the units in ``attrs["units"]``."""
        from moving_bogie.export import to_dataframe

        return to_dataframe(self.to_xarray())

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict: every response under its DOF name (arrays as lists, NaN as None), the steady
        parts, flags, units and frequencies; on periodic supports then the ``bay``'s keys
        (:meth:`~moving_bogie.response.sleeper_series.BayResponse.to_dict`)."""

        def clean(x: ArrayLike) -> list[float | None]:
            return [None if not math.isfinite(v) else float(v) for v in np.asarray(x, dtype=float).ravel()]

        def scalar(v: float) -> float | None:
            return None if not math.isfinite(v) else float(v)

        roots = () if self.frequencies is None else self.frequencies.roots
        series = {
            "tau": clean(self.tau),
            **{name: clean(v) for name, v in self.responses.items()},
            "branch_cut": bool(self.branch_cut),
            "branch_cut_until": None if math.isinf(self.branch_cut_until) else float(self.branch_cut_until),
            "model": self.model,
            "units": dict(self.units),
            "responses": {name: clean(v) for name, v in self.responses.items()},
            "steady": {name: scalar(v) for name, v in self.steady.items()},
            "response_units": dict(self.response_units),
            "induced_frequencies": [{"re": r.re_text, "im": r.im_text, "side": r.side} for r in roots],
            "notes": list(self.notes),
        }
        return series if self.bay is None else series | self.bay.to_dict()


def _dimensionless_times(tau: ArrayLike, scales: Scales | None) -> tuple[np.ndarray, np.ndarray]:
    """(tau, the times as given): dimensionless tau of Eq. (16) (from seconds when ``scales`` are given)."""
    tau = np.asarray(tau, dtype=float)
    tau_in = tau
    if scales is not None:
        tau = tau / scales.t_scale
    if tau.ndim != 1:
        tau = tau.reshape(-1)
    if np.any(tau < 0) or not np.all(np.isfinite(tau)):
        raise ParameterError("tau", "tau must be finite and >= 0")
    return tau, tau_in


def closed_form_response(
    bound: BoundModel,
    tau: ArrayLike,
    *,
    scales: Scales | None = None,
    frequencies: FrequencyResult | None = None,
    branch_cut: bool | str = "auto",
    dps: int = 30,
    progress: Callable[[float], None] | None = None,
    bc_tol: float = 1e-6,
    bc_tau_cap: float = 1e4,
    quad_tol: float = 1e-10,
) -> TimeSeries:
    """Closed-form time series of every degree of freedom of the vehicle (Eqs. (35)-(43)).

    Parameters
    ----------
    bound : BoundModel
        The parameters bound to their model (another vehicle: ``bound.replace(vehicle=...)``; the public
        :func:`moving_bogie.closed_form_response` binds, from SI parameters too).
    tau : array_like of float, >= 0
        Times (dimensionless tau = t sqrt(k_f/m), Eq. (16), unless ``scales`` are given).
    scales : Scales, optional
        The SI scales of Eqs. (15)-(16) (``PhysicalParams.scales()``): ``tau`` is then the time t in seconds
        and the results are in m and rad.
    frequencies : FrequencyResult, optional
        Precomputed induced frequencies (same params, hence the same vehicle); computed at ``dps`` if
        omitted.
    branch_cut : True, False or "auto"
        Include the branch-cut part I_bc (any beam: the Euler-Bernoulli half-line by
        :class:`~moving_bogie.response.branch_cut.BranchCut`, any other cut by
        :class:`~moving_bogie.response.cut_integral.CurveBranchCut`).
        "auto": include it where it exceeds ``bc_tol`` (module docstring).
    dps : int
        Precision of the induced frequencies and residue coefficients when they are computed here.
    progress : callable, optional
        Called with the fraction of the work done (0..1).
    bc_tol : float
        ``auto`` threshold, relative to the largest steady wheel deflection.
    bc_tau_cap : float
        ``auto`` never includes I_bc beyond this dimensionless time (its cost grows with tau).
    quad_tol : float
        Absolute tolerance of the branch-cut quadrature's truncation (units of w_st).

    Returns
    -------
    TimeSeries

    Raises
    ------
    IncompleteFrequencies
        If the frequency count failed (``not frequencies.count_ok``).
    BranchCutUnavailable
        ``branch_cut=True`` when the cut passes through q = 0 (an undamped track above the critical
        velocity, an undamped layered track) or stays bounded (a layered track at alpha = 0).
    """
    tau, tau_in = _dimensionless_times(tau, scales)
    mode = branch_cut_mode(branch_cut)
    bc, notes = branch_cut_or_note(bound, mode)

    def report(fraction: float) -> None:
        if progress is not None:
            progress(fraction)

    def staged(x: float) -> None:
        report(0.8 * x)

    result = frequencies_for(bound, frequencies, dps, staged if progress else None)
    report(0.8)
    expansion = residue_expansion(bound, result, shapes=False)
    sequence, more_notes = axis_roots(bound, result, expansion)
    notes += more_notes
    report(0.85)
    series = _harmonic_sum(expansion, sequence, tau)
    until = _add_branch_cut(series, bc, tau, expansion, sequence, mode, notes, bc_tol, bc_tau_cap, quad_tol)
    report(1.0)
    return _time_series(bound, tau, tau_in, scales, series, expansion, result, until, notes)


def _time_series(
    bound: BoundModel,
    tau: np.ndarray,
    tau_in: np.ndarray,
    scales: Scales | None,
    series: dict[str, np.ndarray],
    expansion: ResidueExpansion,
    result: FrequencyResult,
    until: float,
    notes: list[str],
) -> TimeSeries:
    """The :class:`TimeSeries` of the summed responses (by DOF name), in SI when ``scales`` are given."""
    units_of = bound.vehicle.UNITS
    responses = {name: series[name] for name in expansion.names}
    steady_parts = {name: expansion.steady[name] for name in expansion.names}
    if scales is not None:
        until = until * scales.t_scale
        units = dict(SI_UNITS)
        to_si = {"m": scales.deflection, "rad": scales.rotation}
        responses = {name: to_si[units_of[name]](v) for name, v in responses.items()}
        steady_parts = {name: to_si[units_of[name]](v) for name, v in steady_parts.items()}
        response_units = {name: units_of[name] for name in expansion.names}
        tau = tau_in.reshape(-1)
    else:
        units = dict(DIMENSIONLESS_UNITS)
        response_units = {name: "w_st chi" if units_of[name] == "rad" else "w_st" for name in expansion.names}
    return TimeSeries(
        tau=tau,
        responses=responses,
        steady=steady_parts,
        response_units=response_units,
        branch_cut=bool(until > 0),
        frequencies=result if scales is None else replace(result, scales=scales),
        model=bound.params.vehicle,
        branch_cut_until=until,
        units=units,
        notes=tuple(notes),
        contacts=len(expansion.positions),
    )


def _harmonic_sum(
    expansion: ResidueExpansion, sequence: AxisSequence | None, tau: np.ndarray
) -> dict[str, np.ndarray]:
    """Steady part plus the residues at every induced frequency (Eqs. (36), (39)-(43)), with the sequence
    of roots along the real axis beyond the window when there is one."""
    series = expansion.totals(tau)
    if sequence is not None:
        for name, v in sequence.harmonics(tau, expansion.names).items():
            series[name] += v
    return series


def _add_branch_cut(
    series: dict[str, np.ndarray],
    bc: BranchCut | CurveBranchCut | None,
    tau: np.ndarray,
    expansion: ResidueExpansion,
    sequence: AxisSequence | None,
    mode: str,
    notes: list[str],
    bc_tol: float,
    bc_tau_cap: float,
    quad_tol: float,
) -> float:
    """Add the branch-cut integral I_bc to ``series`` up to the tau where it matters; returns that tau.

    ``mode`` "on": at every time; "auto": until I_bc falls below ``bc_tol`` of the largest steady wheel
    deflection (:func:`~moving_bogie.response.cut_policy.branch_cut_extent`, notes appended), 0 when never
    (and without a branch cut, ``bc`` None).
    """
    if bc is None or not tau.size:
        return 0.0
    s_min = max(s_min_for(bc, e) for e in (expansion, *(sequence.expansions if sequence else ())))
    if mode == "on":
        until = math.inf
    else:
        wheels = expansion.names[: len(expansion.positions)]
        scale = max(*(abs(expansion.steady[name]) for name in wheels), 1e-300)
        until, more = branch_cut_extent(
            bc, float(tau.max()), tol=bc_tol * scale, cap=bc_tau_cap, s_min=s_min, times=tau
        )
        notes += more
    mask = tau <= until
    if not np.any(mask):
        return 0.0
    # the rules of the probes of branch_cut_extent (set by all the times): a traced cut reuses their values
    extra = bc.responses(tau[mask], tol=quad_tol, s_min=s_min, rule_tau=tau)
    for name in expansion.names:
        series[name][mask] += extra[name]
    return until
