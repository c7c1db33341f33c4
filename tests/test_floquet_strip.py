"""The whole strip search (roots/strip.py) and the finite-beam comparison, each against an independent
reference.

References:

- the continuous one-layer track of the same smeared supports (docs/sleepers.md (S2): eta_f = eta_sup +
  eta_f), its roots found by the continuous tracks' own search (roots/frequencies.py, no Floquet theory),
  each with its mirror image -conj(q) and folded by the period Omega_0 into the strip [-Omega_0 / 4,
  3 Omega_0 / 4) of docs/sleepers.md: at short bays the strip holds exactly those roots. The bay's effect
  on a root is the lattice sum's first correction S - G = sum_{j != 0} G(p + j K) (Eq. (S7)), of relative
  size 2 sum_j 4 / (j K)^4 / 4 = 8 zeta(4) / K^4 at p = 0, the tolerance on each root;
- Newton's method on the Hill determinant with one more harmonic on each side (kernels/hill.py), for the
  claim that the roots have converged in the harmonics;
- the finite rail of validation/sleepers_rail.py stepped in time (quintic Hermite elements, point supports,
  Newmark's rule: no harmonics, no receptance, no lattice sum), for the steady contact force of a damped
  Hertz contact over a bay, for the growth rate and the dominant frequency of a wheel in the principal
  parametric zone, and for the decay rate of a heavy wheel's decaying roots.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from moving_bogie.api import induced_frequencies
from moving_bogie.generated import vehicle_hertz_mass, vehicle_mass
from moving_bogie.kernels.hill import FloquetSystem, VehicleMatrices
from moving_bogie.kernels.sleeper_track import SleeperTrack
from moving_bogie.model.catalogue import default_catalogue
from moving_bogie.model.params import DimensionlessParams
from moving_bogie.response.steady_bay import static_loads
from moving_bogie.roots.count.contour import Rectangle, winding_number
from moving_bogie.roots.strip import FloquetResult, floquet_frequencies
from moving_bogie.validation.sleepers_beam import simulate_sleeper_beam
from moving_bogie.validation.sleepers_check import (
    MARGIN,
    FloquetSide,
    SleeperBeamSettings,
    check_sleepers,
    floquet_frequency,
)
from moving_bogie.validation.sleepers_fit import fit_floquet_modes
from moving_bogie.validation.sleepers_rail import SleeperRail

#: the catalogue's rails on periodic supports, (beam, track) -> their generated functions
PERIODIC = default_catalogue().periodic

ZETA4 = math.pi**4 / 90
EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "sleepers.toml"


def _continuous_folded(alpha: float, eta: float, eta_M: float, Omega0: float, top: float) -> list[complex]:
    """The continuous track's roots with Im q <= top, with their mirror images, folded into the strip."""
    params = DimensionlessParams.from_mapping(
        {"beam": "eb", "vehicle": "mass", "eta_f": str(eta), "alpha": str(alpha), "eta_M": str(eta_M)}
    )
    result = induced_frequencies(params)
    roots = [complex(r.q) for r in result.roots]
    roots += [-q.conjugate() for q in roots if q.real > 0]
    x0 = -Omega0 / 4
    return sorted(
        (q - Omega0 * math.floor((q.real - x0) / Omega0) for q in roots if q.imag <= top),
        key=lambda q: q.real,
    )


def _newton(f, q: complex, h: float = 1e-7) -> complex:
    for _ in range(30):
        step = f(q) / ((f(q + h) - f(q - h)) / (2 * h))
        q -= step
        if abs(step) < 1e-13:
            break
    return q


def _assert_matches(result: FloquetResult, reference: list[complex], tol: float) -> None:
    found = sorted((r.q for r in result.roots), key=lambda q: q.real)
    assert result.count == len(reference) == len(found), (result.count, found, reference)
    for q, ref in zip(found, reference):
        assert abs(q - ref) < tol * max(1.0, abs(ref)), (q, ref)


