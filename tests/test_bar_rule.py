"""One meaning of the wheel mass M: the map, the sweep and the lines move the bar (M_b, J_b) by one rule.

At v = 400 m/s, M = 3000 kg on the track of ``examples/uic60-bogie.toml`` (M = 1000 kg, M_b = 2600 kg,
J_b = 2200 kg m^2, d = 2.5 m) the map's cell and the sweep's point must have the same margin under each rule,
and that margin must be the one ``induced_frequencies`` gives (a full count at 30 digits, not the columns of
the map and the sweep) with the bar's values written out by hand: M_b = 2.6 M = 7800 kg and J_b = 2200 x 3 =
6600 kg m^2 when the bar follows (Eq. (63): M_b/M and J_b/(M d^2) held), the file's 2600 kg and 2200 kg m^2
when it is fixed.
"""

import json
from pathlib import Path

import pytest
import xarray as xr

from moving_bogie.cli import main
from moving_bogie.kernels.bound import bind
from moving_bogie.model.files import load_parameters
from moving_bogie.model.physical import PhysicalParams
from moving_bogie.roots.frequencies import induced_frequencies

FILE = str(Path(__file__).parents[1] / "examples" / "uic60-bogie.toml")
POINT = {"v": 400, "M": 3000}
#: the bar at M = 3000 kg under each rule, written out from the file's values (see the module text)
BAR = {"follows": {"M_b": 7800, "J_b": 6600}, "fixed": {"M_b": 2600, "J_b": 2200}}


def reference_margin(rule: str) -> float:
    """min Im omega [1/s] of every induced frequency at the point, the bar's values given explicitly."""
    _, physical = load_parameters(FILE)
    assert physical is not None
    point = PhysicalParams(model=physical.model, **(physical.values() | POINT | BAR[rule]))
    result = induced_frequencies(bind(point.to_dimensionless()), dps=30)
    return min(float(r.q.imag) for r in result.roots) / point.scales().t_scale


def map_margin(tmp_path: Path, rule: str | None) -> tuple[float, xr.Dataset]:
    out = tmp_path / f"map-{rule}.zarr"
    argv = ["stability-map", "--file", FILE, "--range", "v=0:400", "--range", "M=0:3000", "--n", "2"]
    argv += ["--workers", "1", "--out", str(out)] + (["--bar", rule] if rule else [])
    assert main(argv) == 0
    ds = xr.open_zarr(out)
    corner = ds.margin.isel(v=-1, M=-1)  # the grid's last cell: v = 400 m/s, M = 3000 kg
    assert (float(corner.v), float(corner.M)) == pytest.approx((400, 3000), rel=1e-12)
    return float(corner), ds


def sweep_margin(tmp_path: Path, rule: str | None) -> tuple[float, xr.Dataset]:
    out = tmp_path / f"sweep-{rule}.zarr"
    argv = ["sweep", "--file", FILE, "--vary", "v=400", "--vary", "M=3000", "--margin", "--out", str(out)]
    assert main(argv + (["--bar", rule] if rule else [])) == 0
    ds = xr.open_zarr(out)
    return float(ds.margin.values.ravel()[0]), ds


def test_default_rule_is_the_same_in_the_map_and_the_sweep(tmp_path):
    """No --bar: both follow Eq. (63), and both stores say so (issue: 1.22 1/s against 3.64 1/s)."""
    on_map, map_store = map_margin(tmp_path, None)
    on_sweep, sweep_store = sweep_margin(tmp_path, None)
    assert on_map == pytest.approx(on_sweep, rel=1e-9)
    for ds in (map_store, sweep_store):
        assert json.loads(ds.attrs["bar"])["rule"] == "follows"


@pytest.mark.slow
@pytest.mark.parametrize("rule", ["follows", "fixed"])
def test_each_rule_agrees_with_the_full_count_of_the_bar_written_out(tmp_path, rule):
    on_map, map_store = map_margin(tmp_path, rule)
    on_sweep, sweep_store = sweep_margin(tmp_path, rule)
    assert on_map == pytest.approx(on_sweep, rel=1e-9)
    assert on_map == pytest.approx(reference_margin(rule), rel=1e-8)
    assert ("held" in map_store.attrs["vertical_axis"]) == (rule == "fixed")
    assert json.loads(sweep_store.attrs["bar"])["rule"] == rule


