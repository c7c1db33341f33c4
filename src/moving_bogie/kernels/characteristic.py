"""The characteristic function E_chr(q) of a vehicle on n wheels (Eq. (38)) and its q-derivative (Eq. (40)).

E_chr is the determinant of the block system of :mod:`moving_bogie.kernels.vehicle`, built from the
generated vehicle matrices and the track kernel K(xi_i - xi_j, q) of :mod:`moving_bogie.kernels.track`
(dK/dq by double-pole residues; no finite differences); its derivative follows from Jacobi's formula.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike

from moving_bogie.kernels.bound import BoundModel
from moving_bogie.kernels.track import KernelValues, TrackKernel, TrackKernelArray
from moving_bogie.kernels.vehicle import VehicleSystem

if TYPE_CHECKING:
    from moving_bogie.typing import ComplexArray, Mpc


class Characteristic:
    """E_chr and friends at one q, at the current mpmath precision, for a vehicle on n wheels.

    E_chr is the determinant of the block system of :mod:`moving_bogie.kernels.vehicle` (Eq. (38) for
    the paper's bogie up to a constant factor), its derivative comes from Jacobi's formula (Eq. (40)).

    Parameters
    ----------
    bound : BoundModel
        The parameters bound to their model (its vehicle and its track).
    """

    def __init__(self, bound: BoundModel) -> None:
        self.bound = bound
        self.params = bound.params
        self.module = bound.vehicle
        self.kernel = TrackKernel(bound)
        self.evaluations = 0

    @property
    def system(self) -> VehicleSystem:
        """The vehicle's matrices at the current precision (kept by the bound model)."""
        return self.bound.vehicle_system()

    @property
    def names(self) -> tuple:
        """The responses: every DOF of the vehicle, the wheels first (``DOFS`` of the generated module)."""
        return tuple(self.module.DOFS)

    def kernel_values(self, q: Mpc, derivative: bool = False) -> KernelValues:
        """K (and dK/dq) at every distinct offset xi_i - xi_j of the contacts (:attr:`system`)."""
        return self.kernel(q, self.system.offsets, derivative=derivative)

    def __call__(self, q: Mpc) -> Mpc:
        """E_chr(q)."""
        self.evaluations += 1
        return self.system.e_chr(q, self.kernel_values(q).K)

    def value_and_derivative(self, q: Mpc, kernel_values: KernelValues | None = None) -> tuple[Mpc, Mpc]:
        """(E_chr(q), dE_chr/dq): Eq. (40), by Jacobi's formula."""
        self.evaluations += 1
        kv = kernel_values or self.kernel_values(q, derivative=True)
        assert kv.dK is not None  # kernel values with their derivative
        return self.system.value_and_derivative(q, kv.K, kv.dK)

    def numerators(self, q: Mpc, kernel_values: KernelValues | None = None) -> dict[str, Mpc]:
        """Residue numerators n_X(q) (Eqs. (36), (41)-(43)) as a dict by response name."""
        kv = kernel_values or self.kernel_values(q)
        return self.system.numerators(q, kv.K)

    def shape_weights(
        self,
        q: Mpc,
        kernel_values: KernelValues | None = None,
        numerators: dict[str, Mpc] | None = None,
        E: Mpc | None = None,
    ) -> Any:
        """G_j of the n contacts: i q W~(xi, q) = sum_j G_j K(xi - xi_j) / (2 pi E_chr), Eqs. (44)-(47)."""
        kv = kernel_values or self.kernel_values(q)
        return self.system.shape_weights(q, kv.K, numerators, E)


#: The most points :class:`CharacteristicArray` evaluates in one piece (a larger batch is split evenly).
CHUNK = 4096


class CharacteristicArray:
    """E_chr for numpy arrays of q in double precision (argument-principle counting, sweeps).

    ``bound`` as in :class:`Characteristic`. With ``remember`` (a radius), E_chr (a call, not
    :meth:`value_and_derivative`) is evaluated once per point with |q| <= ``remember``: the contours of one
    search that pass through the same points (:mod:`moving_bogie.roots.count.lattice`) share the values,
    and only the points not seen before count as ``evaluations``.
    """

    def __init__(self, bound: BoundModel, remember: float | None = None) -> None:
        self.bound = bound
        self.params = bound.params
        self.module = bound.vehicle
        self.kernel = TrackKernelArray(bound)
        self.system = self.bound.float_system
        self.offsets = [float(x) for x in self.system.offsets]
        self.evaluations = 0
        self._remember = remember
        # the points seen so far, sorted (numpy's order of complex numbers: by real part, then imaginary),
        # and E_chr at each
        self._known = np.empty(0, dtype=complex)
        self._values = np.empty(0, dtype=complex)

    def kernel_values(self, q: ArrayLike, derivative: bool = False) -> KernelValues:
        """K (and dK/dq) at the distinct contact offsets, arrays shaped like ``q``."""
        return self.kernel(np.asarray(q, dtype=complex), self.offsets, derivative=derivative)

    def __call__(self, q: ArrayLike) -> ComplexArray:
        """E_chr(q) (Eq. (38)) at every point of ``q``; a batch larger than :data:`CHUNK` points is evaluated
        in nearly equal pieces of at most that many (the temporaries of one piece stay in the processor's
        cache: a third less time per point on the ten-thousand-point contours of a count). Every value is the
        one the whole batch gives, bit for bit: each point's arithmetic is elementwise, and no piece is small
        enough for the scalar path of :func:`~moving_bogie.kernels.polyroots.quartic_roots`."""
        q = np.asarray(q, dtype=complex)
        if self._remember is None:
            return self._evaluate(q)
        flat = q.ravel()
        near = np.abs(flat) <= self._remember
        if np.all(near):
            return self._remembered(flat).reshape(q.shape)
        out = np.empty(flat.shape, dtype=complex)
        out[near] = self._remembered(flat[near])
        out[~near] = self._evaluate(flat[~near])
        return out.reshape(q.shape)

    def _evaluate(self, q: ComplexArray) -> ComplexArray:
        self.evaluations += q.size
        if q.size <= CHUNK:
            return self.system.e_chr_array(q, self.kernel_values(q).K)
        pieces = np.array_split(q.ravel(), -(-q.size // CHUNK))
        values = [self.system.e_chr_array(z, self.kernel_values(z).K) for z in pieces]
        return np.concatenate(values).reshape(q.shape)

    def _remembered(self, q: ComplexArray) -> ComplexArray:
        """E_chr at the points ``q`` (one-dimensional), evaluated only where not known yet (then kept).

        A point is known when it equals a kept one (``==`` of complex numbers, as a dict's keys compare):
        found by binary search in the sorted kept points. The points not known are evaluated once each."""
        known, values = self._known, self._values
        at = np.minimum(np.searchsorted(known, q), max(known.size - 1, 0))
        found = known[at] == q if known.size else np.zeros(q.shape, dtype=bool)
        out = np.empty(q.shape, dtype=complex)
        out[found] = values[at[found]]
        if not np.all(found):
            new, where = np.unique(q[~found], return_inverse=True)
            fresh = self._evaluate(new)
            out[~found] = fresh[where.ravel()]
            at = np.searchsorted(known, new)  # both sorted: the merge keeps the kept points sorted
            self._known, self._values = np.insert(known, at, new), np.insert(values, at, fresh)
        return out

    def value_and_derivative(self, q: ArrayLike) -> tuple[ComplexArray, ComplexArray]:
        """(E_chr(q), dE_chr/dq) in double precision, by Jacobi's formula (Eq. (40))."""
        q = np.asarray(q, dtype=complex)
        self.evaluations += q.size
        kv = self.kernel_values(q, derivative=True)
        assert kv.dK is not None  # asked for with derivative=True
        return self.system.value_and_derivative_array(q, kv.K, kv.dK)


class ContinuedCharacteristic:
    """E_chr of a :class:`CharacteristicArray` continued analytically through the cut of K: the side of the
    p-roots nearest to ``refs`` fixed to ``above`` (:func:`~moving_bogie.kernels.track.fixed_sides`).

    Where those roots lie on the sides given, it is E_chr; across the cut where they change side it is the
    continuation of E_chr from there, analytic as long as each stays clearly the root nearest to its
    reference (elsewhere its values are nan). Evaluations count on the characteristic it continues.
    """

    def __init__(self, fast: CharacteristicArray, refs: ArrayLike, above: ArrayLike) -> None:
        self.fast = fast
        self.sides = (np.asarray(refs, dtype=complex), np.asarray(above, dtype=bool))

    @property
    def evaluations(self) -> int:
        """Those of the characteristic it continues (which it adds to)."""
        return self.fast.evaluations

    def _kernel_values(self, q: ComplexArray, derivative: bool) -> KernelValues:
        return self.fast.kernel(q, self.fast.offsets, derivative=derivative, sides=self.sides)

    def __call__(self, q: ArrayLike) -> ComplexArray:
        q = np.asarray(q, dtype=complex)
        self.fast.evaluations += q.size
        return self.fast.system.e_chr_array(q, self._kernel_values(q, False).K)

    def value_and_derivative(self, q: ArrayLike) -> tuple[ComplexArray, ComplexArray]:
        q = np.asarray(q, dtype=complex)
        self.fast.evaluations += q.size
        kv = self._kernel_values(q, True)
        assert kv.dK is not None  # asked for with derivative=True
        return self.fast.system.value_and_derivative_array(q, kv.K, kv.dK)
