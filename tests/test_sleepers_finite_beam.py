"""The finite rail on discrete supports against the Floquet theory (moving_bogie.validation.sleepers_*).

The finite rail (quintic Hermite elements, point supports, the vehicle stepped by Newmark's rule) uses no
Floquet theory: no harmonics, no receptance, no lattice sum. The references are

- the exact pinned-pinned frequency (pi / lam)^2 / 2 of a rail on supports (the wave sin(pi x / lam) does
  not move the supports; docs/sleepers.md (S15));
- the Floquet steady response (S17) at a very small speed, against the finite rail's static deflection;
- the Floquet root with Im q < 0 of an unstable case (floquet_frequencies) and the Floquet steady force of
  a stable one (steady_response), against the finite rail's free vibration and loaded run
  (check_sleepers): the issue's 1 % on the growth rate, the dominant frequency and the steady force.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import scipy.sparse.linalg as sla

from moving_bogie.cli import main
from moving_bogie.generated import vehicle_hertz_mass, vehicle_mass
from moving_bogie.kernels.hill import VehicleMatrices
from moving_bogie.kernels.sleeper_track import SleeperTrack
from moving_bogie.model.catalogue import default_catalogue
from moving_bogie.response.steady_bay import static_loads, steady_response
from moving_bogie.validation.sleepers_check import SleeperBeamSettings, check_sleepers
from moving_bogie.validation.sleepers_rail import SleeperRail

#: the catalogue's rails on periodic supports, (beam, track) -> their generated functions
PERIODIC = default_catalogue().periodic

TRACKS = [
    ("sleepers", {"eta_sup": 0.1}),
    ("sleepers-two-layer", {"eta_pad": 0.1, "mu_sl": 0.5, "kappa_bal": 0.5, "eta_bal": 0.1}),
]


def _vehicle(eta_M: float) -> tuple[VehicleMatrices, np.ndarray]:
    values = {"eta_M": eta_M}
    return VehicleMatrices.from_module(vehicle_mass, values), static_loads(vehicle_mass, values)


@pytest.mark.parametrize(("track", "support"), TRACKS)
def test_the_support_element_has_the_generated_dynamic_stiffness(track, support):
    """The support's finite element, its own unknowns condensed out at a frequency w, is lam z(w), z the
    generated support function of docs/sleepers.md (S2) (derivations/sleepers.py)."""
    sleeper_track = SleeperTrack(PERIODIC["eb", track], {"lam": 1.3, "alpha": 0.1, **support})
    m, c, k = sleeper_track.support_element()
    for w in (0.0, 0.4, 1.7):
        d = k + 1j * w * c - w * w * m
        condensed = d[0, 0] - d[0, 1:] @ np.linalg.solve(d[1:, 1:], d[1:, 0]) if d.shape[0] > 1 else d[0, 0]
        assert abs(condensed - 1.3 * sleeper_track.support(np.array(w))) < 1e-12


@pytest.mark.parametrize(("track", "support"), TRACKS)
def test_the_pinned_pinned_mode_is_an_eigenmode_of_the_finite_rail(track, support):
    """sin(pi x / lam) vanishes at every support and at the pinned ends: the finite rail has the eigenvalue
    ((pi / lam)^2 / 2)^2 of (K, M) exactly; the quintic elements (8 per bay) approximate it to far below
    1e-6 (their error falls like h^8 for the eigenvalue)."""
    lam = 1.5
    groups = {"lam": lam, "alpha": 0.1, "kappa_f": 0.0, "eta_f": 0.05, **support}
    rail = SleeperRail(SleeperTrack(PERIODIC["eb", track], groups), 12, 8)
    m, _, k = rail.matrices
    exact = (np.pi / lam) ** 2 / 2
    values = sla.eigsh(k, k=3, M=m, sigma=exact**2, return_eigenvectors=False)
    assert np.min(np.abs(np.sqrt(values) / exact - 1)) < 1e-6


@pytest.mark.parametrize(("track", "support"), TRACKS)
def test_static_deflection_against_the_floquet_steady_response_at_low_speed(track, support):
    """The finite rail's static deflection under the load 2 at a support, a quarter and half a bay from it,
    against the Floquet steady deflection (S17) at alpha = 1e-3 (its dynamic part is of order alpha^2): within
    1e-3, the tolerance to which steady_response converges its time series."""
    lam, bays = 1.5, 28
    groups = {"lam": lam, "alpha": 1e-3, "kappa_f": 0.0, "eta_f": 0.05, **support}
    sleeper_track = SleeperTrack(PERIODIC["eb", track], groups)
    vehicle, loads = _vehicle(1.0)
    steady = steady_response(sleeper_track, vehicle, loads, points=5)
    rail = SleeperRail(sleeper_track, bays, 8)
    stiffness = rail.matrices[2].tocsc()
    for position, floquet in zip(steady.position[:3], steady.deflection[0][:3]):
        dofs, shape, _, _ = rail.contact_shapes(bays // 2 * lam + position)
        force = np.zeros(rail.size)
        force[dofs] = loads[0] * shape
        finite = shape @ sla.spsolve(stiffness, force)[dofs]
        assert abs(finite / floquet - 1) < 1e-3


@pytest.mark.slow
def test_unstable_case_growth_rate_and_frequency_within_one_percent():
    """A wheel in the principal parametric zone (Re q = Omega_0 / 2; bay 2.5 / chi, light damping): the
    free vibration released from the static deflection grows at the Floquet rate -Im q and oscillates at the
    Floquet frequency, each within 1 % (the issue's tolerance)."""
    groups = {"lam": 2.5, "alpha": 0.24, "kappa_f": 0.0, "eta_f": 0.01, "eta_sup": 0.01}
    vehicle, loads = _vehicle(14.0)
    track, settings = SleeperTrack(PERIODIC["eb", "sleepers"], groups), SleeperBeamSettings(periods=30)
    result = check_sleepers(track, vehicle, loads, settings=settings, harmonics=(3, 3))
    assert result.floquet_verdict == "unstable"
    names = [c.quantity for c in result.comparisons]
    assert names == ["growth rate -Im q", "dominant frequency"]
    assert result.rate > 0
    for comparison in result.comparisons:
        assert comparison.relative < 0.01, comparison


@pytest.mark.slow
@pytest.mark.parametrize("module", [vehicle_mass, vehicle_hertz_mass])
def test_stable_case_steady_force_within_one_percent(module):
    """The UIC60 rail of examples/sleepers.toml (its groups) under its wheel, rigid or on a Hertz spring
    (kappa_H 20: k_H = 1.4e9 N/m): no Floquet root with Im q <= 0, and the loaded run's contact force over
    its last bay within 1 % of the Floquet steady force's peak-to-peak."""
    groups = {"lam": 0.8428542781, "alpha": 0.0436009096, "kappa_f": 0.0, "eta_f": 0.0128874112}
    groups["eta_sup"] = 0.3221852804
    values = {"eta_M": 13.998576285, "kappa_H": 20.0, "eta_H": 0.0}
    values = {name: values[name] for name in module.MATRIX_ARGUMENTS}
    vehicle = VehicleMatrices.from_module(module, values)
    settings = SleeperBeamSettings(periods=12)
    track = SleeperTrack(PERIODIC["eb", "sleepers"], groups)
    result = check_sleepers(track, vehicle, static_loads(module, values), settings=settings)
    assert result.floquet_verdict == "stable"
    (force,) = result.comparisons
    assert force.quantity == "steady force over a bay"
    assert force.relative < 0.01, force
    assert result.rate < 0  # the free vibration decays


EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "sleepers.toml"


@pytest.mark.parametrize(
    ("extra", "option"),
    [
        (["--case", "3"], "--case"),
        (["--beam", "tr"], "--beam"),
        (["--tmax", "50"], "--tmax"),
        (["--modes", "100"], "--modes"),
        (["--no-estimate"], "--no-estimate"),
        (["--set", "Mx=50"], "--set"),
    ],
)
def test_options_of_the_continuous_check_are_refused_by_name(capsys, extra, option):
    """A sleeper file with an option that only the continuous tracks' check takes, or a --set of a name
    the file's model does not have (--set itself applies, as on every track): one message naming the
    option, exit status 2, before any computation."""
    assert main(["validate", "--file", str(EXAMPLE), *extra]) == 2
    err = capsys.readouterr().err
    assert option in err and err.count("\n") == 1, err


ZONES = EXAMPLE.parent / "sleepers_zones.toml"


@pytest.mark.slow
@pytest.mark.parametrize(
    ("v", "M", "independent"),
    [
        # -Im Omega in 1/s of an independent Floquet-Hill computation (a separate code) where it was made
        ("97.2881", "1400", 2.90111),
        ("97.2881", "1416", 3.22093),
        ("71.5", "2685", None),
    ],
)
def test_validate_agrees_inside_the_zone_of_the_example(tmp_path, capsys, v, M, independent):
    """examples/sleepers_zones.toml at three points of its principal zone (1400 kg is 25 kg inside the lower
    edge near 1375 kg, 1416 kg near the middle): ``validate`` exits 0, its growth rate and frequency within
    1 % of the Floquet root's; the Floquet rate within 1e-5 of the independent one."""
    text = ZONES.read_text().replace("\nM = 600 ", f"\nM = {M} ").replace("\nv = 100 ", f"\nv = {v} ")
    path = tmp_path / "zone.toml"
    path.write_text(text)
    assert main(["validate", "--file", str(path), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    rate, frequency = out["comparisons"]
    assert rate["quantity"] == "growth rate -Im q" and frequency["quantity"] == "dominant frequency"
    assert rate["relative_diff"] < 0.01 and frequency["relative_diff"] < 0.01
    assert rate["floquet_si"] > 0 and out["agrees"]
    if independent is not None:
        assert abs(rate["floquet_si"] / independent - 1) < 1e-5


@pytest.mark.slow
def test_the_steady_force_is_checked_beside_a_slowly_decaying_vibration(tmp_path, capsys):
    """examples/sleepers_zones.toml just below its parametric zone (v = 97.2881 m/s, M = 1300 kg): stable,
    its least-damped root decays at about 1.35 1/s, so the finite rail's loaded run still carries a
    transient as large as the steady force's variation at its end (its raw last bay differs from the
    Floquet steady force by about 90 %). The finite rail's periodic limit, read from its run alone, agrees
    with the Floquet steady force within the check's 1 %, and the notes say that the transient was removed."""
    text = ZONES.read_text().replace("\nM = 600 ", "\nM = 1300 ").replace("\nv = 100 ", "\nv = 97.2881 ")
    path = tmp_path / "below.toml"
    path.write_text(text)
    assert main(["validate", "--file", str(path), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    (force,) = out["comparisons"]
    assert force["quantity"] == "steady force over a bay" and force["relative_diff"] < 0.01
    assert out["floquet_verdict"] == "stable"
    assert any("periodic limit" in note for note in out["notes"])


def test_the_verdict_line_states_the_numbers_it_judged():
    """Each compared quantity with its two values, the unit, the difference and the tolerance."""
    from moving_bogie.cli.validate_output import format_sleeper_check

    rows = [("growth rate -Im q", 2.90112, 2.90285, "1/s", 0.0006, True), ("x", 1.0, 1.5, "N", 0.5, False)]
    out = {
        "model": "eb/sleepers/mass",
        "floquet_verdict": "unstable",
        "agrees": False,
        "finite_beam": {"bays": 57, "elements_per_bay": 8, "unknowns": 1369, "dt": 0.066},
        "timings": {"floquet_s": 1.0, "finite_beam_s": 2.0},
        "notes": [],
        "comparisons": [
            {"quantity": q, "floquet_si": a, "finite_beam_si": b, "unit_si": u, "relative_diff": r}
            | {"tolerance": 0.01, "within": w}
            for q, a, b, u, r, w in rows
        ],
    }
    verdict = format_sleeper_check(out).splitlines()[-1]
    assert verdict == (
        "verdict: DISAGREE: growth rate -Im q 2.90112 (Floquet) vs 2.90285 (finite beam) 1/s: "
        "0.060% <= 1.00%; x 1 (Floquet) vs 1.5 (finite beam) N: 50.000% > 1.00%"
    )


def _zone_example(folder: Path, vehicle: str, M: str, extra: str = "") -> Path:
    """examples/sleepers_zones.toml with another vehicle, wheel mass M and speed 97.2881 m/s, plus lines."""
    text = ZONES.read_text().replace('vehicle = "mass"', f'vehicle = "{vehicle}"')
    text = text.replace("\nM = 600 ", f"\nM = {M} ").replace("\nv = 100 ", "\nv = 97.2881 ")
    path = folder / f"{vehicle}_{M}.toml"
    path.write_text(text + extra)
    return path


def _bound(path: Path) -> tuple[Any, Any]:
    """The bound model of a sleeper file and its SI scales."""
    import moving_bogie as mb

    physical = mb.load_parameters(path)[1]
    return mb.bind(physical), physical.scales()


#: two wheels 2 m apart, each on a linearised Hertz spring (k_H = 1.4e9 N/m), on the rail of the zone example
TWO_WHEELS_ON_HERTZ_SPRINGS = "d = 2.0\nk_H = 1.4e9\n"


@pytest.mark.parametrize("frequency", [1.2, 1.6])
def test_absorbing_layers_make_the_finite_rail_look_infinite(frequency):
    """A harmonic point load in the first pass band of the zone example's rail (its waves propagate, the
    rail barely damps them): on the infinite rail the receptance under the load does not depend on where the
    rail ends. With the check's absorbing layers (15 / chi at each end) it moves by less than 1e-3 as the
    rail beyond the load grows bay by bay; with pinned ends alone the waves they reflect move it by more than
    50 % (standing waves between the ends)."""
    from moving_bogie.validation.sleepers_check import ABSORBING

    track = _bound(ZONES)[0].track.sleepers
    spreads = []
    for layer in (math.ceil(ABSORBING / track.lam), 0):
        values = []
        for beyond in (10, 11, 12, 13):
            rail = SleeperRail(track, 20 + beyond + 2 * layer, 8, layer)
            m, c, k = rail.matrices
            dofs, shape, _, _ = rail.contact_shapes((layer + 20.3) * track.lam)
            force = np.zeros(rail.size, complex)
            force[dofs] = shape
            w = sla.spsolve((k + 1j * frequency * c - frequency**2 * m).tocsc(), force)
            values.append(abs(shape @ w[dofs]))
        spreads.append(np.ptp(values) / np.mean(values))
    assert spreads[0] < 1e-3 < 0.5 < spreads[1], spreads


@pytest.mark.slow
def test_two_wheels_on_hertz_springs_in_the_zone(tmp_path):
    """Two wheels on Hertz springs in the principal zone (M = 1340 kg; the rear wheel's zone moves down from
    1375-1458 kg with the second wheel and the contact springs): the Floquet root with Im q < 0 and the
    finite rail's free vibration agree on the growth rate and the frequency within 1 %."""
    from moving_bogie.validation.on_supports import check_on_supports

    bound, scales = _bound(_zone_example(tmp_path, "masses", "1340", TWO_WHEELS_ON_HERTZ_SPRINGS))
    assert bound.name == "eb/sleepers/hertz_masses"
    checked = check_on_supports(bound, scales)
    result = checked.supports
    assert result is not None and checked.agrees
    assert list(checked.quantities) == ["growth rate -Im q", "dominant frequency"]
    assert result.floquet_verdict == "unstable"
    assert [c.quantity for c in result.comparisons] == ["growth rate -Im q", "dominant frequency"]
    assert result.rate > 0
    for comparison in result.comparisons:
        assert comparison.relative < 0.01, comparison


class _StableResult:
    """A Floquet search's verdict (stable) and notes, for a check given the steady response only."""

    notes: tuple[str, ...] = ()

    class verdict:  # noqa: N801 - the attribute of a FloquetResult
        state = "stable"


@pytest.mark.slow
def test_two_wheels_on_hertz_springs_steady_force_beside_two_slow_modes(tmp_path):
    """Two wheels on Hertz springs just outside the zone (M = 1400 kg: stable, every Floquet root decays;
    floquet_frequencies finds four, two pairs at Re Omega = Omega_0 / 2 +- 16 and +- 5 rad/s, decaying at
    1.0109 and 1.1069 1/s, the Floquet side taken as given here). Their beating keeps the loaded run's
    transient above 10 % of the steady force's peak-to-peak over the whole record; the periodic limit fitted
    to every signal of the run removes it: every wheel's steady force within 1 % of the Floquet steady
    force (S18), and the transient's four slowest multipliers are those two modes, decay rates within 1 %
    (between pinned ends, without the absorbing layers, the reflected waves spoil the fit: 6 % off,
    docs/sleepers.md (S27))."""
    from moving_bogie.validation.sleepers_check import STEADY_TOL, FloquetSide
    from moving_bogie.validation.sleepers_fit import periodic_limit, smooth_steps

    bound, scales = _bound(_zone_example(tmp_path, "masses", "1400", TWO_WHEELS_ON_HERTZ_SPRINGS))
    track, vehicle = bound.track.sleepers, VehicleMatrices.of(bound)
    loads = static_loads(bound.vehicle, bound.vehicle_values(bound.floats))
    steady = steady_response(track, vehicle, loads, points=129, tol=STEADY_TOL)
    side = FloquetSide(_StableResult(), None, None, steady, 0.0)  # type: ignore[arg-type]
    result = check_sleepers(track, vehicle, loads, floquet=side)
    (force,) = result.comparisons
    assert force.quantity == "steady force over a bay" and force.relative < 0.01, force
    loaded, T0 = result.loaded, track.lam / track.alpha
    signals = smooth_steps(np.vstack([loaded.force, loaded.deflection, loaded.internal]))[:, :-1]
    limit = periodic_limit(loaded.tau[:-1], signals, T0, SleeperBeamSettings().transient * loaded.tau[-1])
    rates = np.sort(-np.log(np.abs(limit.multipliers)) / T0 / scales.t_scale)
    np.testing.assert_allclose(rates[:4], [1.0109, 1.0109, 1.1069, 1.1069], rtol=0.01)  # the slowest


def test_the_check_on_supports_takes_the_bound_model_and_refuses_a_continuous_track():
    """check_on_supports takes what the continuous tracks' check takes, the bound model (and its SI
    scales); a bound model without periodic supports is refused by name before any computation."""
    from moving_bogie import bind, table1_case
    from moving_bogie.errors import ParameterError
    from moving_bogie.validation.on_supports import check_on_supports

    with pytest.raises(ParameterError, match="periodic supports") as err:
        check_on_supports(bind(table1_case(1)))
    assert err.value.parameter == "track"


def _replayed(monkeypatch, module, names: tuple[str, ...]) -> dict[str, int]:
    """Replace each function ``module.<name>`` of ``names`` by one that computes and records its result while
    its arguments are new, and hands back the recorded result when the same function is called again with
    arguments equal to a recorded call's (compared by their pickled bytes, callables left out, a dataclass by
    its fields alone: not by what a ``cached_property`` kept, which a replayed call does not compute). Returns
    the counts of the calls ``computed`` and of those ``replayed`` from the record, updated as they happen."""
    import dataclasses
    import importlib
    import io
    import pickle
    import types

    class ByFields(pickle.Pickler):
        def reducer_override(self, obj: Any) -> Any:
            if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
                return type(obj), tuple(getattr(obj, f.name) for f in dataclasses.fields(obj))
            if isinstance(obj, types.ModuleType):  # a generated module: by its name
                return importlib.import_module, (obj.__name__,)
            return NotImplemented

    def pickled(value: Any) -> bytes:
        out = io.BytesIO()
        ByFields(out).dump(value)
        return out.getvalue()

    recorded: dict[tuple[str, bytes], Any] = {}
    calls = {"computed": 0, "replayed": 0}

    def replaying(name: str, compute: Any) -> Any:
        def function(*args: Any, **kwargs: Any) -> Any:
            data = {key: value for key, value in kwargs.items() if not callable(value)}
            key = (name, pickled((args, sorted(data.items()))))
            if key in recorded:
                calls["replayed"] += 1
            else:
                calls["computed"] += 1
                recorded[key] = compute(*args, **kwargs)
            return recorded[key]

        return function

    for name in names:
        monkeypatch.setattr(module, name, replaying(name, getattr(module, name)))
    return calls


@pytest.mark.slow
def test_the_check_in_si_is_the_dimensionless_check_times_the_scales(monkeypatch):
    """moving_bogie.validate of examples/sleepers.toml in SI and of its dimensionless parameters: the same
    comparisons; the SI values are the dimensionless ones times P / 2 = 32 kN (the file's P = 64 kN) for
    the force, and per second (1 / t_scale) for the rates.

    The two checks compute the same: their Floquet searches and finite-rail runs get equal dimensionless
    arguments (byte for byte), so the SI check's are answered from the dimensionless check's record instead
    of being computed twice (each is a deterministic function of its arguments); a call with any other
    argument (an SI value where a dimensionless one belongs, another rail, another time step) would be
    computed anew and fails the counts. The fits, the comparisons and the SI values run in both checks."""
    import moving_bogie as mb
    from moving_bogie.validation import sleepers_check

    calls = _replayed(monkeypatch, sleepers_check, ("floquet_side", "simulate_sleeper_beam"))
    params, physical = mb.load_parameters(EXAMPLE)
    plain = mb.validate(params)
    computed = calls["computed"]
    assert computed >= 2 and calls["replayed"] == 0  # the Floquet side and at least one run
    si = mb.validate(physical)
    assert calls == {"computed": computed, "replayed": computed}  # every call again, with equal arguments
    from moving_bogie.validation.verdict import ValidationResult

    assert isinstance(si, ValidationResult) and si.supports is not None  # the one type of a check
    assert list(si.quantities) == ["steady force over a bay"] and si.finite is None and si.closed is None
    assert si.model == plain.model == "eb/sleepers/mass" and si.agrees and plain.agrees
    out, bare = si.to_dict(), plain.to_dict()
    from moving_bogie.validation.verdict import CHECK_KEYS, VERDICT_KEYS

    assert set(VERDICT_KEYS) <= set(out)  # the continuous tracks' keys, same meaning
    assert set(CHECK_KEYS) <= set(out) and out["n_modes"] is None and out["L"] > 0  # and all of theirs
    (name,) = out["quantities"]
    assert {"max_abs_diff", "amplitude", "floquet", "finite_beam"} <= set(out["quantities"][name])
    assert out["params"] == params.to_dict() and (out["beam"], out["track"]) == ("eb", "sleepers")
    assert out["relative_diff"] == {c["quantity"]: c["relative_diff"] for c in out["comparisons"]}
    assert "floquet_si" not in bare["comparisons"][0] and "dt_s" not in bare["finite_beam"]
    assert physical.scales().load == 32000.0
    for c, d in zip(out["comparisons"], bare["comparisons"], strict=True):
        assert c["floquet"] == d["floquet"] and c["finite_beam"] == d["finite_beam"]
        unit = 32000.0 if c["unit_si"] == "N" else 1 / physical.scales().t_scale
        assert c["floquet_si"] == pytest.approx(c["floquet"] * unit, rel=1e-14)
