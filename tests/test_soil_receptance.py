"""The rail's receptance on the soil at complex frequency (docs/soil.md, Eq. (S9)) and the soil as a track.

References: (slow) at Omega = 0, the k integral by scipy's quad with the strip's chi; (slow) a direct
two-dimensional quadrature at a complex Omega with Lamb's
closed-form flexibility, scipy's quad in both wavenumbers (no code of soil/); the continuous Winkler track
of the bound model's own parameters (``kernels/continuous_track.py``, residues of a rational kernel) for a
ballasted track on a rigid soil; the strip's quadrature itself where the local stiffness 2 b / U stands
for it (the rule of ``soil/receptance.py``); the strip's quadrature at 1e-10 where chi is interpolated in
the speed (``soil/receptance_chi.py``), and the receptance computed without that interpolation.
"""

from __future__ import annotations

import functools
from pathlib import Path

import numpy as np
import pytest
from scipy import integrate
from soil_cases import RIGID

from moving_bogie.api import bind, soil_vehicle
from moving_bogie.kernels.bound import BoundModel
from moving_bogie.kernels.continuous_track import ContinuousTrack
from moving_bogie.soil import receptance
from moving_bogie.soil.file import load_soil_file, soil_input
from moving_bogie.soil.rail_track import SoilRail
from moving_bogie.soil.receptance import LOCAL_KB, local_stiffness, soil_receptance
from moving_bogie.soil.receptance_chi import speed_table
from moving_bogie.soil.strip import strip_stiffness

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


@pytest.mark.slow
def test_receptance_at_rest_frequency_against_quadpack_in_k():
    """G(Delta, 0) = w(Delta) / P of Eq. (S8): the k integral by scipy's quad_vec (adaptive Gauss-Kronrod
    21, its own breakpoints) over both sides of k = 0, chi(|k|, k v) from the strip's quadrature at 1e-8
    (itself checked against mpmath in tests/test_soil_strip.py); within three times the stated error plus
    1e-7 of the reference (quad_vec's 1e-9 of the whole, chi's 1e-8). G(0) is real (G(-conj Omega) =
    conj G(Omega)), as the two-sided reference shows."""
    loaded = load_soil_file(EXAMPLES / "soil-homogeneous.toml")
    track, soil, v = loaded.track, loaded.soil, 40.0
    xi = np.array([0.0, 2.0])
    got = soil_receptance(track, soil, v, [0.0], xi)

    @functools.cache
    def inv_d(k: float) -> complex:
        kk, w = np.array([abs(k)]), np.array([k * v + 0j])
        # beyond |k| = 60 /m, chi_loc = 2 b / U (within half of chi there, the test below) is below 1e-4 of
        # EI k^4: it moves 1/D by < 1e-4 of the tail, itself < 1e-3 of G (2 / (3 EI 60^3))
        far = abs(k) > 60.0
        chi = (
            local_stiffness(kk, w, soil, track.b)
            if far
            else strip_stiffness(kk, w, soil, track.b, rtol=1e-8).chi
        )
        return complex(1 / (track.EI * k**4 - track.m * (k * v) ** 2 + chi[0]))

    def f(k: float) -> np.ndarray:
        return np.exp(-1j * k * xi) * inv_d(k)

    ends = [1e-9, 1e-3, 1e-2, 0.1, 0.3, 1.0, 3.0, 60.0, np.inf]
    spans = [sorted((s * a, s * b)) for s in (1.0, -1.0) for a, b in zip(ends[:-1], ends[1:], strict=True)]
    # an absolute tolerance for every piece from a first pass of the reference at 1e-3
    rough = np.abs(np.sum([integrate.quad_vec(f, a, b, epsrel=1e-3)[0] for a, b in spans], axis=0)).max()
    pieces = [integrate.quad_vec(f, a, b, epsabs=1e-9 * rough / len(spans), epsrel=0)[0] for a, b in spans]
    ref = np.sum(pieces, axis=0) / (2 * np.pi)
    assert np.all(np.abs(ref.imag) <= 1e-7 * np.abs(ref))
    assert np.all(np.abs(got.G[0] - ref) <= 3 * got.error[0] + 1e-7 * np.abs(ref))
    assert got.error[0] < 1e-5 * abs(got.G[0, 0])


