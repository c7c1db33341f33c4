"""Physical in, physical out: results of a ``[physical]`` input in SI units (Eqs. (15)-(16) inverted).

The dimensionless time is tau = t / t_scale and every time dependence is e^{i q tau} (Eq. (21)), so an
induced frequency q is the angular frequency omega = q / t_scale [rad/s] with time factor e^{i omega t}:
Im omega < 0 grows, with growth time 1 / |Im omega| [s]; Re omega / (2 pi) is its frequency in Hz.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any, Protocol

import mpmath

from moving_bogie.typing import Mpc, Mpf

__all__ = ["root_in_si", "roots_in_si"]


class HasFrequency(Protocol):
    """A root of a frequency result: anything with its induced frequency ``q``."""

    @property
    def q(self) -> Mpc: ...


def root_in_si(q: complex | Mpc, t_scale: float | Mpf, *, digits: int = 12) -> dict[str, Any]:
    """One induced frequency `q` (dimensionless, Eq. (38)) in SI units, as JSON-ready decimal strings.

    Parameters
    ----------
    q : complex or mpmath.mpc
        The root.
    t_scale : float or mpmath.mpf
        ``sqrt(m / k_f)`` [s], :attr:`~moving_bogie.model.scales.Scales.t_scale`.
    digits : int
        Significant digits printed.

    Returns
    -------
    dict
        ``omega`` {"re", "im"} [rad/s], ``frequency_hz`` (Re omega / 2 pi), ``growth_time_s`` (1 / |Im omega|
        when Im omega < 0, else None) and ``decay_time_s`` (1 / Im omega when Im omega > 0, else None).
    """
    with mpmath.workdps(max(digits + 5, 20)):
        omega = mpmath.mpc(q) / mpmath.mpf(t_scale)
        im = omega.imag
        return {
            "omega": {"re": mpmath.nstr(omega.real, digits), "im": mpmath.nstr(im, digits)},
            "frequency_hz": mpmath.nstr(omega.real / (2 * mpmath.pi), digits),
            "growth_time_s": mpmath.nstr(-1 / im, digits) if im < 0 else None,
            "decay_time_s": mpmath.nstr(1 / im, digits) if im > 0 else None,
        }


def roots_in_si(
    roots: Iterable[HasFrequency], t_scale: float | Mpf, *, digits: int = 12
) -> list[dict[str, Any]]:
    """:func:`root_in_si` of each root (objects with ``q``) of a frequency result."""
    return [root_in_si(r.q, t_scale, digits=digits) for r in roots]
