"""Every induced frequency with Im q <= 0 of a track whose receptance is a quadrature (Eq. (48)).

The characteristic function is that of every track, E_chr(q) = det A(q) of the vehicle-rail coupling
(:mod:`moving_bogie.kernels.coupling`) with the track's receptance G(q)
(:meth:`~moving_bogie.kernels.track_model.Track.receptance`), evaluated on arrays of q (one quadrature serves
every q of a call). Such a track (a rail on the soil, docs/soil.md) has G analytic for Im q < 0 and
continuous up to the real axis, its branch points and cuts in Im q >= 0, so the roots that grow are
counted in the window

    -S / 1000 <= Re q <= S,    -S <= Im q <= 0

(the roots come in pairs q, -conj(q)) by the argument principle with no starting guesses
(:func:`~moving_bogie.roots.count.contour.winding_number`: the boundary sampled until every step of
arg E_chr is below pi / 5). S is the far-field radius of the track's continuous equivalent (the same
parameters on the Winkler track of their k_f, :func:`window_radius`), beyond which the rail's bending
and the vehicle's masses decide E_chr on both tracks alike (E_lead of
:mod:`~moving_bogie.roots.count.far_field`), doubled (up to three times) until the track's own E_chr has
rho = |E_chr - E_lead| / |E_lead| <= 1/2 at five points of the window's far edges; rho is checked again
on every sample of the far edges after the count, and above 1/2 the verdict says FAR_FIELD.

Locating: the same boundary samples give the moments s_p = (1 / 2 pi i) oint q^p d log E_chr = sum of the
roots' p-th powers (Delves & Lyness 1967); for n <= 3 roots in a region they are the coefficients of the
polynomial whose zeros start the secant method. A region whose polished roots are not n distinct points
inside it is bisected and its halves counted. The roots with Im q > 0 (decaying) are searched on a track
on the soil in the band under the singular lines of the integral along real k
(:mod:`~moving_bogie.roots.decaying_band`), with the same count and locating; elsewhere they are not.

Errors: the receptance's error e moves E_chr by at most delta E = sum_ij |dE_chr / dG_ij| e, and a root by
delta q = delta E / |E_chr'(q)|; the decimals printed are those delta q leaves, and a root with
|Im q| <= delta q is neither stable nor unstable (a note of reason QUADRATURE: UNDETERMINED). The count
stands when delta E <= |E_chr| / 2 at every sample of the boundary (the winding number is then that of the
exact values); otherwise the boundary is counted again at the track's own tolerance, and if it still
fails, a note of reason QUADRATURE makes the verdict UNDETERMINED.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import mpmath
import numpy as np

from moving_bogie.kernels.arithmetic import Batched
from moving_bogie.kernels.coupling import coupled_system, dynamic_coefficients, dynamic_stiffness
from moving_bogie.roots.count.contour import EdgeZeroError, Rectangle, winding_number
from moving_bogie.roots.count.far_field import MARGIN, FarField, e_lead, far_field_radius
from moving_bogie.roots.count.window import default_window
from moving_bogie.roots.frequency_result import InducedFrequency

if TYPE_CHECKING:
    from moving_bogie.kernels.bound import BoundModel
    from moving_bogie.typing import ComplexArray

__all__ = [
    "QuadratureCharacteristic",
    "count_rectangle",
    "far_check",
    "grown_radius",
    "induced",
    "locate",
    "window_radius",
]

#: Initial boundary samples per side of a region; Delves-Lyness up to this many roots, else bisection.
SAMPLES, MOMENTS = 8, 3
#: The receptance's relative tolerance while counting and starting the roots (a track with a ``tol``): the
#: winding number needs the phase of E_chr only, which an error of 1e-3 moves by 1e-3 rad where |E_chr| is
#: not within 1e-3 of zero (the sampling refines where arg E_chr turns fast); the roots are polished at the
#: track's own tolerance.
COUNT_TOL = 1e-3
#: The first far-field radius tried (doubled until the far field holds), and the smallest window.
FIRST_RADIUS = 0.25
#: Secant iterations, and bisection levels of a region, at most.
SECANT_STEPS, LEVELS = 40, 8


@dataclass
class QuadratureCharacteristic:
    """E_chr(q) = det A(q) on arrays of q, with the track's receptance; every evaluation recorded."""

    bound: BoundModel
    samples: dict[complex, complex] = field(default_factory=dict)
    #: delta E of each sample: the receptance's error carried through E_chr (module docstring)
    bounds: dict[complex, float] = field(default_factory=dict)

    def __post_init__(self) -> None:
        system = self.bound.float_system
        floats = tuple(np.array(A, dtype=float) for A in system.matrices)
        self._dynamic = dynamic_coefficients(floats, Batched)
        self.contacts = system.contacts
        self.tight = getattr(self.bound.track, "tol", None)

    @contextmanager
    def tolerance(self, tol: float | None) -> Iterator[None]:
        """Evaluate at the receptance's relative tolerance ``tol`` inside the block (a track with a
        ``tol`` attribute; None: the track's own)."""
        track = self.bound.track
        if self.tight is None:
            yield
            return
        kept = track.tol  # type: ignore[attr-defined]
        track.tol = self.tight if tol is None else tol  # type: ignore[attr-defined]
        try:
            yield
        finally:
            track.tol = kept  # type: ignore[attr-defined]

    def system(self, q: ComplexArray, G: ComplexArray) -> ComplexArray:
        """A(q) of the coupling for the receptance matrices ``G``."""
        D, _ = dynamic_stiffness(q, self._dynamic, Batched)
        A: ComplexArray = coupled_system(D, G, Batched).A
        return A

    def __call__(self, q: ComplexArray) -> ComplexArray:
        q = np.asarray(q, dtype=complex)
        rec = self.bound.track.receptance(q)
        E: ComplexArray = np.linalg.det(self.system(q, rec.matrix))
        delta = rec.error * self.sensitivity(q, rec.matrix, E) if rec.error else np.zeros(q.shape)
        self.samples.update(zip(q.ravel().tolist(), E.ravel().tolist(), strict=True))
        self.bounds.update(zip(q.ravel().tolist(), np.ravel(delta).tolist(), strict=True))
        return E

    def sensitivity(self, q: ComplexArray, G: ComplexArray, E: ComplexArray) -> np.ndarray:
        """sum_ij |dE_chr / dG_ij| at each q (forward differences of relative step 1e-6 in each entry)."""
        n = self.contacts
        h = 1e-6 * np.maximum(np.abs(G).max(axis=(-2, -1)), 1e-300)
        change = np.zeros(q.shape)
        for i in range(n):
            for j in range(n):
                Gp = G.copy()
                Gp[..., i, j] += h
                change += np.abs(np.linalg.det(self.system(q, Gp)) - E) / h
        return change

    def uncertainty(self, q: complex, slope: complex) -> float:
        """delta q of a root at ``q`` (module docstring); ``slope`` ~ E_chr'(q)."""
        z = np.array([q])
        rec = self.bound.track.receptance(z)
        base = np.linalg.det(self.system(z, rec.matrix))
        change = float(self.sensitivity(z, rec.matrix, base)[0])
        return change * rec.error / max(abs(slope), 1e-300)

    def resolved(self, rect: Rectangle) -> bool:
        """Whether every sample on the boundary of ``rect`` has delta E <= |E_chr| / 2: each phase is then
        within pi / 6 of the exact one, each step of the count within pi / 5 + pi / 3 < pi of it, and the
        winding number is that of the exact values."""
        z = np.array(list(self.samples), dtype=complex)
        keep = _on_boundary(rect, z)
        E = np.abs(np.array(list(self.samples.values()), dtype=complex)[keep])
        delta = np.array([self.bounds.get(key, 0.0) for key in z[keep].tolist()])
        return bool(np.all(delta <= 0.5 * E))


