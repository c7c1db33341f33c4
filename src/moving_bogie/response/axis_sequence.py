"""The decaying induced frequencies along the real axis beyond the search window (Eqs. (35), (40)).

A track whose cut runs along the real axis to infinity (a Timoshenko-Rayleigh beam: the second cut curve
touches the real axis at q = sqrt(S)/r and stays just above it) gives E_chr an unbounded sequence of roots
with small Im q > 0 next to that curve: there the kernel's p-roots are nearly real, the factors e^{i p d}
of K(+-d) do not decay, and det Kmat (:mod:`~moving_bogie.roots.count.far_field`) keeps passing near zero.
They
all decay, so no verdict needs them, but the residue sum of Eq. (35) does: their residues fall off like
(Re q)^-4 and with the default window alone the time series misses by about 1e-8 of w_st.

:func:`axis_sequence` counts and locates them (:func:`~moving_bogie.roots.frequencies.induced_frequencies`
on strips Re q in [X_k, 2 X_k], |Im q| <= 1, the argument principle on the tiling of each strip) strip after
strip, doubling X_k from the window's right edge. The roots of a strip are located by Newton's method from
the large-|q| balance of E_chr (:mod:`~moving_bogie.response.axis_law`) and taken only where they agree
with the count of every tile; elsewhere the strip's tiles are bisected as in any search, and the note says
in how many strips. It stops when the residues of
the next strips are estimated below ``tol``: with A_k the sum of |n_X(q)/(q E_chr'(q))| over the roots of
strip k (both members of each pair, the largest over the responses) and rho = A_k / A_{k-1} (at least 1/8,
the (Re q)^-4 law over a doubling), the rest is estimated as A_k rho / (1 - rho), and also by the envelope
C (Re q)^-4 of the amplitudes found over roots as dense as the densest strip; the larger is kept. That
estimate (an extrapolation of the measured decay, not a proof) is what the time series' note reports.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from moving_bogie.errors import MovingBogieError
from moving_bogie.kernels.bound import BoundModel
from moving_bogie.kernels.characteristic import CharacteristicArray
from moving_bogie.response.axis_law import law_applies, law_roots
from moving_bogie.response.residues import ResidueExpansion, residue_expansion
from moving_bogie.roots.count.contour import Rectangle
from moving_bogie.roots.frequencies import FrequencyResult, induced_frequencies

if TYPE_CHECKING:
    from moving_bogie.model.params import DimensionlessParams

__all__ = ["AxisSequence", "axis_sequence"]

#: Half-height of the strips along the real axis (the sequence lies at Im q ~ 1e-3 - 0.05).
HALF_HEIGHT = 1.0
#: The slowest decay assumed per doubling of Re q ((Re q)^-4 residues, uniformly spaced roots: 1/8).
LAW = 1.0 / 8.0
#: Working precision of these roots: their residues are below 1e-8 of the steady deflection, so 15 digits
#: (confirmed at 25) are far more than the sum needs.
DPS = 15
#: Strips reach at least this many times the start of the sequence before the rest is extrapolated.
MIN_REACH = 2.0
#: Strips are added until Re q reaches this many times the window's edge or the sequence's start at most.
MAX_REACH = 256.0


@dataclass(frozen=True)
class AxisSequence:
    """The roots along the real axis beyond the window, their residues and the estimated rest.

    ``expansions`` are the :class:`~moving_bogie.response.residues.ResidueExpansion` of the strips that
    hold roots, ``reach`` the Re q up to which they were searched, ``tail`` the estimated size of the
    residues beyond (absolute, in the units of the responses; inf when no decay was seen), ``strips`` the
    number of strips counted, ``found`` the roots (pairs once).
    """

    expansions: tuple[ResidueExpansion, ...]
    reach: float
    tail: float
    strips: int
    found: int
    complete: bool  # every strip's count agreed with the roots found
    first: int  # roots (pairs once) in the first strip, Re q <= twice the window's edge
    bisected: int = 0  # roots located by bisection of their tiles (no law, or it disagreed with the count)

    def harmonics(self, tau: ArrayLike, names: tuple[str, ...]) -> dict:
        """The sum of their harmonic parts (:meth:`ResidueExpansion.harmonics`) for ``names``."""
        out = {name: np.zeros(np.shape(tau)) for name in names}
        for expansion in self.expansions:
            for name, v in expansion.harmonics(tau, names).items():
                out[name] += v
        return out

    def _located(self) -> str:
        return _located_text(self.found, self.bisected)

    def note(self, scale: float, start: float) -> str:
        rel = self.tail / scale if scale > 0 else math.inf
        tail = f"{rel:.1e} of the steady deflection" if math.isfinite(rel) else "not bounded (no decay seen)"
        return (
            f"decaying induced frequencies along the real axis beyond the window (a sequence from Re q ~ "
            f"{start:.4g}): {self.found} found in {self.strips} strip(s) up to Re q = {self.reach:.4g} "
            f"(|Im q| <= {HALF_HEIGHT:g}; {self._located()}) and summed; the residues beyond are estimated "
            f"at {tail} "
            "(extrapolated from the amplitudes found: their decay over the last doubling of Re q, at least "
            "the (Re q)^-4 law, and their (Re q)^-4 envelope)"
        )


def _located_text(found: int, bisected: int) -> str:
    """How the roots of the strips were located, for the note."""
    if bisected >= found:
        return "located by bisection of each strip's tiles"
    text = (
        "located by Newton's method from the large-|q| balance of E_chr, confirmed by the count of every tile"
    )
    if bisected:
        text += f" ({bisected} by bisection of the tiles where the balance's roots disagreed with the count)"
    return text


def axis_sequence(bound: BoundModel, result: FrequencyResult, *, start: float, tol: float) -> AxisSequence:
    """Roots of E_chr along the real axis from ``result.window.x1`` outwards (see the module docstring).

    Parameters
    ----------
    bound : BoundModel
    result : FrequencyResult
        The induced frequencies of the window (its right edge is where the strips start).
    start : float
        Re q where the sequence starts (the cut curve touches the real axis there); strips are added at
        least until ``MIN_REACH`` times that.
    tol : float
        Stop when the estimated rest is below this (absolute, units of the responses).
    """
    edge = float(result.window.x1)
    x, expansions, sums, strips, found_roots, complete, first = edge, [], [], 0, 0, True, 0
    envelope, density, tail, bisected = 0.0, 0.0, math.inf, 0
    fast = CharacteristicArray(bound) if law_applies(bound) else None
    while x < MAX_REACH * max(edge, start / 16):
        strip = Rectangle(x, 2 * x, -HALF_HEIGHT, HALF_HEIGHT)
        starts = law_roots(fast, strip) if fast is not None else None
        found = induced_frequencies(
            bound,
            dps=DPS,
            window=strip,
            check_window=False,
            starts=None if starts is None else list(starts),
            balls=True,
        )
        bisected += _bisected(starts, found)
        complete &= found.count_ok
        strips += 1
        first = first if strips > 1 else found.found
        amp = 0.0
        if found.roots:
            expansion = residue_expansion(bound, found, shapes=False, balls=True)
            expansions.append(expansion)
            found_roots += len(found.roots)
            per_root = _amplitudes(expansion)
            amp = float(per_root.sum())
            envelope = max(envelope, float(np.max(per_root * np.abs(expansion.q.real) ** 4)))
            density = max(density, len(found.roots) / x)
        sums.append(amp)
        x *= 2
        if x < MIN_REACH * start or len(sums) < 2:
            continue  # near its start the sequence is sparse and irregular: no extrapolation from there
        tail = _rest(sums[-2], sums[-1], envelope, density, x)
        if tail <= tol:
            break
    return AxisSequence(tuple(expansions), x, tail, strips, found_roots, complete, first, bisected)


def _bisected(starts: np.ndarray | None, found: FrequencyResult) -> int:
    """Roots of a strip not among those located from the law (within 1e-8 relative of one of them): found
    by bisection of their tiles."""
    if starts is None or not starts.size:
        return len(found.roots)
    return sum(bool(np.min(np.abs(starts - complex(r.q))) > 1e-8 * abs(complex(r.q))) for r in found.roots)


def _rest(prev: float, last: float, envelope: float, density: float, x: float) -> float:
    """The residues beyond Re q = x, estimated two ways and the larger kept: the last doubling's sum
    continued geometrically with its measured ratio (at least ``LAW``), and the envelope C (Re q)^-4 of
    the amplitudes found (C the largest a_j |Re q_j|^4) over roots as dense as the densest strip (pairs per
    unit of Re q, both members counted): 2 C density / (3 x^3). inf while the sums do not fall."""
    if prev == 0 and last == 0:
        return 0.0 if envelope == 0 else 2 * envelope * density / (3 * x**3)
    if not (prev > 0 and last < prev):
        return math.inf
    rho = max(last / prev, LAW)
    return max(last * rho / (1 - rho), 2 * envelope * density / (3 * x**3))


def _amplitudes(expansion: ResidueExpansion) -> np.ndarray:
    """Per root (each member of a pair), the largest |amplitude| over the responses."""
    return np.abs(np.stack([expansion.amplitudes[name] for name in expansion.names])).max(axis=0)


def refuse_outside(result: FrequencyResult, covered: int = 0) -> None:
    """Decaying roots beyond the window that the residue sum would miss make it refuse."""
    outside = getattr(result, "decaying_outside", 0)
    if outside and outside != covered:
        raise MovingBogieError(
            f"{outside} decaying induced frequencies lie outside the search window "
            "(found in the window twice as large): the residue sum would leave them out; "
            "pass frequencies computed in a larger window"
        )


def sequence_start(params: DimensionlessParams) -> float | None:
    """Re q = sqrt(S)/r where the cut curve along the real axis of a beam with rotary inertia touches the
    axis (the start of its sequence of decaying roots, docs/frequencies.md), or None for a beam without."""
    S, r = getattr(params, "S", None), getattr(params, "r", None)
    if S is None or r is None or not float(r) > 0:
        return None
    return math.sqrt(float(S)) / float(r)


def axis_roots(
    bound: BoundModel, result: FrequencyResult, expansion: ResidueExpansion
) -> tuple[AxisSequence | None, tuple[str, ...]]:
    """The sequence of decaying roots along the real axis beyond the window (:func:`axis_sequence`) and its
    note, or (None, ()) for a beam without one. The roots that the check window found beyond the window
    must all be among those of the first strip, else the residue sum refuses."""
    start = sequence_start(bound.params)
    if start is None:
        refuse_outside(result)
        return None, ()
    wheels = expansion.names[: len(expansion.positions)]
    scale = max(*(abs(expansion.steady[name]) for name in wheels), 1e-300)
    sequence = axis_sequence(bound, result, start=start, tol=TAIL_TOL * scale)
    refuse_outside(result, sequence.first)
    if not sequence.complete:
        raise MovingBogieError(
            "the decaying induced frequencies along the real axis beyond the window could not all be "
            "located (a strip's count and its roots disagree): no closed-form response"
        )
    return sequence, (sequence.note(scale, start),)


#: The residues of the real-axis sequence left out are estimated below this fraction of the steady deflection.
TAIL_TOL = 2e-10
