"""Steady part and unsteady harmonic part of the closed-form response: residues of Eq. (35).

For every response X (every DOF of the vehicle: the rail's deflection under each wheel, then the bodies'
bounce and pitch) the block system gives i q X~(q) = n_X(q) / E_chr(q) (:mod:`moving_bogie.kernels.vehicle`).
Closing the Bromwich line Im q = -a upward, x(tau) = i * sum Res[X~ e^{i q tau}] + I_bc, that is

    x(tau) = n_X(0)/E_chr(0)                                  steady part, Eq. (39)
           + sum_j n_X(q_j) e^{i q_j tau} / (q_j E_chr'(q_j))  unsteady harmonic part, Eqs. (36), (40)-(43)
           + I_bc                                             branch-cut part (:mod:`branch_cut`)

where the sum runs over every induced frequency, both members q and -conj(q) of each pair. The
coefficients are evaluated once in mpmath at the precision of the roots; the time series is then a
vectorised numpy sum of ``amplitude * exp(i q tau)``, whose cost does not depend on tau.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass
from typing import TYPE_CHECKING

import mpmath
import numpy as np
from numpy.typing import ArrayLike

from moving_bogie.errors import MovingBogieError, ParameterError
from moving_bogie.kernels.bound import BoundModel
from moving_bogie.kernels.characteristic import Characteristic
from moving_bogie.typing import Mpc

if TYPE_CHECKING:
    from moving_bogie.roots.frequencies import FrequencyResult

__all__ = [
    "IncompleteFrequencies",
    "ResidueExpansion",
    "both_members",
    "complete_frequencies",
    "residue_expansion",
]


class IncompleteFrequencies(MovingBogieError):
    """The frequency search did not confirm every induced frequency: the residue sum would be wrong."""


def both_members(result: FrequencyResult) -> list[Mpc]:
    """Every induced frequency of a FrequencyResult, with the mirror -conj(q) of each pair added.

    A root with Re q = 0 within its confirmed decimals is its own mirror and is listed once.

    Raises
    ------
    IncompleteFrequencies
        If ``result.count_ok`` is false (roots missing or a window warning).
    MovingBogieError
        For a multiple root (the simple-pole residue formula of Eq. (40) does not apply).
    """
    if not result.count_ok:
        detail = "; ".join(result.warnings) or f"{result.found} of {result.count} roots found"
        raise IncompleteFrequencies(f"induced frequencies incomplete ({detail}): no closed-form response")
    out: list[Mpc] = []
    # The mirror is formed at the roots' precision: rounded to double, it would sit ~1e-17 off the root,
    # and near a close pair (two bogies interacting through the rail, roots 1e-13 apart) its residue would
    # then be wrong in the fourth digit and the imaginary parts of the pair would not cancel.
    with mpmath.workdps(max(int(getattr(result, "dps", 0) or 0), mpmath.mp.dps)):
        for root in result.roots:
            if root.multiplicity != 1:
                raise MovingBogieError(
                    f"induced frequency {mpmath.nstr(root.q, 10)} has multiplicity {root.multiplicity}: "
                    "the residue formula of Eq. (40) needs simple poles"
                )
            q = +mpmath.mpc(root.q)
            out.append(q)
            if abs(mpmath.re(q)) > mpmath.mpf(10) ** (-root.decimals):
                out.append(-mpmath.conj(q))
    return out


@dataclass(frozen=True)
class ResidueExpansion:
    """The residue coefficients of Eqs. (36)-(43) for one parameter set, ready for vectorised evaluation.

    Attributes
    ----------
    names : tuple of str
        Responses available: every DOF of the vehicle, the wheels first (``DOFS``).
    q : ndarray of complex
        Every induced frequency, both members of each pair.
    amplitudes : dict
        name -> ndarray of complex, ``n_X(q_j) / (q_j E_chr'(q_j))``, aligned with ``q``.
    steady : dict
        name -> float, ``n_X(0) / E_chr(0)`` (Eq. (39)).
    shape_amplitudes : ndarray of complex, shape (len(q), n)
        ``G_j(q_j) / (2 pi q_j E_chr'(q_j))`` of Eq. (47), one column per contact j.
    shape_steady : ndarray of float, shape (n,)
        ``G_j(0) / (2 pi E_chr(0))`` of Eq. (44).
    positions : tuple of float
        The contact positions xi_j (rear wheel at 0): w(xi) = sum_j (weight_j) K(xi - xi_j).
    q_mp, amplitudes_mp : the same at the roots' precision (mpmath).
    """

    names: tuple[str, ...]
    q: np.ndarray
    amplitudes: dict[str, np.ndarray]
    steady: dict[str, float]
    shape_amplitudes: np.ndarray
    shape_steady: np.ndarray
    positions: tuple[float, ...]
    q_mp: tuple[Mpc, ...]
    amplitudes_mp: dict[str, tuple[Mpc, ...]]
    dps: int

    def harmonics(
        self, tau: ArrayLike, names: Iterable[str] | None = None, *, imag_tol: float = 1e-9
    ) -> dict[str, np.ndarray]:
        """Unsteady harmonic parts sum_j a_j e^{i q_j tau} of several responses (real, vectorised).

        The exponentials are computed once for all responses. The imaginary parts of the two members of
        each pair cancel; a residual above ``imag_tol`` times the size of the terms raises (it would
        mean a missing mirror or a wrong amplitude).
        """
        names = tuple(names or self.names)
        tau = np.asarray(tau, dtype=float)
        flat = tau.reshape(-1)
        out = {name: np.zeros(flat.shape) for name in names}
        if self.q.size == 0:
            return {name: v.reshape(tau.shape) for name, v in out.items()}
        A = np.stack([self.amplitudes[name] for name in names], axis=-1)
        absA = np.abs(A)
        block = 32768
        for start in range(0, flat.size, block):
            chunk = flat[start : start + block]
            phase = np.exp(1j * np.multiply.outer(chunk, self.q))
            total = phase @ A
            scale = np.abs(phase) @ absA
            steady = np.array([abs(self.steady[name]) for name in names])
            bad = np.abs(total.imag) > imag_tol * (scale + steady + 1e-300)
            if np.any(bad):
                i, j = np.unravel_index(np.argmax(np.abs(total.imag) / (scale + 1e-300)), total.shape)
                raise MovingBogieError(
                    f"{names[j]}: imaginary part {total.imag[i, j]:.3g} of the residue sum does not cancel "
                    f"at tau = {chunk[i]:g}"
                )
            for k, name in enumerate(names):
                out[name][start : start + chunk.size] = total[:, k].real
        return {name: v.reshape(tau.shape) for name, v in out.items()}

    def harmonic(self, name: str, tau: ArrayLike, *, imag_tol: float = 1e-9) -> np.ndarray:
        """Unsteady harmonic part of one response (see :meth:`harmonics`)."""
        return self.harmonics(tau, (name,), imag_tol=imag_tol)[name]

    def total(self, name: str, tau: ArrayLike) -> np.ndarray:
        """Steady plus unsteady harmonic part (the closed form without I_bc)."""
        return self.steady[name] + self.harmonic(name, tau)

    def totals(self, tau: ArrayLike) -> dict[str, np.ndarray]:
        """Steady plus unsteady harmonic part of every response."""
        return {name: self.steady[name] + v for name, v in self.harmonics(tau).items()}


def residue_expansion(
    bound: BoundModel, frequencies: FrequencyResult, *, shapes: bool = True, balls: bool = False
) -> ResidueExpansion:
    """Residue coefficients for the steady and unsteady harmonic parts, Eqs. (36)-(47).

    Every coefficient is evaluated at the precision of ``frequencies.dps`` with dE_chr/dq from
    :meth:`Characteristic.value_and_derivative` (dK/dq by double-pole residues, no finite differences).

    Parameters
    ----------
    bound : BoundModel
    frequencies : FrequencyResult
        From :func:`moving_bogie.roots.frequencies.induced_frequencies` for the same bound model.
    shapes : bool
        Also compute the shape weights of Eqs. (44)-(47) (needed by :func:`deflection_shape`).
    balls : bool
        Without ``shapes``: the amplitudes in Arb's balls, to ``frequencies.dps`` digits proven
        (:func:`~moving_bogie.response.ball_residues.ball_amplitudes`; the mpmath path for a root where the
        balls do not reach them).

    Raises
    ------
    IncompleteFrequencies, MovingBogieError
        Frequencies incomplete, a multiple root, or E_chr(0) = 0 (no steady state).
    """
    vehicle = bound.params.vehicle
    if frequencies.model != vehicle:
        raise MovingBogieError(f"frequencies were computed for model {frequencies.model!r}, not {vehicle!r}")
    qs = both_members(frequencies)
    chr_ = Characteristic(bound)
    names = chr_.names
    with mpmath.workdps(frequencies.dps):
        zero = mpmath.mpc(0)
        kv0 = chr_.kernel_values(zero)
        E0 = chr_.system.e_chr(zero, kv0.K)
        if abs(E0) < mpmath.mpf(10) ** (-frequencies.dps // 2):
            raise MovingBogieError("E_chr(0) = 0: no steady state (q = 0 is an induced frequency)")
        n0 = chr_.numerators(zero, kv0)
        steady_mp = {name: n0[name] / E0 for name in names}
        amps_mp: dict[str, list[Mpc]] = {name: [] for name in names}
        shape_amps, qs_mp = [], []
        in_balls: list[dict[str, Mpc] | None] = [None] * len(qs)
        if balls and not shapes:
            from moving_bogie.response.ball_residues import ball_amplitudes

            in_balls = ball_amplitudes(bound, qs, names, frequencies.dps)
        for q, found in zip(qs, in_balls):
            q = mpmath.mpc(q)
            qs_mp.append(q)
            amps, shape = (found, None) if found is not None else _residue_mp(chr_, q, shapes)
            for name in names:
                amps_mp[name].append(amps[name])
            if shape is not None:
                shape_amps.append(shape)
        contacts = chr_.system.contacts
        positions = tuple(float(x) for x in chr_.system.positions)
        shape_steady = [0.0] * contacts
        if shapes:
            G0 = chr_.shape_weights(zero, kv0, n0, E0)
            shape_steady = [float(mpmath.re(g / (2 * mpmath.pi * E0))) for g in G0]
    for name in names:
        if abs(mpmath.im(steady_mp[name])) > mpmath.mpf(10) ** (-frequencies.dps // 2) * (
            1 + abs(steady_mp[name])
        ):
            raise MovingBogieError(f"steady part of {name} is not real: {mpmath.nstr(steady_mp[name], 8)}")
    return ResidueExpansion(
        names=names,
        q=np.array([complex(q) for q in qs_mp], dtype=complex),
        amplitudes={name: np.array([complex(a) for a in amps_mp[name]], dtype=complex) for name in names},
        steady={name: float(mpmath.re(steady_mp[name])) for name in names},
        shape_amplitudes=np.array([[complex(g) for g in row] for row in shape_amps], dtype=complex).reshape(
            -1, contacts
        ),
        shape_steady=np.array(shape_steady, dtype=float),
        positions=positions,
        q_mp=tuple(qs_mp),
        amplitudes_mp={name: tuple(v) for name, v in amps_mp.items()},
        dps=frequencies.dps,
    )


def _residue_mp(chr_: Characteristic, q: Mpc, shapes: bool) -> tuple[dict[str, Mpc], list[Mpc] | None]:
    """At one root q, at the working precision: n_X(q) / (q E_chr'(q)) by response name (Eqs. (36),
    (40)-(43)) and, with ``shapes``, G_j(q) / (2 pi q E_chr'(q)) of Eq. (47) (else None)."""
    kv = chr_.kernel_values(q, derivative=True)
    E, dE = chr_.value_and_derivative(q, kv)
    if dE == 0:
        raise MovingBogieError(f"E_chr'({mpmath.nstr(q, 10)}) = 0: a multiple root")
    num = chr_.numerators(q, kv)
    amps = {name: num[name] / (q * dE) for name in chr_.names}
    if not shapes:
        return amps, None
    G = chr_.shape_weights(q, kv, num, E)
    return amps, [g / (2 * mpmath.pi * q * dE) for g in G]


def frequencies_for(
    bound: BoundModel, frequencies: FrequencyResult | None, dps: int, progress: Callable[[float], None] | None
) -> FrequencyResult:
    """The induced frequencies of ``bound``: ``frequencies`` when given (checked to be those of the same
    parameters and vehicle), else computed at ``dps`` digits (Eq. (48))."""
    if frequencies is not None:
        vehicle = bound.params.vehicle
        if frequencies.model != vehicle:
            raise ParameterError(
                "model", f"frequencies were computed for model {frequencies.model!r}, not {vehicle!r}"
            )
        if getattr(frequencies, "params", bound.params) != bound.params:
            raise ParameterError("frequencies", "frequencies were computed for other parameters")
        result = frequencies
    else:
        from moving_bogie.roots.frequencies import induced_frequencies

        result = induced_frequencies(bound, dps=dps, progress=progress)
    return result


def complete_frequencies(
    bound: BoundModel,
    dps: int,
    branch_cut: bool | str | None = "auto",
    progress: Callable[[float], None] | None = None,
) -> FrequencyResult:
    """Every induced frequency of ``bound`` at ``dps`` digits, for a closed form: a
    :class:`~moving_bogie.errors.MovingBogieError` when the search is incomplete (found and counted roots
    differ). ``branch_cut=True`` first refuses a velocity whose branch cut cannot be integrated, before the
    long search."""
    from moving_bogie.response.cut_integral import branch_cut_for
    from moving_bogie.roots.frequencies import induced_frequencies

    if branch_cut is True:
        branch_cut_for(bound)
    result = induced_frequencies(bound, dps=dps, progress=progress)
    if not result.count_ok:
        detail = "; ".join(result.warnings) or f"{result.found} of {result.count} roots confirmed"
        raise MovingBogieError(f"induced frequencies incomplete ({detail}); no closed-form response")
    return result
