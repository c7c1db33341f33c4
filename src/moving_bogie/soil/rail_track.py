"""A track on the soil as the :class:`~moving_bogie.kernels.track_model.Track` of a bound model (Eq. (S9)).

The vehicle's parameters are scaled as on the paper's beam (Eqs. (15)-(17)) with the reference stiffness
k_ref of the track on its soil in the place of k_f (:func:`reference_stiffness`): chi = (k_ref / 4 EI)^(1/4),
tau = sqrt(k_ref / m) t, so q = Omega / sqrt(k_ref / m), xi = chi x, alpha = v / v_ref. The Winkler track of
k_f = k_ref has the kernel K(xi, q) = (pi k_f / (2 chi)) G_SI(xi / chi, Omega) of Eq. (29) (its
D(p, q) is (4 / k_f) times the SI dynamic stiffness, with p = -k / chi: the paper's e^{i p xi} is the
e^{-i k x} of docs/soil.md), and so has the soil: :meth:`SoilRail.receptance` returns
(pi k_ref / (2 chi)) G_SI of :func:`~.receptance.soil_receptance` between the contacts, which
:mod:`moving_bogie.kernels.coupling` couples to the vehicle like any kernel matrix.

G is analytic for Im q < 0 and continuous on the real axis (module :mod:`.receptance`): its branch points
and cuts lie in Im q >= 0 (the branch point q = 0 on the real axis, where G stays finite), so a window of
Im q <= 0 holds none (``has_cut`` False). Above it G stays analytic up to the singular lines of the soil's
and the track's free waves (:mod:`.sheet`): the members ``band_*`` and ``waves_clear`` say where, for the
search of the decaying roots below them (:mod:`moving_bogie.roots.decaying_band`).
"""

from __future__ import annotations

import functools
from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from moving_bogie.kernels.arithmetic import Batched
from moving_bogie.kernels.coupling import kernel_matrix
from moving_bogie.kernels.track_model import WINDOW, RailReceptance, SearchRegion

from .profile import SoilProfile
from .receptance import soil_receptance
from .sheet import SCAN_NOTE, soil_depth, track_waves_clear
from .strip import strip_stiffness
from .track import SoilTrack

if TYPE_CHECKING:
    from moving_bogie.kernels.bound import BoundModel

__all__ = ["SoilRail", "SoilRailSpec", "reference_stiffness"]


def reference_stiffness(track: SoilTrack, soil: SoilProfile) -> float:
    """k_ref (N/m^2): the static support under the rail, D(k_b, 0) - EI k_b^4 at k_b = 1 / b (the soil's
    chi(1/b, 0) alone on the ``soil`` track; in series with the railpads and the ballast on the ballasted
    one), rounded to 12 digits so that the parameters and the track scale with the same number."""
    k_b = np.array([1 / track.b])
    chi = strip_stiffness(k_b, np.zeros(1), soil, track.b).chi
    value = track.rail_stiffness(k_b, np.zeros(1), chi)[0].real - track.EI * k_b[0] ** 4
    return float(f"{value:.12g}")


@dataclass(frozen=True)
class SoilRailSpec:
    """What makes the :class:`SoilRail` of a bound model: the track, its soil, k_ref and the tolerance.

    Called with the bound model (``BoundModel(params, track=spec)``), kept by ``bound.replace`` and
    pickled with it."""

    track: SoilTrack
    soil: SoilProfile
    k_ref: float
    tol: float = 1e-6

    def __call__(self, bound: BoundModel) -> SoilRail:
        return SoilRail(bound, self)


