"""Every parameter file in examples/ runs, and there is one for every track model and both kinds of table.

The results are checked against references computed in the test: each root by the argument principle on a
circle of its own, the layered examples' critical velocities from the dispersion relation in SI units.
"""

import json
import tomllib
from pathlib import Path

import numpy as np
import pytest

from moving_bogie.cli import main
from moving_bogie.generated import CONTACT_SPRINGS, MODULES, VEHICLES
from moving_bogie.kernels.bound import bind
from moving_bogie.kernels.characteristic import CharacteristicArray
from moving_bogie.model.cases import table1_case
from moving_bogie.model.files import load_params_file
from moving_bogie.model.sleeper_input import load_sleeper_file
from moving_bogie.soil.file import is_soil_file

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def _periodic(path: Path) -> bool:
    """Whether the example's model is on periodic supports (read as any parameter file)."""
    return load_params_file(path)[0].model.periodic


#: The continuous tracks' examples, and the rails on discrete supports (a periodic track of the catalogue);
#: a track on soil (soil/) has its own reader (tests/test_soil_track.py runs the soil examples).
ALL = [path for path in sorted(EXAMPLES.glob("*.toml")) if not is_soil_file(path)]
FILES = [path for path in ALL if not _periodic(path)]
SLEEPER_FILES = [path for path in ALL if _periodic(path)]


def test_every_sleeper_example_loads_as_a_model_of_the_catalogue():
    """The sleeper examples load like any other file, as a model of the one catalogue; their groups are
    those of the Floquet reader (model/sleeper_input.py, the same generated scaling in floats)."""
    assert SLEEPER_FILES, "examples/sleepers.toml is the README's and docs/sleepers.md's example"
    for path in SLEEPER_FILES:
        loaded = load_sleeper_file(path)
        params, physical = load_params_file(path)
        assert params.model.periodic and physical is not None
        assert params.model.name == f"{loaded.beam}/{loaded.track}/{loaded.vehicle}"
        for name, value in (loaded.groups | loaded.vehicle_groups).items():
            assert float(getattr(params, name)) == pytest.approx(value, rel=1e-14, abs=1e-300), name
        assert physical.scales().t_scale == pytest.approx(loaded.t_scale, rel=1e-14)


def _kind(path):
    data = tomllib.loads(path.read_text())
    table = "physical" if "physical" in data else "dimensionless"
    params, _ = load_params_file(path)
    return table, params.model


#: Examples whose induced frequencies are tested elsewhere at full cost (the three-layer example, about 7 s:
#: tests/test_layered_search.py certifies its count; the car on two layers, about 12 s: tests/test_car.py);
#: here they run their critical velocity.
SLOW = {"three-layer.toml", "car-two-layer.toml"}


def test_an_example_for_every_model_and_table():
    """Every beam on the paper's track, dimensionless and in SI; every other track, every vehicle once."""
    kinds = [_kind(path) for path in FILES]
    have = {(table, model.beam, model.track) for table, model in kinds}
    wanted = {(table, beam, track) for table in ("dimensionless", "physical") for beam, track in MODULES}
    wanted = {w for w in wanted if w[2] == "one-layer"}
    assert wanted <= have, f"missing examples: {sorted(wanted - have)}"
    assert {track for _, _, track in have} >= {track for _, track in MODULES}
    # each rigid-contact vehicle once, and the Hertz contact springs once (hertz_mass.toml; every vehicle on
    # its contact springs: examples/sleepers_hertz_bogie.toml, tests/test_contact_springs.py)
    vehicles, contact = {model.vehicle for _, model in kinds}, set(CONTACT_SPRINGS.values())
    assert vehicles >= set(VEHICLES) - contact and vehicles & contact


