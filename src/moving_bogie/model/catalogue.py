"""Models as data: every model (beam x track x vehicle) and its parameters, read from the generated kernels.

``python -m derivations`` writes, beside the kernels, a catalogue (``generated/__init__.py``: beams, tracks,
vehicles and which module holds each combination) and the metadata of every dimensionless group
(``generated/parameters.py``: meaning, constraint, default, equation, SI name and unit, exact scaling).
This module turns them into :class:`Model` and :class:`ParameterSpec` objects; nothing here names a model
or a parameter. A catalogue generated elsewhere (a scratch copy of ``derivations/`` with a new model) is
loaded with :func:`load_catalogue` and used exactly like the packaged one.
"""

from __future__ import annotations

import dataclasses
import functools
import importlib
import importlib.util
import itertools
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path
from types import ModuleType

from moving_bogie.errors import ParameterError, did_you_mean
from moving_bogie.model.periodic import PERIODIC, periodic_foundations, periodic_specs

__all__ = [
    "Catalogue",
    "Model",
    "ParameterSpec",
    "contact_spring_vehicle",
    "default_catalogue",
    "get_model",
    "load_catalogue",
]

#: The paper's model: Euler-Bernoulli beam, one-layer track, the bogie of Figure 1b.
DEFAULT_MODEL = {"beam": "eb", "track": "one-layer", "vehicle": "bogie"}


@dataclass(frozen=True)
class ParameterSpec:
    """One dimensionless group, as generated from ``derivations/symbols.py``.

    Attributes
    ----------
    name : str
        The group's name (``"eta_f"``); its command-line option is :attr:`option`.
    meaning : str
        Its definition in words.
    constraint : {"positive", "nonnegative", "underdamped"}
        ``> 0``, ``>= 0``, or ``0 <= x < 1`` (an under-damped foundation).
    equation : str
        The paper's equation that defines it, e.g. ``"(17)"``.
    default : Fraction or None
        Used when an input leaves it out; None when it is required.
    si, unit, si_meaning : str
        The SI parameter it scales, its unit and meaning.
    damping : bool
        Whether it is a viscous damping group (zero on the undamped track of the critical velocity).
    """

    name: str
    meaning: str
    constraint: str
    equation: str
    default: Fraction | None
    si: str
    unit: str
    si_meaning: str
    damping: bool = False

    @property
    def option(self) -> str:
        """Command-line option: ``--eta-f`` for ``eta_f``."""
        return "--" + self.name.replace("_", "-")

    @property
    def range_text(self) -> str:
        """The constraint as a formula, for messages and listings."""
        return {"positive": "> 0", "nonnegative": ">= 0", "underdamped": "0 <= x < 1"}[self.constraint]

    def to_dict(self) -> dict:
        """JSON-ready description."""
        default = None if self.default is None else str(self.default)
        return {
            "name": self.name,
            "meaning": self.meaning,
            "constraint": self.range_text,
            "equation": self.equation,
            "default": default,
            "option": self.option,
            "si": {"name": self.si, "unit": self.unit, "meaning": self.si_meaning},
        }


