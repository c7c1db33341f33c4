"""Every induced frequency in one strip of width Omega_0 up to a stated Im q, converged in the harmonics.

The characteristic function (:mod:`moving_bogie.kernels.hill`) is periodic in q with period Omega_0, so the
strip x0 <= Re q < x0 + Omega_0 holds one copy of every root (docs/sleepers.md, Eq. (S14)). Its roots with Im
q <= top are counted by the argument principle on the rectangle [x0, x0 + Omega_0] x [-depth, top], with no
starting guesses, located by Newton's method from a grid of the window (or, failing that, by bisection) and
polished; the count and the located roots are compared, and the whole is repeated with one more harmonic on
each side until the count is the same and the roots move less than ``tol``. The receptance over real
wavenumbers is analytic below the lowest Im q of the rail's free waves (Eq. (S15),
:meth:`~moving_bogie.kernels.sleeper_track.SleeperTrack.free_wave_floor`): ``top`` is 0.99 of that floor when
it is known and positive, so that decaying roots below it are found too; 0 when the rail is damped along its
length but the floor is not known; slightly below the axis when the rail is undamped between the supports (its
pinned-pinned waves put singular points of the receptance on the real axis). With ``continued=True``,
where the free waves' poles can be followed (:mod:`moving_bogie.kernels.free_wave_poles`: an
Euler-Bernoulli rail on ``sleepers``) the window reaches further, to 0.9 of the smeared rail's free waves'
decay rate, with the receptance continued across the periodic rail's singular lines from ``top``; a band
the continuation cannot search is named with the band above the window (it holds decaying vibrations
only) and the window falls back to ``top``. The band above the window is not searched and the result says
so. The depth is doubled until a band as deep again below the window holds no root.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from moving_bogie.kernels.free_wave_poles import ContinuationError, Sheet, regular_band
from moving_bogie.kernels.hill import FloquetSystem, VehicleMatrices
from moving_bogie.kernels.sleeper_track import SleeperTrack
from moving_bogie.kernels.smeared_rail import smeared_receptance
from moving_bogie.roots.count.contour import EdgeZeroError, Rectangle, winding_number
from moving_bogie.roots.strip_result import CONTINUED, FloquetResult, FloquetRoot

__all__ = ["FloquetResult", "FloquetRoot", "floquet_frequencies"]


#: the receptance's relative tolerance while counting: the winding number needs the phase of the
#: determinant only, and an error of 1e-6 moves it by 1e-6 rad where |det| is not within 1e-6 of zero
COUNT_TOL = 1e-6


#: the receptance's relative tolerance while polishing a root, and while locating one
POLISH_TOL = 1e-12
LOCATE_TOL = 1e-8


def _count(system: FloquetSystem, rect: Rectangle) -> int:
    spacing = min(rect.width, rect.height) / 12
    kept, system.tol = system.tol, COUNT_TOL
    try:
        return winding_number(system, rect, spacing=spacing, max_points=20_000)
    finally:
        system.tol = kept


def _newton(
    system: FloquetSystem,
    q: complex,
    rect: Rectangle,
    margin: float = 0.0,
    max_iter: int = 40,
    cap: float = np.inf,
) -> tuple[complex, float]:
    """Newton's method with a central-difference derivative; returns (q, abs(f / f')).

    An iterate that leaves ``rect`` widened by ``margin`` stops the iteration (residual inf): above the
    window the receptance may be on the far side of its singularities. A step longer than ``cap`` is
    shortened to it.
    """
    step = np.inf
    for _ in range(max_iter):
        if not rect.contains(q, margin=margin):
            return complex(q), float("inf")
        h = 1e-6 * max(1.0, abs(q))
        f0 = system(q)
        d = (system(q + h) - system(q - h)) / (2 * h)
        step = f0 / d
        q = q - step * min(1.0, cap / abs(step)) if abs(step) > 0 else q
        # the receptance is good to system.tol: a step below ten times that is at the noise floor
        if abs(step) < max(1e-13, 10 * system.tol) * max(1.0, abs(q)):
            break
    return complex(q), float(abs(step))


def _locate(system: FloquetSystem, rect: Rectangle, n: int, cell: float, reach: float) -> list[complex]:
    """Bisect ``rect`` (holding n roots) until each piece holds one root of size below ``cell``.

    In a piece that holds one root, Newton's method from its centre may wander through the window
    (``rect`` widened by ``reach``); the root it reaches is taken when it lies in the piece.
    """
    seeded = _seeded(system, rect, n, reach)
    if seeded is not None:
        return seeded
    out: list[complex] = []
    level = [(rect, n)]
    while level:
        nxt = []
        for r, k in level:
            if k == 0:
                continue
            if k == 1:
                q, res = _newton(system, r.center, rect, margin=reach)
                if res < 1e-6 and r.contains(q):
                    out.append(q)
                    continue
            if k == 1 and max(r.width, r.height) < cell:
                out.append(r.center)
                continue
            if max(r.width, r.height) < 1e-9:
                out += [r.center] * k
                continue
            for frac in (0.5, 0.47, 0.53, 0.41):
                a, b = r.split(frac)
                try:
                    ka = _count(system, a)
                    kb = k - ka
                    if ka >= 0 and kb >= 0 and _count(system, b) == kb:
                        nxt += [(a, ka), (b, kb)]
                        break
                except EdgeZeroError:
                    continue
            else:
                out += [r.center] * k
        level = nxt
    return out


def _seeded(system: FloquetSystem, rect: Rectangle, n: int, reach: float) -> list[complex] | None:
    """The n roots of ``rect`` by Newton's method from a 4 x 4 grid of it (a row just below its top) and the
    mirror image ``Omega_0 - conj(q)`` (Eq. (S14)) of each root found, with full steps then with steps of at
    most a tenth of the window; None unless n distinct roots in ``rect`` are reached (then :func:`_locate`
    bisects). The count certifies that none is missing."""
    period = system.track.Omega0
    xs = rect.x0 + (np.arange(4) + 0.5) / 4 * rect.width
    ys = rect.y1 - np.array([5 / 6, 1 / 2, 1 / 6, 0.02]) * rect.height  # the last tried first
    found: list[complex] = []
    for cap in (np.inf, 0.1 * min(rect.width, rect.height)):
        starts = [complex(x, y) for y in ys for x in xs]
        while starts and len(found) < n:
            q, res = _newton(system, starts.pop(), rect, margin=reach, cap=cap)
            if res > 1e-6 or not rect.contains(q):
                continue
            if all(abs(q - r) > 1e-6 * max(1.0, abs(r)) for r in found):
                found.append(q)
                mirror = period - q.conjugate()
                starts.append(mirror - period * np.floor((mirror.real - rect.x0) / period))
    return found if len(found) == n else None


def _roots_at(
    system: FloquetSystem, rect: Rectangle, previous: list[complex] | None, cell: float, reach: float
) -> tuple[int, list[tuple[complex, float]]]:
    """Count in ``rect``, locate (or start from ``previous`` when the count is unchanged) and polish."""
    count = _count(system, rect)
    starts = (
        previous
        if previous is not None and len(previous) == count
        else _locate(system, rect, count, cell, reach)
    )
    system.tol = POLISH_TOL
    polished = [_newton(system, q, rect, margin=reach) for q in starts]
    system.tol = LOCATE_TOL
    return count, polished


def _window(track: SleeperTrack, depth: float, top: float, x0: float) -> Rectangle:
    return Rectangle(x0, x0 + track.Omega0, -depth, top)


def floquet_frequencies(
    track: SleeperTrack,
    vehicle: VehicleMatrices,
    *,
    offset: float = 0.0,
    N0: int = 1,
    N_max: int = 6,
    tol: float = 1e-8,
    depth: float | None = None,
    top: float | None = None,
    continued: bool = False,
) -> FloquetResult:
    """Every root with Im q <= top of the Floquet characteristic in one strip (docs/sleepers.md, Eq. (S14)).

    Parameters
    ----------
    offset : float
        The rear wheel's position relative to a support at tau = 0 (the roots do not depend on it).
    N0, N_max : int
        First and largest N of the harmonics -N-1..N.
    tol : float
        Largest move of a root (relative to max(1, abs(q))) between N - 1 and N: the roots have converged.
    depth, top : float, optional
        Lower and upper edge of the window in Im q (defaults: see the module docstring).
    continued : bool
        Whether the default window reaches across the free waves' singular lines where it can (module
        docstring; off by default: certifying the band costs seconds to a minute); a ``top`` given stops
        the window there.
    """
    if track.Omega0 <= 0:
        raise ValueError("alpha: the Floquet strip needs a moving vehicle (v > 0)")
    floor = track.free_wave_floor()
    sheet = _continued_top(track, floor) if top is None and continued else None
    top = _default_top(track, floor) if top is None else top
    depth = max(track.Omega0, 1.0) if depth is None else depth
    notes: list[str] = []
    system = FloquetSystem(track, vehicle, N0, offset=offset)
    depth = _depth(system, depth, notes)
    skipped: tuple[str, ...] = ()
    if sheet is not None:
        try:
            system.sheet = _sheet(track, top, sheet, N_max)
            return _search(system, depth, sheet, floor, N_max, tol, notes, continued=sheet)
        except (ContinuationError, EdgeZeroError) as exc:
            skipped = (
                f"{top:.6g} < Im q <= {sheet:.6g}: the receptance could not be continued across the "
                f"rail's free waves ({exc})",
            )
            system.sheet, system.N = None, N0
    result = _search(system, depth, top, floor, N_max, tol, notes)
    return replace(result, skipped=skipped)


def _depth(system: FloquetSystem, depth: float, notes: list[str]) -> float:
    """The window's depth: doubled until a band as deep again below the window holds no root."""
    x0, period = -0.25 * system.track.Omega0, system.track.Omega0
    for _ in range(6):
        below = Rectangle(x0, x0 + period, -2 * depth, -depth)
        if _count(system, below) == 0:
            return depth
        depth *= 2
    notes.append(f"roots below Im q = -{depth:g} at every depth tried: the window may be incomplete")
    return depth


