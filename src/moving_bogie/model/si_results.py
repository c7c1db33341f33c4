"""Physical in, physical out: results of a ``[physical]`` input in SI units (Eqs. (15)-(16) inverted).

The dimensionless time is tau = t / t_scale and every time dependence is e^{i q tau} (Eq. (21)), so an
induced frequency q is the angular frequency omega = q / t_scale [rad/s] with time factor e^{i omega t}:
Im omega < 0 grows, with growth time 1 / |Im omega| [s]; Re omega / (2 pi) is its frequency in Hz.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING, Any, Protocol

import mpmath

from moving_bogie.presentation import number_text, quantity_text
from moving_bogie.typing import Mpc, Mpf

if TYPE_CHECKING:
    from moving_bogie.roots.frequency_result import FrequencyResult

__all__ = ["frequency_rows", "root_in_si", "root_table", "roots_in_si"]


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


def frequency_rows(result: FrequencyResult) -> list[tuple[str, str]]:
    """The facts of a frequency result beside its roots, as (name, text) rows: the rate of the root
    nearest instability and the window searched, in SI (1/s, rad/s) when the result has ``scales``."""
    window = result.window
    if result.scales is None:
        degree = mpmath.nstr(result.degree_of_instability, 6)
        return [
            ("degree of instability", degree),
            ("window", f"Re q {window.x0:g}..{window.x1:g}, Im q {window.y0:g}..{window.y1:g}"),
        ]
    t_scale = result.scales.t_scale
    im = [float(mpmath.im(r.q)) / t_scale for r in result.roots]
    rows = [("time scale t_scale = sqrt(m / k_f)", quantity_text(t_scale, "s"))]
    if result.unstable_roots:
        rows.append(("largest growth rate, -min Im omega", quantity_text(-min(im), "1/s")))
    elif im:
        rows.append(("smallest decay rate, min Im omega", quantity_text(min(im), "1/s")))
    re = f"Re omega {number_text(window.x0 / t_scale)}..{quantity_text(window.x1 / t_scale, 'rad/s')}"
    rows.append(
        ("window", f"{re}, Im omega {number_text(window.y0 / t_scale)}..{window.y1 / t_scale:.6g} 1/s")
    )
    return rows


def root_table(result: FrequencyResult) -> tuple[tuple[str, ...], list[tuple[object, ...]]]:
    """(header, rows) of the roots of a frequency result: q to its confirmed digits, or in SI (omega, f and
    the 1/e time, to at most 8 of those digits) when the result has ``scales``."""
    header: tuple[str, ...]
    if result.scales is None:
        header = ("Re q", "Im q (< 0: grows)", "side of the cut", "multiplicity", "digits")
        return header, [(r.re_text, r.im_text, r.side, r.multiplicity, r.digits) for r in result.roots]
    header = (
        "Re omega [rad/s]",
        "Im omega [1/s] (< 0: grows)",
        "f [Hz]",
        "1/e time [s]",
        "side",
        "multiplicity",
    )
    rows: list[tuple[object, ...]] = []
    for r in result.roots:
        si = root_in_si(r.q, result.scales.t_scale, digits=min(8, r.digits))
        time = f"grows in {si['growth_time_s']}" if si["growth_time_s"] else f"decays in {si['decay_time_s']}"
        time = time if si["growth_time_s"] or si["decay_time_s"] else "constant amplitude"
        rows.append(
            ("+-" + si["omega"]["re"], si["omega"]["im"], si["frequency_hz"], time, r.side, r.multiplicity)
        )
    return header, rows