@dataclass(frozen=True)
class Catalogue:
    """The models of one generated package: its index, its parameter metadata and its kernel modules."""

    index: ModuleType
    parameters: ModuleType
    modules: dict = field(repr=False, compare=False)

    def module(self, name: str) -> ModuleType:
        """The generated module ``name`` (``"foundation_eb"``, ``"vehicle_bogie"``) of this catalogue."""
        return self.modules[name]

    @functools.cached_property
    def _sleepers(self) -> ModuleType | None:
        """The generated rails on discrete supports (``sleepers``), None in a catalogue without them."""
        try:
            return self.module("sleepers")
        except ModuleNotFoundError:
            return None

    @functools.cached_property
    def periodic(self) -> dict:
        """(beam, track) -> :class:`~moving_bogie.model.periodic.PeriodicFoundation` of the rails on
        periodic supports (docs/sleepers.md)."""
        return periodic_foundations(self._sleepers, self.parameters)

    def foundation(self, beam: str, track: str) -> ModuleType:
        """The generated foundation of ``beam`` on ``track`` (a module, or a periodic track's metadata)."""
        if (beam, track) in self.periodic:
            found: ModuleType = self.periodic[(beam, track)]
            return found
        return self.module(self.index.MODULES[(beam, track)])

    def has_kernel(self, beam: str, track: str) -> bool:
        """Whether ``beam`` on ``track`` has generated kernels (continuous or periodic)."""
        return (beam, track) in self.index.MODULES or (beam, track) in self.periodic

    @functools.cached_property
    def specs(self) -> dict[str, ParameterSpec]:
        """Every dimensionless group of the catalogue, in declaration order (the periodic tracks' own
        groups last)."""
        out = {}
        metas = dict(self.parameters.PARAMETERS)
        for name, meta in periodic_specs(self._sleepers).items():
            metas.setdefault(name, meta)
        for name, meta in metas.items():
            default = None if meta["default"] is None else Fraction(meta["default"])
            out[name] = ParameterSpec(
                name,
                meta["meaning"],
                meta["constraint"],
                meta["equation"],
                default,
                meta["si"],
                meta["unit"],
                meta["si_meaning"],
                meta.get("damping", False),
            )
        return out

    @property
    def beams(self) -> dict[str, str]:
        return dict(self.index.BEAMS)

    @property
    def tracks(self) -> dict[str, str]:
        sleepers = self._sleepers
        periodic = {} if sleepers is None else {t: m["description"] for t, m in sleepers.TRACKS.items()}
        return dict(self.index.TRACKS) | periodic

    @property
    def vehicles(self) -> dict[str, str]:
        return dict(self.index.VEHICLES)

    def models(self) -> list[Model]:
        """Every model of the catalogue: each beam on each track under each vehicle."""
        kernels = [*self.index.MODULES, *self.periodic]
        return [
            Model(beam, track, vehicle, self)
            for (beam, track), vehicle in itertools.product(kernels, self.vehicles)
        ]


class _LazyModules(dict[str, ModuleType]):
    """Generated modules imported on first use (a model's kernels are loaded only when it is used)."""

    def __init__(self, load: Callable[[str], ModuleType]) -> None:
        super().__init__()
        self._load = load

    def __missing__(self, name: str) -> ModuleType:
        module = self[name] = self._load(name)
        return module


@functools.cache
def default_catalogue() -> Catalogue:
    """The catalogue shipped in :mod:`moving_bogie.generated`."""
    index = importlib.import_module("moving_bogie.generated")
    parameters = importlib.import_module("moving_bogie.generated.parameters")
    modules = _LazyModules(lambda name: importlib.import_module(f"moving_bogie.generated.{name}"))
    return Catalogue(index, parameters, modules)


def load_catalogue(folder: str | Path) -> Catalogue:
    """The catalogue written by ``python -m derivations --root ROOT`` into ``folder``.

    ``folder`` is the generated folder itself (``ROOT/src/moving_bogie/generated``). Its modules import
    nothing, so they are loaded straight from their files under private module names; the packaged
    catalogue is left untouched.

    Raises
    ------
    ParameterError
        Naming ``catalogue`` when the folder holds no generated catalogue.
    """
    folder = Path(folder)
    if not (folder / "__init__.py").is_file() or not (folder / "parameters.py").is_file():
        raise ParameterError(
            "catalogue", f"{folder} holds no generated catalogue (__init__.py, parameters.py)"
        )
    tag = f"moving_bogie_catalogue_{abs(hash(str(folder.resolve())))}"

    def load(name: str) -> ModuleType:
        path = folder / ("__init__.py" if name == "__init__" else f"{name}.py")
        if not path.is_file():
            raise ModuleNotFoundError(f"no generated module {name!r} in {folder}")
        spec = importlib.util.spec_from_file_location(f"{tag}.{name}", path)
        assert spec is not None and spec.loader is not None  # a file location always has a loader
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        return module

    return Catalogue(load("__init__"), load("parameters"), _LazyModules(load))