def test_local_stiffness_is_within_half_of_the_strip_where_the_rule_takes_it():
    """The rule's allowance |chi - chi_loc| <= |chi_loc| where |k| b >= LOCAL_KB, checked against the
    strip's quadrature (its error far below) on both examples' soils at real and complex omega."""
    for name in ("soil-homogeneous.toml", "soil-ballasted.toml"):
        loaded = load_soil_file(EXAMPLES / name)
        b = loaded.track.b
        k1 = np.array([LOCAL_KB, 2 * LOCAL_KB, 8 * LOCAL_KB]) / b
        for omega in (k1 * 50.0, k1 * 50.0 - 30j):
            exact = strip_stiffness(k1, omega, loaded.soil, b, rtol=1e-8).chi
            local = local_stiffness(k1, omega, loaded.soil, b)
            assert np.all(np.abs(exact / local - 1) < 0.5)


def test_ballasted_track_on_rigid_soil_is_the_winkler_track_of_k_ref():
    """Railpads and a massless ballast rod on a rigid soil: D = EI k^4 - m omega^2 + k_pad k_b / (k_pad + k_b)
    up to z_12^2 / (z_22 + chi) over z_11 (E_b A_b / h_b = 4.6e8 N/m^2 against chi >= 6e12 N/m^2 for
    |k| >= 1e-6 / m, about 1e-4) and (omega h_b / c_b)^2 (< 1e-9 with rho_b = 1e-3): the kernel matrix of
    the continuous Winkler track of k_f = k_ref, eta_f = 0, from the same bound parameters, by residues."""
    vehicle = soil_vehicle(soil_input(RIGID))
    bound = bind(vehicle)
    assert isinstance(bound.track, SoilRail)
    winkler = ContinuousTrack(BoundModel(bound.params))
    q = np.array([0.3 - 0.2j, 1.4 - 0.05j])
    got = bound.track.receptance(q)
    ref = winkler.receptance(q).matrix
    assert np.all(np.abs(got.matrix - ref) <= 1e-4 * np.abs(ref) + 3 * got.error)


@pytest.mark.slow
def test_receptance_at_complex_frequency_against_two_dimensional_quadrature():
    """G(0, Omega) at Omega = 25 - 15i rad/s, v = 40 m/s, on the damped homogeneous half-space: chi by
    scipy's quad in k2 of Lamb's flexibility (Re p, Re s >= 0) and the k integral by scipy's quad on
    both sides, no code of soil/ in the reference; within three times the stated error plus the
    reference's own (quad's 1e-6, chi's 1e-9 and the tail's 1e-5 of 2 / (3 EI 60^3), together below
    2e-6 of G)."""
    loaded = load_soil_file(EXAMPLES / "soil-homogeneous.toml")
    track, layer, v, Omega = loaded.track, loaded.soil.layers[0], 40.0, 25.0 - 15.0j

    def chi(k1: float, omega: complex) -> complex:
        """2 pi / int sinc(k2 b) U_Lamb dk2 by scipy's quad: on [0, 1/b] directly, beyond it as a Fourier
        integral of U_Lamb / (k2 b) with the weight sin(k2 b) (QUADPACK's QAWF); within 3e-9 of mpmath's
        quadosc at 15 digits at k1 = 0, 0.3, 2 and 10 / m."""
        mu = layer.mu * (1 + 1j * omega * layer.eta)
        ks2 = layer.rho * omega**2 / mu
        kp2 = ks2 * layer.xi

        def root(z: complex) -> complex:
            r = np.sqrt(complex(z))
            return -r if r.real < 0 else r

        def u(t: float) -> complex:
            k2 = k1 * k1 + t * t
            p, s = root(k2 - kp2), root(k2 - ks2)
            return -ks2 * p / (mu * ((2 * k2 - ks2) ** 2 - 4 * k2 * p * s))

        total, a = 0j, 1.0 / track.b
        for part, unit in ((np.real, 1), (np.imag, 1j)):
            near = lambda t, part=part: part(u(t) * np.sinc(t * track.b / np.pi))  # noqa: E731
            total += unit * integrate.quad(near, 0, a, epsabs=0, epsrel=1e-11, limit=200)[0]
            far = lambda t, part=part: part(u(t) / (t * track.b))  # noqa: E731
            total += (
                unit * integrate.quad(far, a, np.inf, weight="sin", wvar=track.b, epsabs=1e-14, limlst=200)[0]
            )
        return complex(2 * np.pi / (2 * total))

    cache: dict[float, complex] = {}

    def inv_d(k: float) -> complex:
        if k not in cache:
            omega = Omega + k * v
            cache[k] = 1 / (track.EI * k**4 - track.m * omega**2 + chi(abs(k), omega))
        return cache[k]

    # beyond |k| = 60 / m, 1 / D = 1 / (EI k^4) to 1e-5 of itself (chi, m omega^2 / EI k^4 there); below
    # 1e-9 / m the integrand is bounded (D(0, Omega) != 0), a piece of 2e-9 |1 / D(0, Omega)|, left out
    total = complex(2 / (3 * track.EI * 60.0**3))
    for a, b in ((1e-9, 0.1), (0.1, 1.0), (1.0, 4.0), (4.0, 60.0)):
        for sign in (1, -1):
            for part, unit in ((np.real, 1), (np.imag, 1j)):
                f = lambda k, part=part, sign=sign: part(inv_d(sign * k))  # noqa: E731
                total += unit * integrate.quad(f, a, b, limit=200, epsrel=1e-6)[0]
    ref = total / (2 * np.pi)
    got = soil_receptance(track, loaded.soil, v, [Omega])
    assert abs(got.G[0, 0] - ref) <= 3 * got.error[0] + 2e-6 * abs(ref)