class SoilRail:
    """The track on the soil of a bound model (module docstring).

    Parameters
    ----------
    bound : BoundModel
        The vehicle's parameters scaled with k_f = ``spec.k_ref`` (alpha, eta_M, ...).
    spec : SoilRailSpec
        The track and the soil (SI).
    """

    def __init__(self, bound: BoundModel, spec: SoilRailSpec) -> None:
        track = spec.track
        self.spec = spec
        self.chi = (spec.k_ref / (4 * track.EI)) ** 0.25
        self.omega_0 = np.sqrt(spec.k_ref / track.m)
        v_ref = (4 * spec.k_ref * track.EI / track.m**2) ** 0.25
        self.v = float(bound.floats.alpha) * v_ref
        system = bound.float_system
        self._offsets = np.array([float(x) for x in system.offsets]) / self.chi
        self._index = np.array(system.index)
        self._cache: dict[complex, tuple[np.ndarray, float, float]] = {}
        #: The relative tolerance of the next evaluations (a search counts at a looser one, COUNT_TOL).
        self.tol = spec.tol

    @property
    def name(self) -> str:
        """``soil`` or ``ballasted-soil``."""
        return self.spec.track.kind

    @functools.cached_property
    def factor(self) -> float:
        """pi k_ref / (2 chi): K of Eq. (29) per G_SI (m/N)."""
        return float(np.pi * self.spec.k_ref / (2 * self.chi))

    def kernel_values(self, q: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
        """(K at the distinct offsets, shape q.shape + (offsets,), and its error per q), every q not
        evaluated before to :attr:`tol` evaluated in one quadrature (the k nodes shared), the rest from the
        cache."""
        q = np.asarray(q, dtype=complex)
        flat = q.ravel()
        unique = dict.fromkeys(flat.tolist())
        new = np.array(
            [z for z in unique if z not in self._cache or self._cache[z][2] > self.tol], dtype=complex
        )
        if new.size:
            rec = soil_receptance(
                self.spec.track,
                self.spec.soil,
                self.v,
                new * self.omega_0,
                self._offsets,
                tol=self.tol,
                above=True,
            )
            for z, g, e in zip(new.tolist(), rec.G * self.factor, rec.error * self.factor, strict=True):
                self._cache[z] = (g, float(e), self.tol)
        values = np.array([self._cache[z][0] for z in flat.tolist()]).reshape((*q.shape, self._offsets.size))
        errors = np.array([self._cache[z][1] for z in flat.tolist()]).reshape(q.shape)
        return values, errors

    def receptance(
        self, q: ArrayLike, harmonics: Sequence[int] = (0,), *, derivative: bool = False
    ) -> RailReceptance:
        """The kernel matrix K(xi_i - xi_j, q) of the soil (module docstring) at q (a number or an array),
        ``error`` the largest estimate over the q given; no derivative (None). For Im q > 0 it is the
        integral along real wavenumbers, the continued function only under the singular lines
        (:mod:`moving_bogie.roots.decaying_band`).

        Raises
        ------
        ValueError
            For harmonics other than (0,).
        """
        if tuple(harmonics) != (0,):
            raise ValueError(f"harmonics: a track on the soil has the one harmonic 0 (got {harmonics})")
        values, errors = self.kernel_values(q)
        K = [values[..., k] for k in range(values.shape[-1])]
        return RailReceptance(kernel_matrix(K, self._index, Batched), None, float(np.max(errors)))

    def search_region(self) -> SearchRegion:
        """The window Re q >= 0 (the roots come in pairs q, -conj(q): D(-k, -conj w) = conj D(k, w))."""
        return SearchRegion(WINDOW)

    @property
    def kernel_decay(self) -> Fraction | None:
        """3/2: for large |q| the rail's bending dominates (G ~ (1/2 pi) int dk / (EI k^4 - m Omega^2))."""
        return Fraction(3, 2)

    @property
    def has_cut(self) -> bool:
        """No cut in Im q <= 0, where the roots are searched (module docstring)."""
        return False

    @property
    def smeared(self) -> None:
        """None: the critical velocity on the soil is that of its guided waves (``soil/critical.py``)."""
        return None

    # --- the band above the real axis (kernels/track_model.py: BandTrack; soil/sheet.py) ----------------
    @property
    def band_scale(self) -> float:
        """rad/s per unit of q: sqrt(k_ref / m)."""
        return float(self.omega_0)

    @property
    def band_caveat(self) -> str:
        """The track's own lines are scanned, not bounded (:func:`~.sheet.track_waves_clear`)."""
        return SCAN_NOTE

    def band_depth(self, x: float) -> float:
        """The soil's lines' lower bound y_soil at Re q = ``x`` (:func:`~.sheet.soil_depth`), in q."""
        scale = self.band_scale
        return soil_depth(self.spec.soil, self.v, x * scale) / scale

    def waves_clear(self, x0: float, x1: float, y0: float, y1: float) -> bool:
        """No free wave of the track on its soil in the rectangle of q (:func:`~.sheet.track_waves_clear`)."""
        s = self.band_scale
        return track_waves_clear(self.spec.track, self.spec.soil, self.v, (x0 * s, x1 * s, y0 * s, y1 * s))
