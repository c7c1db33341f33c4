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
from dataclasses import dataclass, field

import numpy as np

from moving_bogie.errors import MovingBogieError, ParameterError
from moving_bogie.kernels.bound import bind
from moving_bogie.model.physical import PhysicalParams
from moving_bogie.response.axis_sequence import axis_roots, refuse_outside
from moving_bogie.response.cut_policy import branch_cut_extent, branch_cut_mode, branch_cut_or_note, s_min_for
from moving_bogie.response.residues import ResidueExpansion, residue_expansion
from moving_bogie.response.shapes import KernelGrid

__all__ = [
    "TimeSeries",
    "branch_cut_extent",
    "closed_form_response",
    "deflection_shape",
    "deflection_shape_details",
]

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
    frequencies : FrequencyResult
        The induced frequencies whose residues were summed.
    model : str
    units : dict
        Units by kind of quantity: time ``tau``, rail deflection ``w``, body displacement ``u``, body
        rotation ``theta``, coordinate ``xi``; dimensionless (w_st, w_st chi) or SI (s, m, rad).
    notes : tuple of str
        What the computation decided (e.g. up to which time the branch cut was included).
    contacts : int
        How many of the responses, the first ones, are the rail under a wheel (``CONTACTS``).
    """

    tau: np.ndarray
    responses: dict
    steady: dict
    response_units: dict
    branch_cut: bool
    frequencies: object
    model: str | None = None
    branch_cut_until: float = 0.0
    units: dict = field(default_factory=lambda: dict(DIMENSIONLESS_UNITS))
    notes: tuple = ()
    contacts: int = 1

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
        """Jupyter: the verdict of the frequencies summed first, then the times, steady parts and notes."""
        from moving_bogie.html_repr import html_table

        state = getattr(getattr(self.frequencies, "verdict", None), "state", "frequencies not judged")
        verdict = f"{state.upper()} (the induced frequencies summed)"
        unit = self.units.get("tau", "")
        rows = [
            ("model", self.model),
            ("times", f"{len(self.tau)} from {self.tau[0]:.6g} to {self.tau[-1]:.6g} {unit}".rstrip()),
            ("branch cut included up to", f"{self.branch_cut_until:.6g}" if self.branch_cut else "nowhere"),
        ]
        rows += [
            (f"steady {k}", f"{v:.10g} {self.response_units.get(k, '')}".rstrip())
            for k, v in self.steady.items()
        ]
        return html_table("closed-form time series", verdict, rows, reasons=list(self.notes))

    def to_dict(self) -> dict:
        """JSON-ready dict: every response under its DOF name (arrays as lists, NaN as None), the steady
        parts, flags, units and frequencies."""

        def clean(x):
            return [None if not math.isfinite(v) else float(v) for v in np.asarray(x, dtype=float).ravel()]

        def scalar(v):
            return None if not math.isfinite(v) else float(v)

        return {
            "tau": clean(self.tau),
            **{name: clean(v) for name, v in self.responses.items()},
            "branch_cut": bool(self.branch_cut),
            "branch_cut_until": None if math.isinf(self.branch_cut_until) else float(self.branch_cut_until),
            "model": self.model,
            "units": dict(self.units),
            "responses": {name: clean(v) for name, v in self.responses.items()},
            "steady": {name: scalar(v) for name, v in self.steady.items()},
            "response_units": dict(self.response_units),
            "induced_frequencies": [
                {"re": r.re_text, "im": r.im_text, "side": r.side} for r in self.frequencies.roots
            ],
            "notes": list(self.notes),
        }


def _bound_and_scales(params):
    """(BoundModel, Scales or None) from either kind of parameters (or a bound model)."""
    if isinstance(params, PhysicalParams):
        return bind(params.to_dimensionless()), params.scales()
    return bind(params), None


def _frequencies(bound, frequencies, dps, progress):
    if frequencies is not None:
        vehicle = bound.params.vehicle
        if frequencies.model != vehicle:
            raise ParameterError(
                "model", f"frequencies were computed for model {frequencies.model!r}, not {vehicle!r}"
            )
        if getattr(frequencies, "params", bound.params) != bound.params:
            raise ParameterError("frequencies", "frequencies were computed for other parameters")
        result = frequencies
    else:
        from moving_bogie.roots.frequencies import induced_frequencies

        result = induced_frequencies(bound, dps=dps, progress=progress)
    return result


def closed_form_response(
    params,
    tau,
    *,
    frequencies=None,
    branch_cut="auto",
    dps: int = 30,
    progress: Callable[[float], None] | None = None,
    bc_tol: float = 1e-6,
    bc_tau_cap: float = 1e4,
    quad_tol: float = 1e-10,
) -> TimeSeries:
    """Closed-form time series of every degree of freedom of the vehicle (Eqs. (35)-(43)).

    Parameters
    ----------
    params : DimensionlessParams, BoundModel or PhysicalParams
        The model comes with them (another vehicle: ``params.replace(vehicle=...)``). With physical
        parameters, ``tau`` is the time t in seconds and the results are in m and rad.
    tau : array_like of float, >= 0
        Times (dimensionless tau = t sqrt(k_f/m), Eq. (16), unless physical parameters are given).
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
    bound, scales = _bound_and_scales(params)
    tau = np.asarray(tau, dtype=float)
    if scales is not None:
        tau_in = tau
        tau = tau / scales.t_scale
    if tau.ndim != 1:
        tau = tau.reshape(-1)
    if np.any(tau < 0) or not np.all(np.isfinite(tau)):
        raise ParameterError("tau", "tau must be finite and >= 0")
    mode = branch_cut_mode(branch_cut)
    bc, notes = branch_cut_or_note(bound, mode)

    def report(fraction):
        if progress is not None:
            progress(fraction)

    def staged(x):
        report(0.8 * x)

    result = _frequencies(bound, frequencies, dps, staged if progress else None)
    report(0.8)
    expansion = residue_expansion(bound, result, shapes=False)
    sequence, more_notes = axis_roots(bound, result, expansion)
    notes += more_notes
    report(0.85)
    series = expansion.totals(tau)
    if sequence is not None:
        for name, v in sequence.harmonics(tau, expansion.names).items():
            series[name] += v
    until = 0.0
    if bc is not None and tau.size:
        s_min = max(s_min_for(bc, e) for e in (expansion, *(sequence.expansions if sequence else ())))
        if mode == "on":
            until = math.inf
        else:
            wheels = expansion.names[: len(expansion.positions)]
            scale = max(*(abs(expansion.steady[name]) for name in wheels), 1e-300)
            until, more = branch_cut_extent(
                bc, float(tau.max()), tol=bc_tol * scale, cap=bc_tau_cap, s_min=s_min
            )
            notes += more
        mask = tau <= until
        if np.any(mask):
            extra = bc.responses(tau[mask], tol=quad_tol, s_min=s_min)
            for name in expansion.names:
                series[name][mask] += extra[name]
        else:
            until = 0.0
    report(1.0)
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
        frequencies=result,
        model=bound.params.vehicle,
        branch_cut_until=until,
        units=units,
        notes=tuple(notes),
        contacts=len(expansion.positions),
    )


