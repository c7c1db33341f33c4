"""The points of a parameter sweep: varied parameters, their values, and the blocks the work is cut into.

A sweep is a base parameter set plus any number of varied parameters. On a grid, each varied parameter is
one dimension (``alpha=0.3:0.95:200`` is 200 values from 0.3 to 0.95, ``eta_f=0.01,0.05,0.1`` a list);
a quasi-random design (``sobol:N``, :class:`scipy.stats.qmc.Sobol`) puts N points in the box spanned by
the ranges, along one dimension ``point``. Values are exact: decimal text is read as a Fraction (as the
command line reads every number), grid values are start + (stop - start) k / (count - 1) exactly, and a
Sobol coordinate is the Fraction of its shortest decimal text.

The grid is cut into blocks (one chunk of the store each). A block keeps the whole axis of one parameter
in which E_chr is a polynomial (eta_M, kappa_v or eta_v: a "column", counted at once) and a run of alpha
values (continuation from one column to the next); every other varied parameter is one value per block.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Collection, Container, Mapping
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import numpy as np

from moving_bogie.errors import ParameterError
from moving_bogie.kernels.bound import BoundModel
from moving_bogie.kernels.sweep_characteristic import polynomial_degree
from moving_bogie.model.bar import DEFAULT_BAR, held_groups
from moving_bogie.model.exact import fraction_to_text
from moving_bogie.model.params import DimensionlessParams
from moving_bogie.model.physical import PhysicalParams

__all__ = [
    "Axis",
    "group_coordinate",
    "grid_blocks",
    "Block",
    "SweepSpec",
    "parameter_attributes",
    "parse_sample",
    "parse_vary",
    "si_attributes",
    "sobol_axes",
    "sweep_parameters",
]


def sweep_parameters(params: DimensionlessParams, *, si: bool = False) -> tuple[str, ...]:
    """Names a sweep of ``params`` may vary, from the model's metadata: the groups of its model and their
    alternatives (cf1, cf2 of Eq. (63)); with ``si=True`` (a ``[physical]`` input) the SI counterpart of
    each group instead (``v``, ``M``, ...)."""
    if si:
        return tuple(spec.si for spec in params.model.specs.values())
    return (*params.model.parameters, *params.model.alternatives)


def si_attributes(params: DimensionlessParams, group: str) -> dict[str, str]:
    """Attributes of the SI coordinate of ``group``: its SI unit, name and meaning, and the group it
    scales to (Eqs. (15)-(17), (59)), from the model's metadata."""
    spec = params.model.specs[group]
    return {
        "units": spec.unit,
        "long_name": spec.si,
        "meaning": spec.si_meaning,
        "group": group,
        "equation": spec.equation,
    }


def group_coordinate(axis: Axis, si_names: Container[str]) -> str:
    """Name of the coordinate that keeps the dimensionless group of an SI axis: the group's name, or
    ``<group>_dimensionless`` where an SI parameter has the same name (the spacing ``d``)."""
    return f"{axis.name}_dimensionless" if axis.name in si_names else axis.name


def parameter_attributes(params: DimensionlessParams, name: str) -> dict[str, str]:
    """Attributes of a varied parameter's coordinate: units ("1": every group is dimensionless), meaning
    and equation from the model's metadata."""
    out = {"units": "1", "long_name": name}
    spec = params.model.specs.get(name)
    if spec is not None:
        out.update(meaning=spec.meaning, equation=spec.equation)
    elif name in params.model.alternatives:
        out["meaning"] = params.model.alternatives[name]["meaning"]
    return out


def _number(option: str, text: str) -> Fraction:
    try:
        return Fraction(text.strip())
    except (ValueError, ZeroDivisionError):
        raise ParameterError(option, f"{option}: not a number: {text!r}") from None


