"""The vertical surface flexibility U(k, omega) of the layered half-space (docs/soil.md, Eq. (S3)).

The stack is condensed from the bottom: the half-space's 2 x 2 stiffness, then for each layer upwards
K_top = K_tt - K_tb (K_bb + K_below)^{-1} K_bt. U = [K_surface^{-1}]_zz is the vertical displacement of the
surface per unit vertical traction (both downwards) of the wave exp(i (omega t - k x)); by axisymmetry the
same U(k, omega), k = sqrt(k1^2 + k2^2), is the flexibility of the three-dimensional half-space.
"""

from __future__ import annotations

import numpy as np

from moving_bogie.typing import ComplexArray, FloatArray

from .layer import blocks_of_waves, halfspace_stiffness, layer_stiffness, layer_waves
from .mat2 import Mat2
from .profile import SoilLayer, SoilProfile

__all__ = ["condensed", "surface_flexibility", "surface_stiffness"]


def surface_stiffness(k: ComplexArray, omega: ComplexArray, soil: SoilProfile) -> Mat2:
    """The 2 x 2 stiffness (u_x, u_z) of the whole stack at its surface."""
    stiffness = halfspace_stiffness(k, omega, soil.halfspace)[0]
    for layer in reversed(soil.layers[:-1]):
        tt, tb, bt, bb, _ = layer_stiffness(k, omega, layer)
        stiffness = tt - tb @ (bb + stiffness).inv() @ bt
    return stiffness


def condensed(k: ComplexArray, omega: ComplexArray, soil: SoilProfile) -> tuple[Mat2, ComplexArray]:
    """(K_surface, Delta): the surface stiffness and the secular determinant of the stack.

    Delta, the determinant of the global matrix of wave amplitudes, has no poles in k and vanishes exactly
    at the free surface waves: det K_surface times det of each block eliminated in the condensation
    (together: det of the global stiffness matrix) times det D of every layer and of the half-space (which
    cancels the poles of the layers' stiffness matrices). Each layer's factor is divided by the smooth
    positive (mu (|k| + |k_s|))^4, and Delta is freed of the phases of the normalised exponentials and of
    the divided-difference basis (1 / (s - p) per column): for real k and frequency, on the undamped
    profile, Delta lies on the real or the imaginary axis, which turns only where a layer's vertical
    wavenumber does (at its wave speeds).
    """
    stiffness, det_d = halfspace_stiffness(k, omega, soil.halfspace)
    delta = det_d * _unit(layer_waves(k, omega, soil.halfspace)[2]) / _scale(k, omega, soil.halfspace)
    for layer in reversed(soil.layers[:-1]):
        waves = layer_waves(k, omega, layer)
        tt, tb, bt, bb, det_d = blocks_of_waves(waves, layer.h)
        block = bb + stiffness
        stiffness = tt - tb @ block.inv() @ bt
        p, s, gap, _ = waves
        shift = np.exp(1j * np.imag((p + s) * layer.h)) * _unit(gap) ** 2
        delta = delta * det_d * block.det() * shift / _scale(k, omega, layer)
    return stiffness, delta * stiffness.det() / _scale(k, omega, soil.layers[0])


def _unit(z: ComplexArray) -> ComplexArray:
    return z / np.abs(z)


def _scale(k: ComplexArray, omega: ComplexArray, layer: SoilLayer) -> FloatArray:
    return (layer.mu * (np.abs(k) + np.abs(omega) / layer.c_s)) ** 4


def surface_flexibility(k: ComplexArray, omega: ComplexArray, soil: SoilProfile) -> ComplexArray:
    """U(k, omega): vertical surface displacement per unit vertical surface traction (m^3/N), broadcast.

    Statically, on a homogeneous half-space, U = (1 - nu) / (mu k) (Boussinesq's solution transformed).
    """
    kk = surface_stiffness(np.asarray(k, dtype=complex), np.asarray(omega, dtype=complex), soil)
    return kk.a / kk.det()
