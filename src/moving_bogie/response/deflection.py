"""The beam's deflection shape w(xi, tau) at one time, Eqs. (44)-(47) plus the branch cut.

w(xi, tau) = sum_j G_j K(xi - xi_j, q) over the contacts, at q = 0 (the steady part) and at every induced
frequency (the residues, :mod:`~moving_bogie.response.residues`), with the kernel on a grid of xi
(:class:`~moving_bogie.response.shapes.KernelGrid`), and the branch-cut part I_bc where it can matter
(:mod:`~moving_bogie.response.cut_policy`). The time series at the contacts are
:mod:`~moving_bogie.response.closed_form`'s.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike

from moving_bogie.errors import MovingBogieError, ParameterError
from moving_bogie.kernels.bound import BoundModel
from moving_bogie.response.axis_sequence import refuse_outside
from moving_bogie.response.cut_policy import branch_cut_extent, branch_cut_mode, branch_cut_or_note, s_min_for
from moving_bogie.response.residues import ResidueExpansion, frequencies_for, residue_expansion
from moving_bogie.response.shapes import KernelGrid

if TYPE_CHECKING:
    from moving_bogie.model.physical import Scales
    from moving_bogie.roots.frequencies import FrequencyResult

__all__ = ["deflection_shape", "deflection_shape_details"]


def deflection_shape(bound: BoundModel, xi: ArrayLike, tau: float, **options: Any) -> np.ndarray:
    """Beam deflection w(xi, tau) at one time for an array of xi, Eqs. (44)-(47) plus the branch cut.

    xi is the moving coordinate (0 at the rear wheel, d at the front one). With ``scales`` (SI, as in
    :func:`~moving_bogie.response.closed_form.closed_form_response`) xi is in metres, tau in seconds and
    the result in metres. Keywords: ``scales``, ``frequencies``, ``branch_cut``, ``dps``, ``bc_tol``,
    ``bc_tau_cap``, ``quad_tol`` as in :func:`~moving_bogie.response.closed_form.closed_form_response`
    (``auto`` applies the same rule at this single time), and ``expansion`` (a precomputed
    :class:`ResidueExpansion` with shapes). :func:`deflection_shape_details` also says whether I_bc was
    included.
    """
    return deflection_shape_details(bound, xi, tau, **options)[0]


def deflection_shape_details(
    bound: BoundModel,
    xi: ArrayLike,
    tau: float,
    *,
    scales: Scales | None = None,
    frequencies: FrequencyResult | None = None,
    branch_cut: bool | str = "auto",
    dps: int = 30,
    bc_tol: float = 1e-6,
    bc_tau_cap: float = 1e4,
    quad_tol: float = 1e-10,
    expansion: ResidueExpansion | None = None,
) -> tuple[np.ndarray, bool, tuple]:
    """(w, branch_cut, notes): :func:`deflection_shape`, whether I_bc was included, and why not."""
    xi = np.asarray(xi, dtype=float)
    tau = float(tau)
    if scales is not None:
        xi = scales.chi * xi
        tau = tau / scales.t_scale
    if not (math.isfinite(tau) and tau >= 0):
        raise ParameterError("tau", "tau must be finite and >= 0")
    mode = branch_cut_mode(branch_cut)
    bc, notes = branch_cut_or_note(bound, mode)
    result = frequencies_for(bound, frequencies, dps, None)
    refuse_outside(result)
    if expansion is None:
        expansion = residue_expansion(bound, result, shapes=True)
    flat = xi.reshape(-1)
    grid0 = KernelGrid(bound, 0, dps=result.dps)
    # Eqs. (44)-(47) for n contacts: w(xi) = sum_j weight_j K(xi - xi_j).
    w = sum(a * grid0(flat - x) for a, x in zip(expansion.shape_steady, expansion.positions))
    for q, amplitudes in zip(expansion.q_mp, expansion.shape_amplitudes):
        grid = KernelGrid(bound, q, dps=result.dps)
        w = w + sum(a * grid(flat - x) for a, x in zip(amplitudes, expansion.positions)) * np.exp(
            1j * complex(q) * tau
        )
    scale = np.abs(w).max() if w.size else 0.0
    if w.size and np.abs(w.imag).max() > 1e-8 * max(scale, 1.0):
        raise MovingBogieError(f"deflection shape: imaginary part {np.abs(w.imag).max():.3g} does not cancel")
    w = w.real
    include = False
    if bc is not None and flat.size:
        s_min = s_min_for(bc, expansion)
        include = mode == "on"
        if not include:
            wheels = expansion.names[: len(expansion.positions)]
            ref = max(*(abs(expansion.steady[name]) for name in wheels), 1e-300)
            until, more = branch_cut_extent(bc, tau, tol=bc_tol * ref, cap=bc_tau_cap, s_min=s_min)
            include = tau <= until
            notes += (
                more if include else [*more, f"branch cut below tol {bc_tol:.1e} of the steady deflection"]
            )
        if include:
            w = w + bc.shape(flat, tau, tol=quad_tol, s_min=s_min)
    w = w.reshape(xi.shape)
    return (scales.deflection(w) if scales is not None else w), bool(include), tuple(notes)
