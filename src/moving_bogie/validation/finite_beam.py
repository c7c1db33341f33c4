"""Validation of the infinite-beam solution on a long finite beam by modal expansion (Section 3.2).

The paper checks its closed-form results against a simply supported finite beam in 500 sine modes,
Eqs. (49)-(54). :func:`simulate_finite_beam` does the same in dimensionless variables: the modal
equations of :mod:`moving_bogie.validation.modal` (diagonal + rank-4 matrices), stepped by the
implicit Newmark average-acceleration rule with a Sherman-Morrison-Woodbury solve
(:mod:`moving_bogie.validation.newmark`), on a beam whose length and entry point
:mod:`moving_bogie.validation.geometry` chooses so that the supports stay invisible.

References
----------
N. M. Newmark, "A method of computation for structural dynamics", J. Eng. Mech. Div. ASCE 85(EM3),
67-94 (1959).
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.interpolate import CubicHermiteSpline

from moving_bogie.errors import MovingBogieError
from moving_bogie.kernels.bound import BoundModel
from moving_bogie.model.catalogue import DEFAULT_MODEL
from moving_bogie.validation.corrected import CorrectedModalSystem
from moving_bogie.validation.geometry import BeamGeometry, choose_geometry, default_time_step
from moving_bogie.validation.modal import ModalBeam, ModalSystem
from moving_bogie.validation.newmark import initial_state, newmark_step
from moving_bogie.validation.track_modes import ModalTrack
from moving_bogie.validation.vehicle import Vehicle

__all__ = ["FiniteBeamResult", "simulate_finite_beam"]

#: How many progress reports a run makes at most.
_PROGRESS_REPORTS = 200


@dataclass(frozen=True)
class FiniteBeamResult:
    """Time series of a finite-beam run (dimensionless, Eqs. (16)-(17)).

    Every response of the vehicle is an attribute of its own too (``result.w_rear`` for the paper's
    bogie, whose ``DOFS`` are ``w_rear, w_front, u, theta``).

    Attributes
    ----------
    tau : ndarray
        Output times.
    responses : dict
        Degree-of-freedom name (the vehicle's ``DOFS``) -> time series: the deflection under each wheel,
        ``w(x_j(tau), tau)``, then the bodies' bounce and pitch.
    length, entry : float
        Beam length ``L`` and rear-wheel position ``x0`` at ``tau = 0``.
    n_modes : int
        Number of sine modes ``N``.
    dt : float
        Time step.
    tau_valid : float
        End of the window ``(0, tau_valid)`` in which no wave reflected at a support has reached
        the wheels (fastest modelled wave; see :mod:`moving_bogie.validation.geometry`).
    elapsed_s : float
        Wall time of the time stepping.
    model : str
        The vehicle's name, or "force" (its loads only), for output.
    k_max : float
        Highest modelled wavenumber ``N pi / L``.
    static_correction : bool
        Whether the truncated modes' quasi-static response was added back.
    span : float
        Distance from the rear to the front contact.
    contacts : int
        Number of wheels (the first ``contacts`` entries of :attr:`responses`).
    """

    tau: np.ndarray
    responses: dict[str, np.ndarray]
    length: float
    entry: float
    n_modes: int
    dt: float
    tau_valid: float
    elapsed_s: float
    model: str | None = None
    k_max: float = math.nan
    static_correction: bool = False
    span: float = math.nan
    contacts: int = 0

    def __getattr__(self, name: str) -> np.ndarray:
        responses = self.__dict__.get("responses", {})
        if name in responses:
            return responses[name]
        raise AttributeError(name)


#: The ``model`` of a result that kept only the vehicle's wheel loads (``loads_only=True``).
LOADS_ONLY = "force"


def _check(
    params: Any, tau_max: float, loads_only: bool, n_modes: int, dt: float | None
) -> tuple[ModalTrack, Vehicle]:
    """Refuse bad input before any computation; return the track's blocks and the vehicle (entry 0)."""
    track = ModalTrack.of(params)  # names an unknown beam or track
    vehicle = Vehicle.of(params, 0.0)  # names an unknown vehicle
    if loads_only:
        vehicle = vehicle.loads_only()
    if not (math.isfinite(tau_max) and tau_max > 0):
        raise MovingBogieError(f"tau_max must be a positive finite number (got {tau_max!r})")
    if n_modes < 1:
        raise MovingBogieError(f"n_modes must be at least 1 (got {n_modes!r})")
    if dt is not None and not (math.isfinite(dt) and dt > 0):
        raise MovingBogieError(f"dt must be a positive finite number (got {dt!r})")
    # Newmark needs a positive definite mass in every mode: e.g. rotary inertia for a rotation unknown.
    mass = track.blocks(np.array([1.0]))[0][0]
    if np.min(np.linalg.eigvalsh(mass)) <= 0:
        # name the groups of the mass block that are zero (those whose value changes it)
        zero = [
            name
            for name in track.module.MODAL_ARGUMENTS[1:]
            if track.values.get(name, 0.0) <= 0
            and not np.array_equal(
                ModalTrack(track.module, {**track.values, name: 1.0}).blocks(np.array([1.0]))[0][0], mass
            )
        ]
        raise MovingBogieError(
            "the finite beam needs a positive mass for every unknown of each mode (got "
            + ", ".join(f"{name}={track.values.get(name, 0.0):g}" for name in zero)
            + "): give these groups positive values"
        )
    return track, vehicle


def simulate_finite_beam(
    params: Any,
    tau_max: float,
    *,
    loads_only: bool = False,
    n_modes: int = 500,
    length: float | None = None,
    entry: float | None = None,
    dt: float | None = None,
    tau_out: np.ndarray | None = None,
    progress: Callable[[float], None] | None = None,
    static_correction: bool = True,
) -> FiniteBeamResult:
    """Bogie, two masses or two forces crossing a finite beam, by modal expansion, Eqs. (49)-(54).

    Starts from rest with the loads applied suddenly at ``tau = 0`` (homogeneous initial
    conditions, as in the paper) and steps Eq. (49) (with Eqs. (50)-(51) eliminated, see
    :mod:`moving_bogie.validation.modal`) by Newmark's average acceleration rule (Newmark 1959),
    each step in ``O(n_modes)`` by a Woodbury solve.

    Parameters
    ----------
    params : DimensionlessParams, BoundModel or duck-typed equivalent
        Any beam on any track under any vehicle of the catalogue (its generated per-mode blocks,
        :class:`~moving_bogie.validation.track_modes.ModalTrack`, and the vehicle's matrices); a
        namespace of numbers names its ``beam``, ``track`` and ``vehicle`` (default: the paper's model)
        and carries the groups of that model (a group it leaves out counts as 0) and the vehicle's
        (anything ``float()`` accepts).
    tau_max : float
        End of the run.
    loads_only : bool, optional
        Keep only the vehicle's wheel loads, as constant moving forces (its matrices zeroed; default
        False).
    n_modes : int, optional
        Number of sine modes ``N`` (default 500, as in the paper).
    length, entry : float, optional
        Beam length ``L`` and rear-wheel start ``x0``; by default chosen by
        :func:`~moving_bogie.validation.geometry.choose_geometry` so that no reflection from the
        supports reaches the wheels before `tau_max`, or is damped below 1e-3 when it does, unless
        that would make ``k_max = N pi / L`` smaller than 4.
    dt : float, optional
        Time step; default :func:`~moving_bogie.validation.geometry.default_time_step` (32 steps
        per period of the wavenumbers up to ``min(k_max, 4)``), shortened so that `tau_max` is a
        whole number of steps.
    tau_out : array_like, optional
        Output times in ``[0, tau_max]``, interpolated from the steps by cubic Hermite splines using
        the exact total time derivatives; default: every step.
    progress : callable, optional
        Called with the fraction done (0 to 1) now and then; the core never prints.
    static_correction : bool, optional
        Add back the quasi-static response of the truncated modes at the wheels (residual
        flexibility, :mod:`moving_bogie.validation.corrected`; default True). False gives the
        plain ``N``-mode model of Eq. (49), which converges like ``k_max^-3``.

    Returns
    -------
    FiniteBeamResult

    Raises
    ------
    MovingBogieError
        For an unknown beam, track or model, a track whose modal mass is not positive (e.g. a
        Timoshenko-Rayleigh beam with ``r = 0``), a beam too short for the run, or (static
        correction) a run at or above the undamped critical velocity.
    """
    values = params.params if isinstance(params, BoundModel) else params
    track, vehicle = _check(values, tau_max, loads_only, n_modes, dt)
    geometry = _beam_geometry(track, vehicle, tau_max, n_modes, length, entry)
    h_max = default_time_step(geometry.k_max, track) if dt is None else float(dt)
    n_steps = max(1, math.ceil(tau_max / h_max - 1e-9))
    label = LOADS_ONLY if loads_only else getattr(values, "vehicle", None) or DEFAULT_MODEL["vehicle"]
    run = _Run(track, vehicle, geometry, n_modes, tau_max, n_steps, static_correction)
    return run.result(tau_out, label, progress)


def _beam_geometry(
    track: ModalTrack,
    vehicle: Vehicle,
    tau_max: float,
    n_modes: int,
    length: float | None,
    entry: float | None,
) -> BeamGeometry:
    """The beam's length and the rear wheel's entry (:func:`choose_geometry`), checked to hold the run."""
    alpha, d = vehicle.alpha, vehicle.length
    geometry = choose_geometry(track=track, d=d, tau_max=tau_max, n_modes=n_modes, length=length, entry=entry)
    if geometry.entry < 0 or geometry.entry + d + alpha * tau_max > geometry.length:
        raise MovingBogieError(
            f"the wheels leave the beam before tau_max={tau_max}: entry={geometry.entry}, d={d}, "
            f"alpha={alpha}, length={geometry.length}"
        )
    return geometry


@dataclass(frozen=True)
class _Run:
    """One run of Eq. (49): the modal beam under the vehicle, ``n_steps`` Newmark steps up to ``tau_max``."""

    track: ModalTrack
    vehicle: Vehicle
    geometry: BeamGeometry
    n_modes: int
    tau_max: float
    n_steps: int
    static_correction: bool

    def result(
        self, tau_out: np.ndarray | None, label: str, progress: Callable[[float], None] | None
    ) -> FiniteBeamResult:
        """Step the run and return the vehicle's responses at ``tau_out`` (every step when None); ``label``
        names the vehicle in the result (``model``), for output only."""
        geometry, vehicle, tau_max = self.geometry, self.vehicle, self.tau_max
        h = tau_max / self.n_steps
        tau_steps = np.arange(self.n_steps + 1) * h
        out = tau_steps if tau_out is None else np.asarray(tau_out, dtype=float)
        if tau_out is not None and (out.size == 0 or out.min() < 0 or out.max() > tau_max * (1 + 1e-12)):
            raise MovingBogieError(f"tau_out must be non-empty and lie in [0, tau_max={tau_max}]")
        system_class = CorrectedModalSystem if self.static_correction else ModalSystem
        system = system_class(
            ModalBeam(geometry.length, self.n_modes, self.track),
            dataclasses.replace(vehicle, entry=geometry.entry),
        )
        series, elapsed_s = _integrate(system, h, self.n_steps, progress)

        def resample(values: np.ndarray, rates: np.ndarray) -> np.ndarray:
            if tau_out is None:
                return values
            return CubicHermiteSpline(tau_steps, values, rates)(out)

        size = vehicle.size
        responses = {name: resample(series[i], series[size + i]) for i, name in enumerate(vehicle.dofs)}
        return FiniteBeamResult(
            tau=out,
            responses=responses,
            length=geometry.length,
            entry=geometry.entry,
            n_modes=self.n_modes,
            dt=h,
            tau_valid=geometry.tau_valid,
            elapsed_s=elapsed_s,
            model=label,
            k_max=geometry.k_max,
            static_correction=self.static_correction,
            span=vehicle.length,
            contacts=vehicle.contacts,
        )


def _integrate(
    system: ModalSystem, h: float, n_steps: int, progress: Callable[[float], None] | None
) -> tuple[np.ndarray, float]:
    """Step from rest to ``n_steps h``.

    Returns
    -------
    series : ndarray, shape (2 (n + m), n_steps + 1)
        The vehicle's degrees of freedom and then their total time derivatives, at every step.
    elapsed_s : float
        Wall time.
    """
    size = system.vehicle.size
    out = np.zeros((2 * size, n_steps + 1))
    zero = np.zeros(system.n_dof)
    start = time.perf_counter()
    state = initial_state(0.0, zero, zero.copy(), system.assemble(0.0))
    every = max(1, n_steps // _PROGRESS_REPORTS)
    if progress is not None:
        progress(0.0)
    for i in range(n_steps + 1):
        tau = i * h
        if i > 0:
            state = newmark_step(state, h, system.assemble(tau))
        response = system.response(tau, state.z, state.v)
        out[:size, i], out[size:, i] = response.x, response.dx
        if progress is not None and i > 0 and (i % every == 0 or i == n_steps):
            progress(i / n_steps)
    return out, time.perf_counter() - start