def _layered_v_cr(EI, m, layers):
    """Critical velocity (m/s) of an undamped layered track, from its dispersion relation in SI units.

    Reference, independent of the generated kernels: the equations (L2) of docs/layered_tracks.md without
    damping, for free waves ``e^{i(k x - omega t)}``, with ``layers = [(k_1, m_2), (k_2, m_3), ..., (k_n,)]``
    (the support under the rail, the next mass layer, ...): a chain of masses on springs,

        (EI k^4 + k_1 - m omega^2) W - k_1 Z_2 = 0
        -k_j Z_{j} + (k_j + k_{j+1} - m_{j+1} omega^2) Z_{j+1} - k_{j+1} Z_{j+2} = 0

    a symmetric eigenvalue problem in omega^2 at every k (stiffness tridiagonal, mass diagonal). The
    critical velocity is the smallest local minimum of the phase speed omega_j(k) / k over the branches
    (the load's line tangent to a branch), found on a dense grid of k and refined by a parabola.
    """
    k = np.linspace(0.05, 20.0, 40_000)
    springs = [layer[0] for layer in layers]
    masses = [m] + [layer[1] for layer in layers if len(layer) > 1]
    n = len(masses)
    stiffness = np.zeros((k.size, n, n))
    stiffness[:, 0, 0] = EI * k**4
    for j, spring in enumerate(springs):  # spring j joins mass j to mass j + 1 (or to the ground)
        stiffness[:, j, j] += spring
        if j + 1 < n:
            stiffness[:, j + 1, j + 1] += spring
            stiffness[:, j, j + 1] = stiffness[:, j + 1, j] = -spring
    scale = 1 / np.sqrt(np.array(masses))
    omega2 = np.linalg.eigvalsh(stiffness * scale[:, None] * scale[None, :])
    minima = []
    for speed in np.sqrt(omega2).T / k:
        inner = np.flatnonzero((speed[1:-1] < speed[:-2]) & (speed[1:-1] < speed[2:])) + 1
        for i in inner:
            y0, y1, y2 = speed[i - 1 : i + 2]
            minima.append(y1 - (y2 - y0) ** 2 / (8 * (y2 - 2 * y1 + y0)))
    return min(minima)


@pytest.mark.parametrize("path", [p for p in FILES if p.name in SLOW], ids=sorted(SLOW))
def test_slow_example_gives_its_critical_velocity(capsys, path):
    assert main(["critical-velocity", "--file", str(path), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    si = tomllib.loads(path.read_text())["physical"]
    layers, j = [], 1
    while f"k_{j}" in si:
        layers.append(
            (float(si[f"k_{j}"]), float(si[f"m_{j + 1}"])) if f"m_{j + 1}" in si else (float(si[f"k_{j}"]),)
        )
        j += 1
    reference = _layered_v_cr(float(si["EI"]), float(si["m"]), layers)
    # the grid step of k (5e-4 1/m) leaves the parabola's minimum within ~1e-6 relative of the true one
    assert float(data["v_cr"]) == pytest.approx(reference, rel=1e-5)


def _cut_distances(foundation, params, points) -> list[float]:
    """Distance from each point to the cut of K: min over real p of |q_j(p) - q|, N(p, q_j(p)) = 0.

    Independent of the cut tracer (kernels/cut.py): every root in q of N(p, .) by the eigenvalues of its
    companion matrix on a grid of real p, then the closest p refined by golden-section search (the distance
    is continuous in p).
    """
    args = foundation.float_arguments(params)

    def cut(ps):
        ps = np.atleast_1d(np.asarray(ps, dtype=float))
        coeffs = [
            np.broadcast_to(np.asarray(c, dtype=complex), ps.shape)
            for c in foundation.module.n_coeffs_in_q(ps, **args)
        ]
        c = np.stack(coeffs, axis=-1)
        n = c.shape[-1] - 1
        companion = np.zeros(ps.shape + (n, n), dtype=complex)
        companion[..., 0, :] = -c[..., 1:] / c[..., :1]
        companion[..., np.arange(1, n), np.arange(n - 1)] = 1
        return np.linalg.eigvals(companion)

    grid = np.linspace(-60.0, 60.0, 48_001)
    on_grid = cut(grid)
    return [_refine(cut, grid, np.abs(on_grid - q0).min(axis=-1), q0) for q0 in points]


def _refine(cut, grid, distance_on_grid, q0) -> float:
    def distance(p):
        return float(np.abs(cut(p) - q0).min())

    i = int(distance_on_grid.argmin())
    lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, len(grid) - 1)]
    golden = (np.sqrt(5) - 1) / 2
    for _ in range(60):
        x1, x2 = hi - golden * (hi - lo), lo + golden * (hi - lo)
        if distance(x1) < distance(x2):
            hi = x2
        else:
            lo = x1
    return distance(0.5 * (lo + hi))