def _short_bays_light_wheel() -> tuple[SleeperTrack, VehicleMatrices, float, float]:
    """The track, the wheel, alpha and eta_M of the short-bay tests below (lam = 0.703, a light wheel)."""
    lam, alpha, eta_M = 0.703, 0.3, 2.0
    track = SleeperTrack(PERIODIC["eb", "sleepers"], {"lam": lam, "alpha": alpha, "kappa_f": 0.0})
    track.groups.update(eta_f=0.18, eta_sup=0.02)
    return track, VehicleMatrices.from_module(vehicle_mass, {"eta_M": eta_M}), alpha, eta_M


def test_short_bays_strip_holds_the_continuous_roots_with_one_harmonic():
    """The quick representative of the test below: with no second harmonic set to compare (N_max = N0 = 1)
    the strip search counts and finds the continuous track's decaying root and its mirror image, folded to
    0.686 and 1.996 in the strip [-0.670, 2.011) (the second 0.016 from its edge), and calls them
    UNDETERMINED, without a margin."""
    track, vehicle, alpha, eta_M = _short_bays_light_wheel()
    limited = floquet_frequencies(track, vehicle, N_max=1)
    reference = _continuous_folded(alpha, 0.2, eta_M, track.Omega0, limited.window.y1)
    bay_effect = 8 * ZETA4 / track.K**4
    _assert_matches(limited, reference, bay_effect)
    assert 3 * track.Omega0 / 4 - reference[-1].real < 0.02  # the root near the strip's edge
    assert not limited.converged and limited.notes
    assert limited.verdict.state == "undetermined" and limited.margin is None


@pytest.mark.slow  # about 6 s: converging in the harmonics takes N = 3; the test above keeps N = 1 quick
def test_short_bays_strip_holds_the_continuous_roots_folded_to_its_edge():
    """A light wheel at lam = 0.703: the continuous track's decaying root and its mirror image fold to
    0.686 and 1.996 in the strip [-0.670, 2.011) (the second 0.016 from its edge, both in its upper half);
    the strip search counts and finds both, converged, STABLE with the least-damped root's margin; with
    no second harmonic set to compare (N_max = N0) the same roots are UNDETERMINED (the test above)."""
    track, vehicle, alpha, eta_M = _short_bays_light_wheel()
    tol = 1e-9  # one more harmonic than the default 1e-8 needs: converged at N = 3, not N = 2
    result = floquet_frequencies(track, vehicle, tol=tol)
    top = result.window.y1
    assert result.window.x0 == -track.Omega0 / 4 and top > 0
    reference = _continuous_folded(alpha, 0.2, eta_M, track.Omega0, top)
    bay_effect = 8 * ZETA4 / track.K**4
    _assert_matches(result, reference, bay_effect)
    assert 3 * track.Omega0 / 4 - reference[-1].real < 0.02  # the root near the strip's edge
    assert result.verdict.state == "stable" and result.converged and not result.notes
    assert result.margin == pytest.approx(min(q.imag for q in reference), abs=bay_effect)
    # converged in the harmonics: one more harmonic on each side moves no root by more than the tolerance
    more = FloquetSystem(track, vehicle, result.harmonics + 1, tol=1e-12)
    for root in result.roots:
        assert root.step < tol * max(1.0, abs(root.q))
        assert abs(_newton(more, root.q) - root.q) < 10 * tol * max(1.0, abs(root.q))
    # the dominant harmonic of each root's Hill null vector is the continuous track's (n = 0 at q, n = -1 at
    # its mirror image folded by Omega_0): the frequency the finite-beam check compares is |Re q_c|
    for root in result.roots:
        nu = floquet_frequency(track, vehicle, root.q, result.harmonics)
        assert nu == pytest.approx(abs(reference[0].real), abs=bay_effect)


@pytest.mark.slow
def test_short_bays_unstable_roots_are_the_continuous_ones_folded():
    """A heavy wheel above the critical speed (alpha 1.2, eta_M 20) at lam = 0.5: the continuous track's
    unstable root and its mirror image, and nothing else below the free waves, UNSTABLE."""
    lam, alpha, eta_M = 0.5, 1.2, 20.0
    track = SleeperTrack(
        PERIODIC["eb", "sleepers"],
        {"lam": lam, "alpha": alpha, "kappa_f": 0.0, "eta_f": 0.04, "eta_sup": 0.01},
    )
    result = floquet_frequencies(track, VehicleMatrices.from_module(vehicle_mass, {"eta_M": eta_M}))
    reference = _continuous_folded(alpha, 0.05, eta_M, track.Omega0, result.window.y1)
    _assert_matches(result, reference, 8 * ZETA4 / track.K**4)
    assert result.verdict.state == "unstable" and result.margin is None and result.unstable_count == 2


