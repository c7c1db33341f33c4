"""The Python sweep called from a plain script: worker processes import the script again, so an unguarded
call is refused before anything starts, with one message naming ``if __name__ == "__main__":``; a guarded
script runs; a start that fails leaves no store behind."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parent.parent

CALL = 'sweep(table1_case(1), {"alpha": "0.5:1:3", "eta_M": "5:100:3"}, "s.zarr", workers=1)'
HEAD = "from moving_bogie import table1_case\nfrom moving_bogie.sweep import sweep\n\n"


def _run_script(folder: Path, text: str) -> subprocess.CompletedProcess[str]:
    script = folder / "script.py"
    script.write_text(text)
    env = os.environ | {"PYTHONPATH": str(REPO / "src")}
    return subprocess.run(
        [sys.executable, str(script)], cwd=folder, env=env, capture_output=True, text=True, timeout=600
    )


def test_an_unguarded_script_is_told_the_guard_and_writes_nothing(tmp_path):
    run = _run_script(tmp_path, HEAD + f"ds = {CALL}\nprint(int(ds.computed.sum()))\n")
    assert run.returncode == 1
    last = run.stderr.strip().splitlines()[-1]
    assert 'if __name__ == "__main__":' in last and "line 4" in last and "nothing was started" in last
    assert "Nanny" not in run.stderr
    assert not (tmp_path / "s.zarr").exists()


@pytest.mark.slow
def test_a_guarded_script_runs_its_sweep_on_a_worker(tmp_path):
    body = f"\ndef main():\n    ds = {CALL}\n    print(int(ds.computed.sum()))\n\n\n"
    body += 'if __name__ == "__main__":\n    main()\n'
    run = _run_script(tmp_path, HEAD + body)
    assert run.returncode == 0, run.stderr
    assert run.stdout.split() == ["9"]  # every point of the 3 x 3 grid computed


def test_a_failed_start_leaves_no_store(tmp_path, monkeypatch):
    import moving_bogie.sweep.engine as engine
    from moving_bogie import table1_case
    from moving_bogie.errors import ParameterError
    from moving_bogie.sweep import sweep

    def no_cluster(*_args, **_kwargs):
        raise RuntimeError("Nanny failed to start")

    monkeypatch.setattr(engine, "make_client", no_cluster)
    out = tmp_path / "s.zarr"
    with pytest.raises(RuntimeError, match="Nanny"):
        sweep(table1_case(1), {"alpha": "0.5:1:3", "eta_M": "5:100:3"}, out, workers=1)
    assert not out.exists() and not list(tmp_path.iterdir())
    (out / "kept").mkdir(parents=True)  # a folder that was there before is never removed
    with pytest.raises(ParameterError, match="--out"):  # there, and neither resumed nor overwritten
        sweep(table1_case(1), {"alpha": "0.5:1:3", "eta_M": "5:100:3"}, out, workers=1)
    assert (out / "kept").exists()
