"""The rails on periodic supports as tracks of the one catalogue (docs/sleepers.md).

``python -m derivations`` writes the rails on discrete supports every l into ``generated/sleepers.py``: per
beam the symbol, per support track (``TRACKS``) its support, its groups (``PARAMETERS[track][beam]``: SI
name, unit, constraint, default) and their exact scaling (``dimensionless_<track>_<group>``, the scales
``scales_<track>``: the paper's, Eqs. (15)-(17), with the smeared support stiffness k_e in the place of
k_f). :class:`PeriodicFoundation` presents one beam on one such track with the metadata a generated
foundation module carries (``MODEL_PARAMETERS``, ``SCALE_PARAMETERS``, ``GROUP_OVERRIDES``,
``DESCRIPTION``, ``ARGUMENTS``), so that a :class:`~moving_bogie.model.catalogue.Model` on it is a model
like any other: ``eb/sleepers/bogie`` beside ``eb/two-layer/bogie``. It also scales SI values exactly
(:meth:`PeriodicFoundation.scales`, :meth:`PeriodicFoundation.dimensionless`): the track's own groups by
its generated functions, every other group (the beam's, the vehicle's) by the paper's with k_f = k_e.
Nothing here names a track, a beam or a group: everything comes from the generated metadata.
"""

from __future__ import annotations

import functools
import importlib
import sys
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from fractions import Fraction
from types import ModuleType
from typing import Any

__all__ = ["PERIODIC", "PeriodicFoundation", "periodic_foundations", "periodic_specs"]

#: The kind of a track whose supports repeat every bay (``TRACK_KIND`` of its foundation).
PERIODIC = "periodic"

#: The equation of the sleeper groups' scaling (docs/sleepers.md).
_EQUATION = "(S2)"


