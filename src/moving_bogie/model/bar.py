"""What moves with the wheel mass: the one rule of maps, lines and sweeps (Eq. (63)).

The bogie's bar (its frame: mass M_b, pitch inertia J_b; the groups mu_v, J_b) is given either through the
coefficients cf1 = mu_v / eta_M and cf2 = J_b / (eta_M d^2) of Eq. (63) or by its own values. Along an axis
of the wheel mass (eta_M, or M in SI) one of the two is held:

- ``"follows"`` (the default everywhere, the paper's convention of Table 1 and Figures 3, 4, 7, 8): cf1 and
  cf2 are held, so the bar's mass and inertia scale with the wheel mass (and J_b with d^2);
- ``"fixed"``: the bar's mu_v and J_b (M_b and J_b in SI) keep the base point's values whatever varies.

The groups concerned are those an alternative input of the metadata sets (``Model.alternatives``), so a
vehicle added in ``derivations/`` follows the same rule with no edit here.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING

from moving_bogie.errors import ParameterError
from moving_bogie.model.params import DimensionlessParams

if TYPE_CHECKING:
    from moving_bogie.model.catalogue import Model

__all__ = [
    "BAR_RULES",
    "DEFAULT_BAR",
    "bar_note",
    "check_bar",
    "follow_bar",
    "held_groups",
    "moves_bar",
    "rule_note",
]

#: The rules, each with what it means (the text of the JSON outputs and the store attributes).
BAR_RULES = {
    "follows": "the bar's mass and inertia follow the wheel mass: cf1 = mu_v/eta_M = M_b/M and "
    "cf2 = J_b/(eta_M d^2) held, Eq. (63)",
    "fixed": "the bar's mass and inertia are held at the base point's values (mu_v, J_b; M_b, J_b in SI) "
    "whatever varies",
}

#: The rule of every map, line and sweep unless told otherwise.
DEFAULT_BAR = "follows"


def check_bar(rule: str) -> str:
    """``rule`` if it is one of :data:`BAR_RULES`, else a :class:`ParameterError` naming ``bar``."""
    if rule not in BAR_RULES:
        raise ParameterError("bar", f"bar must be one of {', '.join(BAR_RULES)} (got {rule!r})")
    return rule


def held_groups(params: DimensionlessParams, rule: str, varied: Iterable[str] = ()) -> tuple[str, ...]:
    """The groups held at the base point's values under ``rule``: none for ``"follows"``; for ``"fixed"``
    those an alternative sets (mu_v, J_b) that the model has, unless varied themselves."""
    if check_bar(rule) == "follows":
        return ()
    sets = {meta["sets"] for meta in params.model.alternatives.values()}
    return tuple(sorted((sets & set(params.model.specs)) - set(varied)))


def bar_note(params: DimensionlessParams, rule: str, parameter: str) -> dict[str, str] | None:
    """The rule as JSON (``{"rule": ..., "meaning": ...}``) when ``parameter`` moves the bar (the wheel mass
    under Eq. (63)); None for an axis that does not."""
    return rule_note(rule) if moves_bar(params.model, parameter) else None


def moves_bar(model: Model, group: str) -> bool:
    """Whether ``group`` moves the bar under ``"follows"`` (a group an alternative of Eq. (63) depends on)."""
    return any(group in meta["depends"] for meta in model.alternatives.values())


def rule_note(rule: str) -> dict[str, str]:
    """The rule as JSON: ``{"rule": ..., "meaning": ...}``."""
    return {"rule": rule, "meaning": BAR_RULES[check_bar(rule)]}


def follow_bar(
    base: DimensionlessParams, point: DimensionlessParams, rule: str, varied: Iterable[str] = ()
) -> DimensionlessParams:
    """``point`` with the bar moved by ``rule`` from the base point ``base`` (Eq. (63)).

    For a point given by its own values (a sweep of SI values holds M_b and J_b, whatever M does): under
    ``"follows"``, each group an alternative sets (mu_v, J_b) is set again from the alternative's value at
    ``base`` (cf1, cf2) and the point's groups it depends on (eta_M, d), unless that group is varied itself
    (``varied``: group names) or nothing it depends on moved; under ``"fixed"``, ``point`` as it is."""
    if check_bar(rule) == "fixed":
        return point
    model = point.model
    changes = {}
    for name, meta in model.alternatives.items():
        depends = meta["depends"]
        if meta["sets"] in varied or all(getattr(point, d) == getattr(base, d) for d in depends):
            continue
        set_by = getattr(model.catalogue.parameters, f"set_by_{name}")
        changes[meta["sets"]] = set_by(getattr(base, name), **{d: getattr(point, d) for d in depends})
    return point.replace(**changes) if changes else point
