"""Whether the vehicle moves above the critical velocity: the speed regime carried by every verdict.

The critical velocity alpha_cr of a constant moving force (Eqs. (65)-(66); the smallest local minimum of the
phase speed of free waves, :func:`~moving_bogie.stability.velocity.critical_velocity.critical_velocity`)
depends on
the track only. Above it the moving load radiates waves into the beam (its steady response is no longer
localised), and the paper's analysis is subcritical: the branch-cut picture, the counts and the verdicts
are computed all the same, but they describe a regime the paper does not analyse and the vibrations of
Eqs. (35)-(47) may grow without bound along the track. Every verdict therefore states
``supercritical`` (true/false) beside ``v_cr``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from moving_bogie.errors import MovingBogieError
from moving_bogie.model.params import DimensionlessParams
from moving_bogie.model.physical import PhysicalParams

__all__ = ["SUPERCRITICAL_MEANING", "SpeedRegime", "speed_regime"]

#: What a supercritical speed means for the analysis (printed with every supercritical verdict).
SUPERCRITICAL_MEANING = (
    "above the critical velocity the moving load radiates waves along the beam (no localised steady "
    "state); the paper's analysis is subcritical, so the induced frequencies and the verdict are computed "
    "but describe a regime it does not analyse: treat them with caution"
)


@dataclass(frozen=True)
class SpeedRegime:
    """The speed of a parameter set against the critical velocity of its track.

    Attributes
    ----------
    alpha, alpha_cr : float
        The velocity ratio and the critical one (Eqs. (16), (65)-(66)); alpha_cr None when the track's
        critical velocity could not be determined (``note`` says why).
    supercritical : bool or None
        ``alpha > alpha_cr``; None when alpha_cr is not determined.
    v, v_cr : float or None
        The same in m/s for a ``[physical]`` input.
    note : str or None
        The critical velocity's own caveat (a lowest branch whose phase speed has no minimum).
    """

    alpha: float
    alpha_cr: float | None
    supercritical: bool | None
    v: float | None = None
    v_cr: float | None = None
    note: str | None = None

    def to_dict(self) -> dict[str, Any]:
        """JSON: ``alpha_cr``, ``supercritical`` (and ``v``, ``v_cr`` in m/s for SI), with the meaning."""
        out: dict[str, Any] = {
            "alpha": self.alpha,
            "alpha_cr": self.alpha_cr,
            "supercritical": self.supercritical,
        }
        if self.v_cr is not None:
            out |= {"v": self.v, "v_cr": self.v_cr, "v_unit": "m/s"}
        if self.supercritical:
            out["meaning"] = SUPERCRITICAL_MEANING
        if self.note:
            out["note"] = self.note
        return out

    def line(self) -> str:
        """One line of text: the speed against v_cr, and what a supercritical speed means."""
        if self.alpha_cr is None:
            return (
                f"speed: UNDETERMINED against the critical velocity (alpha = {self.alpha:.6g}): {self.note}"
            )
        if self.v_cr is not None:
            speed = f"v = {self.v:.6g} m/s, v_cr = {self.v_cr:.6g} m/s"  # SI: the groups in --json
        else:
            speed = f"alpha = {self.alpha:.6g}, alpha_cr = {self.alpha_cr:.6g}"
        if self.supercritical:
            return f"speed: SUPERCRITICAL, {speed}: {SUPERCRITICAL_MEANING}"
        return f"speed: subcritical, {speed}"


def speed_regime(params: DimensionlessParams, physical: PhysicalParams | None = None) -> SpeedRegime:
    """The :class:`SpeedRegime` of ``params`` (its track's critical velocity, computed afresh).

    Parameters
    ----------
    params : DimensionlessParams
    physical : PhysicalParams, optional
        Adds the speeds in m/s (v_cr = alpha_cr v_ref, Eq. (16)).
    """
    alpha = float(params.alpha)
    alpha_cr, note = _critical(params)
    supercritical = None if alpha_cr is None else alpha > alpha_cr
    if physical is None:
        return SpeedRegime(alpha, alpha_cr, supercritical, note=note)
    v_ref = physical.scales().v_ref
    v_cr = None if alpha_cr is None else alpha_cr * v_ref
    return SpeedRegime(alpha, alpha_cr, supercritical, v=alpha * v_ref, v_cr=v_cr, note=note)


#: alpha_cr and its caveat per track: (beam, track, the track's undamped groups).
_CACHE: dict[tuple[str, str, tuple[tuple[str, Any], ...]], tuple[float | None, str | None]] = {}


def _critical(params: DimensionlessParams) -> tuple[float | None, str | None]:
    """alpha_cr and its caveat, computed once per track (model and track groups) in a process."""
    from moving_bogie.stability.velocity.critical_velocity import critical_velocity

    model = params.model
    groups = tuple(
        (name, getattr(params, name))
        for name in model.foundation.MODEL_PARAMETERS
        if name in model.parameters and not model.specs[name].damping
    )
    key = (model.beam, model.track, groups)
    if key not in _CACHE:
        try:
            res = critical_velocity(params)
        except MovingBogieError as exc:  # no minimum of the phase speed found: say so, do not guess
            _CACHE[key] = (None, f"critical velocity not determined: {exc}")
        else:
            _CACHE[key] = (float(res.alpha_cr), res.to_dict().get("note"))
    return _CACHE[key]