def test_map_json_and_label_name_the_rule(capsys):
    argv = ["stability-map", "--file", FILE, "--range", "v=0:400", "--range", "M=0:3000", "--n", "2"]
    assert main([*argv, "--workers", "1", "--bar", "fixed", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["bar"]["rule"] == "fixed"
    assert data["axes"]["y"]["note"] == "M_b, J_b fixed"


def test_rule_not_for_a_parameter_that_does_not_move_the_bar():
    """kappa_v moves no bar: its map JSON carries no rule (bar_note is None)."""
    from moving_bogie.model.bar import bar_note, held_groups

    params, _ = load_parameters(FILE)
    assert bar_note(params, "fixed", "kappa_v") is None
    assert held_groups(params, "follows") == ()
    assert set(held_groups(params, "fixed")) == {"mu_v", "J_b"}


@pytest.mark.slow
def test_lines_with_the_bar_held_cross_where_the_full_count_changes():
    """Lines traced with mu_v, J_b held (degree 2 in eta_M): on each branch the unstable count of
    induced_frequencies (30 digits, the bar held by at_theta) 2 % below and above differs by one."""
    from moving_bogie.model.bar import held_groups
    from moving_bogie.model.cases import table1_case
    from moving_bogie.stability.lines.instability_lines import instability_lines

    params = table1_case(1).replace(d="1.5")
    res = instability_lines(bind(params), held=held_groups(params, "fixed"), verify=True)
    assert res.branches
    for branch in res.branches:
        assert branch.verified is not None
        assert abs(branch.verified[2] - branch.verified[4]) == 1


SLEEPERS = Path(__file__).parents[1] / "examples" / "sleepers_hertz_bogie.toml"


@pytest.mark.parametrize("rule", ["follows", "fixed"])
def test_a_sleeper_sweep_moves_the_bar_by_the_same_rule(rule):
    """A sleeper sweep's point M = 3000 kg of examples/sleepers_hertz_bogie.toml (M = 1000 kg, M_b = 2600 kg,
    J_b = 2200 kg m^2): its vehicle is the one of the bar's values written out by hand (as above), under
    each rule; varying M_b itself is never overridden."""
    import tomllib

    from moving_bogie.sweep.sleepers import _input

    data = tomllib.loads(SLEEPERS.read_text())
    point = _input(data, str(SLEEPERS), {"M": 3000.0}, rule, ("M",))
    written = _input(data, str(SLEEPERS), {"M": 3000.0, **BAR[rule]}, "fixed", ())
    assert point.vehicle_groups == pytest.approx(written.vehicle_groups, rel=1e-12)  # SI in floats
    own = _input(data, str(SLEEPERS), {"M": 3000.0, "M_b": 5000.0}, rule, ("M", "M_b"))
    by_hand = _input(data, str(SLEEPERS), {"M": 3000.0, "M_b": 5000.0, "J_b": BAR[rule]["J_b"]}, "fixed")
    assert own.vehicle_groups == pytest.approx(by_hand.vehicle_groups, rel=1e-12)


def test_a_sleeper_sweep_names_its_rule():
    """A sleeper sweep along M names its rule in the store's description and the summary, as the
    continuous sweep does; along v (which does not move the bar) it names none."""
    import tomllib

    from moving_bogie.sweep.sleepers import make_sleeper_spec

    data = tomllib.loads(SLEEPERS.read_text())
    along_m = make_sleeper_spec(data, str(SLEEPERS), {"M": "1000,1001"}, bar="fixed")
    assert along_m.describe()["bar"]["rule"] == "fixed"
    assert "bar" not in make_sleeper_spec(data, str(SLEEPERS), {"v": "40,41"}).describe()


def test_a_sleeper_map_refuses_a_bar_that_would_follow(capsys):
    """The map on sleepers is a pencil in the wheel mass alone (S19): a bogie's bar cannot follow M there,
    so the default rule is refused naming --bar, before any computation."""
    args = ["stability-map", "--file", str(SLEEPERS), "--range", "v=20:200", "--range", "M=0:2000"]
    args += ["--n", "2"]
    assert main(args) == 2
    assert "--bar" in capsys.readouterr().err
