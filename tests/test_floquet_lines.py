"""D-decomposition lines and the (v, M) map of a vehicle on sleepers (docs/sleepers.md, (S19)-(S22)).

References: the Hill determinant of kernels/hill.py (FloquetSystem, built without the pencil); the argument
principle's count (roots/count/contour.py) on the window of roots/strip.py, which knows nothing of the
D-decomposition; the symmetry (S14), which puts the principal zone's crossings on Re q = Omega_0 / 2.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np
import pytest

from moving_bogie.cli import main
from moving_bogie.generated import vehicle_hertz_mass, vehicle_mass
from moving_bogie.kernels.hill import FloquetSystem, VehicleMatrices
from moving_bogie.kernels.mass_pencil import mass_pencil
from moving_bogie.kernels.sleeper_track import SleeperTrack
from moving_bogie.model.catalogue import default_catalogue
from moving_bogie.roots.count.contour import Rectangle, winding_number
from moving_bogie.stability.maps.d_lines import d_column

#: the catalogue's rails on periodic supports, (beam, track) -> their generated functions
PERIODIC = default_catalogue().periodic

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"

#: long, lightly damped bays with a heavy wheel: the principal parametric zone of test_floquet_search.py,
#: with a little damping along the rail so that the real axis is regular (S15)
ZONE_TRACK = {"lam": 1.5, "alpha": 0.25, "kappa_f": 0.0, "eta_f": 0.002, "eta_sup": 0.005}


@pytest.mark.parametrize("module, values", [(vehicle_mass, {"eta_M": 1.0}), (vehicle_hertz_mass, None)])
def test_pencil_is_the_hill_matrix_at_every_mass(module, values):
    """det(A + eta_M B) equals the Hill determinant of FloquetSystem at that eta_M (a complex q, two
    masses); for the rigid contact A = I (no root at eta_M -> 0, Eq. (S19))."""
    if values is None:
        values = {"eta_M": 1.0, "kappa_H": 20.0, "eta_H": 0.1}
    track = SleeperTrack(PERIODIC["eb", "sleepers"], ZONE_TRACK)
    pencil = mass_pencil(track, module, values, 1)
    q = 0.37 - 0.05j
    A, B = pencil.matrices(q)
    for eta in (0.7, 5.0):
        vehicle = VehicleMatrices.from_module(module, values | {"eta_M": eta})
        reference = FloquetSystem(track, vehicle, 1, tol=pencil.tol)(q)
        assert abs(np.linalg.det(A + eta * B) - reference) < 1e-9 * max(1.0, abs(reference))
    if module is vehicle_mass:
        assert np.array_equal(A, np.eye(len(A)))


@pytest.mark.slow
def test_zone_edges_are_the_d_decomposition_crossings():
    """The principal zone: two crossings on Re q = Omega_0 / 2, +1 then -1, converged in the harmonics.
    The argument principle on floquet_frequencies' window (the strip, Im q in [-max(Omega_0, 1), 0]) counts
    0 roots just below the lower edge, 1 just inside it and 0 just above the upper edge (1% of the zone's
    width away), as the column's counts say."""
    track = SleeperTrack(PERIODIC["eb", "sleepers"], ZONE_TRACK)
    column = d_column(mass_pencil(track, vehicle_mass, {"eta_M": 1.0}, 2), eta_max=6.0)
    assert not column.notes and column.converged
    assert [c.change for c in column.crossings] == [1, -1]
    lo, hi = (c.eta_M for c in column.crossings)
    for c in column.crossings:
        assert abs(c.q - track.Omega0 / 2) < 1e-8 * track.Omega0
    omega0 = track.Omega0
    window = Rectangle(-omega0 / 4, 3 * omega0 / 4, -max(omega0, 1.0), 0.0)
    delta = 0.01 * (hi - lo)
    for eta, expected in ((lo - delta, 0), (lo + delta, 1), (hi + delta, 0)):
        assert column.counts([eta])[0] == expected
        vehicle = VehicleMatrices.from_module(vehicle_mass, {"eta_M": eta})
        system = FloquetSystem(track, vehicle, 2, tol=1e-6)
        spacing = min(window.width, window.height) / 12
        assert winding_number(system, window, spacing=spacing, max_points=20_000) == expected, eta


@pytest.mark.parametrize(
    "extra, option",
    [
        (["--d", "1.5"], "--d"),
        (["--d", "0"], "--d"),  # a zero is given too (0.0 == False must not hide it)
        (["--eta-f", "0.0"], "--eta-f"),
        (["--range", "v=0:100"], "--range"),
        (["--range", "M=-10:100"], "--range"),
        (["--range", "w=1:2"], "--range"),
        (["--n", "1"], "--n"),
        (["--parameter", "kappa_v"], "--parameter"),
        (["--workers", "0"], "--workers"),
        (["--units", "dimensionless"], "--units"),
    ],
)
def test_bad_options_are_named_before_any_computation(extra, option, capsys):
    """Each option that a sleeper map cannot take is named in one line, exit 2, no traceback."""
    code = main(["stability-map", "--file", str(EXAMPLES / "sleepers.toml"), "--json", *extra])
    out = json.loads(capsys.readouterr().out)
    assert code == 2
    assert option in out["error"]


