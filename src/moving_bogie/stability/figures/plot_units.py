"""Units of the stability figures and their JSON: the dimensionless groups, or their SI counterparts.

A ``[physical]`` input is analysed in the dimensionless groups (Eqs. (15)-(17), (59)) and shown in SI: the
velocity ``v`` [m/s] instead of alpha, the wheel mass ``M`` [kg] instead of eta_M, a spacing ``d = 2.5 m``.
Every group is proportional to its SI counterpart at fixed scales (EI, m, k_f), so one factor per group,
from the generated scaling (:meth:`~moving_bogie.model.physical.PhysicalParams.si_factor`), converts a
whole axis; an induced frequency q is the angular frequency q / t_scale [rad/s]. Nothing here names a
parameter: names, units and factors come from the model's metadata.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import xarray
    from matplotlib.axes import Axes

    from moving_bogie.model.params import DimensionlessParams
    from moving_bogie.model.physical import PhysicalParams

__all__ = ["PlaneUnits", "axis_label", "mark_operating_point", "unit_suffix"]

#: Style of the operating point (the input's own parameters) on maps and line figures.
OPERATING_POINT: dict[str, Any] = dict(marker="*", ms=13, mfc="gold", mec="k", ls="none", zorder=5)


def unit_suffix(coord: xarray.DataArray) -> str:
    """`` m/s`` for a coordinate (xarray) with SI ``units``; empty for a dimensionless one."""
    units = coord.attrs.get("units", "1")
    return "" if units in ("1", "") else f" {units}"


def axis_label(coord: xarray.DataArray) -> str:
    """Axis label of a store coordinate: ``v [m/s]`` in SI, the group's name when dimensionless."""
    units = coord.attrs.get("units", "1")
    return str(coord.name) if units in ("1", "") else f"{coord.name} [{units}]"


def mark_operating_point(ax: Axes, x: float, y: float, *, label: str = "operating point") -> None:
    """Mark the input's own point (x, y) on ``ax``, labelled for the legend (and for reading it back)."""
    ax.plot([x], [y], label=label, **OPERATING_POINT)


