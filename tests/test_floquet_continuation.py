"""The receptance continued across the rail's free waves (kernels/free_wave_poles.py) and the strip search
beyond them (roots/strip.py), each against an independent reference.

References:

- a contour integral of -z / D around a crossed pole (the residue the continuation adds);
- analyticity: the continued receptance is analytic across a singular line of the free waves, so its value
  at a point of the line is the mean of its values on a circle around it (Cauchy's formula, the trapezoid
  rule, exponentially accurate for a function analytic on a larger disc); the integral over real
  wavenumbers as it stands jumps across the line by the crossed poles' residues, and its circle mean misses
  its value there by as much (checked too, so that the test can fail);
- the continuous one-layer track of the same smeared supports (docs/sleepers.md (S2): eta_f = eta_sup +
  eta_f), its roots found by the continuous tracks' own search (roots/frequencies.py: residues of the
  dispersion polynomial, no Floquet theory, no free-wave lines), folded into the strip: at short bays the
  strip holds those roots, to the bay's effect 8 zeta(4) / K^4 (tests/test_floquet_strip.py), also those
  beyond the periodic rail's first free waves;
- the finite rail of validation/sleepers_rail.py stepped in time (no harmonics, no receptance, no lattice
  sum), for the decay rate of the example's wheel, whose root lies beyond the free waves.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from test_floquet_strip import EXAMPLE_GROUPS, PERIODIC, ZETA4, _assert_matches, _continuous_folded

from moving_bogie.generated import vehicle_mass
from moving_bogie.kernels.free_wave_poles import Sheet, sheet_poles
from moving_bogie.kernels.hill import VehicleMatrices
from moving_bogie.kernels.periodic_receptance import receptance
from moving_bogie.kernels.sleeper_track import SleeperTrack
from moving_bogie.response.steady_bay import static_loads
from moving_bogie.roots.strip import floquet_frequencies
from moving_bogie.validation.sleepers_beam import simulate_sleeper_beam
from moving_bogie.validation.sleepers_check import MARGIN
from moving_bogie.validation.sleepers_fit import fit_floquet_modes
from moving_bogie.validation.sleepers_rail import SleeperRail


def _long_bay_track() -> SleeperTrack:
    """A long bay (lam = 2.5, alpha = 0.24): the rail's first pass band lies within a few K of p = 0, where
    its free waves' poles carry residues of order 1; light damping along the rail (eta_f = 0.01) and
    damped supports (eta_sup = 0.2)."""
    groups = {"lam": 2.5, "alpha": 0.24, "kappa_f": 0.0, "eta_f": 0.01, "eta_sup": 0.2}
    return SleeperTrack(PERIODIC["eb", "sleepers"], groups)


def test_a_crossed_poles_residue_against_a_contour_integral():
    """Short bays (lam = 0.703, alpha = 0.3, eta_f = 0.02, eta_sup = 0.18) at q = -0.495 + 0.15 i: a zero
    of D near p = -31.33 has crossed the real axis from above (its side below the free waves is +1, it
    now lies below); its residue coefficient z^2 / h'(p*) is that of -z / D, here (1 / 2 pi i) times the
    integral of -z / D over a circle of radius 1e-4 around it (64-point trapezoid rule, D from the lattice
    sum of sleeper_track.py, not from h)."""
    groups = {"lam": 0.703, "alpha": 0.3, "kappa_f": 0.0, "eta_f": 0.02, "eta_sup": 0.18}
    track = SleeperTrack(PERIODIC["eb", "sleepers"], groups)
    q = complex(-0.495, 0.15)
    found = sheet_poles(track, q, 4 * track.K + 10, 0.99 * track.free_wave_floor(), 2, 0.0)
    assert found.crossed == 1
    pole, side, coefficient = found.poles[0], found.sides[0], found.coefficients[0]
    assert side == 1 and pole.imag < 0 and abs(pole.real + 31.33) < 0.01
    circle = pole + 1e-4 * np.exp(2j * np.pi * np.arange(64) / 64)
    w = q + track.alpha * circle
    integrand = -track.support(w) / (1 + track.support(w) * track.lattice_sum(circle, w))
    residue = np.mean(integrand * (circle - pole))  # (1 / 2 pi i) int f dp over the circle
    assert abs(coefficient - residue) < 1e-6 * abs(residue)


@pytest.mark.slow  # about a minute: each value above the line follows the free waves' poles
def test_continued_receptance_is_analytic_across_a_free_wave_line():
    """At q = 0.05 i, above the free waves' floor (eta_f = 0.01), two poles of the integrand near p = +-3.41
    have crossed the real axis (residues of order 1): the continued receptance there equals its mean over a
    circle of radius 0.005 (which the singular line cuts; 8 points) to 1e-6 of its size; the integral over
    real p as it stands does not (its mean differs by more than 1e-2)."""
    track = _long_bay_track()
    q0, radius = 0.05j, 0.005
    sheet = Sheet(0.99 * track.free_wave_floor())
    crossed = sheet_poles(track, q0, 5 * track.K + 10, sheet.y0, 2, 0.0)
    assert crossed.crossed >= 1  # the line passes below q0: the circle straddles it
    points = q0 + radius * np.exp(2j * np.pi * np.arange(8) / 8)

    def H(q: complex, continued: bool) -> np.ndarray:
        rec = receptance(track, q, [-1, 0], tol=1e-12, continued_from=sheet if continued else None)
        return rec.matrix

    centre = H(q0, True)
    size = np.max(np.abs(centre))
    mean = np.mean([H(q, True) for q in points], axis=0)
    assert np.max(np.abs(mean - centre)) < 1e-6 * size
    physical_mean = np.mean([H(q, False) for q in points], axis=0)
    assert np.max(np.abs(physical_mean - H(q0, False))) > 1e-2 * size


@pytest.mark.slow  # the continued window is searched with one harmonic set
def test_short_bays_root_beyond_the_free_waves_is_the_continuous_one():
    """A light wheel at lam = 0.703 on supports that carry most of the damping (eta_f = 0.02, eta_sup =
    0.18; smeared: eta = 0.2, the continuous track of tests/test_floquet_strip.py): the continuous track's
    decaying root 0.686 + 0.115 i and its mirror image lie beyond the periodic rail's free waves (Im q =
    0.02); the continued strip search counts and finds both, to the bay's effect, and states the depth it
    searched."""
    lam, alpha, eta_M = 0.703, 0.3, 2.0
    groups = {"lam": lam, "alpha": alpha, "kappa_f": 0.0, "eta_f": 0.02, "eta_sup": 0.18}
    track = SleeperTrack(PERIODIC["eb", "sleepers"], groups)
    vehicle = VehicleMatrices.from_module(vehicle_mass, {"eta_M": eta_M})
    result = floquet_frequencies(track, vehicle, N_max=1, continued=True)
    assert result.continued_to == pytest.approx(0.9 * 0.2) and result.window.y1 == result.continued_to
    reference = _continuous_folded(alpha, 0.2, eta_M, track.Omega0, result.window.y1)
    assert len(reference) == 2 and all(q.imag > result.free_waves for q in reference)
    _assert_matches(result, reference, 8 * ZETA4 / track.K**4)
    # without the continuation the window stops below the free waves and holds neither
    below = floquet_frequencies(track, vehicle, N_max=1, continued=False)
    assert below.count == 0 and below.window.y1 < result.free_waves


@pytest.mark.slow  # about a minute: the continued window of the example, then 20 periods of the finite rail
def test_the_examples_root_beyond_the_free_waves_against_the_finite_rails_free_decay():
    """examples/sleepers.toml (a 600 kg wheel): the continued search finds one pair of decaying roots, both
    beyond the rail's free waves (Im q = eta_f = 0.0129); the finite rail of validation/sleepers_rail.py
    (no harmonics, no receptance), released from the static deflection, decays at their rate Im q within
    the finite-beam check's 1 % (measured: 0.12 %); its fit starts at tau = 0, the run falling below
    1e-6 of its start within 20 bay-passing periods."""
    vehicle = VehicleMatrices.from_module(vehicle_mass, {"eta_M": 13.998576285})
    track = SleeperTrack(PERIODIC["eb", "sleepers"], dict(EXAMPLE_GROUPS))
    result = floquet_frequencies(track, vehicle, continued=True)
    assert result.verdict.state == "stable" and result.count == 2 and result.continued_to is not None
    least = result.least_damped
    assert least is not None and least.q.imag > result.free_waves
    T0 = track.lam / track.alpha
    tau = 20 * T0
    margin = math.ceil(MARGIN / track.lam)
    rail = SleeperRail(track, 2 * margin + math.ceil(track.alpha * tau / track.lam) + 1, 4)
    loads = static_loads(vehicle_mass, {"eta_M": 13.998576285})
    run = simulate_sleeper_beam(
        rail, vehicle, loads, entry=margin * track.lam, tau_max=tau, dt=T0 / 100, loaded=False
    )
    rate = fit_floquet_modes(run.tau, run.deflection, T0, 0.0).rate
    assert abs(-rate / least.q.imag - 1) < 0.01, (rate, least.q)


@pytest.mark.parametrize("where", [["--case", "1"], ["--file", "examples/soil-mass.toml"]])
def test_continued_is_refused_off_sleepers(where, capsys):
    from moving_bogie.cli import main

    root = __import__("pathlib").Path(__file__).resolve().parent.parent
    argv = [a if not a.startswith("examples/") else str(root / a) for a in where]
    assert main(["frequencies", *argv, "--continued"]) == 2
    err = capsys.readouterr().err
    assert "--continued applies to a rail on sleepers" in err and "Traceback" not in err


@pytest.mark.slow  # the continued search of the example (a few seconds)
def test_the_command_line_searches_beyond_the_free_waves_when_asked(capsys):
    """``frequencies --continued`` runs the continued search: the pair of roots of the test above (beyond
    the free waves, which the search without it does not reach) and the depth searched in the JSON."""
    import json
    from pathlib import Path

    from moving_bogie.cli import main

    file = str(Path(__file__).resolve().parent.parent / "examples" / "sleepers.toml")
    assert main(["frequencies", "--file", file, "--json"]) == 0
    plain = json.loads(capsys.readouterr().out)
    assert main(["frequencies", "--file", file, "--continued", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert len(out["roots"]) == 2 and not plain["roots"] and out["stable"]
    assert out["region"]["continued_to_im"] > out["region"]["free_waves_im"]
    assert plain["region"]["continued_to_im"] is None