def parse_vary(
    text: str, known: Collection[str], *, option: str = "--vary", needs_count: bool = True
) -> tuple[str, tuple[Fraction, ...]]:
    """``NAME=START:STOP:COUNT`` or ``NAME=V1,V2,...`` -> (name, exact values); NAME one of ``known``.

    With ``needs_count=False`` (a quasi-random design), ``NAME=START:STOP`` gives the range (start, stop).

    Raises
    ------
    ParameterError
        Naming ``option`` for malformed text or an unknown name.
    """
    name, sep, spec = text.partition("=")
    name = name.strip()
    if not sep or not name or not spec.strip():
        raise ParameterError(option, f"{option} {text!r}: expected NAME=START:STOP:COUNT or NAME=V1,V2,...")
    if name not in known:
        names = ", ".join(known)
        raise ParameterError(option, f"{option} {text!r}: unknown parameter {name!r} (known: {names})")
    if ":" in spec:
        parts = spec.split(":")
        if not needs_count and len(parts) == 2:
            start, stop = (_number(option, p) for p in parts)
            if start == stop:
                raise ParameterError(option, f"{option} {text!r}: empty range")
            return name, (start, stop)
        if len(parts) != 3:
            raise ParameterError(option, f"{option} {text!r}: a range is START:STOP:COUNT")
        start, stop = _number(option, parts[0]), _number(option, parts[1])
        try:
            count = int(parts[2])
        except ValueError:
            raise ParameterError(option, f"{option} {text!r}: COUNT must be an integer") from None
        if count < 1 or (count == 1 and start != stop):
            raise ParameterError(option, f"{option} {text!r}: COUNT must be >= 2 (or 1 with START = STOP)")
        if not needs_count:
            return name, (start, stop)
        values = (
            (start,) if count == 1 else tuple(start + (stop - start) * k / (count - 1) for k in range(count))
        )
        return name, values
    values = tuple(_number(option, v) for v in spec.split(",") if v.strip())
    if not values or len(set(values)) != len(values):
        raise ParameterError(option, f"{option} {text!r}: give distinct values")
    if not needs_count:
        raise ParameterError(option, f"{option} {text!r}: a sampled parameter needs a range START:STOP")
    return name, values


def parse_sample(text: str) -> int:
    """``sobol:N`` -> N (the number of quasi-random points)."""
    kind, _, n = text.partition(":")
    if kind.strip() != "sobol" or not n.strip().isdigit() or int(n) < 1:
        raise ParameterError("--sample", f"--sample {text!r}: expected sobol:N with N >= 1")
    return int(n)


@dataclass(frozen=True)
class Axis:
    """One varied parameter: its name and exact values (on a Sobol design, one value per point).

    ``name`` and ``values`` are always the dimensionless group the computation uses. An axis given in SI
    units (a ``[physical]`` input) also keeps the SI parameter ``si``, its ``unit`` and the exact SI
    ``si_values`` it was given, of which ``values`` are the groups (Eqs. (15)-(17), (59)).
    """

    name: str
    values: tuple[Fraction, ...]
    si: str | None = None
    unit: str | None = None
    si_values: tuple[Fraction, ...] = ()

    @property
    def label(self) -> str:
        """The name the store and the figures use: the SI name, or the group's name."""
        return self.si or self.name

    @property
    def si_floats(self) -> np.ndarray:
        return np.array([float(v) for v in self.si_values])

    @property
    def floats(self) -> np.ndarray:
        return np.array([float(v) for v in self.values])


@dataclass(frozen=True)
class Block:
    """One chunk of the sweep: index slices into each dimension of the store."""

    index: int
    slices: tuple[slice, ...]


def grid_blocks(shape: tuple[int, ...], chunks: tuple[int, ...]) -> list[Block]:
    """The blocks of a store of ``shape`` cut into ``chunks``, in a fixed order (a block's index is its
    place in that order)."""
    ranges = [range(0, n, c) for n, c in zip(shape, chunks)]
    out = []
    for k, starts in enumerate(itertools.product(*ranges)):
        slices = tuple(slice(s, min(s + c, n)) for s, c, n in zip(starts, chunks, shape))
        out.append(Block(k, slices))
    return out


