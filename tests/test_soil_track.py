"""Tracks on the soil: files, the ballasted track's determinant, free waves, critical velocity, moving load.

References: the ballasted track's 3 x 3 dynamic stiffness matrix built from its definition (the ballast rod's
cot and 1/sin entries) and numpy's determinant; on stiff soil, the beam on the Winkler foundation of the
static equivalent stiffness (its closed form through Struve functions, mpmath) solved by brentq; the Rayleigh
cubic and the free beam's closed-form dispersion for the critical velocities of a beam on a homogeneous
half-space; mpmath's quadrature of the static deflection over that closed form; and (slow) a direct
two-dimensional Fourier quadrature of the moving-load deflection with Lamb's flexibility, by scipy's adaptive
quad in both wavenumbers.
"""

from __future__ import annotations

import json
import tomllib
from pathlib import Path

import numpy as np
import pytest
from scipy import integrate, optimize, special

from moving_bogie.cli import main
from moving_bogie.errors import ParameterError
from moving_bogie.soil import critical
from moving_bogie.soil.critical import critical_velocity, free_waves
from moving_bogie.soil.file import load_soil_file, soil_input
from moving_bogie.soil.moving_load import PEAK_XTOL, deflection
from moving_bogie.soil.profile import soil_profile
from moving_bogie.soil.track import SoilTrack

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
BALLASTED = {
    "EI": 1.29e7, "m": 120.0, "k_pad": 5e8, "c_pad": 2.5e5, "m_s": 490.0,
    "E_b": 130e6, "rho_b": 1700.0, "h_b": 0.35, "A_b": 1.25, "b": 1.25,
}  # fmt: skip
HALF = [{"rho": 1800.0, "c_s": 60.0, "nu": 0.45}]


def test_file_per_rail_doubles_the_track_and_the_load():
    data = {"model": {"track": "soil", "per": "rail"}, "physical": {"EI": 6e6, "m": 60, "b": 1.3, "P": 8e4}}
    loaded = soil_input(data | {"soil": HALF})
    assert (loaded.track.EI, loaded.track.m, loaded.track.b, loaded.load) == (12e6, 120.0, 1.3, 16e4)
    per_track = soil_input(data | {"model": {"track": "soil"}, "soil": HALF})
    assert (per_track.per, per_track.track.EI, per_track.load) == ("track", 6e6, 8e4)


@pytest.mark.parametrize(
    ("change", "key"),
    [
        ({"model": {"track": "soil", "per": "axle"}}, "per"),
        ({"physical": {"EI": 6e6, "m": 60}}, "b"),
        ({"physical": {"EI": 6e6, "m": 60, "b": 1.3, "k_pad": 1e8}}, "k_pad"),
        ({"physical": {"EI": -6e6, "m": 60, "b": 1.3}}, "EI"),
        ({"soil": []}, "soil"),
        (
            {
                "soil": [
                    {"h": 2, "rho": 1800, "c_s": 60, "nu": 0.3},
                    {"rho": 1800, "c_s": 80, "nu": 0.3, "eta": -1},
                ]
            },
            "eta",
        ),
    ],
)
def test_file_errors_name_the_key(change, key):
    data = {"model": {"track": "soil"}, "physical": {"EI": 6e6, "m": 60, "b": 1.3}, "soil": HALF} | change
    with pytest.raises(ParameterError) as info:
        soil_input(data)
    assert info.value.parameter == key


