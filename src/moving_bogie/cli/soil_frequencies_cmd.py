"""``frequencies --file`` on a soil-track file that names a vehicle: the roots and the verdict on the soil.

The result is the one :class:`~moving_bogie.roots.frequency_result.FrequencyResult` of every track, printed by
the same functions as the ``frequencies`` command (``--json``: the same schema), in SI; the speed is compared
with the critical velocity of the track on its soil (the least phase velocity of its guided waves,
``soil/critical.py``), beyond which a vehicle may radiate and lose stability (Metrikine & Popp 1999).
"""

from __future__ import annotations

import argparse
from dataclasses import dataclass
from typing import Any

__all__ = ["SoilRun", "equivalent_params", "run_soil_frequencies", "soil_frequencies", "soil_speed_regime"]

#: Options of ``frequencies`` that a soil-track file does not take (its values are in the file).
REFUSED = ("window", "certify")


def _refuse_options(args: argparse.Namespace) -> None:
    from moving_bogie.errors import ParameterError

    from .common import parameter_options

    given = [name for name in REFUSED if getattr(args, name, None)]
    given += [name for name, _, _ in parameter_options() if getattr(args, name, None) is not None]
    for key in ("case", "beam", "track", "vehicle"):
        if getattr(args, key, None) is not None:
            given.append(key)
    if given:
        flag = "--" + given[0].replace("_", "-")
        raise ParameterError(
            given[0], f"{flag} does not apply to a soil-track file: its values are in the file (docs/soil.md)"
        )


def soil_speed_regime(data: Any, v: float, v_ref: float) -> Any:
    """The speed against the critical velocity of the track on its soil (``soil/critical.py``)."""
    import math

    from moving_bogie.soil.critical import critical_velocity
    from moving_bogie.stability.velocity.supercritical import SpeedRegime

    crit = critical_velocity(data.track, data.soil)
    if not math.isfinite(crit.v_cr):
        note = "no guided wave of the track on its soil was found"
        return SpeedRegime(v / v_ref, None, None, v, None, note)
    note = "the least phase velocity of the guided waves of the track on its soil"
    return SpeedRegime(v / v_ref, crit.v_cr / v_ref, v > crit.v_cr, v, crit.v_cr, note)


@dataclass(frozen=True)
class SoilRun:
    """What ``frequencies --file`` prints for a vehicle on the soil: the result, the SI parameters, the
    speed regime and the soil's own keys of the JSON output (``soil``)."""

    result: Any
    physical: Any
    regime: Any
    soil: dict[str, Any]

    def title(self) -> str:
        """The first line of the text output."""
        return (
            f"vehicle {self.physical.vehicle} on the {self.soil['track']} track on "
            f"{len(self.soil['layers'])} soil layer(s) (input per {self.soil['per']}; groups scaled with "
            f"k_ref = {self.soil['k_ref']:.6g} N/m^2)"
        )


def soil_frequencies(args: argparse.Namespace) -> SoilRun:
    """The induced frequencies of the file's vehicle on its track on the soil (module docstring)."""
    _refuse_options(args)
    from moving_bogie.api import induced_frequencies, load_soil_vehicle

    from .common import soil_settings
    from .progress import progress_bar

    data = load_soil_vehicle(args.file, soil_settings(args))
    physical = data.physical
    with progress_bar("induced frequencies on the soil", enabled=not args.json) as update:
        result = induced_frequencies(data, progress=update)
    regime = soil_speed_regime(data.input, float(physical.v), physical.scales().v_ref)
    soil = {
        "track": data.input.track.kind,
        "per": data.input.per,
        "k_ref": data.rail.k_ref,
        "layers": data.input.soil.to_dict(),
    }
    return SoilRun(result, physical, regime, soil)


def equivalent_params(run: SoilRun) -> dict[str, Any]:
    """The JSON ``params`` of a vehicle on the soil: the keys of every track's (the groups of the vehicle on
    the Winkler-equivalent track of k_ref, ``track`` "one-layer", by which the roots are scaled) and
    ``equivalent_of``, the track on the soil they stand for (docs/soil.md, "A vehicle on the soil")."""
    soil = run.soil
    layers = len(soil["layers"])
    return run.result.params.to_dict() | {
        "equivalent_of": f"the {soil['track']} track on {layers}-layer soil: the groups of the rail on the "
        f"Winkler track of k_ref = {soil['k_ref']:.6g} N/m^2, which scale the roots"
    }


def run_soil_frequencies(args: argparse.Namespace) -> int:
    """``frequencies --file`` on a soil-track file with a vehicle, printed as on every track (the JSON with a
    ``soil`` key); exit 1 unless the count is matched and the verdict decided."""
    from .frequencies_output import report

    run = soil_frequencies(args)
    extra = {"soil": run.soil, "params": equivalent_params(run)}
    report(args, run.result, run.physical, run.regime, extra=extra, title=run.title())
    result = run.result
    return 0 if result.count_ok and result.verdict.determined else 1