@dataclass(frozen=True)
class PeriodicFoundation:
    """One beam on one track of periodic supports, with a generated foundation module's metadata.

    Attributes
    ----------
    beam, track : str
        Names of ``generated/sleepers.py`` (``BEAMS``, ``TRACKS``).
    module : module
        The generated ``sleepers`` module of the catalogue.
    paper : module
        The catalogue's generated ``parameters`` module (the paper's scaling of the other groups).
    """

    beam: str
    track: str
    module: ModuleType = field(repr=False, compare=False)
    paper: ModuleType = field(repr=False, compare=False)

    TRACK_KIND = PERIODIC

    @property
    def _table(self) -> dict[str, dict[str, Any]]:
        table: dict[str, dict[str, Any]] = self.module.PARAMETERS[self.track][self.beam]
        return table

    @property
    def _tag(self) -> str:
        return self.track.replace("-", "_")

    @property
    def reference(self) -> tuple[str, str, str]:
        """The SI reference stiffness of one support (name, unit, meaning); k_e = reference / l."""
        name, unit, meaning = self.module.TRACKS[self.track]["reference"]
        return name, unit, meaning

    @property
    def DESCRIPTION(self) -> str:  # noqa: N802 - the name of the generated modules' attribute
        """The track's description."""
        return f"{self.beam} beam: {self.module.TRACKS[self.track]['description']}"

    @property
    def MODEL_PARAMETERS(self) -> tuple[str, ...]:  # noqa: N802
        """The track's and the beam's groups."""
        return tuple(self._table)

    @property
    def ARGUMENTS(self) -> tuple[str, ...]:  # noqa: N802
        """The frequency w, then the groups of the beam's symbol and the supports."""
        return ("w", *self.MODEL_PARAMETERS)

    @property
    def SCALE_PARAMETERS(self) -> dict[str, dict[str, str]]:  # noqa: N802
        """EI, m, the reference stiffness of one support, the bay l and the load P (the scales of (S2))."""
        paper: dict[str, dict[str, str]] = self.paper.SCALE_PARAMETERS
        name, unit, meaning = self.reference
        bay = next(spec for spec in self._table.values() if spec["si"] == "l")
        out = {key: value for key, value in paper.items() if key != "k_f" and key != "P"}
        out[name] = {"unit": unit, "meaning": f"{meaning} (reference stiffness k_e = {name} / l)"}
        out["l"] = {"unit": bay["unit"], "meaning": bay["si_meaning"]}
        return out | {"P": paper["P"]}

    @property
    def GROUP_OVERRIDES(self) -> dict[str, dict[str, Any]]:  # noqa: N802
        """The SI names, meanings, constraints and defaults of the groups this track scales its own way."""
        paper: dict[str, dict[str, Any]] = self.paper.PARAMETERS
        out: dict[str, dict[str, Any]] = {
            name: {"meaning": f"{meta['meaning']}, with k_f = k_e (the smeared support stiffness)"}
            for name, meta in paper.items()
            if "k_f" in meta["meaning"]
        }
        for name, spec in self._table.items():
            default = None if spec["default"] is None else Fraction(str(spec["default"]))
            out[name] = out.get(name, {}) | {
                "si": spec["si"],
                "unit": spec["unit"],
                "si_meaning": spec["si_meaning"],
                "constraint": spec["constraint"],
                "default": default,
            }
        return out

    @property
    def DEGREE_N(self) -> int:  # noqa: N802
        """Degree of the beam's symbol N~ in p."""
        return 2 * int(self.module.BEAMS[self.beam]["degree_p2"])

    DEGREE_Q = 0
    DEGREE_N_IN_Q = None

    # --- the generated functions of this beam and track (docs/sleepers.md, (S1)-(S2)) ------------------
    @functools.cached_property
    def symbol_groups(self) -> tuple[str, ...]:
        """The groups of the beam's symbol N~, Q~ (arguments of :attr:`n_coeffs`, :attr:`q_coeffs`)."""
        return tuple(self.module.BEAMS[self.beam]["groups"])

    @functools.cached_property
    def moving_groups(self) -> tuple[str, ...]:
        """The groups of the moving symbol (arguments of :attr:`moving_n_coeffs` besides q, alpha)."""
        return tuple(self.module.BEAMS[self.beam]["moving_groups"])

    @functools.cached_property
    def support_groups(self) -> tuple[str, ...]:
        """The groups of the support's stiffness z(w) (arguments of :attr:`support`)."""
        return tuple(self.module.TRACKS[self.track]["support_arguments"])

    @functools.cached_property
    def n_coeffs(self) -> Callable[..., Any]:
        """N~(p, w) of the beam as a polynomial in p^2 (highest power first)."""
        return getattr(self.module, f"n_coeffs_{self.beam}")

    @functools.cached_property
    def q_coeffs(self) -> Callable[..., Any]:
        """Q~(p, w) of the beam as a polynomial in p^2 (highest power first)."""
        return getattr(self.module, f"q_coeffs_{self.beam}")

    @functools.cached_property
    def moving_n_coeffs(self) -> Callable[..., Any]:
        """N~(p, q + alpha p) as a polynomial in p (highest power first)."""
        return getattr(self.module, f"moving_n_coeffs_{self.beam}")

    @functools.cached_property
    def moving_q_coeffs(self) -> Callable[..., Any]:
        """Q~(p, q + alpha p) as a polynomial in p (highest power first)."""
        return getattr(self.module, f"moving_q_coeffs_{self.beam}")

    @functools.cached_property
    def support(self) -> Callable[..., Any]:
        """z(w) = (Z_s / l) / k_e of the track's supports."""
        return getattr(self.module, f"support_{self._tag}")

    @functools.cached_property
    def support_polynomials(self) -> Callable[..., Any]:
        """(numerator, denominator) of z(w) as polynomials in w (highest power first)."""
        return getattr(self.module, f"support_polynomials_{self._tag}")

    @functools.cached_property
    def damping_groups(self) -> frozenset[str]:
        """The viscous damping groups of this beam and track (the track's own by their unit, N s..., the
        others by the paper's metadata), set to zero on the undamped rail."""
        paper: dict[str, dict[str, Any]] = self.paper.PARAMETERS
        own = {name for name, spec in self._table.items() if _damping_unit(spec["unit"])}
        return frozenset(own | {name for name, meta in paper.items() if meta.get("damping", False)})

    def __reduce__(self) -> tuple[Callable[..., PeriodicFoundation], tuple[str, ...]]:
        """Pickled by its names and those of its generated modules (imported again where unpickled)."""
        return (_rebuild, (self.beam, self.track, self.module.__name__, self.paper.__name__))

    # --- scaling ------------------------------------------------------------------------------------
    def scales(self, values: Mapping[str, Any], sqrt: Callable[[Any], Any]) -> tuple[Any, Any, Any, Any]:
        """(chi, v_ref, w_st, t_scale) of (S2) from the SI ``values`` (w_st = P chi / (2 k_e))."""
        name = self.reference[0]
        chi, v_ref, t_scale, k_e = getattr(self.module, f"scales_{self._tag}")(
            sqrt, values["EI"], values["m"], values[name], values["l"]
        )
        return chi, v_ref, values["P"] * chi / (2 * k_e), t_scale

    def smeared_stiffness(self, values: Mapping[str, Any], sqrt: Callable[[Any], Any]) -> Any:
        """k_e = reference / l, the stiffness in the place of the paper's k_f."""
        name = self.reference[0]
        return getattr(self.module, f"scales_{self._tag}")(
            sqrt, values["EI"], values["m"], values[name], values["l"]
        )[3]

    def dimensionless(self, group: str, values: Mapping[str, Any], sqrt: Callable[[Any], Any]) -> Any:
        """The group ``group`` from the SI ``values``: the track's own scaling, else the paper's with
        k_f = k_e."""
        own = getattr(self.module, f"dimensionless_{self._tag}_{group}", None)
        if own is not None:
            return _call(own, values, sqrt)
        smeared = dict(values) | {"k_f": self.smeared_stiffness(values, sqrt)}
        return _call(getattr(self.paper, f"dimensionless_{group}"), smeared, sqrt)


