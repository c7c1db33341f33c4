"""One interface for every track: a sleeper-track file runs the same commands and reads the same JSON as a
continuous track's file (docs/sleepers.md).

References: the JSON keys of ``frequencies --json`` on the continuous example (the schema a script reads);
the growth rate of the zone example at v = 97.2881 m/s, M = 1400 kg, 2.90111 1/s from an independent
Floquet-Hill computation (the issue's table; the strip search's own value agrees to 1e-5); the textbook
pinned-pinned frequency of an Euler-Bernoulli span l between two simple supports, (pi / l)^2 sqrt(EI / m);
the sleeper-passing frequency 2 pi v / l; the critical velocity of the paper's Eq. (65) on the smeared
one-layer track, (4 k EI / m^2)^(1/4) with k = k_sup / l + k_f.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

import moving_bogie
from moving_bogie.cli import main

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def _json(capsys: pytest.CaptureFixture[str], *args: str) -> tuple[int, dict]:
    code = main([*args, "--json"])
    return code, json.loads(capsys.readouterr().out)


@pytest.mark.slow
def test_frequencies_json_has_one_schema_on_every_track(capsys):
    """The sleeper file's JSON holds every key of the continuous file's, the same verdict object and the
    same root fields, plus the strip (Omega_0, harmonics) and the margin; the stable example's margin is
    in 1/s."""
    code, continuous = _json(capsys, "frequencies", "--file", str(EXAMPLES / "uic60-bogie.toml"))
    assert code == 0
    code, sleepers = _json(capsys, "frequencies", "--file", str(EXAMPLES / "sleepers.toml"))
    assert code == 0
    assert set(continuous) <= set(sleepers)
    assert set(continuous["verdict"]) == set(sleepers["verdict"])
    assert sleepers["verdict"]["state"] == "stable" and sleepers["stable"] is True
    assert sleepers["region"]["kind"] == "strip" and sleepers["region"]["harmonics"]
    # Omega_0 = 2 pi v / l of the file (v = 40 m/s, l = 0.6 m)
    assert sleepers["region"]["Omega_0_rad_s"] == pytest.approx(2 * math.pi * 40 / 0.6, rel=1e-12)
    assert sleepers["margin_1_s"] is not None and sleepers["margin_1_s"] > 0


@pytest.mark.slow
def test_an_unstable_sleeper_root_reads_like_a_continuous_one(capsys):
    """--set on a sleeper file; the root's fields are the continuous roots' (omega in rad/s, the growth
    time), its growth rate the independent Floquet-Hill value."""
    code, out = _json(
        capsys,
        "frequencies",
        "--file",
        str(EXAMPLES / "sleepers_zones.toml"),
        "--set",
        "M=1400",
        "--set",
        "v=97.2881",
    )
    assert code == 0 and out["verdict"]["state"] == "unstable"
    (root,) = [r for r in out["roots"] if float(r["im"]) < 0]
    continuous_fields = {"re", "im", "side", "multiplicity", "digits", "residual", "omega", "frequency_hz"}
    assert continuous_fields <= set(root)
    assert -float(root["omega"]["im"]) == pytest.approx(2.90111, rel=1e-5)


def test_the_python_api_takes_a_sleeper_file():
    """load_parameters reads the file into the one catalogue; bind gives it its strip; the model is listed
    with the others."""
    params, physical = moving_bogie.load_parameters(EXAMPLES / "sleepers.toml")
    assert params.model.name == "eb/sleepers/mass" and physical is not None
    bound = moving_bogie.bind(params)
    region = bound.track.search_region()
    assert region.kind == "strip"
    scales = physical.scales()
    assert region.period / scales.t_scale == pytest.approx(2 * math.pi * 40 / 0.6, rel=1e-12)
    assert bound.replace(eta_M=20).track_factory is bound.track_factory


def test_the_roots_entry_takes_the_search_region_from_the_bound_model():
    """roots.frequencies.induced_frequencies serves every track: on a strip the window's options are refused
    by name, and a strip's options on a window are unknown keywords (both before any search)."""
    from moving_bogie.roots.count.contour import Rectangle
    from moving_bogie.roots.frequencies import induced_frequencies

    params, _ = moving_bogie.load_parameters(EXAMPLES / "sleepers.toml")
    strip = moving_bogie.bind(params)
    for option in ({"window": Rectangle(0, 1, -1, 1)}, {"certify": True}, {"starts": [1j]}, {"balls": True}):
        with pytest.raises(TypeError, match="a search of one strip takes none of them"):
            induced_frequencies(strip, **option)
    window = moving_bogie.bind(moving_bogie.table1_case(1))
    with pytest.raises(TypeError, match="N_max"):
        induced_frequencies(window, N_max=3)


def test_critical_velocity_on_sleepers_is_the_smeared_tracks_with_the_track_frequencies(capsys):
    code, out = _json(capsys, "critical-velocity", "--file", str(EXAMPLES / "sleepers.toml"), "--set", "v=80")
    assert code == 0
    EI, m, bay, k_sup, v = 6.42e6, 60.21, 0.6, 6.0e7, 80.0  # examples/sleepers.toml, --set v=80
    supports = out["on_supports"]
    pinned = (math.pi / bay) ** 2 * math.sqrt(EI / m)
    assert supports["pinned_pinned_rad_s"] == pytest.approx(pinned, rel=1e-12)
    assert supports["sleeper_passing_rad_s"] == pytest.approx(2 * math.pi * v / bay, rel=1e-12)
    assert float(out["v_cr"]) == pytest.approx((4 * (k_sup / bay) * EI / m**2) ** 0.25, rel=1e-9)


def test_a_sleeper_map_summary_has_the_continuous_maps_keys():
    """The sleeper map's summary has the keys of the continuous map's with their meaning: the axes in the
    groups (alpha = v / v_ref and eta_M = M chi / m: at the file's own v and M, the file's groups), the
    vertical axis' group and the parameters; the continuous map of Case 1 has the same keys."""
    from moving_bogie.stability.maps.map import MAP_KEYS

    params, physical = moving_bogie.load_parameters(EXAMPLES / "sleepers_zones.toml")
    smap = moving_bogie.sleeper_map(physical, [float(physical.v)], [float(physical.M)], verify=0, workers=1)
    out = smap.summary()
    assert set(MAP_KEYS) <= set(out) and out["parameter"] == "eta_M"
    assert out["alpha_range"][0] == pytest.approx(float(params.alpha), rel=1e-12)
    assert out["eta_M_range"][0] == pytest.approx(float(params.eta_M), rel=1e-12)
    assert out["params"] == params.to_dict() and out["unstable_fraction"] in (0.0, 1.0)
    case1 = moving_bogie.stability_map(moving_bogie.table1_case(1), alphas=[0.2], thetas=[50.0], workers=1)
    assert set(MAP_KEYS) <= set(case1.summary()) and f"{case1.parameter}_range" in case1.summary()
