"""Stacks of 2 x 2 complex matrices held as their four entries (contiguous arrays, elementwise arithmetic:
much faster than matmul or strided (..., 2, 2) arrays for the millions of small matrices of the soil)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from moving_bogie.typing import ComplexArray

__all__ = ["Mat2"]


@dataclass(frozen=True)
class Mat2:
    """[[a, b], [c, d]], each entry an array (all broadcast together)."""

    a: ComplexArray
    b: ComplexArray
    c: ComplexArray
    d: ComplexArray

    def __matmul__(self, o: Mat2) -> Mat2:
        return Mat2(
            self.a * o.a + self.b * o.c,
            self.a * o.b + self.b * o.d,
            self.c * o.a + self.d * o.c,
            self.c * o.b + self.d * o.d,
        )

    def __add__(self, o: Mat2) -> Mat2:
        return Mat2(self.a + o.a, self.b + o.b, self.c + o.c, self.d + o.d)

    def __sub__(self, o: Mat2) -> Mat2:
        return Mat2(self.a - o.a, self.b - o.b, self.c - o.c, self.d - o.d)

    def __neg__(self) -> Mat2:
        return Mat2(-self.a, -self.b, -self.c, -self.d)

    def det(self) -> ComplexArray:
        return self.a * self.d - self.b * self.c

    def inv(self) -> Mat2:
        det = self.det()
        return Mat2(self.d / det, -self.b / det, -self.c / det, self.a / det)

    def array(self) -> ComplexArray:
        """As an array of shape (..., 2, 2)."""
        a, b, c, d = np.broadcast_arrays(self.a, self.b, self.c, self.d)
        return np.stack([np.stack([a, b], -1), np.stack([c, d], -1)], -2)