def _call(func: Callable[..., Any], values: Mapping[str, Any], sqrt: Callable[[Any], Any]) -> Any:
    names = func.__code__.co_varnames[: func.__code__.co_argcount]
    return func(**{name: (sqrt if name == "sqrt" else values[name]) for name in names})


def _rebuild(beam: str, track: str, module: str, paper: str) -> PeriodicFoundation:
    """The :class:`PeriodicFoundation` of ``beam`` on ``track`` with the generated modules of these names
    (unpickling: a module loaded already, else imported)."""
    sleepers, parameters = (
        sys.modules.get(name) or importlib.import_module(name) for name in (module, paper)
    )
    return PeriodicFoundation(beam, track, sleepers, parameters)


def periodic_foundations(sleepers: ModuleType | None, paper: ModuleType) -> dict:
    """(beam, track) -> :class:`PeriodicFoundation` of every rail on periodic supports (none without
    a generated ``sleepers`` module)."""
    if sleepers is None:
        return {}
    return {
        (beam, track): PeriodicFoundation(beam, track, sleepers, paper)
        for track in sleepers.TRACKS
        for beam in sleepers.BEAMS
    }


@functools.cache
def _damping_unit(unit: str) -> bool:
    """A viscous damping's SI unit has a force times a time (``N s``, ``N s/m``, ``N s/m^2``)."""
    return unit.startswith("N s")


def periodic_specs(sleepers: ModuleType | None) -> dict[str, dict[str, Any]]:
    """Metadata (as ``generated/parameters.py`` writes it) of the groups only periodic tracks have."""
    out: dict[str, dict[str, Any]] = {}
    if sleepers is None:
        return out
    for track in sleepers.TRACKS:
        for beam in sleepers.BEAMS:
            for name, spec in sleepers.PARAMETERS[track][beam].items():
                out.setdefault(
                    name,
                    {
                        "meaning": f"{spec['si_meaning']} ({spec['si']}), scaled by the smeared support",
                        "constraint": spec["constraint"],
                        "equation": _EQUATION,
                        "default": spec["default"],
                        "si": spec["si"],
                        "unit": spec["unit"],
                        "si_meaning": spec["si_meaning"],
                        "damping": _damping_unit(spec["unit"]),
                    },
                )
    return out