@dataclass(frozen=True)
class Model:
    """A model: a beam on a track under a vehicle, with its generated kernels and parameters.

    Attributes
    ----------
    beam, track, vehicle : str
        Names from the catalogue (``moving-bogie models`` lists them).
    catalogue : Catalogue
        Where its kernels come from (the packaged one unless loaded with :func:`load_catalogue`).
    """

    beam: str
    track: str
    vehicle: str
    catalogue: Catalogue = field(default_factory=default_catalogue, repr=False, compare=False)

    @property
    def name(self) -> str:
        """``beam/track/vehicle``."""
        return f"{self.beam}/{self.track}/{self.vehicle}"

    @property
    def foundation(self) -> ModuleType:
        """Generated kernel of the beam on its track: N(p, q), Q(p, q) and their derivatives (Eq. (24)); on
        periodic supports the :class:`~moving_bogie.model.periodic.PeriodicFoundation` of the rail."""
        return self.catalogue.foundation(self.beam, self.track)

    @property
    def periodic(self) -> bool:
        """Whether the track's supports repeat every bay (a rail on sleepers, docs/sleepers.md)."""
        return getattr(self.foundation, "TRACK_KIND", None) == PERIODIC

    @property
    def vehicle_kernels(self) -> ModuleType:
        """Generated kernel of the vehicle: E_chr, its partials, residue numerators (Eqs. (36)-(47))."""
        return self.catalogue.module(f"vehicle_{self.vehicle}")

    @functools.cached_property
    def parameters(self) -> tuple[str, ...]:
        """The dimensionless groups this model needs, in the catalogue's order."""
        used = set(self.foundation.MODEL_PARAMETERS) | set(self.vehicle_kernels.MODEL_PARAMETERS)
        return tuple(name for name in self.catalogue.specs if name in used)

    @functools.cached_property
    def specs(self) -> dict[str, ParameterSpec]:
        """:class:`ParameterSpec` of each of :attr:`parameters`, with this track's SI names and meanings.

        A track may name SI parameters its own way (the railpads ``k_1``, ``c_1`` of a layered track stand
        where the one-layer track has ``k_f``, ``c_f``); the generated ``GROUP_OVERRIDES`` say so.
        """
        overrides = getattr(self.foundation, "GROUP_OVERRIDES", {})
        return {
            name: dataclasses.replace(self.catalogue.specs[name], **overrides.get(name, {}))
            for name in self.parameters
        }

    @property
    def scale_parameters(self) -> dict[str, dict]:
        """SI parameters that set the scales of Eqs. (15)-(16) on this track: name -> unit and meaning.

        ``EI``, ``m``, the reference stiffness (``k_f``; ``k_1`` on a layered track) and the load ``P``.
        """
        own = getattr(self.foundation, "SCALE_PARAMETERS", None)
        return dict(own if own is not None else self.catalogue.parameters.SCALE_PARAMETERS)

    @property
    def si_names(self) -> dict[str, str]:
        """The catalogue's SI name -> this track's SI name, for the names a track renames."""
        return dict(getattr(self.foundation, "SI_NAMES", {}))

    @property
    def damping(self) -> tuple[str, ...]:
        """The model's viscous damping groups (foundation and vehicle), in the catalogue's order."""
        return tuple(name for name, spec in self.specs.items() if spec.damping)

    @property
    def alternatives(self) -> dict[str, dict]:
        """Alternative inputs valid for this model (Table 1's cf1, cf2 of Eq. (63)): name -> metadata."""
        out = {}
        for name, meta in self.catalogue.parameters.ALTERNATIVES.items():
            if meta["sets"] in self.parameters and set(meta["depends"]) <= set(self.parameters):
                out[name] = meta
        return out

    @property
    def wheel_mass(self) -> str:
        """The group of the wheels' mass (the generated ``WHEEL_MASS``): the default axis of the stability
        maps, lines and sweeps beside the velocity alpha."""
        return self.vehicle_kernels.WHEEL_MASS

    @property
    def primary_stiffness(self) -> str | None:
        """The group of the stiffness on the wheels, the primary suspension (the generated
        ``PRIMARY_STIFFNESS``; None for a vehicle without one): the critical stiffness's parameter."""
        return self.vehicle_kernels.PRIMARY_STIFFNESS

    @property
    def degrees(self) -> dict[str, int]:
        """Degrees of N and Q in p (Eq. (24)) and of N in q."""
        f = self.foundation
        return {"N_in_p": f.DEGREE_N, "Q_in_p": f.DEGREE_Q, "N_in_q": f.DEGREE_N_IN_Q}

    def to_dict(self) -> dict:
        """JSON-ready description: names, descriptions, degrees, parameters with SI units."""
        return {
            "beam": self.beam,
            "track": self.track,
            "vehicle": self.vehicle,
            "description": self.foundation.DESCRIPTION,
            "vehicle_description": self.catalogue.vehicles[self.vehicle],
            "degrees": self.degrees,
            "parameters": [spec.to_dict() for spec in self.specs.values()],
            "alternatives": {
                name: dict(meta, depends=list(meta["depends"])) for name, meta in self.alternatives.items()
            },
            "scale_parameters": self.scale_parameters,
        }


