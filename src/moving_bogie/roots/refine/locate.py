"""Locating the roots counted in a region (step 2 of
:func:`~moving_bogie.roots.frequencies.induced_frequencies`): bisection with the argument principle until a
cell holds one root that Newton's method reaches without leaving it; a cell that cannot be split
consistently is handed to Newton's method from a grid of starts.
"""

from __future__ import annotations

from typing import TypeAlias

import mpmath
import numpy as np

from moving_bogie.errors import MovingBogieError
from moving_bogie.kernels.characteristic import CharacteristicArray, ContinuedCharacteristic
from moving_bogie.roots.count.contour import EdgeZeroError, Rectangle, Region, piece_points, winding_numbers
from moving_bogie.roots.count.outcomes import Note, Reason, Unlocated
from moving_bogie.typing import Mpc

__all__ = ["FastCharacteristic", "locate", "newton_inside", "newton_inside_many"]

#: E_chr in double precision, batched: itself, or continued analytically through the cut.
FastCharacteristic: TypeAlias = CharacteristicArray | ContinuedCharacteristic
#: A located root: its start for polishing, its multiplicity, and the cell that holds it.
LocatedCell: TypeAlias = tuple[Mpc, int, Region]


def locate(
    fast: FastCharacteristic, rect: Region, n: int, newton_cell: float
) -> tuple[list[LocatedCell], Unlocated | None]:
    """Bisect ``rect`` (holding ``n`` roots) into cells of one root each.

    Returns ([(q0, multiplicity, cell)], warning). A cell that cannot be split into halves whose counts
    add up (a root on every split line tried) is handed to Newton's method from a grid of starts inside
    it; if that does not find its roots either, they are missing from the result and ``warning`` is an
    :class:`~moving_bogie.roots.count.outcomes.Unlocated` (the count then disagrees with the roots found:
    the verdict is UNDETERMINED unless the cell lies in Im q > 0, where a missing root cannot be unstable).
    """
    out: list[LocatedCell] = []
    warning: Unlocated | None = None
    level: list[tuple[Region, int]] = [(rect, n)]
    spent = fast.evaluations
    while level:
        if fast.evaluations - spent > _LOCATE_POINTS:  # bounded time: Newton from grids
            for r, k in level:
                starts = _grid_roots(fast, r, k) if k else []
                if len(starts) != k:
                    text = f"gave up splitting {r} holding {k} root(s) ({_LOCATE_POINTS} evaluations)"
                    warning = Unlocated(r, k - len(starts), Note(Reason.LOCATE, text))
                out += [(q, 1, r) for q in starts]
            break
        # every cell of a level is split at once: one batched evaluation of E_chr per refinement of the
        # contours of all their halves (what costs is mostly the call, not the points)
        split: list[tuple[Region, int, tuple[float, ...]]] = []
        # a cell between two cut curves is only ever split across Re q, so its height never shrinks: its
        # smaller side decides (bisecting it further only makes a sliver a root sits in)
        single = [r for r, k in level if k == 1 and min(r.width, r.height) <= newton_cell]
        reached = dict(zip(map(id, single), newton_inside_many(fast, single)))
        for r, k in level:
            if k == 0:
                continue
            size = max(r.width, r.height)
            q = reached.get(id(r))
            if q is not None:
                out.append((q, 1, r))
                continue
            if size < 1e-10 * max(1.0, abs(r.center)):
                out.append((mpmath.mpc(r.center), k, r))  # a cluster of k roots: a multiple root
                continue
            split.append((r, k, _towards_origin(r) + _FRACTIONS))
        level = []
        failed: list[tuple[Region, int, tuple[float, ...]]] = []
        while split:
            # two halves each (a cell at a fold of the cut may give three pieces), each cell at its next
            # split fraction
            pieces = [r.split(fracs[0]) for r, _, fracs in split]
            flat = [piece for group in pieces for piece in group]
            counts = winding_numbers(fast, flat, max_points=[piece_points(piece) for piece in flat])
            retry: list[tuple[Region, int, tuple[float, ...]]] = []
            at = 0
            for (r, k, fracs), group in zip(split, pieces):
                mine = [c for c in counts[at : at + len(group)] if not isinstance(c, EdgeZeroError)]
                at += len(group)
                if len(mine) < len(group) or sum(mine) != k:
                    retry.append((r, k, fracs[1:]))
                else:
                    level.extend(zip(group, mine))
            split = [c for c in retry if c[2]]
            failed += [c for c in retry if not c[2]]
        for r, k, _ in failed:
            starts = _grid_roots(fast, r, k)
            if len(starts) != k:
                text = f"could not split {r} holding {k} root(s) into consistent halves"
                warning = Unlocated(r, k - len(starts), Note(Reason.LOCATE, text))
            out += [(q, 1, r) for q in starts]
    return out, warning


#: Evaluations of E_chr one call of :func:`locate` may spend splitting (a few seconds); the cells not yet
#: resolved then get Newton's method from a grid of starts, and a warning if that falls short.
_LOCATE_POINTS = 300_000

#: Split fractions tried in turn until the halves' counts add up to the cell's.
_FRACTIONS = (0.5, 0.45, 0.55, 0.4, 0.6, 0.35, 0.65, 0.3, 0.7, 0.25, 0.75)

#: Within this distance of q = 0 lie the vehicle's and the beam's own roots (the default window's scale).
_NEAR = 16.0


