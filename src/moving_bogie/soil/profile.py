"""The soil as data: layers over a half-space, top first, from ``[[soil]]`` tables (docs/soil.md).

Each table gives ``h`` (m; the last table has none: the half-space), ``rho`` (kg/m^3), the stiffness as
``E`` (Pa) and ``nu``, or as ``c_s`` and ``c_p`` (m/s), or ``c_s`` and ``nu``, and ``eta`` (s, Kelvin-Voigt:
the Lame constants times 1 + i omega eta; 0 allowed). Every value is checked before any work, and an error
names the layer (``soil[2]``, counted from 1 at the top) and the key.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
from typing import Any

from moving_bogie.errors import ParameterError, suggestion

__all__ = ["SoilLayer", "SoilProfile", "soil_profile"]

LAYER_KEYS = ("h", "rho", "E", "nu", "c_s", "c_p", "eta")


@dataclass(frozen=True)
class SoilLayer:
    """One layer (``h`` in m, ``inf`` for the half-space) with its real Lame constants and damping."""

    h: float
    rho: float
    mu: float
    lam: float
    eta: float

    @property
    def c_s(self) -> float:
        """Shear-wave speed (m/s) without damping."""
        return math.sqrt(self.mu / self.rho)

    @property
    def c_p(self) -> float:
        """Compression-wave speed (m/s) without damping."""
        return math.sqrt((self.lam + 2 * self.mu) / self.rho)

    @property
    def nu(self) -> float:
        """Poisson's ratio."""
        return self.lam / (2 * (self.lam + self.mu))

    @property
    def xi(self) -> float:
        """k_p^2 / k_s^2 = mu / (lambda + 2 mu), the same at every frequency under Kelvin-Voigt damping."""
        return self.mu / (self.lam + 2 * self.mu)


@dataclass(frozen=True)
class SoilProfile:
    """Layers over a half-space, top first (the last layer has ``h = inf``)."""

    layers: tuple[SoilLayer, ...]

    @property
    def halfspace(self) -> SoilLayer:
        return self.layers[-1]

    @property
    def c_s_min(self) -> float:
        return min(layer.c_s for layer in self.layers)

    def undamped(self) -> SoilProfile:
        """The same profile with eta = 0 in every layer (its free waves)."""
        return SoilProfile(tuple(replace(layer, eta=0.0) for layer in self.layers))

    def to_dict(self) -> list[dict[str, float]]:
        """The layers as SI values (h, rho, c_s, c_p, nu, eta), the half-space without h."""
        out = []
        for layer in self.layers:
            row = {"rho": layer.rho, "c_s": layer.c_s, "c_p": layer.c_p, "nu": layer.nu, "eta": layer.eta}
            out.append(({"h": layer.h} if math.isfinite(layer.h) else {}) | row)
        return out


def _number(table: Mapping[str, Any], key: str, where: str) -> float | None:
    if key not in table:
        return None
    value = table[key]
    if isinstance(value, bool) or not isinstance(value, int | float) and not hasattr(value, "is_finite"):
        raise ParameterError(key, f"{where}: {key} must be a number (got {value!r})")
    number = float(value)
    if not math.isfinite(number):
        raise ParameterError(key, f"{where}: {key} must be finite (got {value!r})")
    return number


def _positive(value: float | None, key: str, where: str, unit: str) -> float:
    if value is None:
        raise ParameterError(key, f"{where}: {key} is missing ({unit})")
    if value <= 0:
        raise ParameterError(key, f"{where}: {key} must be positive (got {value:g} {unit})")
    return value


def _moduli(values: dict[str, float | None], rho: float, where: str) -> tuple[float, float]:
    """(mu, lambda) from E and nu, c_s and c_p, or c_s and nu."""
    E, nu, c_s, c_p = (values[k] for k in ("E", "nu", "c_s", "c_p"))
    if E is not None and (c_s is not None or c_p is not None):
        extra = "c_s" if c_s is not None else "c_p"
        raise ParameterError(
            extra, f"{where}: give E and nu, or c_s and c_p (or c_s and nu), not E and {extra}"
        )
    if c_p is not None and nu is not None:
        raise ParameterError("nu", f"{where}: nu follows from c_s and c_p; give one of them")
    if E is None and c_s is None:
        raise ParameterError("E", f"{where}: E (with nu) or c_s (with c_p or nu) is missing")
    if c_s is not None and c_p is None and nu is None:
        raise ParameterError("c_p", f"{where}: c_s needs c_p or nu")
    if c_s is None and nu is None:
        raise ParameterError("nu", f"{where}: E needs nu")
    if c_p is not None:
        c_s = _positive(c_s, "c_s", where, "m/s")
        ratio2 = (_positive(c_p, "c_p", where, "m/s") / c_s) ** 2
        if ratio2 <= 4 / 3:
            raise ParameterError(
                "c_p", f"{where}: c_p must exceed c_s sqrt(4/3) = {c_s * math.sqrt(4 / 3):g} m/s (nu > -1)"
            )
        mu = rho * c_s**2
        return mu, rho * c_p**2 - 2 * mu
    assert nu is not None
    if not -1 < nu < 0.5:
        raise ParameterError("nu", f"{where}: nu must lie in (-1, 0.5) (got {nu:g})")
    if c_s is not None:
        mu = rho * _positive(c_s, "c_s", where, "m/s") ** 2
    else:
        mu = _positive(E, "E", where, "Pa") / (2 * (1 + nu))
    return mu, 2 * mu * nu / (1 - 2 * nu)


def _layer(table: Any, index: int, last: bool) -> SoilLayer:
    where = f"soil[{index}]" + (" (the half-space)" if last else "")
    if not isinstance(table, Mapping):
        raise ParameterError("soil", f"{where} must be a table (got {table!r})")
    for key in table:
        if key not in LAYER_KEYS:
            raise ParameterError(key, f"{where}: unknown key {key!r}; {suggestion(key, LAYER_KEYS)}")
    values = {key: _number(table, key, where) for key in LAYER_KEYS}
    if last:
        if values["h"] is not None:
            raise ParameterError("h", f"{where}: the last [[soil]] table is the half-space and has no h")
        h = math.inf
    else:
        h = _positive(values["h"], "h", where, "m")
    rho = _positive(values["rho"], "rho", where, "kg/m^3")
    mu, lam = _moduli(values, rho, where)
    eta = 0.0 if values["eta"] is None else values["eta"]
    if eta < 0:
        raise ParameterError("eta", f"{where}: eta must be >= 0 (got {eta:g} s)")
    return SoilLayer(h=h, rho=rho, mu=mu, lam=lam, eta=eta)


def soil_profile(tables: Any) -> SoilProfile:
    """The profile of a file's ``[[soil]]`` array of tables, every value checked (errors name the layer).

    Examples
    --------
    >>> top, below = {"h": 2, "rho": 1800, "c_s": 80, "c_p": 300}, {"rho": 2000, "E": 1e8, "nu": 0.3}
    >>> soil = soil_profile([top, below])
    >>> [round(layer.c_s, 3) for layer in soil.layers]
    [80.0, 138.675]
    """
    if not isinstance(tables, Sequence) or isinstance(tables, str) or not tables:
        raise ParameterError(
            "soil", "soil must be an array of [[soil]] tables, top first, the last one the half-space"
        )
    n = len(tables)
    return SoilProfile(tuple(_layer(t, i + 1, i == n - 1) for i, t in enumerate(tables)))
