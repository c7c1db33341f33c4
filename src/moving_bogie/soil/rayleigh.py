"""The surface-wave (Rayleigh) modes of the elastic layered half-space: phase velocity c(omega) per mode.

A mode is a real pole of U(k, omega) with k = omega / c and c below the shear speed of the half-space (a
trapped wave): a zero of the secular determinant of the undamped profile, which has no poles (1 / U and
det K of the surface stiffness have poles of their own, and a pole beside a mode within one grid step hides
it). Each frequency's interval of c, from ``c_floor`` times the least shear speed to the half-space's shear
speed, is scanned on a grid that breaks at every layer's wave speeds; every sign change is refined, all
frequencies at once. Modes are numbered from the slowest (the fundamental, mode 0) at each frequency. Two
modes closer than one grid step in c are not separated: ``points`` sets the grid.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from moving_bogie.typing import FloatArray

from .flexibility import condensed
from .illinois import IntArray, illinois
from .profile import SoilProfile

BoolArray = npt.NDArray[np.bool_]

__all__ = ["SoilModes", "secular", "soil_modes"]


@dataclass(frozen=True)
class SoilModes:
    """Phase velocities ``c[i, j]`` (m/s) of mode j at ``omega[i]`` (rad/s); NaN above a mode's count."""

    omega: FloatArray
    c: FloatArray

    def mode(self, j: int) -> tuple[FloatArray, FloatArray]:
        """(omega, c) where mode j exists."""
        if j >= self.c.shape[1]:
            return np.empty(0), np.empty(0)
        ok = np.isfinite(self.c[:, j])
        return self.omega[ok], self.c[ok, j]

    def to_list(self, modes: int | None = None) -> list[dict[str, object]]:
        """``[{"mode": j, "omega": [...], "c": [...]}, ...]`` in rad/s and m/s."""
        count = self.c.shape[1] if modes is None else min(modes, self.c.shape[1])
        out: list[dict[str, object]] = []
        for j in range(count):
            w, c = self.mode(j)
            out.append({"mode": j, "omega": w.tolist(), "c": c.tolist()})
        return out


def secular(c: FloatArray, omega: FloatArray, soil: SoilProfile) -> FloatArray:
    """The secular determinant at k = omega / c (:func:`~.flexibility.condensed`) projected on its axis:
    real, with no poles, changing sign at each mode (and possibly at a layer's wave speed)."""
    value = condensed(np.asarray(omega / c, dtype=complex), np.asarray(omega, dtype=complex), soil)[1]
    return np.real(value) + np.imag(value)


def _regime_grid(soil: SoilProfile, c_floor: float, points: int) -> tuple[FloatArray, BoolArray]:
    """The c grid and a mask of its cells that hold no wave speed of a layer (where the axis of
    :func:`secular` may turn: a sign change there is no mode)."""
    low, top = c_floor * soil.c_s_min, soil.halfspace.c_s * (1 - 1e-9)
    speeds = np.array([c for layer in soil.layers[:-1] for c in (layer.c_s, layer.c_p) if low < c < top])
    grid = np.unique(
        np.concatenate([np.linspace(low, top, points), speeds * (1 - 1e-9), speeds * (1 + 1e-9)])
    )
    crossing = np.zeros(len(grid) - 1, dtype=bool)
    for c in speeds:
        crossing |= (grid[:-1] < c) & (grid[1:] > c)
    return grid, ~crossing


def _dips(
    grid: FloatArray, f: FloatArray, valid: BoolArray, omega: FloatArray, soil: SoilProfile, sub: int = 24
) -> list[tuple[IntArray, FloatArray, FloatArray]]:
    """Brackets of the pairs of modes that fall between two grid points: where |f| has a local minimum with
    no sign change, the two cells around it are sampled ``sub`` times finer (f has no poles, so two close
    zeros show as such a dip). Returns (rows, lo, hi) of the sign changes found there."""
    same = (np.sign(f[:, :-2]) == np.sign(f[:, 1:-1])) & (np.sign(f[:, 1:-1]) == np.sign(f[:, 2:]))
    dip = same & (np.abs(f[:, 1:-1]) < np.abs(f[:, :-2])) & (np.abs(f[:, 1:-1]) < np.abs(f[:, 2:]))
    dip &= valid[:-1] & valid[1:]
    rows, cols = np.nonzero(dip)
    if rows.size == 0:
        return []
    fine = grid[cols, None] + (grid[cols + 2] - grid[cols])[:, None] * np.linspace(0, 1, 2 * sub + 1)
    g = secular(fine, omega[rows, None], soil)
    r, j = np.nonzero(np.sign(g[:, :-1]) * np.sign(g[:, 1:]) < 0)
    return [(rows[r], fine[r, j], fine[r, j + 1])]


def soil_modes(
    omega: FloatArray, soil: SoilProfile, *, points: int = 200, c_floor: float = 0.5, modes: int | None = None
) -> SoilModes:
    """The trapped surface-wave modes of the undamped ``soil`` at each positive ``omega`` (rad/s).

    The secular function has no poles (:func:`~.flexibility.condensed`), so each sign change on the grid is
    a mode, and two modes within one grid step show as a dip of |f| without a sign change, which is
    sampled finer (:func:`_dips`).

    Parameters
    ----------
    points : int
        Grid points in c per frequency.
    c_floor : float
        The scan starts at ``c_floor`` times the least shear speed (every mode is faster than 0.87 times
        it for nu >= 0; 0.5 leaves room for any admissible nu).
    modes : int, optional
        Refine only the slowest ``modes`` modes at each frequency (all by default).
    """
    elastic = soil.undamped()
    omega = np.atleast_1d(np.asarray(omega, dtype=float))
    grid, valid = _regime_grid(elastic, c_floor, points)
    f = secular(grid[None, :], omega[:, None], elastic)
    change = (np.sign(f[:, :-1]) * np.sign(f[:, 1:]) < 0) & valid
    rows, cols = np.nonzero(change)
    lo, hi = [grid[cols]], [grid[cols + 1]]
    rows_all: list[IntArray] = [rows]
    for row, a, b in _dips(grid, f, valid, omega, elastic):
        rows_all.append(row)
        lo.append(a)
        hi.append(b)
    rows = np.concatenate(rows_all)
    if modes is not None:  # the slowest brackets of each frequency (lo ascends within a row)
        order = np.lexsort((np.concatenate(lo), rows))
        rank = np.arange(order.size) - np.searchsorted(rows[order], rows[order])
        keep = np.sort(order[rank < modes])
        rows, lo, hi = rows[keep], [np.concatenate(lo)[keep]], [np.concatenate(hi)[keep]]
    w_rows = omega[rows]
    roots = illinois(lambda c, i: secular(c, w_rows[i], elastic), np.concatenate(lo), np.concatenate(hi))
    count = np.bincount(rows, minlength=len(omega))
    c = np.full((len(omega), max(int(count.max(initial=0)), 1)), np.nan)
    for i in range(len(omega)):
        found = np.sort(roots[rows == i])
        c[i, : len(found)] = found
    return SoilModes(omega=omega, c=c)