def _perimeter(rect: Rectangle, z: ComplexArray) -> np.ndarray:
    """The position along the counter-clockwise boundary of ``rect`` (bottom, right, top, left edges)."""
    w, h = rect.width, rect.height
    x, y = z.real - rect.x0, z.imag - rect.y0
    tol = 1e-12 * max(w, h)
    return np.select(
        [abs(y) <= tol, abs(x - w) <= tol, abs(y - h) <= tol],
        [
            x,
            w + y,
            w + h + (w - x),
        ],
        default=2 * w + h + (h - y),
    )


def _on_boundary(rect: Rectangle, z: ComplexArray) -> np.ndarray:
    tol = 1e-12 * max(rect.width, rect.height)
    inside = (z.real >= rect.x0 - tol) & (z.real <= rect.x1 + tol) & (z.imag >= rect.y0 - tol)
    inside &= z.imag <= rect.y1 + tol
    edge = (abs(z.real - rect.x0) <= tol) | (abs(z.real - rect.x1) <= tol)
    edge |= (abs(z.imag - rect.y0) <= tol) | (abs(z.imag - rect.y1) <= tol)
    return np.asarray(inside & edge)


def _moments_start(E: QuadratureCharacteristic, rect: Rectangle, n: int) -> np.ndarray:
    """The n roots of ``rect`` from the moments of its boundary samples (Newton's identities)."""
    z = np.array(list(E.samples), dtype=complex)
    w = np.array(list(E.samples.values()), dtype=complex)
    keep = _on_boundary(rect, z)
    z, w = z[keep], w[keep]
    order = np.argsort(_perimeter(rect, z))
    z, w = np.append(z[order], z[order][0]), np.append(w[order], w[order][0])
    dlog = np.log(w[1:] / w[:-1])
    mid = 0.5 * (z[1:] + z[:-1])
    s = [np.sum(mid**p * dlog) / (2j * np.pi) for p in range(1, n + 1)]
    e = [1.0 + 0j]
    for k in range(1, n + 1):  # Newton's identities: k e_k = sum_i (-1)^(i-1) e_(k-i) s_i
        e.append(sum((-1) ** (i - 1) * e[k - i] * s[i - 1] for i in range(1, k + 1)) / k)
    return np.roots([(-1) ** k * e[k] for k in range(n + 1)])


