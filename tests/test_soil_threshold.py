"""The D-decomposition in the wheel mass along real q (stability/maps/real_axis.py) and the threshold mass on
the soil (docs/soil.md, "The threshold mass").

References: the instability lines of the continuous tracks (stability/lines/: real roots of E_chr traced by
continuation from the residue kernels, no pencil and no receptance quadrature), on the continuous track
itself and, through the soil's receptance, for a ballasted track on a rigid soil (the Winkler track of
k_f = k_ref); on the soil example, the argument principle (winding numbers of E_chr on rectangles, no
D-decomposition) at masses on both sides of the threshold, and a grid of E_chr values around the root the
window search returns (the winding number of every grid cell from its corners).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from moving_bogie.api import bind, induced_frequencies, load_soil_vehicle, soil_vehicle
from moving_bogie.cli import main
from moving_bogie.kernels.bound import BoundModel
from moving_bogie.model.cases import table1_case
from moving_bogie.model.physical import PhysicalParams
from moving_bogie.roots.count.contour import Rectangle, winding_number
from moving_bogie.roots.quadrature_window import QuadratureCharacteristic
from moving_bogie.roots.verdict import UNSTABLE
from moving_bogie.soil.file import soil_input
from moving_bogie.stability.lines.instability_lines import instability_lines
from moving_bogie.stability.maps.map import stability_map
from moving_bogie.stability.maps.real_axis import real_axis_column, window_column
from moving_bogie.stability.maps.real_axis_map import real_axis_map

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def _line_at(bound, alpha: float, theta_max: float, spacings=None) -> list[tuple[float, float, bool]]:
    """(eta_M, q, unstable above) of every instability line at ``alpha``: linear interpolation between the
    traced points (spaced at most h_max = 0.01 of the box, so within ~1e-5 of the line)."""
    lines = instability_lines(
        bound, alpha_range=(alpha - 0.02, alpha + 0.02), theta_max=theta_max, q_max=3.0, spacings=spacings
    )
    out = []
    for br in lines.branches:
        order = np.argsort(br.alpha)
        a, t, q = br.alpha[order], br.theta[order], br.q[order]
        k = np.searchsorted(a, alpha)
        if 0 < k < a.size:
            w = (alpha - a[k - 1]) / (a[k] - a[k - 1])
            up = bool(br.unstable_above[order][k])
            out.append(((1 - w) * t[k - 1] + w * t[k], (1 - w) * q[k - 1] + w * q[k], up))
    return sorted(out)


def test_crossings_on_a_continuous_track_are_its_instability_lines():
    """Table 1's case 1 (a bogie, the bar following the wheel mass as Eq. (63)) at its alpha = 0.8: the
    one crossing and its direction are those of the traced instability line."""
    bound = bind(table1_case(1))
    col = real_axis_column(bound, q_max=2.0, eta_max=200.0, samples=64)
    ref = _line_at(bound, float(bound.floats.alpha), 200.0)
    assert len(col.crossings) == len(ref) == 1
    (eta, q, above), c = ref[0], col.crossings[0]
    assert abs(c.eta_M / eta - 1) < 1e-4 and abs(c.q / q - 1) < 1e-4
    assert c.change == (1 if above else -1)
    assert col.threshold == c and not col.notes


RIGID = {
    "model": {"track": "ballasted-soil", "vehicle": "mass"},
    "physical": {
        "EI": 1.29e7, "m": 120.0, "k_pad": 5e8, "c_pad": 1e5, "m_s": 0.0, "E_b": 1.3e13, "rho_b": 1e-3,
        "h_b": 0.35, "A_b": 1.25, "b": 1.25, "P": 1e5, "M": 3000.0, "v": 1500.0,
    },
    "soil": [{"rho": 2000.0, "c_s": 1e6, "nu": 0.33, "eta": 1e-6}],
}  # fmt: skip


@pytest.mark.slow
def test_threshold_on_a_rigid_soil_is_that_of_the_winkler_track_of_k_ref():
    """Railpads (k_pad + i omega c_pad) on a massless stiff ballast on a rigid soil: the Winkler track of
    k_f = k_ref (the static support in series) and c_f = c_pad, up to k_pad over the ballast and soil in
    series (5e8 / 4.3e13 ~ 1.2e-5, twice that in the damping); at 1500 m/s (alpha ~ 1.3, supercritical)
    a mass has one crossing, the same as on the instability line of that Winkler track (interpolated,
    ~1e-5): agreement within 1e-4."""
    vehicle = soil_vehicle(soil_input(RIGID))
    bound = bind(vehicle)
    p = RIGID["physical"]
    winkler = PhysicalParams(
        beam="eb", vehicle="mass", EI=p["EI"], m=p["m"], k_f=vehicle.rail.k_ref, c_f=p["c_pad"], P=p["P"],
        M=p["M"], v=p["v"],
    ).to_dimensionless()  # fmt: skip
    alpha = float(bound.floats.alpha)
    assert abs(float(winkler.alpha) / alpha - 1) < 1e-12
    ref = _line_at(bind(winkler), alpha, 50.0, spacings=[0.0])
    col = real_axis_column(bound, q_max=3.0, eta_max=50.0, samples=24)
    assert len(col.crossings) == len(ref) == 1
    (eta, q, above), c = ref[0], col.crossings[0]
    assert abs(c.eta_M / eta - 1) < 1e-4 and abs(c.q / q - 1) < 1e-4
    assert c.change == (1 if above else -1) == 1
    assert not col.notes


def _count(E: QuadratureCharacteristic, box: Rectangle) -> int:
    """The winding number of E_chr on ``box`` at the receptance's tolerance 1e-4 (its phase only)."""
    with E.tolerance(1e-4):
        return winding_number(E, box, spacing=max(box.width, box.height) / 8, max_points=2000)


