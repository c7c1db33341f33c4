"""Starting points for the decaying roots along the real axis, from the large-|q| balance of E_chr.

For large |q| the characteristic function of a two-contact vehicle is E_chr = E_lead (1 + O(|q|^-1)) with
E_lead proportional to K(d) K(-d) - K(0)^2 (``e_chr_leading_<vehicle>_<track>`` of
``generated/asymptotics.py``, derived in ``derivations/asymptotics.py``; d the wheel spacing). Along the
real axis beyond sqrt(S)/r every p-root of a Timoshenko-Rayleigh beam is nearly real (they grow like |q|,
``ROOT_GROWTH``), so h(q) = K(d) K(-d) / K(0)^2 is a slowly varying factor times e^{i (p_u - p_l) d}
(p_u, p_l the real roots that K(d) and K(-d) take) and |h| stays near 1: the roots of E_lead, and next to
them those of E_chr, sit where the phase of h passes through 0 (mod 2 pi), about 2 pi / (d (p_u - p_l)')
apart.

:func:`law_roots` samples arg h on the real axis of a strip finely enough for that phase (the spacing from
the p-roots at the strip's far end: the phase of any e^{i (p_k - p_j) d} turns by at most
d (max Re p - min Re p) / x per unit of Re q at Re q = x, the roots growing linearly), takes the points
where it passes through 0 and runs Newton's method on E_chr itself from each (double precision, all at
once). Not every such point has a root next to it (the balance holds only to O(1/|q|)), and Newton's
method may land on a root twice: the distinct roots found inside the strip are returned, and
:func:`~moving_bogie.roots.frequencies.induced_frequencies` takes them only where they agree with the
argument-principle count of every tile of the strip.
"""

from __future__ import annotations

import numpy as np

from moving_bogie.kernels.bound import BoundModel
from moving_bogie.kernels.characteristic import CharacteristicArray
from moving_bogie.roots.count.contour import Rectangle

__all__ = ["law_applies", "law_roots"]

#: Samples of arg h per radian of its largest possible turn (8: a crossing is never stepped over).
SAMPLES_PER_RADIAN = 8.0
#: Im q of the Newton starts (the roots lie at Im q ~ 1e-3 - 0.05, just above the real axis).
START_IM = 0.02
NEWTON_STEPS = 40
#: Newton has converged when its step is below this relative to |q|; two roots closer than
#: DISTINCT * |q| are one.
CONVERGED = 1e-13
DISTINCT = 1e-8


def law_applies(bound: BoundModel) -> bool:
    """The balance holds for a vehicle with two contacts (offsets 0 and +-d) on a track whose p-roots
    grow like |q| (``ROOT_GROWTH`` of the generated asymptotics is 1 for every root)."""
    from moving_bogie.generated import asymptotics

    offsets = sorted(float(x) for x in bound.offsets)
    track = bound.foundation.__name__.rsplit(".", 1)[-1].removeprefix("foundation_")
    growth = asymptotics.ROOT_GROWTH.get(track, ())
    leading = f"e_chr_leading_{bound.params.vehicle}_{track}"
    return (
        len(offsets) == 3
        and offsets[1] == 0.0
        and offsets[0] == -offsets[2] != 0.0
        and tuple(growth) == ("1",)
        and hasattr(asymptotics, leading)
    )


def law_roots(fast: CharacteristicArray, strip: Rectangle) -> np.ndarray:
    """Distinct roots of E_chr in ``strip`` reached by Newton's method from the zeros of the phase of
    h = K(d) K(-d) / K(0)^2 on its real axis (module docstring); double precision."""
    d = max(abs(float(x)) for x in fast.offsets)
    far = fast.kernel.p_roots(np.array([complex(strip.x1)]))[0]
    rate = d * float(np.ptp(far.real)) / strip.x1  # radians of arg h per unit of Re q, at most
    n = int(np.ceil(SAMPLES_PER_RADIAN * rate * strip.width)) + 2
    x = np.linspace(strip.x0, strip.x1, n)
    K0, Km, Kp = _kernels_at(fast, x)
    phase = np.angle(Kp * Km / K0**2)
    flips = (np.sign(phase[:-1]) != np.sign(phase[1:])) & (np.abs(phase[:-1] - phase[1:]) < np.pi)
    starts = x[:-1][flips] - phase[:-1][flips] * np.diff(x)[flips] / (phase[1:] - phase[:-1])[flips]
    return _distinct(_newton(fast, starts + 1j * START_IM), strip)


def _kernels_at(fast: CharacteristicArray, x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """K(0), K(-d), K(d) at the real points x."""
    K = fast.kernel_values(x + 0j).K
    by_offset = dict(zip((float(o) for o in fast.offsets), K))
    d = max(by_offset)
    return by_offset[0.0], by_offset[-d], by_offset[d]


def _newton(fast: CharacteristicArray, q: np.ndarray) -> np.ndarray:
    """Newton's method on E_chr from every start at once; the points that converged (others dropped)."""
    q = q.astype(complex)
    done = np.zeros(q.shape, dtype=bool)
    with np.errstate(all="ignore"):
        for _ in range(NEWTON_STEPS):
            live = ~done & np.isfinite(q)
            if not np.any(live):
                break
            E, dE = fast.value_and_derivative(q[live])
            step = E / dE
            q[live] = q[live] - step
            done[live] = np.abs(step) <= CONVERGED * np.abs(q[live])
    return q[done & np.isfinite(q)]


def _distinct(q: np.ndarray, strip: Rectangle) -> np.ndarray:
    """The points of ``q`` inside the strip, each root once (by increasing Re q)."""
    q = np.sort_complex(q[[strip.contains(z) for z in q]]) if q.size else q
    keep: list[complex] = []
    for z in q:
        if not any(abs(z - w) <= DISTINCT * abs(z) for w in keep):
            keep.append(complex(z))
    return np.array(keep, dtype=complex)
