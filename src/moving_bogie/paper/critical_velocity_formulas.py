"""The paper's closed forms of the critical velocity, Eqs. (65)-(66), for its two beams on its track.

They hold for one model each (Euler-Bernoulli with a Pasternak layer, Eq. (65); Timoshenko-Rayleigh without
one, Eq. (66)), so they belong to the paper, not to the generic runtime: the critical velocity itself is
computed from the generated N(p, q) of any model (:mod:`moving_bogie.stability.velocity.critical_velocity`),
and
:func:`paper_formula` is what a caller passes as its ``formula`` to compare with the print. The proofs that
the printed formulas equal the derived minimum are in ``derivations/paper.py``.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping

import mpmath

from moving_bogie.model.catalogue import DEFAULT_MODEL, Model
from moving_bogie.typing import Mpf

__all__ = ["PAPER_FORMULAS", "formula_eb", "formula_tr", "paper_formula"]


def formula_eb(eta_s: float | Mpf = 0) -> Mpf:
    """Eq. (65): alpha_cr = sqrt(1 + eta_s) (alpha_ref = 1)."""
    return mpmath.sqrt(1 + mpmath.mpf(eta_s))


def formula_tr(S: float | Mpf, r: float | Mpf) -> Mpf:
    """Eq. (66) as printed: sqrt(r^2 - S - 8 r^2 S^2 + 4 S^(3/2) sqrt(4 r^4 S - r^2 + S)) / (2 (S - r^2))."""
    S, r = mpmath.mpf(S), mpmath.mpf(r)
    r2 = r * r
    inner = mpmath.sqrt(4 * r2 * r2 * S - r2 + S)
    return mpmath.sqrt(r2 - S - 8 * r2 * S * S + 4 * S**1.5 * inner) / (2 * (S - r2))


#: The paper's closed forms (beam, track) -> (equation, function of the track's groups).
PAPER_FORMULAS: dict[tuple[str, str], tuple[str, Callable[[Mapping[str, Mpf]], Mpf | None]]] = {
    ("eb", DEFAULT_MODEL["track"]): ("Eq. (65)", lambda g: formula_eb(g["eta_s"])),
    ("tr", DEFAULT_MODEL["track"]): (
        "Eq. (66)",
        lambda g: formula_tr(g["S"], g["r"]) if g["eta_s"] == 0 else None,
    ),
}


def paper_formula(model: Model, groups: Mapping[str, Mpf]) -> tuple[str, Mpf] | None:
    """(equation, alpha_cr) of the paper's closed form for ``model``'s beam and track, or None.

    ``groups`` are the track's groups (mpf); the ``formula`` hook of
    :func:`~moving_bogie.stability.velocity.critical_velocity.critical_velocity`.
    """
    paper = PAPER_FORMULAS.get((model.beam, model.track))
    if paper is None:
        return None
    value = paper[1](groups)
    return None if value is None else (paper[0], value)
