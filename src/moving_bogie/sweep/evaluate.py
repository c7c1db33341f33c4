"""The work of one block of a sweep (run on a worker): a verdict for every point, as plain arrays.

Every point gets the number of unstable induced frequencies (roots of E_chr, Eq. (38), with Im q < 0) and
the degree of instability, from the column count of :mod:`moving_bogie.stability.maps.column` (argument
principle over a whole column of eta_M, kappa_v or eta_v values, roots by Newton's method continued from
the neighbouring alpha). Points the column count cannot settle get a full count
(:func:`~moving_bogie.roots.frequencies.induced_frequencies`); ``check`` further points per block, drawn
at random with the block's index as seed, are verified by a full count too, and a disagreement replaces
the verdict (``checked = -1``). A point whose count no method could certify has ``certain = False``,
``n_unstable = -1`` and a NaN degree: it is never classified. The ``margin`` of a point, measured when the
task asks for it (``margin``), is the smallest Im q of its induced frequencies
(:mod:`~moving_bogie.stability.maps.column_margin`); it costs about three times the count, so a block without
it has no ``margin`` and ``margin_bound`` arrays (:data:`MARGIN_VARIABLES`).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field
from fractions import Fraction
from typing import TypeAlias

import numpy as np

from moving_bogie.errors import MovingBogieError
from moving_bogie.kernels.bound import BoundModel
from moving_bogie.stability.maps.column import ColumnResult
from moving_bogie.stability.maps.map import map_columns

__all__ = ["BlockTask", "MARGIN_VARIABLES", "VARIABLES", "evaluate_block"]

#: Data variables of a block: (name, dtype, fill value, description).
VARIABLES = (
    ("stable", "bool", False, "no induced frequency with Im q < 0 (False where not certain)"),
    (
        "n_unstable",
        "int16",
        -1,
        "number of unstable induced frequencies, pairs q, -conj(q) once (-1: unknown)",
    ),
    ("degree_of_instability", "float64", np.nan, "most negative Im q; 0 where stable, NaN where not certain"),
    (
        "margin",
        "float64",
        np.nan,
        "smallest Im q of the induced frequencies: the decay rate where stable, the degree where unstable; "
        "NaN where undetermined; in 1/s (Im omega = Im q / t_scale) in a sweep in SI units",
    ),
    (
        "margin_bound",
        "bool",
        False,
        "the margin is a lower bound: no root of the column's window lies below it (above it, or the cut)",
    ),
    ("certain", "bool", False, "the count is certified (column count or full count)"),
    ("settled", "bool", False, "the verdict comes from a full count (induced_frequencies)"),
    ("checked", "int8", 0, "verified by a full count: 1 agreed, -1 disagreed (verdict replaced), 0 not"),
    ("computed", "bool", False, "the point's block has been computed and written"),
)

#: The variables of :data:`VARIABLES` that only a block measuring the margin has.
MARGIN_VARIABLES = ("margin", "margin_bound")


@dataclass(frozen=True)
class BlockTask:
    """What a worker needs for one block: parameters (with their model), the block's values of each varied
    parameter.

    ``design`` "grid": ``values[k]`` are the block's values along dimension k; "sobol": one value per
    point for every parameter. ``fixed`` holds groups at their base value with every point's changes
    (:attr:`~moving_bogie.sweep.design.SweepSpec.fixed`).
    """

    index: int
    bound: BoundModel
    names: tuple[str, ...]
    values: tuple[tuple[Fraction, ...], ...]
    design: str
    column: str | None
    roots: bool
    max_roots: int
    check: int
    fixed: dict[str, Fraction] = field(default_factory=dict)
    held: tuple[str, ...] = ()
    margin: bool = False

    def evaluate(self) -> dict[str, np.ndarray]:
        """:func:`evaluate_block` of this task."""
        return evaluate_block(self)


#: A block index (one entry per dimension of the block).
Index: TypeAlias = tuple[int, ...]
#: Points counted as one group: (changes of the other varied parameters, exact alphas or None, exact
#: thetas or None, the block index of each alpha (row) and theta (entry)).
PointGroup: TypeAlias = tuple[
    dict[str, Fraction], list[Fraction] | None, list[Fraction] | None, list[list[Index]]
]


def evaluate_block(task: BlockTask) -> dict[str, np.ndarray]:
    """Arrays of the block (shape of the block; ``roots_re``/``roots_im`` with a trailing root axis; the
    :data:`MARGIN_VARIABLES` only when ``task.margin``)."""
    if task.design == "sobol":
        shape: tuple[int, ...] = (len(task.values[0]),)
        groups: list[PointGroup] = [(_point(task, (i,)), None, None, [[(i,)]]) for i in range(shape[0])]
    else:
        shape = tuple(len(v) for v in task.values)
        groups = _grid_groups(task)
    n = np.full(shape, -1, dtype=np.int16)
    degree = np.full(shape, np.nan)
    margin = np.full(shape, np.nan)
    bound = np.zeros(shape, dtype=bool)
    certain = np.zeros(shape, dtype=bool)
    settled = np.zeros(shape, dtype=bool)
    roots = np.full((*shape, task.max_roots), complex(np.nan, np.nan))
    # without a column every point is a column of one at its own wheel mass: nothing varies, nothing is held
    parameter, held = (task.column, task.held) if task.column else (task.bound.model.wheel_mass, ())
    for changes, alphas, thetas, index_grid in groups:
        point = task.bound.replace(**(task.fixed | changes)) if changes else task.bound
        alphas = alphas if alphas is not None else [point.params.alpha]
        thetas = thetas if thetas is not None else [getattr(point.params, parameter)]
        options = {"margin": task.margin}
        columns = map_columns(point, parameter, alphas, thetas, options, held=held)
        for col, row in zip(columns, index_grid):
            col_settled, col_margin, col_bound = _settled_and_margins(col)
            for j, index in enumerate(row):
                settled[index] = bool(col_settled[j])
                if not col.uncertain[j]:
                    certain[index] = True
                    n[index] = col.count[j]
                    degree[index] = col.degree[j]
                    margin[index] = col_margin[j]
                    bound[index] = bool(col_bound[j])
                    r = col.roots[j][: task.max_roots]
                    roots[index][: len(r)] = r
    checked = _check(task, shape, n, degree, certain, settled, roots, (margin, bound))
    out = {
        "stable": certain & (n == 0),
        "n_unstable": n,
        "degree_of_instability": degree,
        "certain": certain,
        "settled": settled,
        "checked": checked,
        "computed": np.ones(shape, dtype=bool),
    }
    if task.margin:
        out["margin"], out["margin_bound"] = margin, bound
    if task.roots:
        out["roots_re"], out["roots_im"] = roots.real.copy(), roots.imag.copy()
    return out


def _settled_and_margins(col: ColumnResult) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``settled``, ``margin`` and ``margin_bound`` of a column of :func:`map_columns`, which fills them all
    (a column is settled; its margins are NaN where not measured)."""
    if col.settled is None or col.margin is None or col.margin_bound is None:
        raise RuntimeError("map_columns returned a column without its settled cells or margins")
    return col.settled, col.margin, col.margin_bound