@dataclass(frozen=True)
class PlaneUnits:
    """How the groups of a stability plane are shown: themselves, or converted to SI.

    Attributes
    ----------
    names, units : dict
        Group -> shown name (``"v"``) and unit (``"m/s"``; ``"1"`` for a group shown as itself).
    factors : dict
        Group -> SI value of the group 1 (the shown value is ``factor * group``).
    t_scale : float or None
        ``sqrt(m / k_f)`` [s] in SI: an induced frequency q is shown as q / t_scale [rad/s].
    operating : dict
        Group -> the input's own value (dimensionless), for the operating point.
    alpha_cr : float or None
        The critical velocity of the track (:mod:`~moving_bogie.stability.velocity.supercritical`), drawn
        dotted;
        None: the figure draws alpha = 1 (Eq. (65) without a shear layer).
    base : dict
        The SI parameters of the input, as text (``PhysicalParams.to_dict``), for the figures' titles.
    notes : dict
        Group -> a note its axis label and JSON carry (what moves with the wheel mass: ``"M_b, J_b follow
        M"``, :mod:`~moving_bogie.model.bar`).
    """

    names: dict[str, str] = field(default_factory=dict)
    units: dict[str, str] = field(default_factory=dict)
    factors: dict[str, float] = field(default_factory=dict)
    t_scale: float | None = None
    operating: dict[str, float] = field(default_factory=dict)
    alpha_cr: float | None = None
    base: dict[str, str | None] = field(default_factory=dict)
    notes: dict[str, str] = field(default_factory=dict)

    @classmethod
    def of(
        cls, params: DimensionlessParams, physical: PhysicalParams | None = None, *, operating: bool = False
    ) -> PlaneUnits:
        """The units of ``params``: SI when ``physical`` (its SI parameters) is given, else the groups.

        ``operating`` records the input's own point (marked on the figures).
        """
        from moving_bogie.stability.velocity.supercritical import speed_regime

        own = {name: float(getattr(params, name)) for name in params.model.parameters} if operating else {}
        alpha_cr = speed_regime(params).alpha_cr
        if physical is None:
            return cls(operating=own, alpha_cr=alpha_cr)
        specs = params.model.specs
        return cls(
            names={name: spec.si for name, spec in specs.items()},
            units={name: spec.unit for name, spec in specs.items()},
            factors={name: physical.si_factor(name) for name in specs},
            t_scale=physical.scales().t_scale,
            operating=own,
            alpha_cr=alpha_cr,
            base=physical.to_dict(),
        )

    @property
    def si(self) -> bool:
        return self.t_scale is not None

    def name(self, group: str) -> str:
        return self.names.get(group, group)

    def unit(self, group: str) -> str:
        return self.units.get(group, "1")

    def value(self, group: str, x: Any) -> Any:
        """The shown value of ``x`` (a group's value: any real number type, or a numpy array)."""
        return x * self.factors.get(group, 1.0)

    def group_value(self, group: str, shown: float) -> float:
        """The group's value of a shown value (inverse of :meth:`value`)."""
        return shown / self.factors.get(group, 1.0)

    def label(self, group: str) -> str:
        """Axis label: ``v [m/s]``, or the group's name, and its note (``M [kg] (M_b, J_b follow M)``)."""
        text = f"{self.name(group)} [{self.unit(group)}]" if group in self.units else group
        return f"{text} ({self.notes[group]})" if group in self.notes else text

    def legend(self, group: str, x: float) -> str:
        """Legend entry of one value: ``d = 2.5 m``, or ``d = 2.95544`` for a group."""
        unit = f" {self.unit(group)}" if group in self.units else ""
        return f"{self.name(group)} = {self.value(group, x):.6g}{unit}"

    def frequency(self, q: Any) -> Any:
        """An induced frequency shown: omega = q / t_scale [rad/s] in SI, else q itself (any number type,
        or a numpy array)."""
        return q / self.t_scale if self.t_scale is not None else q

    @property
    def frequency_unit(self) -> str:
        return "rad/s" if self.si else "1"

    def quantity(self, group: str, x: float) -> dict[str, Any]:
        """JSON of one value: ``{"name", "value", "unit"}``, with the group's own value in SI."""
        out: dict[str, Any] = {
            "name": self.name(group),
            "value": float(self.value(group, x)),
            "unit": self.unit(group),
        }
        if self.si and group in self.units:
            out["group"] = {"name": group, "value": float(x)}
        return out

    def critical(self, ax: Axes, x_range: tuple[float, float] | None = None) -> None:
        """The critical velocity of the track, dotted and labelled (alpha = 1 unlabelled when unknown).

        With ``x_range`` (the shown velocity axis) a critical velocity beyond it is not drawn but listed in
        the legend as beyond the axis (a note in the legend, where it hides no cell of the plane).
        """
        value = self.value("alpha", 1.0 if self.alpha_cr is None else self.alpha_cr)
        if x_range is not None and not min(x_range) <= value <= max(x_range):
            if self.alpha_cr is not None:
                ax.plot([], [], color="k", ls=":", lw=1, label=self._critical_text() + ": beyond this axis")
            return
        if self.alpha_cr is None:
            ax.axvline(1.0, color="k", ls=":", lw=1)
            return
        ax.axvline(value, color="k", ls=":", lw=1, label=self._critical_text())

    def _critical_text(self) -> str:
        unit = f" {self.unit('alpha')}" if self.si else ""
        shown = self.value("alpha", self.alpha_cr)
        return f"{self.name('alpha')}_cr = {shown:.6g}{unit} (critical velocity)"

    def fixed_text(self, params: DimensionlessParams, parameter: str, held: tuple[str, ...] = ()) -> dict:
        """The parameters a plane (alpha, ``parameter``) holds fixed, as title text (SI values for an SI
        input, with their units; :func:`~moving_bogie.stability.figures.margin_plot.fixed_parameters`);
        the groups Eq. (63) ties to ``parameter`` are said to follow it, unless ``held``
        (:mod:`~moving_bogie.model.bar`)."""
        from moving_bogie.stability.figures.margin_plot import fixed_parameters

        follow = {
            self.name(
                meta["sets"]
            ): f"follows {self.name(parameter)} ({name} = {float(getattr(params, name)):.4g})"
            for name, meta in params.model.alternatives.items()
            if parameter in meta["depends"] and meta["sets"] not in held
        }
        values = self.base if self.si else params.to_dict()
        shown = {self.name("alpha"), self.name(parameter)}
        return fixed_parameters(params.model, values, shown, si=self.si, follow=follow)

    def mark(self, ax: Axes, x_group: str, y_group: str) -> bool:
        """Mark the operating point on a plane (x_group, y_group) when it is known; True if marked."""
        if x_group not in self.operating or y_group not in self.operating:
            return False
        x, y = self.operating[x_group], self.operating[y_group]
        mark_operating_point(ax, self.value(x_group, x), self.value(y_group, y))
        return True

    def with_si(self, data: Any) -> Any:
        """JSON ``data`` (any JSON value) with, in SI, an ``"si"`` object beside the groups of every object:
        each group's SI counterpart as ``{"value", "unit"}`` (and ``omega`` [rad/s] beside a real frequency
        ``q``). Unchanged for dimensionless units."""
        if not self.si:
            return data
        if isinstance(data, list):
            return [self.with_si(x) for x in data]
        if not isinstance(data, dict):
            return data
        out = {k: self.with_si(v) for k, v in data.items()}
        si: dict[str, dict[str, Any]] = {}
        for key, value in data.items():
            number = isinstance(value, int | float) and not isinstance(value, bool)
            if key in self.units and number:
                si[self.name(key)] = {"value": float(self.value(key, value)), "unit": self.unit(key)}
            elif key == "q" and number:
                si["omega"] = {"value": float(self.frequency(value)), "unit": self.frequency_unit}
        if si:
            out["si"] = si
        return out

    def axis(self, group: str, lo: float, hi: float, count: int | None = None) -> dict:
        """JSON of a plot axis: shown name, unit, range (shown values) and the group with its range."""
        out: dict[str, Any] = {"name": self.name(group), "unit": self.unit(group)}
        out["range"] = [float(self.value(group, lo)), float(self.value(group, hi))]
        out["group"] = {"name": group, "range": [float(lo), float(hi)]}
        if group in self.notes:
            out["note"] = self.notes[group]
        return out | ({"count": count} if count is not None else {})

    def to_dict(self) -> dict:
        """JSON-ready: units and factors of the shown quantities."""
        return {
            "units": "si" if self.si else "dimensionless",
            "quantities": {g: {"name": self.name(g), "unit": self.unit(g)} for g in self.units},
            "frequency_unit": self.frequency_unit,
        }
