"""``moving-bogie sweep --file`` on a sleeper-track file: each point is one Floquet strip search.

References: the direct call of ``floquet_frequencies`` at each point (the file read by
``load_sleeper_file`` with the point's value, the track and vehicle built here), converted to rad/s with
the file's own time scale; the checks of bad values need no reference (the message and that nothing is
computed).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from moving_bogie.cli import main
from moving_bogie.sweep.store import open_sweep

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "sleepers.toml"


def _no_computation(monkeypatch: pytest.MonkeyPatch) -> None:
    def refuse(*args: object, **kwargs: object) -> None:
        raise AssertionError("a point was computed")

    monkeypatch.setattr("moving_bogie.sweep.sleepers.sleeper_point", refuse)


@pytest.mark.parametrize(
    "options, fragment",
    [
        (["--vary", "v=0:40:2"], "--vary v: v must be positive"),
        (["--vary", "v=40:80:3", "--vary", "M=-1,600"], "M must be a positive"),
        (["--vary", "P=1,2"], "unknown parameter 'P'"),
        (["--vary", "v=40:80"], "START:STOP:COUNT"),
        (["--vary", "v=40,50", "--case", "1"], "give either --case or --file, not both"),
        (["--vary", "v=40,50", "--roots"], "--roots does not apply"),
        (["--vary", "v=40,50", "--margin"], "--margin does not apply"),
        (["--vary", "v=40,50", "--check", "2"], "--check does not apply"),
        (["--vary", "v=40,50", "--alpha", "0.5"], "--alpha does not apply"),
    ],
)
def test_a_bad_option_is_named_before_any_computation(tmp_path, capsys, monkeypatch, options, fragment):
    """One line naming the option or the value, exit 2, no store and no point computed."""
    _no_computation(monkeypatch)
    out = tmp_path / "s.zarr"
    assert main(["sweep", "--file", str(EXAMPLE), *options, "--out", str(out)]) == 2
    assert fragment in capsys.readouterr().err
    assert not out.exists()


def _direct(path: Path, v: float) -> dict[str, Any]:
    """The reference: floquet_frequencies at the point, in rad/s (docs/sleepers.md, Eq. (S14))."""
    from moving_bogie.generated import vehicle_mass
    from moving_bogie.kernels.hill import VehicleMatrices
    from moving_bogie.kernels.sleeper_track import SleeperTrack
    from moving_bogie.model.sleeper_input import load_sleeper_file
    from moving_bogie.roots.strip import floquet_frequencies

    d = load_sleeper_file(path, overrides={"v": v})
    res = floquet_frequencies(
        SleeperTrack(d.foundation, d.groups), VehicleMatrices.from_module(vehicle_mass, d.vehicle_groups)
    )
    im = min((r.q.imag for r in res.roots), default=np.nan)
    return {
        "count": res.count,
        "located": len(res.roots),
        "converged": res.converged,
        "verdict": res.verdict.state,
        "Omega_im": im / d.t_scale,
        "N": res.harmonics,
    }


@pytest.mark.slow
def test_an_interrupted_sweep_resumes_and_equals_the_direct_search(tmp_path, capsys):
    """Two speeds of examples/sleepers.toml: Ctrl-C after the first point keeps it, --resume computes only
    the second, and each stored point is the direct floquet_frequencies at that speed."""
    import tomllib

    from moving_bogie.sweep.engine import run_sweep
    from moving_bogie.sweep.sleepers import make_sleeper_spec

    spec = make_sleeper_spec(tomllib.loads(EXAMPLE.read_text()), str(EXAMPLE), {"v": "40,65"})
    out = tmp_path / "s.zarr"

    def interrupt(index: int) -> None:
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        run_sweep(spec, out, on_block=interrupt)
    assert open_sweep(out).computed.values.tolist() == [True, False]
    argv = ["sweep", "--file", str(EXAMPLE), "--vary", "v=40,65", "--out", str(out), "--resume", "--json"]
    assert main(argv) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["points_computed"] == 1 and summary["blocks"] == [1, 2]
    assert summary["scheduler"] == "in-process"  # a small sweep starts no cluster (IN_PROCESS_POINTS)
    from moving_bogie.sweep.plan import SWEEP_KEYS

    assert set(SWEEP_KEYS) <= set(summary) and summary["units"] == {"v": "m/s"}  # every track's keys
    ds = open_sweep(out).compute()
    assert summary["unstable_fraction"] == float(ds.unstable.values.mean())
    assert ds.v.attrs["units"] == "m/s" and ds.v.attrs["exact"] == ["40", "65"]
    assert ds.attrs["kind"] == "sleepers" and ds.attrs["model"] == "eb/sleepers/mass"
    for k, v in enumerate([40.0, 65.0]):
        ref = _direct(EXAMPLE, v)
        point = ds.isel(v=k)
        assert int(point.n_roots) == ref["count"] and int(point.harmonics) == ref["N"]
        assert bool(point.stable) == (ref["verdict"] == "stable")
        assert bool(point.unstable) == (ref["verdict"] == "unstable")
        assert bool(point.certain) == (ref["converged"] and ref["count"] == ref["located"])
        np.testing.assert_allclose(float(point.Omega_im), ref["Omega_im"], rtol=1e-9)
        # Omega_0 = 2 pi v / l with the file's l = 0.6 m
        assert float(point.Omega0) == pytest.approx(2 * np.pi * v / 0.6, rel=1e-12)


def _store(tmp_path: Path, vary: dict[str, str]) -> tuple[Path, object]:
    """An empty store of ``vary`` on examples/sleepers.toml (nothing computed)."""
    import tomllib

    from moving_bogie.sweep.sleepers import make_sleeper_spec

    spec = make_sleeper_spec(tomllib.loads(EXAMPLE.read_text()), str(EXAMPLE), vary)
    out = tmp_path / "s.zarr"
    spec.create_store(out)
    return out, spec


def test_resume_of_another_sweep_is_refused(tmp_path, capsys, monkeypatch):
    """--resume checks the stored description (values, file values) before computing anything."""
    _no_computation(monkeypatch)
    out, _ = _store(tmp_path, {"v": "40,65"})
    argv = ["sweep", "--file", str(EXAMPLE), "--vary", "v=40,70", "--out", str(out), "--resume"]
    assert main(argv) == 2
    assert "--resume" in capsys.readouterr().err
    argv = [
        "sweep",
        "--file",
        str(EXAMPLE),
        "--vary",
        "v=40,65",
        "--set",
        "M=700",
        "--out",
        str(out),
        "--resume",
    ]
    assert main(argv) == 2
    assert "holds a different sweep" in capsys.readouterr().err


def test_views_draw_the_stored_growth_rate_and_verdicts(tmp_path, capsys):
    """sweep-plot of a sleeper store: --x alone draws -Omega_im of the unstable points (stored values
    written here: the view is checked, not the search); --x --y the map; both PNGs written."""
    from moving_bogie.sweep.sleeper_plots import plot_sleeper_sweep
    from moving_bogie.sweep.sleeper_store import SLEEPER_VARIABLES

    out, spec = _store(tmp_path, {"v": "40:80:3", "c_sup": "1e4,3e4"})
    shape = (3, 2)
    arrays = {name: np.full(shape, fill, dtype=dtype) for name, dtype, fill, *_ in SLEEPER_VARIABLES}
    arrays["unstable"][1, :] = True
    arrays["stable"][0, :] = arrays["stable"][2, 0] = True  # (2, 1) undetermined
    arrays["Omega_im"][1, :] = [-3.0, -1.5]
    arrays["certain"][...] = True
    arrays["computed"][...] = True
    spec.write_block(out, (slice(0, 3), slice(0, 2)), arrays)
    fig = plot_sleeper_sweep(open_sweep(out), "v", sel={"c_sup": 1e4})
    unstable = next(line for line in fig.axes[0].lines if line.get_label().startswith("unstable"))
    assert unstable.get_xydata().tolist() == [[60.0, 3.0]]
    png = tmp_path / "line.png"
    assert main(["sweep-plot", str(out), "--x", "v", "--sel", "c_sup=3e4", "--out", str(png)]) == 0
    assert png.stat().st_size > 0
    png2 = tmp_path / "map.png"
    assert main(["sweep-plot", str(out), "--x", "v", "--y", "c_sup", "--out", str(png2)]) == 0
    assert png2.stat().st_size > 0
    assert main(["sweep-plot", str(out), "--x", "v", "--out", str(png)]) == 2
    assert "--sel: fix c_sup" in capsys.readouterr().err
