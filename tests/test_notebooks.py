"""Every notebook in notebooks/ runs from top to bottom (in quick mode).

The notebooks are committed as jupytext percent-format ``.py`` files. Each test converts one to
``.ipynb`` in a temporary folder and executes it with nbclient on a kernel that runs *this*
interpreter (a ``python3`` kernelspec written to a temporary JUPYTER_PATH), with
``MOVING_BOGIE_QUICK=1`` so that the notebooks use their reduced grids. A failing cell fails the test
with the cell's traceback.
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
NOTEBOOKS = sorted((ROOT / "notebooks").glob("[0-9][0-9]-*.py"))


def test_notebooks_exist():
    assert [p.name for p in NOTEBOOKS] == [
        "01-quickstart.py",
        "02-table2.py",
        "03-vibrations-and-validation.py",
        "04-instability-lines.py",
        "05-change-the-model.py",
        "06-sweeps.py",
        "07-layered-track.py",
        "08-a-full-car.py",
    ]


@pytest.fixture(scope="session")
def jupyter_path(tmp_path_factory):
    """A JUPYTER_PATH holding a ``python3`` kernelspec that starts this interpreter."""
    pytest.importorskip("ipykernel")
    root = tmp_path_factory.mktemp("jupyter")
    spec = root / "kernels" / "python3"
    spec.mkdir(parents=True)
    kernel = {
        "argv": [sys.executable, "-m", "ipykernel_launcher", "-f", "{connection_file}"],
        "display_name": "Python 3 (moving-bogie tests)",
        "language": "python",
    }
    (spec / "kernel.json").write_text(json.dumps(kernel))
    return root


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_notebook_runs(path, tmp_path, monkeypatch, jupyter_path):
    jupytext = pytest.importorskip("jupytext")
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    monkeypatch.setenv("JUPYTER_PATH", str(jupyter_path))
    monkeypatch.setenv("MOVING_BOGIE_QUICK", "1")
    monkeypatch.setenv("PYDEVD_DISABLE_FILE_VALIDATION", "1")

    ipynb = tmp_path / f"{path.stem}.ipynb"
    jupytext.write(jupytext.read(path), ipynb)
    notebook = nbformat.read(ipynb, as_version=4)
    client = nbclient.NotebookClient(
        notebook,
        kernel_name="python3",
        timeout=600,
        resources={"metadata": {"path": str(tmp_path)}},
    )
    start = time.perf_counter()
    try:
        client.execute()
    except nbclient.exceptions.CellExecutionError as exc:
        pytest.fail(f"{path.name}: a cell failed\n{exc}", pytrace=False)
    elapsed = time.perf_counter() - start
    print(f"{path.name}: {elapsed:.1f} s")
