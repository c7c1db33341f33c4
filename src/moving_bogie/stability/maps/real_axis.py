"""D-decomposition in the wheel mass along the real axis of a track given by its receptance (Eq. (48)).

A track whose kernel has the one harmonic 0 (a continuous track, the rail on the soil of docs/soil.md)
gives E_chr(q) = det A(q) of the vehicle-rail coupling (:mod:`moving_bogie.kernels.coupling`) with its
receptance G(q) (:meth:`~moving_bogie.kernels.track_model.Track.receptance`). The vehicle's dynamic
stiffness is affine in the wheel mass group eta_M (it enters the mass matrix only), and A is affine in it,
so at every q

    A(q; eta_M) = A_0(q) + eta_M B(q),     mu = 1 / eta_M = eig(-A_0^{-1} B)

as on sleepers (:mod:`~moving_bogie.kernels.mass_pencil`, Eq. (S19)), from one receptance. A root q(eta_M)
changes side of the real axis only where eta_M(q) is real for a real q: the D-curve M(Omega) of the
D-decomposition. The real axis 0 < q <= q_max is sampled (the roots come in pairs q, -conj(q), so the
count in Re q >= 0 is that of q > 0), the eigenvalues are matched from sample to sample, and every sign
change of Im mu with Re mu > 0 is polished by Brent's method
(:func:`~moving_bogie.stability.maps.d_lines.real_crossings`). The rule of hatching of d_lines gives the
direction: the unstable count grows by one as eta_M increases through the crossing when Im mu falls
through 0 as q increases (eta_M(q) analytic at the crossing: G is analytic across the real axis away from
its branch points).

**q = 0** is a branch point of the soil's kernel (its cut when the soil's waves are faster than the load,
docs/soil.md), and no crossing happens there at a finite mass: the wheel mass enters D as -q^2 M, so
B(0) = 0 and mu(0) = 0 (eta_M = infinity). The samples are the midpoints of equal cells of (0, q_max];
a crossing at a mass above ``eta_max`` is not reported, and one at q > q_max is not searched
(:func:`window_column` takes q_max beyond every real root of the masses of its axis: beyond the far-field
radius of the window search, where the rail's bending decides E_chr, :mod:`~.quadrature_window`).

**Accuracy.** The scan runs at the receptance's relative tolerance SCAN_TOL (only the signs of Im mu are
used), the polishing at the track's own; ``moved`` of each crossing is the relative change of eta_M when
the receptance is computed 100 times more accurately there (0 for a track of closed-form receptance).
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from moving_bogie.errors import ParameterError
from moving_bogie.roots.quadrature_window import QuadratureCharacteristic, grown_radius, window_radius
from moving_bogie.stability.maps.d_lines import DCrossing, match_branches, real_crossings, signed_counts

if TYPE_CHECKING:
    from moving_bogie.kernels.bound import BoundModel

__all__ = ["ReceptancePencil", "RealAxisColumn", "real_axis_column", "window_column"]

#: The receptance's relative tolerance along the scan (signs of Im mu only).
SCAN_TOL = 1e-4
#: The relative change of eta_M with a 100 times tighter receptance called converged.
MOVE_TOL = 1e-3
#: The note of a branch with Re mu > 0 and Im mu > 0 at q_max: Im mu must still fall through 0 (a crossing
#: that makes a root grow) beyond the scan, at a lighter mass than its range holds.
_BEYOND = "Im(1 / eta_M) > 0 at the top of the scan: a crossing lies beyond it (at a lighter mass)"


class ReceptancePencil:
    """A(q) + eta_M B(q) of ``bound``'s vehicle on its track (module docstring); ``evaluations`` counts the
    values of q at which the receptance was computed.

    Raises
    ------
    ParameterError
        When the vehicle has no wheel mass, or its coupling is not affine in it (naming ``vehicle``).
    """

    def __init__(self, bound: BoundModel) -> None:
        name = bound.model.wheel_mass
        if name not in bound.params.to_dict():
            raise ParameterError("vehicle", f"vehicle {bound.model.vehicle!r} has no wheel mass")
        self.bound = bound
        self.chr = QuadratureCharacteristic(bound)
        self._at = [QuadratureCharacteristic(bound.replace(**{name: x})) for x in (1, 2, 3)]
        self.evaluations = 0
        q = np.array([0.3 - 0.1j])
        n = self.chr.contacts
        G = np.broadcast_to(np.eye(n, dtype=complex), (1, n, n))
        A1, A2, A3 = (E.system(q, G) for E in self._at)
        if not np.allclose(A3 - 2 * A2 + A1, 0, atol=1e-12 * float(np.abs(A3).max())):
            raise ParameterError("vehicle", f"the coupling is not affine in the wheel mass {name}")

    @contextmanager
    def tolerance(self, tol: float | None) -> Iterator[None]:
        """The receptance at relative tolerance ``tol`` inside the block (None: the track's own)."""
        with self.chr.tolerance(tol):
            yield

    def matrices(self, qs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(A_0, B) at every q of ``qs`` from one receptance call (Eq. (S19)'s pencil, harmonic 0)."""
        qs = np.asarray(qs, dtype=complex)
        G = self.bound.track.receptance(qs).matrix
        self.evaluations += qs.size
        A1, A2 = (E.system(qs, G) for E in self._at[:2])
        return A1 - (A2 - A1), A2 - A1

    def inverse_masses_many(self, qs: np.ndarray) -> np.ndarray:
        """mu = 1 / eta_M at every q (rows), unordered within a row."""
        A0, B = self.matrices(qs)
        return np.linalg.eigvals(-np.linalg.solve(A0, B))

    def inverse_masses(self, q: float) -> np.ndarray:
        """mu = 1 / eta_M for every eta_M that makes E_chr vanish at the one q."""
        return self.inverse_masses_many(np.array([q]))[0]


@dataclass(frozen=True)
class RealAxisColumn:
    """The crossings at one velocity (sorted by eta_M) on 0 < q <= q_max, and what limits the count."""

    alpha: float
    q_max: float
    crossings: tuple[DCrossing, ...]
    samples: int
    evaluations: int
    notes: tuple[str, ...] = field(default=())

    def counts(self, etas: np.ndarray | list[float]) -> np.ndarray:
        """Unstable roots (Re q >= 0) at each eta_M: none at eta_M -> 0, plus the signed crossings below."""
        return signed_counts(self.crossings, etas)

    @property
    def threshold(self) -> DCrossing | None:
        """The crossing at the smallest eta_M beyond which a root has Im q < 0 (None: stable up to
        eta_max)."""
        for c in self.crossings:
            if self.counts([c.eta_M * (1 + 1e-9)])[0] > 0:
                return c
        return None


def _moved(pencil: ReceptancePencil, q: float, mu: complex) -> float:
    """The relative change of eta_M at the crossing (q, mu) with a receptance 100 times tighter."""
    tight = getattr(pencil.bound.track, "tol", None)
    if tight is None:
        return 0.0
    with pencil.tolerance(tight / 100):
        mus = pencil.inverse_masses(q)
    near = complex(mus[np.argmin(np.abs(mus - mu))])
    return float(abs(1 / near.real - 1 / mu.real) * mu.real)


def real_axis_column(
    bound: BoundModel,
    *,
    q_max: float,
    eta_max: float,
    samples: int = 48,
    progress: Callable[[float], None] | None = None,
) -> RealAxisColumn:
    """Every real crossing with 0 < eta_M <= eta_max and 0 < q <= q_max at ``bound``'s velocity (module
    docstring)."""
    if samples < 4:
        raise ValueError("samples: at least 4")
    pencil = ReceptancePencil(bound)
    qs = (np.arange(samples) + 0.5) * q_max / samples
    with pencil.tolerance(SCAN_TOL):
        mus = pencil.inverse_masses_many(qs)
    for k in range(1, samples):
        mus[k] = match_branches(mus[k - 1], mus[k])
    if progress is not None:
        progress(0.5)
    top = mus[-1]
    beyond = [] if not np.any((top.real > 0) & (top.imag > 0)) else [_BEYOND]
    with pencil.tolerance(None):
        hits, notes = real_crossings(pencil, qs, mus, eta_max)
    notes = beyond + notes
    found = [DCrossing(q, float(1 / mu.real), change, _moved(pencil, q, mu)) for q, mu, change, _, _ in hits]
    found.sort(key=lambda c: c.eta_M)
    worst = max((c.moved for c in found), default=0.0)
    if not worst < MOVE_TOL:
        notes.append(f"a receptance 100 times more accurate moves eta_M by {worst:.2g} (relative)")
    if np.cumsum([c.change for c in found]).min(initial=0) < 0:
        notes.append("the signed crossings give a negative count: a crossing is missing")
    if progress is not None:
        progress(1.0)
    alpha = float(bound.floats.alpha)
    return RealAxisColumn(alpha, q_max, tuple(found), samples, pencil.evaluations, tuple(notes))


def window_column(
    bound: BoundModel,
    *,
    equivalent: BoundModel,
    eta_max: float,
    eta_min: float,
    samples: int = 64,
    progress: Callable[[float], None] | None = None,
) -> RealAxisColumn:
    """:func:`real_axis_column` up to the radius S beyond which no real root exists at any wheel mass of
    [eta_min, eta_max]: the largest far-field radius of ``equivalent`` (the same parameters on the
    continuous track of their k_f) at masses spaced by factors of 2 over that range (it grows as the mass
    falls: a lighter mass vibrates faster), grown until the track's own E_chr at eta_min is within 1/2 of
    E_lead on the window's far edges (:mod:`~moving_bogie.roots.quadrature_window`). A crossing at a mass
    below eta_min is not searched (module docstring: the count starts from none at eta_M -> 0).
    ``samples`` is the number of samples over the radius of eta_max; the scan keeps their density up to S."""
    from fractions import Fraction

    name = bound.model.wheel_mass
    steps = max(1, int(np.ceil(np.log2(eta_max / eta_min))))
    radii = []
    for eta in np.geomspace(eta_min, eta_max, steps + 1):
        value = Fraction(float(eta)).limit_denominator(10**9)
        r, far = window_radius(equivalent.replace(**{name: value}))
        if far.radius is None:
            raise ParameterError("vehicle", f"no far field of the Winkler equivalent at {name} = {eta:.6g}")
        radii.append(r)
    light = bound.replace(**{name: Fraction(float(eta_min)).limit_denominator(10**9)})
    radius = grown_radius(QuadratureCharacteristic(light), max(radii))
    count = int(np.ceil(samples * radius / radii[-1]))  # the density of ``samples`` over eta_max's radius
    return real_axis_column(bound, q_max=radius, eta_max=eta_max, samples=count, progress=progress)