@pytest.mark.slow
def test_threshold_mass_of_the_example_against_the_argument_principle():
    """examples/soil-unstable.toml: one crossing, +1 as M grows, below the file's M. The argument principle
    on a box under the crossing frequency counts no root 2 % below the threshold mass and one 2 % above
    it (the root leaves the real axis downwards there), and one at the file's M."""
    vehicle = load_soil_vehicle(EXAMPLES / "soil-unstable.toml")
    bound = bind(vehicle)
    eta_file = float(bound.floats.eta_M)
    col = window_column(
        bound, equivalent=BoundModel(bound.params), eta_max=2 * eta_file, eta_min=eta_file / 4
    )
    assert not col.notes
    threshold = col.threshold
    assert threshold is not None and threshold.change == 1 and threshold.eta_M < eta_file
    assert list(col.counts([0.98 * threshold.eta_M, 1.02 * threshold.eta_M, eta_file])) == [0, 1, 1]
    q = threshold.q
    box = Rectangle(0.5 * q, 1.5 * q, -0.5 * q, 0.0)
    counts = [
        _count(QuadratureCharacteristic(bound.replace(eta_M=f * threshold.eta_M)), box) for f in (0.98, 1.02)
    ]
    assert counts == [0, 1]


@pytest.mark.slow
def test_unstable_root_of_the_example_against_a_grid_of_winding_numbers():
    """The one root with Im q < 0 that the window search finds on examples/soil-unstable.toml: on a 4 x 4
    grid of cells of 0.002 whose middle cell is centred on it, the corners' E_chr wind once around that cell
    and 0 around every other (each corner-to-corner step of arg E_chr below 3 pi / 4: a simple zero at a
    cell's centre turns it by pi / 2 along each edge), so the root is within 0.001 of the grid's own, and
    |E_chr| is least at a corner of that cell."""
    vehicle = load_soil_vehicle(EXAMPLES / "soil-unstable.toml")
    result = induced_frequencies(vehicle)
    assert result.count == 1 and len(result.roots) == 1 and result.verdict.state == UNSTABLE
    root = complex(result.roots[0].q)
    assert root.imag < 0
    h = 0.002
    assert root.imag < -1.5 * h  # the grid stays below the real axis
    x = root.real + h * (np.arange(5) - 2.5)
    y = root.imag + h * (np.arange(5) - 2.5)
    Z = x[None, :] + 1j * y[:, None]  # rows: Im q, columns: Re q
    E = QuadratureCharacteristic(bind(vehicle))
    with E.tolerance(None):
        W = E(Z)
    step_x, step_y = np.angle(W[:, 1:] / W[:, :-1]), np.angle(W[1:, :] / W[:-1, :])
    assert np.abs(step_x).max() < 0.75 * np.pi and np.abs(step_y).max() < 0.75 * np.pi
    winding = np.rint((step_x[:-1, :] + step_y[:, 1:] - step_x[1:, :] - step_y[:, :-1]) / (2 * np.pi))
    assert winding.sum() == 1 and np.abs(winding).max() == 1
    i, j = np.argwhere(winding == 1)[0]
    assert (i, j) == (2, 2)  # the cell centred on the root
    least = np.unravel_index(np.argmin(np.abs(W)), W.shape)
    assert least[0] in (i, i + 1) and least[1] in (j, j + 1)