@dataclass(frozen=True)
class SweepSpec:
    """A sweep: base parameters, model, varied parameters, design and per-point options.

    ``design`` is "grid" (one dimension per axis) or "sobol" (one dimension ``point``). ``roots`` keeps
    the unstable roots of every point; ``margin`` measures the stability margin of every point (the
    smallest Im q of its induced frequencies: about four times the work of the count alone, so asked for
    rather than made); ``check`` is the number of points per block verified by a full count.
    ``physical`` (:class:`~moving_bogie.model.physical.PhysicalParams` of a ``[physical]`` input) makes it
    a sweep in SI units: the axes carry their SI values, the store's dimensions are the SI names.
    ``bar`` says what moves with the wheel mass (:mod:`~moving_bogie.model.bar`, :attr:`fixed`).
    """

    bound: BoundModel  # the base point's bound model: each point is bound.replace(...), its track kept
    model: str  # the vehicle's name (params.vehicle), for the store's attributes
    axes: tuple[Axis, ...]
    design: str = "grid"
    roots: bool = False
    max_roots: int = 8
    check: int = 1
    margin: bool = False
    block_points: int = 2048
    extra: dict[str, Any] = field(default_factory=dict)
    physical: PhysicalParams | None = None
    bar: str = DEFAULT_BAR

    def __post_init__(self) -> None:
        if self.model != self.params.vehicle:
            raise ParameterError(
                "model", f"model {self.model!r} is not the parameters' vehicle {self.params.vehicle!r}"
            )
        names = [a.name for a in self.axes]
        if not names:
            raise ParameterError("--vary", "give at least one --vary NAME=...")
        if len(set(names)) != len(names):
            raise ParameterError("--vary", f"--vary: a parameter is varied twice ({', '.join(names)})")
        for alternative, meta in self.params.model.alternatives.items():  # cf1 sets mu_v, Eq. (63), ...
            if alternative in names and meta["sets"] in names:
                raise ParameterError(
                    "--vary", f"--vary: vary either {alternative} or {meta['sets']}, not both"
                )
        for a in self.axes:  # every value must make valid parameters: fail before any computation
            for v in {min(a.values), max(a.values)}:
                try:
                    self.params.replace(**(self.fixed | {a.name: v}))
                except ParameterError as exc:
                    raise ParameterError("--vary", f"--vary {a.label}: {exc}") from None

    @property
    def params(self) -> DimensionlessParams:
        """The base point's parameters."""
        return self.bound.params

    @property
    def si(self) -> bool:
        """Whether the sweep is given and stored in SI units (a ``[physical]`` input)."""
        return self.physical is not None

    @property
    def fixed(self) -> dict[str, Fraction]:
        """Groups held at their base value whatever varies, passed with every point's changes: the bar's
        mu_v, J_b under the rule ``bar = "fixed"`` (M_b, J_b in SI), none under the default ``"follows"``
        (cf1, cf2 of Eq. (63) held, as in the maps and lines; :mod:`~moving_bogie.model.bar`).
        """
        return {name: getattr(self.params, name) for name in held_groups(self.params, self.bar)}

    @property
    def dims(self) -> tuple[str, ...]:
        return ("point",) if self.design == "sobol" else tuple(a.label for a in self.axes)

    @property
    def shape(self) -> tuple[int, ...]:
        return (
            (len(self.axes[0].values),) if self.design == "sobol" else tuple(len(a.values) for a in self.axes)
        )

    @property
    def size(self) -> int:
        return math.prod(self.shape)

    @property
    def held(self) -> tuple[str, ...]:
        """Groups that do not follow the parameters they depend on: those an alternative sets (mu_v, J_b,
        Eq. (63)) that are varied or :attr:`fixed`."""
        sets = {meta["sets"] for meta in self.params.model.alternatives.values()}
        return tuple(sorted(sets & ({a.name for a in self.axes} | set(self.fixed))))

    @property
    def column_parameter(self) -> str | None:
        """The varied parameter counted a whole column at a time (None on a Sobol design).

        E_chr must be a polynomial in it at fixed q and alpha: the groups that follow it (mu_v, J_b follow
        eta_M at fixed cf1, cf2) all follow, or all are :attr:`held` (a sweep in SI units over the wheel
        mass M keeps the frame's M_b and J_b: the generated ``FIXED_POLYNOMIAL_DEGREES``).
        """
        if self.design == "sobol":
            return None
        for a in self.axes:
            try:
                polynomial_degree(self.bound, a.name, set(self.held) - {a.name})
            except (ParameterError, AttributeError):
                continue
            return a.name
        return None

    @property
    def chunks(self) -> tuple[int, ...]:
        """Chunk length along each dimension (see the module text)."""
        if self.design == "sobol":
            return (min(self.block_points, self.size),)
        column = self.column_parameter
        out = [len(a.values) if a.name == column else 1 for a in self.axes]
        per_column = math.prod(out)
        stride = next((k for k, a in enumerate(self.axes) if a.name == "alpha"), None)
        if stride is None:
            stride = next((k for k, a in enumerate(self.axes) if a.name != column), None)
        if stride is not None:
            out[stride] = min(len(self.axes[stride].values), max(8, -(-self.block_points // per_column)))
        return tuple(out)

    def blocks(self) -> list[Block]:
        """Every block, in a fixed order (its index is its place in that order)."""
        return grid_blocks(self.shape, self.chunks)

    def describe(self) -> dict[str, Any]:
        """JSON-ready description (stored in the attributes; a resumed sweep must match it)."""
        return (
            {
                "model": self.model,
                "params": self.params.to_dict(),
                "design": self.design,
                "varied": self.extra.get("ranges")
                or {a.name: [fraction_to_text(v) for v in a.values] for a in self.axes},
                "points": self.size,
                "roots": self.roots,
                "max_roots": self.max_roots,
                "check": self.check,
                "margin": self.margin,
                "chunks": list(self.chunks),
            }
            | ({"bar": self.bar} if self.bar != DEFAULT_BAR else {})
            | (self._describe_si(self.physical) if self.physical is not None else {})
        )

    def _describe_si(self, physical: PhysicalParams) -> dict[str, Any]:
        varied = self.extra.get("si_ranges") or {
            a.si: [fraction_to_text(v) for v in a.si_values] for a in self.axes
        }
        return {"units": "si", "physical": physical.to_dict(), "varied_si": varied}

    def operating_point(self) -> dict[str, float]:
        """The base point's value of every varied parameter, by the store's names: the SI value of a
        ``[physical]`` input, else the group's value (the point figures mark)."""
        if self.si:
            return {a.label: float(getattr(self.physical, a.label)) for a in self.axes}
        return {a.name: float(getattr(self.params, a.name)) for a in self.axes}


def sobol_axes(ranges: Mapping[str, tuple[Fraction, ...]], n: int, *, seed: int = 0) -> tuple[Axis, ...]:
    """N quasi-random points (scrambled Sobol, fixed seed) in the box of ``ranges`` {name: (lo, hi)}."""
    import warnings

    from scipy.stats import qmc

    sampler = qmc.Sobol(len(ranges), scramble=True, seed=seed)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # balance properties want a power of 2; any N is allowed
        u = sampler.random(n)
    axes = []
    for k, (name, (lo, hi)) in enumerate(ranges.items()):
        x = float(lo) + (float(hi) - float(lo)) * u[:, k]
        axes.append(Axis(name, tuple(Fraction(repr(float(v))) for v in x)))
    return tuple(axes)