def test_chi_interpolated_in_speed_within_its_estimate():
    """chi(k, k v) interpolated in v from the table of soil/receptance_chi.py, at speeds between its
    Chebyshev points, against the strip's quadrature at 1e-10 there (itself checked against mpmath in
    tests/test_soil_strip.py): within the stated estimate (plus the direct value's own error) wherever the
    estimate is below 1e-3 of chi; and the estimate is that small at the small wavenumbers (the soil there
    a half-space faster than every speed) and large where a soil's wave speed lies in the range."""
    loaded = load_soil_file(EXAMPLES / "soil-ballasted.toml")
    soil, b = loaded.soil, loaded.track.b
    k = np.geomspace(1e-3, 2.5, 9)
    speeds = np.linspace(21.3, 118.9, 7)  # none at a Chebyshev point of [21.3, 118.9]
    chi, error = speed_table(k, speeds, soil, b, tol=1e-5)
    kk = np.tile(k, speeds.size)
    direct = strip_stiffness(kk, kk * np.repeat(speeds, k.size), soil, b, rtol=1e-10)
    relative = error / np.abs(chi)
    used = relative < 1e-3
    assert used[:, :4].all() and not used[:, -1].any()
    gap = np.abs(chi.ravel() - direct.chi) - direct.error
    assert np.all(gap[used.ravel()] <= error.ravel()[used.ravel()]), np.max(gap / error.ravel())


@pytest.mark.slow
def test_receptance_of_many_speeds_with_the_speed_table_against_each_alone(monkeypatch):
    """The moving load's receptance at six speeds in one call with chi at the first nodes interpolated in
    the speed (the table made to serve six) against the same speeds without the table: within the two
    stated errors, the table having spared strip quadratures."""
    loaded = load_soil_file(EXAMPLES / "soil-ballasted.toml")
    speeds = np.linspace(30.0, 110.0, 6)
    monkeypatch.setattr(receptance, "BY_SPEED", 2)
    table = soil_receptance(loaded.track, loaded.soil, speeds, np.zeros(6), tol=1e-5)
    monkeypatch.setattr(receptance, "BY_SPEED", 10**9)
    alone = soil_receptance(loaded.track, loaded.soil, speeds, np.zeros(6), tol=1e-5)
    assert table.chi_quadratures < alone.chi_quadratures
    assert np.all(np.abs(table.G[:, 0] - alone.G[:, 0]) <= table.error + alone.error)