@pytest.mark.slow
def test_a_sleeper_map_takes_an_m_axis_above_zero_and_set(capsys):
    """--range M=1000:2000 (the counts still start from M -> 0 below the axis) and --set on a sleeper map:
    the cells checked by the strip search (floquet_frequencies, an independent count at the cell) agree."""
    args = ["stability-map", "--file", str(EXAMPLES / "sleepers_zones.toml"), "--range", "v=90:100"]
    args += ["--range", "M=1000:2000", "--n", "3", "--workers", "1", "--set", "c_f=600", "--json"]
    assert main(args) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["M_kg"] == [1000.0, 2000.0, 3]
    assert out["checks"] and all(check["agrees"] for check in out["checks"])


def _previous_column(pencil, monkeypatch, **options):
    """The column as the D-decomposition computed it before its short cuts (the reference): each crossing
    followed with one more harmonic by Brent's method on its bracket, and Brent's method run to its
    tolerance on every sign change (a jump between two branches included)."""
    from moving_bogie.stability.maps import d_lines

    with monkeypatch.context() as m:
        m.setattr(d_lines, "POLISH_ITER", 100)
        m.setattr(d_lines, "_follow", lambda finer, q, mu, a, b: d_lines._polish(finer, a, b, mu, mu))
        return d_column(pencil, **options)


@pytest.mark.parametrize(
    "v, zone",
    [
        (97.0, True),  # the principal zone: two crossings on Re q = Omega_0 / 2
        pytest.param(30.0, False, marks=pytest.mark.slow),  # no crossing; two branches swap near q = 0
    ],
)
def test_the_short_cuts_give_the_previous_crossings(v, zone, monkeypatch):
    """On the map of examples/sleepers_zones.toml: the crossings, their changes, their move with one more
    harmonic and the notes of a column are those of the previous algorithm (Brent's method on every
    bracket, :func:`_previous_column`), so the counts of every cell are the same."""
    from moving_bogie import bind, load_parameters
    from moving_bogie.stability.maps.sleeper_map import track_at

    _, physical = load_parameters(EXAMPLES / "sleepers_zones.toml")
    bound, scales = bind(physical), physical.scales()
    track = track_at(bound, v / scales.v_ref)
    pencil = mass_pencil(track, bound.vehicle, bound.vehicle_values(bound.floats), 2)
    eta_max = 3000.0 / scales.mass
    fast = d_column(pencil, eta_max=eta_max)
    previous = _previous_column(pencil, monkeypatch, eta_max=eta_max)
    assert fast.notes == previous.notes == ()
    assert [c.change for c in fast.crossings] == [c.change for c in previous.crossings]
    assert bool(fast.crossings) == zone
    for a, b in zip(fast.crossings, previous.crossings):
        assert abs(a.eta_M - b.eta_M) <= 1e-12 * b.eta_M and abs(a.q - b.q) <= 1e-12 * track.Omega0
        assert abs(a.moved - b.moved) <= 1e-9  # the followed crossing is Brent's to 1e-9 in eta_M
    etas = np.linspace(0, eta_max, 400)
    assert np.array_equal(fast.counts(etas), previous.counts(etas))


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="glibc's mallopt")
def test_only_a_worker_keeps_its_freed_memory():
    """The sleeper map's workers take big arrays from the heap (mallopt accepts both settings); the caller's
    own process is left with glibc's defaults."""
    from concurrent.futures import ProcessPoolExecutor

    from moving_bogie.stability.maps.d_map import keep_freed_memory

    assert keep_freed_memory() is False
    with ProcessPoolExecutor(1) as pool:
        assert pool.submit(keep_freed_memory).result() is True


def test_margin_on_a_continuous_map_is_named(capsys):
    """--margin colours a sleeper map; the continuous map has every margin without it: named, exit 2."""
    args = ["stability-map", "--file", str(EXAMPLES / "uic60-bogie.toml"), "--n", "2", "--margin", "--json"]
    assert main(args) == 2
    assert "--margin" in json.loads(capsys.readouterr().out)["error"]


@pytest.mark.slow
def test_the_margins_of_a_sleeper_map_are_the_strip_searchs(tmp_path):
    """examples/sleepers_zones.toml at v = 97.2881 m/s with margins: the two cells inside the principal zone
    grow at -Im Omega = 2.90111 and 3.22093 1/s, those of an independent Floquet-Hill computation (a separate
    code; the test of validate at the same points) within 1e-5; the cell below the zone, which the
    D-decomposition counts stable (its crossings, independent of the strip search), decays (margin > 0)
    and is the map's smallest decay rate; JSON and CSV carry the margins."""
    import moving_bogie as mb

    _, physical = mb.load_parameters(EXAMPLES / "sleepers_zones.toml")
    smap = mb.sleeper_map(physical, [97.2881], [1300.0, 1400.0, 1416.0], verify=0, workers=1, margin=True)
    assert smap.margin is not None and smap.margin_bound is not None
    assert smap.count[:, 0].tolist() == [0, 1, 1]
    np.testing.assert_allclose(-smap.margin[1:, 0], [2.90111, 3.22093], rtol=1e-5)
    assert smap.margin[0, 0] > 0 and smap.min_decay_rate == smap.margin[0, 0]
    data = smap.to_dict()
    assert data["margin_1_s"] == smap.margin.tolist() and data["min_decay_rate_1_s"] == smap.margin[0, 0]
    header, first = smap.to_csv().splitlines()[:2]
    assert header.endswith(",margin_1_s")
    assert float(first.split(",")[-1]) == pytest.approx(smap.margin[0, 0], rel=1e-9)  # 10 digits