#: The range of Im q kept by the secant method: the growing side (its iterates stay where G is defined).
BELOW = (-math.inf, 0.0)


def _secant(
    E: QuadratureCharacteristic, q0: complex, h: float, band: tuple[float, float] = BELOW
) -> tuple[complex, complex, float]:
    """The secant method from q0 (Im q kept in ``band``) at the track's own tolerance; returns (root,
    slope, |last step|)."""
    with E.tolerance(None):
        return _secant_steps(E, q0, h, band)


def _secant_steps(
    E: QuadratureCharacteristic, q0: complex, h: float, band: tuple[float, float]
) -> tuple[complex, complex, float]:
    """The secant iterations of :func:`_secant`, every iterate (the start too) kept in ``band`` of Im q,
    where the receptance is the function counted."""
    lo, hi = band
    a = complex(q0.real, min(max(q0.imag, lo), hi))  # a start from the moments may lie just outside
    b = a + h
    fa, fb = complex(E(np.array([a]))[0]), complex(E(np.array([b]))[0])
    step = np.inf
    for _ in range(SECANT_STEPS):
        slope = (fb - fa) / (b - a) if b != a else 0
        if slope == 0:
            break
        c = b - fb / slope
        c = complex(c.real, min(max(c.imag, lo), hi))
        step = abs(c - b)
        a, fa, b = b, fb, c
        fb = complex(E(np.array([b]))[0])
        if step < 1e-12 * max(1.0, abs(b)) or fb == 0:
            break
    slope = (fb - fa) / (b - a) if b != a else 0j
    return b, slope, float(step)


def count_rectangle(
    E: QuadratureCharacteristic,
    rect: Rectangle,
    tol: float = COUNT_TOL,
    max_step: float = np.pi / 5,
    samples: int = SAMPLES,
) -> tuple[int, bool]:
    """The winding number of ``rect`` at the receptance's tolerance ``tol`` (``samples`` initial samples
    along its longer side, steps of arg E_chr below ``max_step``, at most pi / 3), counted again at the
    track's own tolerance when a boundary sample's delta E exceeds |E_chr| / 2; and whether the count
    stands (:meth:`resolved`: each sampled phase then within pi / 6 of the exact one, each step of the
    count within max_step + pi / 3 < pi of it)."""
    spacing = max(rect.width, rect.height) / samples
    with E.tolerance(tol):
        n = winding_number(E, rect, spacing=spacing, max_step=max_step, max_points=4000)
    if E.resolved(rect) or E.tight is None:
        return n, E.resolved(rect)
    with E.tolerance(None):
        n = winding_number(E, rect, spacing=spacing, max_step=max_step, max_points=4000)
    return n, E.resolved(rect)