@pytest.mark.parametrize(
    ("options", "named"),
    [
        (["--eta-f", "0.1"], "--eta-f"),
        (["--verify"], "--verify"),
        (["--parameter", "kappa_v"], "--parameter"),
        (["--range", "v=100:200"], "--range v"),
        (["--range", "M=10:200"], "--range M"),
        (["--alpha-max", "2"], "--range"),
        (["--bar", "fixed"], "--bar"),
    ],
)
def test_instability_lines_on_a_soil_file_names_an_option_that_does_not_apply(options, named, capsys):
    """Each refusal names its option and exits 2 before any computation."""
    assert main(["instability-lines", "--file", str(EXAMPLES / "soil-unstable.toml"), *options]) == 2
    assert named in capsys.readouterr().err


@pytest.mark.parametrize(
    ("options", "named"),
    [
        (["--lines"], "--lines"),
        (["--npz", "map.npz"], "--npz"),
        (["--units", "dimensionless"], "--units"),
        (["--range", "v=0:100"], "--range v"),
        (["--kappa-v", "0.1"], "--kappa-v"),
    ],
)
def test_stability_map_on_a_soil_file_names_an_option_that_does_not_apply(options, named, capsys):
    """Each refusal names its option and exits 2 before any column is computed."""
    assert main(["stability-map", "--file", str(EXAMPLES / "soil-unstable.toml"), *options]) == 2
    assert named in capsys.readouterr().err


@pytest.mark.slow
def test_map_from_real_axis_columns_is_the_continuous_map_of_counts():
    """real_axis_map on a continuous track (Table 1's case 1 at alpha = 1.4, supercritical: two crossings
    in its mass axis) counts the same growing roots in every cell as the continuous stability map
    (argument-principle counts on a contour shared by a column, no D-decomposition)."""
    params = table1_case(1)
    alphas, masses = [1.4], [1.5, 3.0, 30.0]
    columns = [(bind(params.replace(alpha=str(a))),) * 2 for a in alphas]  # continuous: its own equivalent
    smap = real_axis_map(
        columns,
        alphas,
        masses,
        scales=(1.0, 1.0, 1.0),
        name="bogie",
        track="continuous",
        identity="",
        workers=1,
    )
    ref = stability_map(bind(params), parameter="eta_M", alphas=alphas, thetas=masses, workers=1)
    assert np.array_equal(smap.count, ref.count) and not smap.notes
    assert list(smap.count[:, 0]) == [2, 3, 3]
