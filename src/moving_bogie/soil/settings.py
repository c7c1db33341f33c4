"""``--set KEY=VALUE`` on a soil-track file: the file as if edited (docs/soil.md).

A key is a ``[physical]`` key of the file (``v``, ``EI``, ``M``, ``k_pad``, ``b``, ...; the track's keys and
``P`` may be added) or a soil layer's key with the layer's number appended, counting from 1 at the top
(``c_s1``, ``h2``, ``E1``, ``rho3``, ``nu1``, ``eta1``, ``c_p1``; the half-space is the last layer). A layer
gives its stiffness as E and nu, c_s and nu, or c_s and c_p: a stiffness key the layer does not give
replaces the one it stands for and holds the other (``c_s1`` on a layer of E and nu gives c_s and nu, the
same nu). The edited contents are then checked by the file's own checks (:func:`~.file.soil_input`).
"""

from __future__ import annotations

import copy
import re
from collections.abc import Mapping
from typing import Any

from moving_bogie.errors import ParameterError, did_you_mean

from .profile import LAYER_KEYS
from .track import LOAD_KEYS, TRACK_KINDS, UNITS

__all__ = ["key_unit", "settable_keys", "with_settings"]

#: The ways a layer gives its stiffness (soil.profile): two keys each.
STIFFNESS_FORMS = (("E", "nu"), ("c_s", "nu"), ("c_s", "c_p"))
#: The SI unit of each layer key (soil.profile).
LAYER_UNITS = {"h": "m", "rho": "kg/m^3", "E": "Pa", "nu": "1", "c_s": "m/s", "c_p": "m/s", "eta": "s"}
_LAYER_KEY = re.compile(rf"^({'|'.join(LAYER_KEYS)})([1-9][0-9]*)$")


def settable_keys(data: Mapping[str, Any]) -> tuple[str, ...]:
    """The keys ``--set`` takes on the parsed file ``data``: its ``[physical]`` keys, the track's keys and
    P, and every layer key with the layer's number (the half-space without ``h``)."""
    physical = data.get("physical", {})
    kind = data.get("model", {}).get("track")
    track = TRACK_KINDS.get(kind, ())
    keys = [*physical, *track, *LOAD_KEYS] if isinstance(physical, Mapping) else [*track, *LOAD_KEYS]
    layers = data.get("soil", [])
    n = len(layers) if isinstance(layers, list) else 0
    for i in range(1, n + 1):
        keys += [f"{key}{i}" for key in LAYER_KEYS if not (key == "h" and i == n)]
    return tuple(dict.fromkeys(keys))


def key_unit(key: str) -> str:
    """The SI unit of a settable key (a ``[physical]`` key of the track or a numbered layer key)."""
    match = _LAYER_KEY.match(key)
    return LAYER_UNITS[match.group(1)] if match else UNITS.get(key, "1")


def _stiffness(layer: dict[str, Any], key: str, index: int) -> None:
    """Drop the stiffness key that ``key`` replaces in ``layer`` (module docstring), or refuse ``key``."""
    given = tuple(k for forms in STIFFNESS_FORMS for k in forms if k in layer)
    old = next((f for f in STIFFNESS_FORMS if set(f) == set(given)), None)
    if old is None or key in old:
        return
    for form in STIFFNESS_FORMS:
        kept = set(form) & set(old)
        if key in form and kept:
            for other in set(old) - kept:
                del layer[other]
            return
    keys = ", ".join(f"{k}{index}" for k in old)
    raise ParameterError(
        f"{key}{index}",
        f"{key}{index}: soil layer {index} gives its stiffness as {' and '.join(old)}; set {keys}, "
        "or the key that replaces one of them (E, nu, c_s, c_p pair as E and nu, c_s and nu, c_s and c_p)",
    )


def with_settings(data: Mapping[str, Any], settings: Mapping[str, float]) -> dict[str, Any]:
    """A copy of the parsed file ``data`` with the ``settings`` (key -> SI value) applied (module docstring).

    Raises
    ------
    ParameterError
        Naming the key, for a key the file does not take (the message lists those it takes) or a stiffness
        key that fits no form of its layer.
    """
    out = copy.deepcopy(dict(data))
    allowed = settable_keys(data)
    for key, value in settings.items():
        if key not in allowed and key == f"h{len(data.get('soil', []))}":
            raise ParameterError(key, f"{key}: the last soil layer is the half-space and has no depth h")
        if key not in allowed:
            hint = did_you_mean(key, allowed)
            raise ParameterError(
                key,
                f"{key} is not a key of this soil-track file; {hint + ' ' if hint else ''}it takes "
                f"{', '.join(allowed)} (layer keys numbered from 1 at the top)",
            )
        match = _LAYER_KEY.match(key)
        if match is None:
            out.setdefault("physical", {})[key] = value
            continue
        name, index = match.group(1), int(match.group(2))
        layer = out["soil"][index - 1]
        if name in ("E", "nu", "c_s", "c_p"):
            _stiffness(layer, name, index)
        layer[name] = value
    return out