def locate(
    E: QuadratureCharacteristic, rect: Rectangle, n: int, band: tuple[float, float] = BELOW, level: int = 0
) -> list[tuple[complex, complex, float]]:
    """The n roots of ``rect`` as (q, slope, last step), the secant's iterates kept in ``band`` of Im q;
    fewer when they could not be located."""
    if n == 0:
        return []
    if n <= MOMENTS:
        h = 1e-4 * max(rect.width, rect.height)
        found = [_secant(E, q0, h, band) for q0 in _moments_start(E, rect, n)]
        margin = 1e-9 * max(rect.width, rect.height)
        good = [r for r in found if rect.contains(r[0], margin) and r[2] < 1e-6 * max(1.0, abs(r[0]))]
        distinct = {(round(r[0].real, 8), round(r[0].imag, 8)) for r in good}
        if len(good) == n and len(distinct) == n:
            return good
    if level >= LEVELS:
        return []
    out = []
    for half in rect.split(0.5):
        try:
            out += locate(E, half, count_rectangle(E, half)[0], band, level + 1)
        except EdgeZeroError:
            return out
    return out


#: Doublings of the window tried until rho <= MARGIN on the first samples of its far edges.
FAR_DOUBLINGS = 3


def _far_edges(radius: float) -> np.ndarray:
    """Five points of the far edges of the window of size ``radius`` (right edge, bottom edge)."""
    return radius * np.array([1.0, 1.0 - 0.5j, 1.0 - 1.0j, 0.5 - 1.0j, 0.0 - 1.0j])


def grown_radius(E: QuadratureCharacteristic, radius: float) -> float:
    """``radius`` doubled (at most FAR_DOUBLINGS times) until rho <= MARGIN at :func:`_far_edges`."""
    for _ in range(FAR_DOUBLINGS):
        with E.tolerance(COUNT_TOL):
            E(_far_edges(radius))
        if far_check(E, radius) <= MARGIN:
            break
        radius *= 2
    return radius


def far_check(E: QuadratureCharacteristic, radius: float) -> float:
    """The largest rho = |E_chr - E_lead| / |E_lead| over the samples at |q| >= radius."""
    z = np.array([q for q in E.samples if abs(q) >= radius * (1 - 1e-12)], dtype=complex)
    if z.size == 0:
        return np.inf
    track, system = E.bound.track, E.bound.float_system
    with E.tolerance(COUNT_TOL):  # rho against 1/2 needs no more (the samples' own tolerance: cached)
        G = track.receptance(z).matrix
    K = [G[..., 0, 0]] if system.contacts == 1 else _kernel_list(G, system.index, len(system.offsets))
    with np.errstate(all="ignore"):
        full = np.array([E.samples[q] for q in z.tolist()])
        main = e_lead(system, z, K)
        rho = np.abs(full - main) / np.abs(main)
    return float(np.max(np.where(np.isfinite(rho), rho, np.inf)))


def _kernel_list(G: ComplexArray, index: list[list[int]], count: int) -> list[ComplexArray]:
    """The kernel values at each distinct offset from the matrices G (the first entry that has it)."""
    out: list[ComplexArray | None] = [None] * count
    for i, row in enumerate(index):
        for j, k in enumerate(row):
            if out[k] is None:
                out[k] = G[..., i, j]
    return [x for x in out if x is not None]


def induced(
    E: QuadratureCharacteristic, q: complex, slope: complex, step: float, side: str = "below"
) -> InducedFrequency:
    """The root at ``q`` with its decimals (those its error delta q leaves) and residual."""
    delta = max(E.uncertainty(q, slope), step, 1e-15 * max(1.0, abs(q)))
    decimals = max(0, math.floor(-math.log10(2 * delta)))
    digits = max(0, decimals + math.floor(math.log10(max(abs(q), 1e-300))) + 1)
    residual = abs(complex(E(np.array([q]))[0]) / slope) if slope else float("inf")
    return InducedFrequency(mpmath.mpc(q.real, q.imag), side, 1, mpmath.mpf(residual), digits, decimals)


def window_radius(equivalent: BoundModel) -> tuple[float, FarField]:
    """S and its far-field check: the smallest radius R = FIRST_RADIUS 2^k beyond which the continuous
    equivalent's E_chr has no root with Im q < 0 (rho <= 1/2 up to 32 R,
    :func:`~moving_bogie.roots.count.far_field.far_field_radius`); the default window's size when there
    is none (the verdict then says so)."""
    far = far_field_radius(equivalent, FIRST_RADIUS)
    return (default_window(equivalent).x1 if far.radius is None else far.radius), far