def get_model(
    beam: str | None = None,
    track: str | None = None,
    vehicle: str | None = None,
    catalogue: Catalogue | None = None,
) -> Model:
    """The model of a catalogue by its names (None: the paper's choice, :data:`DEFAULT_MODEL`).

    Raises
    ------
    ParameterError
        Naming ``beam``, ``track`` or ``vehicle`` and listing the valid names.
    """
    catalogue = catalogue or default_catalogue()
    chosen = {"beam": beam, "track": track, "vehicle": vehicle}
    valid = {"beam": catalogue.beams, "track": catalogue.tracks, "vehicle": catalogue.vehicles}
    names: dict[str, str] = {}
    for key, value in chosen.items():
        if value is None:
            names[key] = DEFAULT_MODEL[key]
        elif value not in valid[key]:
            hint = did_you_mean(value, valid[key])
            message = f"{key} must be one of {', '.join(valid[key])} (got {value!r})"
            raise ParameterError(key, message + (f"; {hint}" if hint else ""))
        else:
            names[key] = value
    if not catalogue.has_kernel(names["beam"], names["track"]):
        raise ParameterError(
            "track", f"no generated kernel for beam {names['beam']!r} on track {names['track']!r}"
        )
    return Model(catalogue=catalogue, beam=names["beam"], track=names["track"], vehicle=names["vehicle"])


def contact_spring_vehicle(vehicle: str, keys: Iterable[str], catalogue: Catalogue | None = None) -> str:
    """The vehicle a parameter set with these `keys` runs: `vehicle` itself, or its variant on Hertz contact
    springs when a key sets the contact spring (a generated ``CONTACT_SPRING_GROUPS`` group or its SI name:
    ``k_H``, ``c_H``, ``kappa_H``, ``eta_H``) and the catalogue's ``CONTACT_SPRINGS`` gives `vehicle` one
    (``bogie`` -> ``hertz_bogie``). A vehicle without a variant (one already on contact springs, or an
    unknown name, which the model's lookup then reports) is returned as it is.
    """
    catalogue = catalogue or default_catalogue()
    groups = catalogue.index.CONTACT_SPRING_GROUPS
    contact = set(groups) | {catalogue.specs[group].si for group in groups}
    if contact.isdisjoint(keys):
        return vehicle
    return str(catalogue.index.CONTACT_SPRINGS.get(vehicle, vehicle))