def _search(
    system: FloquetSystem,
    depth: float,
    top: float,
    floor: float,
    N_max: int,
    tol: float,
    notes: list[str],
    continued: float | None = None,
) -> FloquetResult:
    """Count, locate and converge in the harmonics the roots of the window [x0, x0 + Omega_0] x
    [-depth, top] (the steps of :func:`floquet_frequencies`)."""
    track, N0 = system.track, system.N
    x0 = -0.25 * track.Omega0
    cell = 0.05 * min(track.Omega0, depth)
    notes = list(notes)
    rect = _window(track, depth, top, x0)
    # Newton's iterates may leave the window by a little, never up to the singular lines above it
    ceiling = track.smeared_wave_floor() if continued is not None else floor
    reach = 0.05 * min(rect.width, rect.height)
    if ceiling > top:
        reach = min(reach, 0.5 * (ceiling - top))
    count, roots = _roots_at(system, rect, None, cell, reach)
    converged, steps = False, [np.inf] * len(roots)
    for N in range(N0 + 1, N_max + 1):
        system.N = N
        new_count, new_roots = _roots_at(system, rect, [q for q, _ in roots], cell, reach)
        if new_count == count and len(new_roots) == len(roots):
            steps = [abs(a[0] - b[0]) for a, b in zip(new_roots, roots)]
            count, roots = new_count, new_roots
            if all(s < tol * max(1.0, abs(q)) for s, (q, _) in zip(steps, roots)):
                converged = True
                break
        else:
            count, roots, steps = new_count, new_roots, [np.inf] * len(new_roots)
    if not converged:
        notes.append(f"the roots have not converged in the harmonics up to N = {system.N}")
    if len(roots) != count:
        notes.append(f"{count} root(s) counted but {len(roots)} located")
    if top < 0 and not any(q.imag < top for q, _ in roots):
        notes.append(
            f"roots with {top:.3g} < Im q <= 0 are not searched (rail undamped between the supports)"
        )
    found = tuple(FloquetRoot(q, res, s) for (q, res), s in zip(roots, steps))
    return FloquetResult(
        found,
        count,
        system.N,
        converged,
        rect,
        track.Omega0,
        system.evaluations,
        tuple(notes),
        floor,
        continued,
    )