#: the rail of examples/sleepers.toml in its groups (model/sleeper_input.py), a stable case
EXAMPLE_GROUPS = {
    "lam": 0.8428542781,
    "alpha": 0.0436009096,
    "kappa_f": 0.0,
    "eta_f": 0.0128874112,
    "eta_sup": 0.3221852804,
}


# slow (a finite rail of 12 periods); quick: the growth rate against the finite rail below, and the Hertz
# wheel on sleepers against the rigid one (tests/test_hertz.py)
@pytest.mark.slow
def test_damped_hertz_contact_steady_force_over_a_bay_against_the_finite_rail():
    """The wheel of examples/sleepers.toml on a damped Hertz spring (kappa_H 20, eta_H 5: at Omega_0 the
    dashpot is 2 eta_H Omega_0 / kappa_H = 16 % of the spring): the finite rail's contact force over its
    last bay within 1 % of the Floquet steady force's peak-to-peak (its mean is the static load whatever
    the damping; the dashpot moves the peak-to-peak by 4 % from eta_H = 1 to 5). A coarse finite model:
    4 elements per bay, 100 steps per period (the benchmark's convergence study: 2e-3 each), 12 periods
    (after 6 the transient still stands at 2 %)."""
    values = {"eta_M": 13.998576285, "kappa_H": 20.0, "eta_H": 5.0}
    vehicle = VehicleMatrices.from_module(vehicle_hertz_mass, values)
    track = SleeperTrack(PERIODIC["eb", "sleepers"], dict(EXAMPLE_GROUPS))
    settings = SleeperBeamSettings(elements=4, steps_per_period=100, periods=12)
    result = check_sleepers(track, vehicle, static_loads(vehicle_hertz_mass, values), settings=settings)
    assert result.floquet_verdict == "stable"
    (force,) = result.comparisons
    assert force.quantity == "steady force over a bay"
    assert force.relative < 0.01, force


def test_growth_rate_its_spread_and_dominant_frequency_against_the_finite_rail():
    """A wheel in the principal parametric zone (lam 2.5, alpha 0.24, eta_M 14): its Floquet root (counted
    in a box around Re q = Omega_0 / 2, polished at N = 3) grows at the finite rail's rate within 0.3 %,
    the rate fitted to either half of the fit window spreads by less than 0.3 % of it, and the dominant
    frequency of the Hill null vector (the harmonic with the largest contact displacement) is the finite
    rail's spectral peak within 0.3 %."""
    groups = {"lam": 2.5, "alpha": 0.24, "kappa_f": 0.0, "eta_f": 0.01, "eta_sup": 0.01}
    track = SleeperTrack(PERIODIC["eb", "sleepers"], groups)
    values = {"eta_M": 14.0}
    vehicle = VehicleMatrices.from_module(vehicle_mass, values)
    system = FloquetSystem(track, vehicle, N=3, tol=1e-6)
    omega0 = track.Omega0
    box = Rectangle(0.4 * omega0, 0.6 * omega0, -0.1 * omega0, -1e-3 * omega0)
    assert winding_number(system, box, spacing=box.width / 10) == 1
    system.tol = 1e-12
    q = _newton(system, box.center)
    assert box.contains(q)
    frequency = floquet_frequency(track, vehicle, q, 3)
    search = FloquetResult((), 1, 3, True, box, omega0, 0)  # the box's count stands for the search
    side = FloquetSide(search, q, frequency, None, 0.0)
    # a coarse finite model (4 elements per bay, 100 steps per period; its rate extrapolated to dt -> 0 from
    # the runs at dt and 2 dt) and 30 periods, so that each half of the fit window holds 9
    settings = SleeperBeamSettings(elements=4, steps_per_period=100, periods=30)
    result = check_sleepers(
        track, vehicle, static_loads(vehicle_mass, values), settings=settings, floquet=side
    )
    rate, spread = -q.imag, result.rate_spread
    assert abs(result.rate / rate - 1) < 3e-3, (result.rate, rate)
    assert spread < 3e-3 * rate, (spread, rate)
    (growth, dominant) = result.comparisons
    assert dominant.relative < 3e-3, dominant