def _towards_origin(r: Region) -> tuple[float, ...]:
    """A first split fraction for a large rectangle (a far-field window's) that cuts off its part within
    about ``_NEAR`` of q = 0 along its longer side, where the roots gather: bisection would need log2(size /
    _NEAR) levels of long contours to get there. None (an empty tuple) for a small region or a curved cell."""
    if type(r) is not Rectangle or max(r.width, r.height) < 8 * _NEAR:
        return ()
    lo, hi = (r.x0, r.x1) if r.width >= r.height else (r.y0, r.y1)
    if lo >= 0:
        cut = lo + max(_NEAR, lo)
    elif hi <= 0:
        cut = hi - max(_NEAR, -hi)
    else:
        cut = _NEAR if hi >= -lo else -_NEAR
    frac = (cut - lo) / (hi - lo)
    return (frac,) if 0.01 < frac < 0.35 or 0.65 < frac < 0.99 else ()


def _grid_roots(fast: FastCharacteristic, rect: Region, k: int) -> list[Mpc]:
    """Distinct roots inside ``rect`` reached by Newton's method from a 7 x 7 grid of starts (at most k)."""
    found: list[complex] = []
    xs = np.linspace(rect.x0, rect.x1, 9)[1:-1]
    ys = np.linspace(rect.y0, rect.y1, 9)[1:-1]
    for y in ys:
        for x in xs:
            z = complex(x, y)
            if not rect.contains(z):
                continue
            q = _newton_from(fast, z, rect)
            if q is not None and all(abs(q - o) > 1e-9 * max(1.0, abs(q)) for o in found):
                found.append(q)
    return [mpmath.mpc(q) for q in found[:k]]


def _newton_from(fast: FastCharacteristic, q: complex, rect: Region) -> complex | None:
    """Double-precision Newton from ``q``; the root if it converges inside ``rect``."""
    for _ in range(40):
        try:
            E, dE = (complex(v[0]) for v in fast.value_and_derivative(np.array([q])))
        except MovingBogieError:
            return None
        if dE == 0 or not np.isfinite(dE) or not np.isfinite(E):
            return None
        step = E / dE
        q -= step
        if abs(step) < 1e-13 * max(1, abs(q)):
            return q if rect.contains(q) else None
    return None


def newton_inside(fast: FastCharacteristic, rect: Region, starts: int = 9) -> Mpc | None:
    """Double-precision Newton steps from the cell centre and, in a long cell (one along the cut holds its
    root anywhere along it), from ``starts - 1`` more points along its longer side, all in one batch; an
    iterate leaving the cell's box by more than a quarter of its size is dropped. Returns the first root
    reached that lies in the cell: the cell holds one root by its count, so a root found in it is that one.
    """
    return newton_inside_many(fast, [rect], starts)[0]


def _starts(rect: Region, starts: int) -> np.ndarray:
    """The Newton starts of :func:`newton_inside` in ``rect``: its centre first."""
    c = complex(rect.center)
    long = max(rect.width, rect.height) > 4 * min(rect.width, rect.height)
    u = (np.arange(starts) - (starts - 1) / 2) / starts if long else np.zeros(1)
    u = u[np.argsort(np.abs(u), kind="stable")]  # the centre first
    return c + u * (rect.width if rect.width >= rect.height else 1j * rect.height)


def newton_inside_many(fast: FastCharacteristic, rects: list[Region], starts: int = 9) -> list[Mpc | None]:
    """:func:`newton_inside` of several cells at once: the starts of all of them are one batch, so each
    Newton iteration is one evaluation of E_chr and dE_chr/dq for every cell (what costs is mostly the
    call, not the points). Each cell's iterates stay its own: the same steps, kept or dropped by its box."""
    if not rects:
        return []
    firsts = [_starts(r, starts) for r in rects]
    q = np.concatenate(firsts)
    owner = np.concatenate([np.full(z.size, k) for k, z in enumerate(firsts)])
    boxes = np.array([_box(r) for r in rects], dtype=float)[owner]
    live = np.ones(q.size, dtype=bool)
    done = np.zeros(q.size, dtype=bool)
    for _ in range(30):
        idx = np.nonzero(live & ~done)[0]
        if not idx.size:
            break
        try:
            E, dE = (np.asarray(v, dtype=complex) for v in fast.value_and_derivative(q[idx]))
        except MovingBogieError:
            return [None] if len(rects) == 1 else _one_by_one(fast, rects, starts)
        with np.errstate(all="ignore"):
            step = E / dE
        ok = np.isfinite(step) & (dE != 0)
        q[idx[ok]] -= step[ok]
        z, box = q[idx], boxes[idx]
        inside = (z.real >= box[:, 0]) & (z.real <= box[:, 1]) & (z.imag >= box[:, 2]) & (z.imag <= box[:, 3])
        live[idx[~(ok & inside)]] = False
        done[idx[ok]] = np.abs(step[ok]) < 1e-13 * np.maximum(1, np.abs(q[idx[ok]]))
    found: list[Mpc | None] = [None] * len(rects)
    for k in np.nonzero(live & done)[0]:
        cell = int(owner[k])
        if found[cell] is None and rects[cell].contains(complex(q[k])):
            found[cell] = mpmath.mpc(complex(q[k]))
    return found


def _box(rect: Region) -> tuple[float, float, float, float]:
    """The cell's bounding box widened by a quarter of its size: Newton iterates that leave it are dropped."""
    margin = 0.25 * max(rect.width, rect.height)
    return (rect.x0 - margin, rect.x1 + margin, rect.y0 - margin, rect.y1 + margin)


def _one_by_one(fast: FastCharacteristic, rects: list[Region], starts: int) -> list[Mpc | None]:
    """Each cell on its own, when the batch could not be evaluated (one cell's failure stays its own)."""
    return [newton_inside_many(fast, [r], starts)[0] for r in rects]
