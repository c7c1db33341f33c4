"""First boundary samples of a rectangle near the origin on a lattice shared by every rectangle.

The argument principle (:mod:`~moving_bogie.roots.count.contour`) samples a rectangle's edges at most
``min(size / 64, edge / 8)`` apart, and at most 0.005 apart within |q| <= 10. Here those samples are the
multiples j h of the lattice step h = 0.005 / 2^k (the largest such step within both bounds, so never
coarser than that rule), besides the corners. Rectangles that share a line then share its samples: the
tiles of a window and the strips of the window twice as large along their common edges, and the halves of a
cell being located (:func:`~moving_bogie.roots.refine.locate.locate`) along the edges they inherit, with
the refinement next to a corner (a branch point of K just beside it) inherited too when the step stays the
same. E_chr evaluated once at a point (:class:`~moving_bogie.kernels.characteristic.CharacteristicArray`
with ``remember``) then serves every contour through it.
"""

from __future__ import annotations

import numpy as np

from moving_bogie.typing import ComplexArray

#: The coarsest lattice step: the initial sampling step within ``NEAR`` of the origin (contour.py's).
STEP = 0.005
#: Within this modulus of q = 0 the sampling step is ``STEP``; a rectangle reaching beyond keeps the
#: sampling that grows with |q| (:func:`~moving_bogie.roots.count.contour.initial_samples`).
NEAR = 10.0
#: A lattice step below this (a cell near the size where locating stops) is not used: the multiples j h
#: would no longer be exact in double precision next to |q| of order one.
FINEST = 1e-13


def lattice_step(bound: float) -> float:
    """The largest STEP / 2^k (k >= 0) not above ``bound``."""
    step = STEP
    while step > bound:
        step /= 2
    return step


def lattice_boundary(x0: float, x1: float, y0: float, y1: float) -> ComplexArray | None:
    """The counter-clockwise closed boundary (last point = first) of the rectangle [x0, x1] x [y0, y1]:
    its corners and, on each edge, the lattice points strictly between them (the step of each edge from
    ``min(size / 64, edge / 8)``, :func:`lattice_step`). None when the rectangle reaches beyond ``NEAR`` or
    is too small for the lattice (``FINEST``)."""
    corners = [complex(x0, y0), complex(x1, y0), complex(x1, y1), complex(x0, y1)]
    if max(abs(c) for c in corners) > NEAR:
        return None
    size = max(x1 - x0, y1 - y0)
    pieces = []
    for a, b in zip(corners, corners[1:] + corners[:1]):
        step = lattice_step(min(size / 64, abs(b - a) / 8))
        if step < FINEST:
            return None
        pieces.append(_edge(a, b, step))
    z = np.concatenate(pieces)
    return np.append(z, z[0])


def _edge(a: complex, b: complex, step: float) -> ComplexArray:
    """The corner ``a`` and the multiples of ``step`` strictly between a and b on the axis-parallel edge
    from a to b, in that direction (the end b is the next edge's first point)."""
    horizontal = a.imag == b.imag
    lo, hi = sorted((a.real, b.real) if horizontal else (a.imag, b.imag))
    u = np.arange(np.floor(lo / step) + 1, np.ceil(hi / step)) * step
    u = u[(u > lo) & (u < hi)]
    if (b.real < a.real) if horizontal else (b.imag < a.imag):
        u = u[::-1]
    points = u + 1j * a.imag if horizontal else a.real + 1j * u
    return np.concatenate([[a], points])