def _sheet(track: SleeperTrack, y0: float, top: float, N_max: int) -> Sheet:
    """The sheet continued from ``y0``: within the quadrature's reach at N_max harmonics widened twice by
    its tail's factor 1.6 (beyond, the poles are followed one by one) no free wave's pole whose residue
    exceeds the polish's tolerance, or else the locating steps' (the receptance is then computed to that
    one), crosses the real axis below ``top`` in the strip; ContinuationError when one does (the search
    does not continue then: following every crossing pole costs seconds per value)."""
    reach = 1.6**2 * ((N_max + 2) * track.K + 2 * track.K + 10)
    x0 = -0.25 * track.Omega0
    # the receptance's scale (its largest free-rail entry) is at least that of the harmonic 0 mid-strip
    scale = abs(smeared_receptance(track, complex(x0 + track.Omega0 / 2, top), [0.0])[0])
    for tol in (POLISH_TOL, LOCATE_TOL):
        if regular_band(track, x0, x0 + track.Omega0, y0, top, reach, N_max + 1, tol * scale):
            return Sheet(y0, reach, tol * scale)
    raise ContinuationError(
        f"a free wave's pole whose residue exceeds {LOCATE_TOL:g} of the receptance crosses the real "
        "axis in the band"
    )


def _continued_top(track: SleeperTrack, floor: float) -> float | None:
    """The top of a window continued across the free waves: :data:`CONTINUED` of the smeared rail's free
    waves (the singular lines of the smeared part of Eq. (S11)), when the free waves' poles can be
    followed and it lies above the periodic rail's; else None."""
    top = CONTINUED * track.smeared_wave_floor()
    return top if floor > 0 and top > floor else None


def _default_top(track: SleeperTrack, floor: float) -> float:
    """The window's upper edge: below the free waves' floor, on the axis, or just below it (module doc)."""
    if floor > 0:
        return 0.99 * floor
    return 0.0 if float(track.groups.get("eta_f", 0.0)) > 0 else -1e-3 * track.Omega0
