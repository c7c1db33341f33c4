"""Stability boundaries on an undamped (eta_f = 0) or near-undamped foundation (Sections 3.5, 3.8).

Convention. With eta_f = 0 the cut of K lies on the real q-axis for |Re q| >= q_c (the branch point); K
there is the limit from below (eta_f -> 0+ moves the cut up to Im q = eta_f, so the real axis lies below
it): :class:`~moving_bogie.kernels.sweep_characteristic.SweepCharacteristic` ``(below=True)``. An induced
frequency is unstable when Im q < 0; a real one is neutral (constant amplitude).

What degenerates. In the gap |Re q| < q_c, K is analytic and, with an undamped vehicle, E_chr (Eq. (38)) is
real on the real axis (exactly, factor 1). Real induced frequencies then fill whole regions of the
(alpha, theta) plane and the instability lines of :mod:`instability_lines` (E_chr = 0 with q real: two
equations) degenerate. Two different boundaries replace them:

* **eta_f = 0 exactly** ("undamped"): the number of roots with Im q < 0 changes where two real roots collide
  and leave the axis as a pair q, conj(q) (E = E_q = 0), where a root crosses the real axis on the cut
  (values from below, E complex there: an ordinary crossing), or where a real root reaches the branch
  point q_c.
* **the limit eta_f -> 0+** ("limit"): a real root q0 of the undamped problem moves to
  q0 - eta_f E_eta / E_q + O(eta_f^2) (E_eta = dE/deta_f; by E(q; -eta_f) = conj E(q; eta_f) on the
  gap it is imaginary there, E_q is real), so it becomes unstable, with growth rate proportional to eta_f,
  when Im(E_eta) / E_q > 0. Small foundation damping destabilises such roots (Case 5: Im q = -0.0091
  eta_f for eta_f -> 0, real at eta_f = 0). The limit count is the eta_f = 0 count plus these roots; for
  0 < eta_f < :data:`NEAR_UNDAMPED` it is the count at eta_f to first order in eta_f (roots there lie
  within ~eta_f of the real axis, too close for the ordinary methods).

Method (no continuation: the boundary is located by counts). At fixed alpha the eta_f = 0 count comes from
the argument principle on a whole column of theta values
(:func:`~moving_bogie.stability.maps.column.stability_column`, upper edge 1e-7 below the real axis, so real
roots count as neutral, sampled densely around every branch point of K on the axis); the real roots in the
gap are the sign changes of the real E_chr on samples ``q_step`` apart (finer where |E| dips), bisected,
and the sign of Im(E_eta) / E_q is read from E_chr at eta_f = :data:`DAMPING_PROBE` (Im E is odd in eta_f
on the gap). Every change of either count between grid values of theta is bisected to a tolerance and
named by its mechanism (:data:`MECHANISMS`); a pair of changes closer together than the grid step, or a
pair of real roots closer than ``q_step / 4096``, can be missed (stated in the outputs).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import numpy as np

from moving_bogie.kernels.bound import BoundModel
from moving_bogie.kernels.cut import cut_locus
from moving_bogie.kernels.sweep_characteristic import SweepCharacteristic
from moving_bogie.stability.maps.column import branch_points, branch_samples, exact, stability_column
from moving_bogie.stability.maps.column_count import horner_rows
from moving_bogie.typing import FloatArray

__all__ = [
    "CONVENTION",
    "DAMPING_PROBE",
    "NEAR_UNDAMPED",
    "MECHANISMS",
    "Boundary",
    "UndampedColumn",
    "UndampedCounter",
    "boundaries",
    "parameter_grid",
    "regime",
    "statement",
    "title",
    "uncertain_warning",
]

#: Below this eta_f (and above 0) the foundation is treated as near-undamped: the limit eta_f -> 0+.
NEAR_UNDAMPED = 1e-5
#: eta_f at which the sign of dIm q/deta_f of a real root is read.
DAMPING_PROBE = Fraction(1, 10**6)
#: Im q of the counting rectangle's upper edge at eta_f = 0 (just below the cut on the real axis).
TOP = -1e-7

CONVENTION = (
    "eta_f = 0: K on the cut (the real q-axis beyond the branch point q_c) is the limit from below "
    "(eta_f -> 0+); an induced frequency is unstable when Im q < 0, a real one is neutral"
)


def regime(eta_f: float | Fraction) -> str:
    """ "damped" (ordinary methods), "undamped" (eta_f = 0) or "near-undamped" (0 < eta_f < NEAR_UNDAMPED)."""
    eta_f = float(eta_f)
    if eta_f == 0:
        return "undamped"
    return "near-undamped" if eta_f < NEAR_UNDAMPED else "damped"


def parameter_grid(theta_max: float, points: int) -> np.ndarray:
    """``points`` even values up to theta_max, after 5 geometric ones from theta_max / 1000."""
    small = np.geomspace(1e-3, 1.0 / points, 6)[:-1]
    return theta_max * np.concatenate([small, np.linspace(1.0, points, points) / points])


def uncertain_warning(where: str, unsure: dict[float, int], margin: float) -> list[str]:
    """One warning for the counts not certified, ``unsure`` = {alpha: number}; empty when there are none."""
    unsure = {a: n for a, n in unsure.items() if n}
    if not unsure:
        return []
    return [
        f"{where}{sum(unsure.values())} count(s) at {len(unsure)} velocities (alpha {min(unsure):.4g} to "
        f"{max(unsure):.4g}) not certified: an unstable root within {max(1e-7, margin):.0e} of the real axis "
        "is not resolved there, so a boundary nearby may be misplaced or missing"
    ]


def statement(eta_f: float | Fraction) -> str:
    """What the stability lines of a foundation with this eta_f are, in one sentence ("" when damped)."""
    if regime(eta_f) == "undamped":
        return (
            "eta_f = 0: real induced frequencies fill whole regions, so instability lines degenerate; lines "
            "shown are boundaries of instability at eta_f = 0 exactly (kind 'undamped') and in the limit "
            "eta_f -> 0+ (kind 'limit'); convention: " + CONVENTION
        )
    if regime(eta_f) == "near-undamped":
        return (
            f"eta_f = {float(eta_f):g} is near-undamped: lines shown are the boundaries of instability in "
            "the limit eta_f -> 0+ (kind 'limit', first order in eta_f); convention: " + CONVENTION
        )
    return ""


def title(eta_f: float | Fraction) -> str:
    """Two-line figure title saying what is drawn for an undamped or near-undamped foundation."""
    if regime(eta_f) == "undamped":
        return (
            "eta_f = 0: instability lines degenerate; shown: boundaries of instability at eta_f = 0\n"
            "and in the limit eta_f -> 0+ (K on the cut from below; real roots neutral)"
        )
    return (
        f"eta_f = {float(eta_f):g} (near-undamped): boundaries of instability in the limit\n"
        "eta_f -> 0+ (first order in eta_f; K on the cut from below)"
    )


@dataclass(frozen=True)
class UndampedColumn:
    """Counts at one alpha: ``undamped`` (eta_f = 0), ``limit`` (eta_f -> 0+), ``real`` (real gap roots)."""

    alpha: float
    thetas: np.ndarray
    undamped: np.ndarray
    limit: np.ndarray
    real: np.ndarray
    uncertain: np.ndarray


class UndampedCounter:
    """Exact and limit counts of unstable induced frequencies along columns of theta (module text).

    Parameters
    ----------
    bound : BoundModel
        Its eta_f is ignored (set to 0); the vehicle is that of its model.
    parameter : str, optional
        The swept vehicle parameter (eta_M, kappa_v or eta_v; default the wheel mass,
        ``Model.wheel_mass``).
    q_step : float
        Sampling of the gap 0 < q < q_c for real roots.
    margin : float
        A count with an unstable root less than ``margin`` below the real axis is flagged uncertain (for a
        near-undamped eta_f: such a root may lie on either side at that eta_f, e.g. next to a branch point).
    """

    def __init__(
        self, bound: BoundModel, parameter: str | None = None, *, q_step: float = 0.002, margin: float = 0.0
    ) -> None:
        self.margin = float(margin)
        self.bound = bound.replace(eta_f=0)
        self.params = self.bound.params
        parameter = parameter or self.params.model.wheel_mass
        self.parameter = parameter
        self.q_step = float(q_step)
        self.sweep = SweepCharacteristic(self.bound, parameter, below=True)
        self.probe = SweepCharacteristic(self.bound.replace(eta_f=DAMPING_PROBE), parameter)
        self._cuts: dict[float, tuple[float, list[float]]] = {}

    def gap_end(self, alpha: float) -> float:
        """q_c: the branch point, where the cut (on the real axis) begins; 0 when there is no gap."""
        return self._cut(alpha)[0]

    def _cut(self, alpha: float) -> tuple[float, list[float]]:
        """(q_c, branch points with Re q > 0) of the cut at eta_f = 0 (all on the real axis)."""
        alpha = float(alpha)
        if alpha not in self._cuts:
            x = cut_locus(self.bound.replace(alpha=exact(alpha)), 0.0, 4.0, samples=801).x_start
            qc = float(x) if np.isfinite(x) and x > 0 else 0.0
            self._cuts[alpha] = (qc, branch_points(self.bound, alpha))
        return self._cuts[alpha]

    def real_roots(self, alpha: float, thetas: FloatArray) -> tuple[np.ndarray, FloatArray, np.ndarray]:
        """Real roots in the gap: (row index, q, destabilised by small eta_f), one entry per root.

        Sign changes of the real E_chr on samples ``q_step`` apart; where |E| has a local minimum without
        a sign change (two roots may hide between samples) the two neighbouring intervals are sampled 64
        times finer, twice (pairs closer than ``q_step / 4096`` stay unseen). Each bracket is bisected.
        """
        qc = self.gap_end(alpha)
        n = int(np.ceil(qc / self.q_step))
        empty = (np.zeros(0, dtype=int), np.zeros(0), np.zeros(0, dtype=bool))
        if n < 3:
            return empty
        qs = np.linspace(0.0, qc, n + 1)[1:-1]
        scale = float(np.max(thetas))
        K, _, _ = self.sweep.kernel(qs, alpha)
        E = horner_rows(self.sweep.coefficients(qs, K, scale=scale), (thetas / scale)[:, None])
        with np.errstate(all="ignore"):
            real_rows = np.max(np.abs(E.imag) / np.abs(E), axis=1) < 1e-8  # an undamped vehicle
        Q = np.broadcast_to(qs, E.shape)
        rows, lo, hi, dips = _scan(np.arange(len(thetas))[real_rows], Q[real_rows], E.real[real_rows])
        for _ in range(2):
            if not dips[0].size:
                break
            r, a, b = dips
            Q = a[:, None] + (b - a)[:, None] * np.linspace(0.0, 1.0, 65)[None, :]
            R = self._real(Q, alpha, np.broadcast_to(thetas[r][:, None], Q.shape))
            r2, lo2, hi2, dips = _scan(r, Q, R)
            rows, lo, hi = np.concatenate([rows, r2]), np.concatenate([lo, lo2]), np.concatenate([hi, hi2])
        if not rows.size:
            return empty
        th = thetas[rows]
        f_lo = self._real(lo, alpha, th)
        for _ in range(44):
            mid = 0.5 * (lo + hi)
            f_mid = self._real(mid, alpha, th)
            same = np.sign(f_mid) == np.sign(f_lo)
            lo, f_lo, hi = np.where(same, mid, lo), np.where(same, f_mid, f_lo), np.where(same, hi, mid)
        q = (0.5 * (lo + hi)).astype(complex)
        a = np.full(len(q), alpha)
        _, E_q = self.sweep.e_and_dq(q, a, th)
        E_probe = self.probe(q, a, th)
        return rows, q.real, (E_probe.imag * E_q.real) > 0

    def _real(self, q: FloatArray, alpha: float, theta: FloatArray) -> FloatArray:
        """The real E_chr at real points q of the gap, with theta per point."""
        q = np.asarray(q, dtype=float)
        return self.sweep(q.astype(complex).ravel(), np.full(q.size, alpha), np.ravel(theta)).real.reshape(
            q.shape
        )

    def __call__(self, alpha: float, thetas: Sequence[float] | FloatArray) -> UndampedColumn:
        thetas = np.asarray(thetas, dtype=float)
        extra = branch_samples(self._cut(alpha)[1])
        col = stability_column(self.sweep, alpha, thetas, top=TOP, extra=extra)
        rows, _, unstable = self.real_roots(alpha, thetas)
        real = np.bincount(rows, minlength=len(thetas))
        limit = col.count + np.bincount(rows[unstable], minlength=len(thetas))
        shallow = np.array([bool(len(r)) and float(np.max(r.imag)) > -self.margin for r in col.roots])
        return UndampedColumn(float(alpha), thetas, col.count.copy(), limit, real, col.uncertain | shallow)


@dataclass(frozen=True)
class Boundary:
    """A value of theta at one alpha where a count changes: ``kind`` "undamped" (eta_f = 0) or "limit"
    (eta_f -> 0+), the counts just below and above (bisection bracket ``low``..``high``), and what happens
    there (``mechanism``, a key of :data:`MECHANISMS`)."""

    kind: str
    alpha: float
    theta: float
    low: float
    high: float
    count_below: int
    count_above: int
    mechanism: str = ""


#: What changes at a boundary, read from the counts at the two ends of its bracket.
MECHANISMS = {
    "collision": "two real induced frequencies meet and leave the real axis as a pair q, conj(q)",
    "crossing": "an induced frequency crosses the real axis (on the cut of K, values from below; or in the "
    "gap, where E_chr is complex with a damped vehicle)",
    "branch point": "a real induced frequency reaches a branch point of K",
    "damping sign": "a real induced frequency changes the sign of dIm q/deta_f (stable or unstable for "
    "small eta_f > 0)",
    "mixed": "several of these at once (within the bisection tolerance)",
}


def _mechanism(kind: str, d_real: int, d_undamped: int) -> str:
    """The mechanism of a boundary from the changes of the real-root and eta_f = 0 counts across it."""
    if kind == "limit" and d_undamped == 0:
        return "damping sign" if d_real == 0 else ("collision" if abs(d_real) == 2 else "mixed")
    if d_real == 0:
        return "crossing"
    if abs(d_real) == 2 and 2 * d_undamped == -d_real:
        return "collision"
    return "branch point" if abs(d_real) == 1 else "mixed"


def boundaries(
    counter: UndampedCounter, alpha: float, grid: Sequence[float] | FloatArray, *, tol: float
) -> tuple[list[Boundary], UndampedColumn, int]:
    """Every change of the eta_f = 0 and of the limit count along ``grid`` (values of theta), to ``tol``.

    Returns ``(boundaries, column, unsure)``: the :class:`Boundary` list sorted by kind and theta, the counts
    on the grid, and how many counts (grid and bisection) were not certified.
    """
    grid = np.asarray(grid, dtype=float)
    col = counter(alpha, grid)
    unsure = int(np.sum(col.uncertain))
    brackets: list[list[Any]] = []  # [kind, theta below, theta above, count below, count above], narrowed
    for kind in ("undamped", "limit"):
        c = getattr(col, kind)
        for i in np.nonzero(c[:-1] != c[1:])[0]:
            brackets.append([kind, grid[i], grid[i + 1], int(c[i]), int(c[i + 1])])
    while brackets and max(b[2] - b[1] for b in brackets) > tol:
        mids = np.array([0.5 * (b[1] + b[2]) for b in brackets])
        mid = counter(alpha, mids)
        unsure += int(np.sum(mid.uncertain))
        for k, b in enumerate(brackets):
            if b[2] - b[1] <= tol:
                continue
            n = int(getattr(mid, b[0])[k])
            if n == b[3]:
                b[1] = mids[k]
            else:
                b[2], b[4] = mids[k], n
    out: list[Boundary] = []
    if brackets:
        ends = counter(alpha, np.array([b[1] for b in brackets] + [b[2] for b in brackets]))
        m = len(brackets)
        d_real = ends.real[m:] - ends.real[:m]
        d_undamped = ends.undamped[m:] - ends.undamped[:m]
        out = [
            Boundary(k, float(alpha), 0.5 * (lo + hi), float(lo), float(hi), n0, n1, _mechanism(k, dr, du))
            for (k, lo, hi, n0, n1), dr, du in zip(brackets, d_real, d_undamped)
        ]
    out.sort(key=lambda b: (b.kind, b.theta))
    return out, col, unsure


def _scan(
    rows: np.ndarray, Q: FloatArray, R: FloatArray
) -> tuple[np.ndarray, FloatArray, FloatArray, tuple[np.ndarray, FloatArray, FloatArray]]:
    """Sign changes of R along each row of Q (brackets) and local minima of |R| without one (dips).

    Returns ``(rows, lo, hi, (dip rows, dip start, dip end))``, a dip spanning the two intervals around
    the minimum.
    """
    r, i = np.nonzero(np.sign(R[:, :-1]) * np.sign(R[:, 1:]) < 0)
    A, S = np.abs(R), np.sign(R)
    dip = (
        (A[:, 1:-1] < A[:, :-2])
        & (A[:, 1:-1] < A[:, 2:])
        & (S[:, :-2] == S[:, 1:-1])
        & (S[:, 2:] == S[:, 1:-1])
    )
    dr, di = np.nonzero(dip)
    return rows[r], Q[r, i], Q[r, i + 1], (rows[dr], Q[dr, di], Q[dr, di + 2])