def _winding_number(characteristic, q0, radius, points=512) -> float:
    """(change of arg E_chr around the circle |q - q0| = radius) / 2 pi, in double precision (Eq. (38))."""
    circle = q0 + radius * np.exp(2j * np.pi * np.arange(points + 1) / points)
    steps = np.diff(np.unwrap(np.angle(characteristic(circle))))
    assert np.abs(steps).max() < 0.5, "the circle is too coarse to follow arg E_chr"
    return steps.sum() / (2 * np.pi)


#: Examples whose check takes over 5 s on one core (the car's 22 roots, the two-layer and Timoshenko-Rayleigh
#: searches): in the full suite only.
HEAVY = {"car.toml", "two-layer.toml", "physical_tr.toml", "dimensionless_tr.toml"}


@pytest.mark.parametrize(
    "path",
    [
        pytest.param(p, id=p.name, marks=[pytest.mark.slow] if p.name in HEAVY else [])
        for p in FILES
        if p.name not in SLOW
    ],
)
def test_example_roots_are_simple_zeros_of_the_characteristic_equation(capsys, path):
    """Every reported root against the argument principle on a tiling of its own (cf. roots/count/contour.py).

    Reference: a circle around each reported root, clear of the other roots and of the cut of K (its
    distance computed in the test), on which E_chr is evaluated in double precision (the numpy kernels,
    not the mpmath ones that polished the root): arg E_chr winds exactly once, so the circle holds one
    simple zero. The verdict follows from the signs of Im q (Eq. (35)).
    """
    assert main(["frequencies", "--file", str(path), "--json", "--dps", "20"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["count_ok"] and data["count"] == data["found"] == len(data["roots"])
    assert data["roots"], "an induced frequency was expected"
    params, _ = load_params_file(path)
    characteristic = CharacteristicArray(bind(params))
    foundation = bind(params).foundation_model
    roots = np.array([complex(float(r["re"]), float(r["im"])) for r in data["roots"]])
    # Close pairs (a car's two bogies interact only through the rail: roots 1e-10 and 2e-7 apart) are
    # below what a double-precision winding number resolves well; such a cluster is checked as a whole (it
    # winds once per member), and tests/test_car.py separates its members at high precision.
    clusters = []
    for q0 in roots:
        for cluster in clusters:
            if abs(cluster[0] - q0) < 1e-5:
                cluster.append(q0)
                break
        else:
            clusters.append([q0])
    centres = np.array([np.mean(c) for c in clusters])
    for cluster, centre, to_cut in zip(clusters, centres, _cut_distances(foundation, params, centres)):
        others = np.abs(np.delete(centres, np.flatnonzero(centres == centre)) - centre)
        clear = min([to_cut, *others])
        spread = max(abs(q - centre) for q in cluster)
        assert clear > 1e-6 and spread < 0.01 * clear, f"root {centre} lies on the cut or on another root"
        winding = _winding_number(characteristic, centre, 0.3 * clear)
        assert round(winding, 6) == len(cluster), (centre, len(cluster))
    unstable = roots.imag < 0
    assert data["verdict"]["state"] == ("unstable" if unstable.any() else "stable")


def test_dimensionless_example_is_case7_written_out():
    # Reference: Table 1 of the paper, Case 7 (data/table1_cases.csv).
    params, _ = load_params_file(EXAMPLES / "dimensionless_eb.toml")
    assert params == table1_case(7)


def test_physical_example_is_near_case7_without_suspension_damping():
    # Reference: Table 1, Case 7 (eta_v = 0 here: c_v = 0); the SI values are rounded, hence 3 %.
    params, _ = load_params_file(EXAMPLES / "physical_eb.toml")
    case7 = table1_case(7).as_float()
    got = params.as_float()
    for name in ("eta_f", "eta_M", "d", "mu_v", "J_b", "kappa_v", "alpha"):
        assert getattr(got, name) == pytest.approx(getattr(case7, name), rel=3e-2), name
    assert got.eta_v == 0