def test_cli_bad_file_exits_2(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    bad.write_text(
        '[model]\ntrack = "soil"\n[physical]\nEI = 6e6\nm = 60\nb = 1.3\n[[soil]]\nrho = 1800\nc_s = 60\n'
    )
    assert main(["dispersion", "--file", str(bad), "--json"]) == 2
    message = json.loads(capsys.readouterr().out)
    assert "soil[1]" in json.dumps(message) and "c_p" in json.dumps(message)


def test_ballasted_determinant_is_the_stiffness_matrix_determinant():
    track = SoilTrack(kind="ballasted-soil", **BALLASTED)
    k1, omega, chi = np.array([0.3, 1.7]), np.array([40.0, 900.0]), np.array([3e7 + 2e6j, 8e8 - 1e7j])
    lam = omega * track.h_b / np.sqrt(track.E_b / track.rho_b)
    z = track.E_b * track.A_b / track.h_b * lam
    k_p = track.k_pad + 1j * omega * track.c_pad
    for i in range(2):
        rail = track.EI * k1[i] ** 4 - track.m * omega[i] ** 2
        matrix = [
            [rail + k_p[i], -k_p[i], 0],
            [-k_p[i], k_p[i] + z[i] / np.tan(lam[i]) - track.m_s * omega[i] ** 2, -z[i] / np.sin(lam[i])],
            [0, -z[i] / np.sin(lam[i]), z[i] / np.tan(lam[i]) + chi[i]],
        ]
        ref = np.linalg.det(np.array(matrix)) * (np.sin(lam[i]) / lam[i]) ** 2
        got = track.determinant(k1[i : i + 1], omega[i : i + 1], chi[i : i + 1])[0]
        assert abs(got / ref - 1) < 1e-10
        schur = np.linalg.det(np.array(matrix)) / np.linalg.det(np.array(matrix)[1:, 1:])
        assert (
            abs(track.rail_stiffness(k1[i : i + 1], omega[i : i + 1], chi[i : i + 1])[0] / schur - 1) < 1e-10
        )


def _static_chi(a: float, mu: float, nu: float, b: float) -> float:
    """The homogeneous half-space's static chi in closed form: J(x) = int_0^x K_0 through the modified
    Struve functions, L_{-1} = L_1 + 2 / pi (scipy)."""
    x = a * b
    if x > 50:  # J(x) = pi / 2 - O(e^-x); the Struve form overflows there
        return float(2 * np.pi / ((1 - nu) / mu * np.pi / x))
    l_minus1 = special.modstruve(1, x) + 2 / np.pi
    j = np.pi * x / 2 * (special.k0(x) * l_minus1 + special.k1(x) * special.modstruve(0, x))
    return float(2 * np.pi / ((1 - nu) / mu * 2 * j / x))


def test_stiff_soil_is_a_winkler_foundation_of_the_static_stiffness():
    """A heavy beam on stiff soil (c_s = 2000 m/s) above the foundation's cut-on: its free wave at 1500 rad/s
    is the Winkler beam's of the static chi(k1, 0), to O((c / c_s)^2) (about 1e-2 here)."""
    soil = soil_profile([{"rho": 2000.0, "c_s": 2000.0, "nu": 0.3}])
    track = SoilTrack(kind="soil", EI=1e7, m=1e5, b=1.3)
    mu, nu = soil.layers[0].mu, soil.layers[0].nu
    omega = 1500.0

    def winkler(k: float) -> float:
        return track.EI * k**4 + _static_chi(k, mu, nu, track.b) - track.m * omega**2

    c_ref = omega / optimize.brentq(winkler, 0.01, 100.0, xtol=1e-14)
    waves = free_waves(track, soil, np.array([omega]))
    c = waves.c[0][np.isfinite(waves.c[0])]
    assert c.size == 1
    assert abs(c[0] / c_ref - 1) < (c_ref / 2000.0) ** 2


def _rayleigh_speed(path: Path) -> float:
    """c_R of the homogeneous half-space of the soil file ``path`` (its one [[soil]] table's c_s and nu, read
    with tomllib, not through the package): the root in (0, 1) of the Rayleigh cubic
    x^3 - 8 x^2 + (24 - 16 / kappa^2) x - 16 (1 - 1 / kappa^2) = 0, x = (c_R / c_s)^2, kappa = c_p / c_s
    (Achenbach, Wave Propagation in Elastic Solids, Section 5.11), by numpy's companion-matrix roots; the
    package finds its modes from the layered determinant instead (soil/rayleigh.py)."""
    (layer,) = tomllib.loads(path.read_text(encoding="utf-8"))["soil"]
    kappa2 = 2 * (1 - layer["nu"]) / (1 - 2 * layer["nu"])  # (c_p / c_s)^2 from Poisson's ratio
    xi = np.roots([1, -8, 24 - 16 / kappa2, -16 * (1 - 1 / kappa2)])
    return layer["c_s"] * np.sqrt(min(x.real for x in xi if abs(x.imag) < 1e-12 and 0 < x.real < 1))


def test_beam_on_homogeneous_halfspace_critical_velocities():
    """A light beam: the guided branch ends on the Rayleigh wave, so v_cr = c_R (the Rayleigh cubic), and the
    free beam crosses c_R at omega = c_R^2 sqrt(m / EI)."""
    loaded = load_soil_file(EXAMPLES / "soil-homogeneous.toml")
    c_r = _rayleigh_speed(EXAMPLES / "soil-homogeneous.toml")
    result = critical_velocity(loaded.track, loaded.soil, np.geomspace(1.0, 30.0, 6))
    assert abs(result.v_cr / c_r - 1) < 1e-6
    assert abs(result.v_cr_uncoupled / c_r - 1) < 1e-10
    assert abs(result.omega_uncoupled / (c_r**2 * np.sqrt(loaded.track.m / loaded.track.EI)) - 1) < 1e-9


def test_meeting_on_the_track_curve_against_the_nested_search(monkeypatch):
    """The meeting of the track's own curve with the soil's fundamental mode, found as the root of the soil's
    secular function along that curve, against the nested search (Illinois steps in omega on the track's
    determinant at c_0(omega), a mode search per step), taken when the check of the first is made to
    fail; on the ballasted example's rail branch end (between the default grid's frequencies 51.7 and
    64.6 rad/s)."""
    loaded = load_soil_file(EXAMPLES / "soil-ballasted.toml")
    meeting = critical._meeting.__wrapped__
    w, c = meeting(loaded.track, loaded.soil, 51.717213988518196, 64.62630336220614)
    monkeypatch.setattr(critical, "MEETING_CHECK", 0.0)
    w_ref, c_ref = meeting(loaded.track, loaded.soil, 51.717213988518196, 64.62630336220614)
    assert 51.7 < w < 64.7
    assert abs(w / w_ref - 1) < 1e-10
    assert abs(c / c_ref - 1) < 1e-10


def test_static_deflection_against_closed_form_quadrature():
    """w_static = (P / pi) int_0^inf dk / (EI k^4 + chi_0(k)), chi_0 in closed form (Struve functions),
    summed by scipy's adaptive quad (the piece below k = 1e-12, of order 1e-12 ln(1e12), is left out)."""
    loaded = load_soil_file(EXAMPLES / "soil-homogeneous.toml")
    track, soil = loaded.track, loaded.soil
    mu, nu = soil.layers[0].mu, soil.layers[0].nu

    def f(k: float) -> float:
        return 1 / (track.EI * k**4 + _static_chi(k, mu, nu, track.b))

    pieces = ((1e-12, 1e-3), (1e-3, 0.1), (0.1, 10.0), (10.0, np.inf))
    ref = (
        loaded.load
        / np.pi
        * sum(integrate.quad(f, a, b, epsabs=0, epsrel=1e-11, limit=200)[0] for a, b in pieces)
    )
    got = deflection(track, soil, loaded.load, 0.0)
    assert abs(got.w[0] / ref - 1) < 1e-5
    assert got.error[0] < 1e-4 * got.w[0]


@pytest.mark.slow
def test_moving_load_against_direct_two_dimensional_quadrature():
    """w(0) at 50 m/s on the damped homogeneous half-space: both wavenumber integrals by scipy's adaptive
    quad (QUADPACK, relative tolerances only: the integrands are ~1e-10) with Lamb's closed-form flexibility,
    no code of soil/ in the reference."""
    loaded = load_soil_file(EXAMPLES / "soil-homogeneous.toml")
    track, layer, v = loaded.track, loaded.soil.layers[0], 50.0

    def lamb(k, omega):
        mu = layer.mu * (1 + 1j * omega * layer.eta)
        ks2 = layer.rho * omega**2 / mu
        kp2 = ks2 * layer.xi
        p, s = np.sqrt(k * k - kp2 + 0j), np.sqrt(k * k - ks2 + 0j)
        p, s = (p if p.real >= 0 else -p), (s if s.real >= 0 else -s)
        return (
            -ks2 * p / (mu * ((2 * k * k - ks2) ** 2 - 4 * k * k * p * s))
            if omega
            else (1 - layer.nu) / (mu * k)
        )

    def inner(k1):
        w = k1 * v
        parts = []
        for part in (np.real, np.imag):
            f = lambda k2, part=part: part(np.sinc(k2 * track.b / np.pi) * lamb(np.hypot(k1, k2), w))  # noqa: E731
            near = np.sqrt(max((w / 56.9) ** 2 - k1 * k1, 0.0))
            head = integrate.quad(
                f, 0, 30, points=[near] if 0 < near < 30 else None, limit=400, epsrel=1e-10
            )[0]
            g = lambda k2, part=part: part(lamb(np.hypot(k1, k2), w)) / (k2 * track.b)  # noqa: E731
            parts.append(head + integrate.quad(g, 30, np.inf, weight="sin", wvar=track.b, epsabs=1e-22)[0])
        chi = 2 * np.pi / (2 * (parts[0] + 1j * parts[1]))
        return 1 / (track.EI * k1**4 - track.m * w**2 + chi)

    outer = integrate.quad(
        lambda k: inner(k).real, 1e-7, 60, limit=400, epsrel=1e-8, points=[0.01, 0.1, 1, 3]
    )[0]
    ref = loaded.load / np.pi * outer
    got = deflection(track, loaded.soil, loaded.load, v)
    assert abs(got.w[0] / ref - 1) < 1e-4


def test_dispersion_command_json(capsys):
    path = str(EXAMPLES / "soil-homogeneous.toml")
    assert main(["dispersion", "--file", path, "--omega", "1,10,50", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["per"] == "rail" and out["soil_modes"][0]["mode"] == 0
    assert out["soil_modes"][0]["omega"] == [1.0, 10.0, 50.0]
    assert len(out["track_waves"]["c_uncoupled"]) == 3


@pytest.mark.slow
@pytest.mark.parametrize("settings", [{}, {"c_s1": 50.0}])
def test_ballasted_example_critical_velocity_against_disba(tmp_path, capsys, settings):
    """The uncoupled estimate: the track's own curve (closed form, chi = 0) crosses the fundamental mode
    of disba (Dunkin's method), found here by brentq; the coupled value ends on the same point (its branch
    meets the fundamental mode, chi -> 0 there); the command writes both and the figure. With c_s1 = 50
    m/s, waves that only follow the soil's mode at low frequency are split off by a grid frequency: the
    coupled value must still be taken on the rail's branch."""
    disba = pytest.importorskip("disba")
    loaded = load_soil_file(EXAMPLES / "soil-ballasted.toml", settings=settings)
    layers = loaded.soil.layers
    th = np.array([layer.h if np.isfinite(layer.h) else 0.0 for layer in layers]) / 1e3
    vp, vs = (np.array([getattr(layer, c) for layer in layers]) / 1e3 for c in ("c_p", "c_s"))
    rho = np.array([layer.rho for layer in layers]) / 1e3
    pd = disba.PhaseDispersion(th, vp, vs, rho, algorithm="dunkin", dc=1e-6)

    def gap(w: float) -> float:
        c0 = pd(np.array([2 * np.pi / w]), mode=0).velocity[0] * 1e3
        return w / loaded.track.undamped().free_wavenumber(np.array([w + 0j])).real[0] - c0

    w_ref = optimize.brentq(gap, 20.0, 100.0, xtol=1e-10)
    c_ref = w_ref / loaded.track.undamped().free_wavenumber(np.array([w_ref + 0j])).real[0]
    figure = tmp_path / "disp.png"
    assert (
        main(
            [
                "critical-velocity",
                "--file",
                str(EXAMPLES / "soil-ballasted.toml"),
                "--json",
                "--plot",
                str(figure),
                *[f"--set={key}={value:g}" for key, value in settings.items()],
            ]
        )
        == 0
    )
    out = json.loads(capsys.readouterr().out)
    assert abs(out["v_cr_uncoupled"] / c_ref - 1) < 1e-6
    assert abs(out["v_cr"] / c_ref - 1) < 1e-6
    assert figure.stat().st_size > 10_000


@pytest.mark.slow
def test_moving_load_command_peak(capsys, tmp_path):
    """The peak refined between grid points is at least every grid value, between the grid's neighbours of
    the largest, and its speed is the Rayleigh speed for this light beam (the guided branch hugs it).

    Reference: c_R of the file's half-space from the Rayleigh cubic (``_rayleigh_speed``), which is v_cr of
    this beam (``test_beam_on_homogeneous_halfspace_critical_velocities``): the lightly damped response
    peaks there. Tolerance: the command refines between the grid's two neighbours of the largest value (two
    grid steps, 2 h = 16 m/s) by scipy's bounded Brent search with xatol = PEAK_XTOL 2 h, which stops when
    its bracket lies within 2 (sqrt(eps) |v| + xatol / 3) of its best point (soil/moving_load.py): the
    peak is known to that, 1.07e-3 m/s, and no better."""
    figure = tmp_path / "daf.png"
    path = EXAMPLES / "soil-homogeneous.toml"
    lo, hi, n = 48.0, 64.0, 3
    argv = ["moving-load", "--file", str(path), "--range", f"v={lo:g}:{hi:g}:{n}", "--json", "--plot"]
    assert main([*argv, str(figure)]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["per"] == "rail" and out["P"] == 80e3 and out["w_static"] > 0
    assert out["daf_peak"] >= max(out["daf"]) and 50 <= out["v_peak"] <= 60
    step = (hi - lo) / (n - 1)
    bracket = 2 * (np.sqrt(np.finfo(float).eps) * out["v_peak"] + PEAK_XTOL * 2 * step / 3)
    c_r = _rayleigh_speed(path)
    assert abs(out["v_peak"] - c_r) <= bracket, (out["v_peak"], c_r, bracket)
    assert figure.stat().st_size > 10_000