def _grid_groups(task: BlockTask) -> list[PointGroup]:
    """(changes, exact alphas or None, exact thetas or None, block index per alpha and theta) for every
    combination of the values of the other varied parameters."""
    names = task.names
    ia = names.index("alpha") if "alpha" in names else None
    it = names.index(task.column) if task.column else None
    others = [k for k in range(len(names)) if k not in (ia, it)]
    n_alpha = len(task.values[ia]) if ia is not None else 1
    n_theta = len(task.values[it]) if it is not None else 1
    out: list[PointGroup] = []
    for combo in itertools.product(*(range(len(task.values[k])) for k in others)):
        index_grid: list[list[Index]] = []
        for a in range(n_alpha):
            row: list[Index] = []
            for t in range(n_theta):
                index = [0] * len(names)
                for k, i in zip(others, combo):
                    index[k] = i
                if ia is not None:
                    index[ia] = a
                if it is not None:
                    index[it] = t
                row.append(tuple(index))
            index_grid.append(row)
        changes = {names[k]: task.values[k][i] for k, i in zip(others, combo)}
        alphas = list(task.values[ia]) if ia is not None else None
        thetas = list(task.values[it]) if it is not None else None
        out.append((changes, alphas, thetas, index_grid))
    return out


def _point(task: BlockTask, index: Index) -> dict[str, Fraction]:
    if task.design == "sobol":
        return {name: vals[index[0]] for name, vals in zip(task.names, task.values)}
    return {name: vals[i] for name, vals, i in zip(task.names, task.values, index)}


def _check(
    task: BlockTask,
    shape: Index,
    n: np.ndarray,
    degree: np.ndarray,
    certain: np.ndarray,
    settled: np.ndarray,
    roots: np.ndarray,
    margins: tuple[np.ndarray, np.ndarray],
) -> np.ndarray:
    """Verify ``task.check`` random points of the block by a full count (module text); a replaced verdict
    takes its margin (``margins``: the arrays of the margin and its bound flag) from that count."""
    from moving_bogie.roots.frequencies import induced_frequencies

    checked = np.zeros(shape, dtype=np.int8)
    candidates = [i for i in np.ndindex(shape) if certain[i] and not settled[i]]
    if not candidates or task.check <= 0:
        return checked
    rng = np.random.default_rng(task.index)
    for k in rng.choice(len(candidates), size=min(task.check, len(candidates)), replace=False):
        index = candidates[int(k)]
        try:
            res = induced_frequencies(task.bound.replace(**(task.fixed | _point(task, index))), dps=15)
        except MovingBogieError:
            continue
        if not (res.count_ok and res.verdict.determined):
            continue
        unstable = sorted((complex(r.q) for r in res.unstable_roots), key=lambda q: q.imag)
        if len(unstable) == n[index]:
            checked[index] = 1
            continue
        checked[index] = -1
        n[index] = len(unstable)
        degree[index] = min([0.0, *(q.imag for q in unstable)])
        margins[0][index] = min((float(r.q.imag) for r in res.roots), default=np.nan)
        margins[1][index] = False
        roots[index][:] = complex(np.nan, np.nan)
        roots[index][: min(len(unstable), task.max_roots)] = unstable[: task.max_roots]
        settled[index] = True
    return checked
