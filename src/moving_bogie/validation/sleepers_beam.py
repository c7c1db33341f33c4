"""A vehicle crossing the finite rail on discrete supports in the time domain (docs/sleepers.md, (S25)).

The rail of :mod:`moving_bogie.validation.sleepers_rail` (sparse ``M_r, C_r, K_r``, unknowns ``z_r``) carries
a vehicle of generated matrices ``M, C, K`` (contacts first,
:class:`~moving_bogie.kernels.hill.VehicleMatrices`) whose wheels sit at ``x_c(tau) = entry + alpha tau +
xi_c``. With ``a_c = N(x_c)`` the Hermite shapes at a wheel (``a'_c``, ``a''_c`` their x-derivatives), a
wheel follows the rail,

    x_c = a_c . z_r,   x_c' = a_c . z_r' + alpha a'_c . z_r,   x_c'' = a_c . z_r'' + 2 alpha a'_c . z_r'
                                                                      + alpha^2 a''_c . z_r,

and pushes on it with ``F_c = s_c - (M x'' + C x' + K x)_c``; the internal rows ``(M x'' + C x' + K x)_i``
vanish (the same coupling as the continuous rail's finite beam, :mod:`moving_bogie.validation.modal`).
The unknowns are ``z = (z_r, x_i)``; the matrices are a constant sparse part (the rail and the vehicle's
internal block) plus ``U(tau) V(tau)^T`` of rank ``r`` (the vehicle's size), with
``U = [a_1 .. a_n, e_i]``. Newmark's average-acceleration rule (:mod:`moving_bogie.validation.newmark`)
steps it; its effective matrix, sparse plus rank ``r``, is solved by the Sherman-Morrison-Woodbury
identity with the sparse part factorised once (SuperLU).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import splu

from moving_bogie.kernels.hill import VehicleMatrices
from moving_bogie.validation.newmark import AVERAGE_ACCELERATION, NewmarkState
from moving_bogie.validation.sleepers_rail import SleeperRail

__all__ = ["BeamRun", "simulate_sleeper_beam"]


@dataclass(frozen=True)
class BeamRun:
    """Time series of one run (dimensionless, docs/sleepers.md (S2)).

    ``deflection`` and ``force`` are the rail under each wheel and the contact force (contacts x times),
    ``internal`` the vehicle's other unknowns; ``dt`` the time step, ``entry`` the rear wheel's start.
    """

    tau: np.ndarray
    deflection: np.ndarray
    force: np.ndarray
    internal: np.ndarray
    dt: float
    entry: float
    elapsed_s: float


class _Coupled:
    """The rail and the vehicle: the constant sparse part and the rank-r part at a time."""

    def __init__(self, rail: SleeperRail, vehicle: VehicleMatrices, loads: np.ndarray, entry: float) -> None:
        self.rail, self.entry = rail, entry
        self.alpha = rail.track.alpha
        self.nc = vehicle.contacts
        self.m, self.c, self.k = (
            np.asarray(x).real for x in (vehicle.mass, vehicle.damping, vehicle.stiffness)
        )
        self.r = self.m.shape[0]
        self.ni = self.r - self.nc
        self.nr = rail.size
        self.n = self.nr + self.ni
        self.offsets = np.asarray(vehicle.positions, float)
        self.loads = np.asarray(loads, float)
        self._shapes: tuple[float, list] = (math.nan, [])
        inner = slice(self.nc, self.r)
        self.base = [
            sp.block_diag([rail_matrix, sp.csc_matrix(vehicle_matrix[inner, inner])], format="csc")
            for rail_matrix, vehicle_matrix in zip(rail.matrices, (self.m, self.c, self.k))
        ]

    def shapes(self, tau: float) -> list[tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]]:
        """(unknowns, a, a', a'') of every wheel at ``tau`` (kept: a step asks three times)."""
        if self._shapes[0] != tau:
            shapes = [self.rail.contact_shapes(self.entry + self.alpha * tau + xi) for xi in self.offsets]
            self._shapes = (tau, shapes)
        return self._shapes[1]

    def low_rank(self, tau: float) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """``U`` (n x r) and the rows ``V_M, V_C, V_K`` (r x n) at ``tau`` (Eq. (S26))."""
        n, nc, nr, al = self.n, self.nc, self.nr, self.alpha
        u = np.zeros((n, self.r))
        vm, vc, vk = (np.zeros((self.r, n)) for _ in range(3))
        for j, (dofs, a, a1, a2) in enumerate(self.shapes(tau)):
            u[dofs, j] = a
            m, c, k = self.m[:, j : j + 1], self.c[:, j : j + 1], self.k[:, j : j + 1]
            vm[:, dofs] += m * a
            vc[:, dofs] += 2 * al * m * a1 + c * a
            vk[:, dofs] += al * al * m * a2 + al * c * a1 + k * a
        u[nr:, nc:] = np.eye(self.ni)
        for v, matrix in ((vm, self.m), (vc, self.c), (vk, self.k)):
            v[:, nr:] = matrix[:, nc:]
            v[nc:, nr:] = 0.0  # the internal block is in the sparse part
        return u, vm, vc, vk

    def force_vector(self, tau: float, loaded: bool) -> np.ndarray:
        """The static wheel loads on the rail, ``sum_c s_c a_c`` (zero for a free vibration)."""
        f = np.zeros(self.n)
        if loaded:
            for s, (dofs, a, _, _) in zip(self.loads, self.shapes(tau)):
                f[dofs] += s * a
        return f

    def vehicle_state(
        self, tau: float, z: np.ndarray, v: np.ndarray, acc: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray]:
        """(rail deflection under each wheel, contact force F_c = s_c - (M x'' + C x' + K x)_c)."""
        al, nr = self.alpha, self.nr
        x, dx, ddx = (np.empty(self.r) for _ in range(3))
        for j, (dofs, a, a1, a2) in enumerate(self.shapes(tau)):
            x[j] = a @ z[dofs]
            dx[j] = a @ v[dofs] + al * a1 @ z[dofs]
            ddx[j] = a @ acc[dofs] + 2 * al * a1 @ v[dofs] + al * al * a2 @ z[dofs]
        x[self.nc :], dx[self.nc :], ddx[self.nc :] = z[nr:], v[nr:], acc[nr:]
        rows = slice(0, self.nc)
        force = self.loads - (self.m[rows] @ ddx + self.c[rows] @ dx + self.k[rows] @ x)
        return x, force


def _woodbury(lu: object, u: np.ndarray, w: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """``(B + U W) x = rhs`` with ``B`` factorised (``lu.solve``), ``U`` n x r, ``W`` r x n (Hager 1989)."""
    both = lu.solve(np.column_stack([rhs, u]))  # type: ignore[attr-defined]
    y, bu = both[:, 0], both[:, 1:]
    capacitance = np.eye(u.shape[1]) + w @ bu
    return y - bu @ np.linalg.solve(capacitance, w @ y)


def simulate_sleeper_beam(
    rail: SleeperRail,
    vehicle: VehicleMatrices,
    loads: np.ndarray,
    *,
    entry: float,
    tau_max: float,
    dt: float,
    loaded: bool = True,
    every: int = 1,
    progress: Callable[[float], None] | None = None,
) -> BeamRun:
    """Step the vehicle over the finite rail from the static deflection under its loads at ``tau = 0``.

    ``loaded``: the loads stay on (the run tends to the steady response, docs/sleepers.md (S16)); False:
    they are removed at ``tau = 0`` and the run is the free vibration released from the static deflection.
    Output every ``every`` steps; ``progress`` is called with the fraction of steps done (100 times).
    """
    system = _Coupled(rail, vehicle, loads, entry)
    steps = int(np.ceil(tau_max / dt - 1e-9))
    h = tau_max / steps
    beta, gamma = AVERAGE_ACCELERATION.beta, AVERAGE_ACCELERATION.gamma
    mb, cb, kb = system.base
    u, vm, vc, vk = system.low_rank(0.0)
    z = _woodbury(splu(kb), u, vk, system.force_vector(0.0, True))  # the static deflection
    zero = np.zeros(system.n)
    acc0 = _woodbury(splu(mb), u, vm, system.force_vector(0.0, loaded) - kb @ z - u @ (vk @ z))
    state = NewmarkState(0.0, z, zero, acc0)
    lu = splu((mb + gamma * h * cb + beta * h * h * kb).tocsc())
    count = steps // every + 1
    tau = np.arange(count) * every * h
    deflection, force = np.empty((system.nc, count)), np.empty((system.nc, count))
    internal = np.empty((system.ni, count))
    start = time.perf_counter()
    for i in range(steps + 1):
        if i > 0:
            t = i * h
            u, vm, vc, vk = system.low_rank(t)
            zp = state.z + h * state.v + (h * h * (0.5 - beta)) * state.a
            vp = state.v + (h * (1 - gamma)) * state.a
            rhs = system.force_vector(t, loaded) - cb @ vp - kb @ zp - u @ (vc @ vp + vk @ zp)
            acc = _woodbury(lu, u, vm + gamma * h * vc + beta * h * h * vk, rhs)
            state = NewmarkState(t, zp + beta * h * h * acc, vp + gamma * h * acc, acc)
        if i % every == 0:
            x, f = system.vehicle_state(state.t, state.z, state.v, state.a)
            k = i // every
            deflection[:, k], force[:, k], internal[:, k] = x[: system.nc], f, x[system.nc :]
        if progress is not None and (i + 1) % max(1, steps // 100) == 0:
            progress((i + 1) / (steps + 1))
    return BeamRun(tau, deflection, force, internal, h, entry, time.perf_counter() - start)