@pytest.mark.slow
def test_decaying_roots_of_a_heavy_wheel_against_the_finite_rails_free_decay():
    """The rail of examples/sleepers.toml under a wheel five times as heavy (M = 3000 kg): STABLE, with a
    pair of decaying roots (q and Omega_0 - conj(q)) below the rail's free waves; the finite rail's free
    vibration (80 bay-passing periods, 4 elements per bay, 100 steps per period) decays at their rate
    Im q, within the finite-beam check's 1 % (measured: 0.2 %)."""
    values = {"eta_M": 5 * 13.998576285}
    vehicle = VehicleMatrices.from_module(vehicle_mass, values)
    track = SleeperTrack(PERIODIC["eb", "sleepers"], dict(EXAMPLE_GROUPS))
    result = floquet_frequencies(track, vehicle)
    assert result.verdict.state == "stable" and result.count == 2
    low, high = sorted((r.q for r in result.roots), key=lambda q: q.real)
    assert high == pytest.approx(track.Omega0 - low.conjugate(), abs=1e-9)
    assert result.margin == pytest.approx(low.imag) and low.imag < result.free_waves
    T0 = track.lam / track.alpha
    tau = 80 * T0
    margin = math.ceil(MARGIN / track.lam)
    rail = SleeperRail(track, 2 * margin + math.ceil(track.alpha * tau / track.lam) + 1, 4)
    loads = static_loads(vehicle_mass, values)
    run = simulate_sleeper_beam(
        rail, vehicle, loads, entry=margin * track.lam, tau_max=tau, dt=T0 / 100, loaded=False
    )
    rate = fit_floquet_modes(run.tau, run.deflection, T0, 0.4 * tau).rate
    assert abs(-rate / result.margin - 1) < 0.01, (rate, result.margin)


def test_the_stable_example_reports_its_margin(capsys):
    """frequencies --json on examples/sleepers.toml: STABLE, no root below the rail's free waves, whose
    decay rate is the margin: the pinned-pinned waves do not move the supports, so they decay at
    c_f / (2 m) (computed here from the file's c_f and m)."""
    import json
    import tomllib

    from moving_bogie.cli import main

    physical = tomllib.loads(EXAMPLE.read_text())["physical"]
    assert main(["frequencies", "--file", str(EXAMPLE), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["verdict"]["state"] == "stable" and out["roots"] == [] and out["count"] == 0
    rate = physical["c_f"] / (2 * physical["m"])
    assert out["margin_1_s"] == pytest.approx(rate, rel=1e-9)
    assert out["region"]["free_waves_im_rad_s"] == pytest.approx(rate, rel=1e-9)
    assert out["margin_source"] == "the rail's free waves"
    top = out["window"]["im"][1] / float(out["si"]["t_scale_s"])
    assert top == pytest.approx(0.99 * rate, rel=1e-9)
    assert any(w.startswith("beyond the window: ") for w in out["warnings"])


@pytest.mark.parametrize(
    ("top", "roots", "margin", "source"),
    [
        (0.99, (), 1.0, "the rail's free waves"),
        (0.5, (), 0.5, "the window's top"),
        (0.99, (0.3 + 0.3j, 0.7 + 0.3j), 0.3, "a root"),
        (0.99, (0.3 - 0.3j,), None, None),
    ],
)
def test_the_margin_is_what_the_window_vouches_for(top, roots, margin, source):
    """A stable result's margin is its least-damped root, or the free waves' rate when the window reaches
    0.99 of it, or else only the window's top (nothing above it was searched); an unstable one has none."""
    from moving_bogie.roots.strip import FloquetRoot

    window = Rectangle(-0.25, 0.75, -1.0, top)
    found = tuple(FloquetRoot(q, 0.0, 0.0) for q in roots)
    result = FloquetResult(found, len(found), 2, True, window, 1.0, 0, (), free_waves=1.0)
    assert result.margin == (None if margin is None else pytest.approx(margin))
    assert result.margin_source == source
