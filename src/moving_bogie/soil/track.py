"""Tracks on the soil (docs/soil.md): a beam directly on the soil, and Mezher's ballasted track.

Per track (the two rails together; a file given per rail is doubled on reading, :mod:`.file`). Time factor
exp(i omega t), waves exp(i (omega t - k1 x)), deflections downwards.

- ``soil``: a beam (EI, m) on the strip of half-width b: the rail's dynamic stiffness is
  D(k1, omega) = EI k1^4 - m omega^2 + chi(k1, omega) (Eq. (S6)).
- ``ballasted-soil`` (Mezher et al. 2016): rails (EI, m) on railpads (k_pad + i omega c_pad, per metre) on
  sleepers (a distributed mass m_s) on a ballast layer, a rod of height h_b, modulus E_b, density rho_b and
  cross-section A_b per metre, whose dynamic stiffness is (E_b A_b / h_b) lam [[cot lam, -1/sin lam],
  [-1/sin lam, cot lam]], lam = omega h_b / c_b, c_b = sqrt(E_b / rho_b), on the strip of half-width b
  (Eq. (S7)). Condensed on the rail:
  D = EI k1^4 - m omega^2 + k_p - k_p^2 / (k_p + z_11 - m_s omega^2 - z_12^2 / (z_22 + chi)).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

import numpy as np
import numpy.typing as npt

Array = npt.NDArray[Any]

__all__ = ["LOAD_KEYS", "TRACK_KINDS", "UNITS", "SoilTrack"]

#: The tracks on soil, and the [physical] keys each needs (SI, per track or per rail).
TRACK_KINDS = {
    "soil": ("EI", "m", "b"),
    "ballasted-soil": ("EI", "m", "k_pad", "c_pad", "m_s", "E_b", "rho_b", "h_b", "A_b", "b"),
}
#: [physical] keys of a soil-track file besides the track's: the moving load.
LOAD_KEYS = ("P",)
#: The SI unit of each [physical] key of a soil-track file.
UNITS = {
    "EI": "N m^2",
    "m": "kg/m",
    "b": "m",
    "k_pad": "N/m^2",
    "c_pad": "N s/m^2",
    "m_s": "kg/m",
    "E_b": "Pa",
    "rho_b": "kg/m^3",
    "h_b": "m",
    "A_b": "m^2/m",
    "P": "N",
}


@dataclass(frozen=True)
class SoilTrack:
    """A track on the soil, per track (SI). Ballast fields are 0 on the ``soil`` track."""

    kind: str
    EI: float
    m: float
    b: float
    k_pad: float = 0.0
    c_pad: float = 0.0
    m_s: float = 0.0
    E_b: float = 0.0
    rho_b: float = 0.0
    h_b: float = 0.0
    A_b: float = 0.0

    @property
    def ballasted(self) -> bool:
        return self.kind == "ballasted-soil"

    def undamped(self) -> SoilTrack:
        """The same track without railpad damping (its free waves)."""
        return replace(self, c_pad=0.0)

    def _ballast(self, omega: Array) -> tuple[Array, Array, Array]:
        """(sinc, z_11 sinc, z_12 sinc) of the ballast rod, sinc = sin(lam) / lam (no poles in omega)."""
        lam = omega * self.h_b / np.sqrt(self.E_b / self.rho_b)
        stiffness = self.E_b * self.A_b / self.h_b
        sinc = np.sinc(lam / np.pi)
        return sinc, stiffness * np.cos(lam), -stiffness * np.ones_like(sinc)

    def rail_stiffness(self, k1: Array, omega: Array, chi: Array) -> Array:
        """D(k1, omega): the rail's dynamic stiffness on the soil of equivalent stiffness chi (N/m^2)."""
        beam = self.EI * k1**4 - self.m * omega**2
        if not self.ballasted:
            return beam + chi
        k_p = self.k_pad + 1j * omega * self.c_pad
        sinc, z11, z12 = self._ballast(omega)
        below = k_p * sinc + z11 - self.m_s * omega**2 * sinc - z12**2 / (z11 + chi * sinc)
        return beam + k_p - k_p**2 * sinc / below

    def chi_sensitivity(self, omega: Array, chi: Array) -> Array:
        """dD/dchi of :meth:`rail_stiffness` at (omega, chi) (it does not depend on k1): 1 on the ``soil``
        track; through the railpads, sleepers and ballast on the ballasted one."""
        if not self.ballasted:
            return np.ones(np.broadcast(omega, chi).shape, dtype=complex)
        k_p = self.k_pad + 1j * omega * self.c_pad
        sinc, z11, z12 = self._ballast(omega)
        bottom = z11 + chi * sinc
        below = k_p * sinc + z11 - self.m_s * omega**2 * sinc - z12**2 / bottom
        return k_p**2 * sinc * (z12**2 * sinc / bottom**2) / below**2

    def determinant(self, k1: Array, omega: Array, chi: Array) -> Array:
        """A multiple of D free of the poles of the track's own parts: zero exactly at its free waves.

        On the ballasted track, det of the rail-sleeper-ballast stiffness matrix times (sin lam / lam)^2.
        """
        beam = self.EI * k1**4 - self.m * omega**2
        if not self.ballasted:
            return beam + chi
        k_p = self.k_pad + 1j * omega * self.c_pad
        sinc, z11, z12 = self._ballast(omega)
        bottom = z11 + chi * sinc
        middle = (k_p - self.m_s * omega**2) * sinc + z11
        return (beam + k_p) * (middle * bottom - z12**2) - k_p**2 * sinc * bottom

    def wave_determinant(self, k1: Array, omega: Array, chi: Array) -> Array:
        """:meth:`determinant` without the zeros of the ballast rod's sin(lam) / lam (lam = n pi, on the real
        axis, where D itself does not vanish): zero exactly at the track's free waves."""
        det = self.determinant(k1, omega, chi)
        return det / self._ballast(omega)[0] if self.ballasted else det

    def free_wavenumber(self, omega: Array) -> Array:
        """k1 > 0 of the track's free wave without the soil (chi = 0: the ballast's bottom free), or NaN.

        D is linear in EI k1^4, so k1 = ((m omega^2 - F) / EI)^(1/4) with F the rest of D at k1 = 0.
        """
        rest = self.rail_stiffness(np.zeros_like(omega), omega, np.zeros_like(omega))
        value = -np.real(rest) / self.EI
        return np.where(value > 0, np.abs(value) ** 0.25, np.nan)