def deflection_shape(params, xi, tau: float, **options) -> np.ndarray:
    """Beam deflection w(xi, tau) at one time for an array of xi, Eqs. (44)-(47) plus the branch cut.

    xi is the moving coordinate (0 at the rear wheel, d at the front one). With physical parameters
    xi is in metres, tau in seconds and the result in metres. Keywords: ``frequencies``,
    ``branch_cut``, ``dps``, ``bc_tol``, ``bc_tau_cap``, ``quad_tol`` as in :func:`closed_form_response`
    (``auto`` applies the same rule at this single time), and ``expansion`` (a precomputed
    :class:`ResidueExpansion` with shapes). :func:`deflection_shape_details` also says whether I_bc was
    included.
    """
    return deflection_shape_details(params, xi, tau, **options)[0]


def deflection_shape_details(
    params,
    xi,
    tau: float,
    *,
    frequencies=None,
    branch_cut="auto",
    dps: int = 30,
    bc_tol: float = 1e-6,
    bc_tau_cap: float = 1e4,
    quad_tol: float = 1e-10,
    expansion: ResidueExpansion | None = None,
) -> tuple[np.ndarray, bool, tuple]:
    """(w, branch_cut, notes): :func:`deflection_shape`, whether I_bc was included, and why not."""
    bound, scales = _bound_and_scales(params)
    xi = np.asarray(xi, dtype=float)
    tau = float(tau)
    if scales is not None:
        xi = scales.chi * xi
        tau = tau / scales.t_scale
    if not (math.isfinite(tau) and tau >= 0):
        raise ParameterError("tau", "tau must be finite and >= 0")
    mode = branch_cut_mode(branch_cut)
    bc, notes = branch_cut_or_note(bound, mode)
    result = _frequencies(bound, frequencies, dps, None)
    refuse_outside(result)
    if expansion is None:
        expansion = residue_expansion(bound, result, shapes=True)
    flat = xi.reshape(-1)
    grid0 = KernelGrid(bound, 0, dps=result.dps)
    # Eqs. (44)-(47) for n contacts: w(xi) = sum_j weight_j K(xi - xi_j).
    w = sum(a * grid0(flat - x) for a, x in zip(expansion.shape_steady, expansion.positions))
    for q, amplitudes in zip(expansion.q_mp, expansion.shape_amplitudes):
        grid = KernelGrid(bound, q, dps=result.dps)
        w = w + sum(a * grid(flat - x) for a, x in zip(amplitudes, expansion.positions)) * np.exp(
            1j * complex(q) * tau
        )
    scale = np.abs(w).max() if w.size else 0.0
    if w.size and np.abs(w.imag).max() > 1e-8 * max(scale, 1.0):
        raise MovingBogieError(f"deflection shape: imaginary part {np.abs(w.imag).max():.3g} does not cancel")
    w = w.real
    include = False
    if bc is not None and flat.size:
        s_min = s_min_for(bc, expansion)
        include = mode == "on"
        if not include:
            wheels = expansion.names[: len(expansion.positions)]
            ref = max(*(abs(expansion.steady[name]) for name in wheels), 1e-300)
            until, more = branch_cut_extent(bc, tau, tol=bc_tol * ref, cap=bc_tau_cap, s_min=s_min)
            include = tau <= until
            notes += (
                more if include else [*more, f"branch cut below tol {bc_tol:.1e} of the steady deflection"]
            )
        if include:
            w = w + bc.shape(flat, tau, tol=quad_tol, s_min=s_min)
    w = w.reshape(xi.shape)
    return (scales.deflection(w) if scales is not None else w), bool(include), tuple(notes)
