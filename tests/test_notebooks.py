"""Every notebook in notebooks/ runs from top to bottom (in quick mode).

The notebooks are committed as jupytext percent-format ``.py`` files. Each test runs one through
``notebooks/run.py`` (the headless runner the README documents, ``python notebooks/run.py NOTEBOOK.py``):
converted in memory and executed with nbclient on a kernel that runs *this* interpreter (a ``python3``
kernelspec written to a temporary JUPYTER_PATH), with ``MOVING_BOGIE_QUICK=1`` (``--quick``) so that the
notebooks use their reduced grids. A failing cell fails the test with the cell's traceback.

A notebook the documentation build has already run is not run twice. The build (``docs/conf.py``, which
``.ci/run`` runs before the tests) executes every notebook through the same runner in quick mode into
``docs/tutorials/NAME.ipynb``; where that copy is current (newer than its source and every file of the
package: the rule by which the build keeps it, ``run.is_current``) and is a complete run of the notebook
as it is now (its code cells are the source's, every one ran, none raised, in quick mode:
``run.check_executed``), the test checks that copy instead. Otherwise (a fresh checkout, an edited
notebook or module) it runs the notebook.

The kernel runs with matplotlib's Agg backend (``MPLBACKEND=Agg``): ``plt.show()`` draws nothing, so the
test pays for the computations and not for rendering a PNG of every figure (about a tenth of the notebooks'
time). That loses no check: under the inline backend too, a figure that fails to draw (a bad mathtext
label) is no failing cell, since the backend draws after the cell has finished. The figures are drawn for
the documentation site, whose build runs every notebook through the same runner with the inline backend.
"""

from __future__ import annotations

import sys
from pathlib import Path

import pytest
from optional_tools import NOTEBOOK_INSTALL, NOTEBOOK_VARIABLE, require_notebook_tools
from scripts import load_script

ROOT = Path(__file__).resolve().parent.parent
NOTEBOOKS = sorted((ROOT / "notebooks").glob("[0-9][0-9]-*.py"))
#: Where the documentation build keeps the notebooks it ran (``docs/conf.py``).
TUTORIALS = ROOT / "docs" / "tutorials"


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
        "09-sleepers.py",
        "10-soil.py",
    ]


def _runner():
    """notebooks/run.py, the documented headless runner (README, "Documentation"), loaded from its path."""
    return load_script("notebooks/run.py")


@pytest.mark.slow
@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_notebook_runs(path, tmp_path, monkeypatch):
    require_notebook_tools()
    runner = _runner()
    built = TUTORIALS / f"{path.stem}.ipynb"
    if runner.is_current(path, built) and not runner.check_executed(path, built, quick=True):
        print(f"{path.name}: checked the documentation build's run ({built})")
        return
    monkeypatch.setenv("MPLBACKEND", "Agg")  # the kernel inherits it (module docstring)
    try:
        elapsed = runner.run_notebook(path, quick=True, out=tmp_path / f"{path.stem}.ipynb")
    except runner.CellFailed as exc:
        pytest.fail(str(exc), pytrace=False)
    print(f"{path.name}: {elapsed:.1f} s")


def test_runner_reports_a_failing_cell(tmp_path, capsys):
    """The runner's exit status and message for a notebook whose cell raises."""
    require_notebook_tools()
    bad = tmp_path / "99-bad.py"
    bad.write_text("# %%\nx = 1\n\n# %%\nraise ValueError('the cell of 99-bad')\n\n# %%\ny = 2\n")
    runner, out = _runner(), tmp_path / "99-bad.ipynb"
    assert runner.main([str(bad), "--out", str(out)]) == 1
    assert "the cell of 99-bad" in capsys.readouterr().err
    # the copy it kept is no complete run: the test above would run the notebook instead of checking it
    problems = ["code cell 1 raised ValueError", "code cell 2 did not run"]
    assert runner.check_executed(bad, out, quick=False) == problems
    assert "it was not run with quick=True" in runner.check_executed(bad, out, quick=True)
    # the first cell alone did run: as a notebook of that cell, the copy is complete, until its text changes
    import nbformat

    notebook = nbformat.read(str(out), as_version=4)
    notebook.cells = notebook.cells[:1]
    nbformat.write(notebook, str(out))
    bad.write_text("# %%\nx = 1\n")
    assert runner.check_executed(bad, out, quick=False) == []
    bad.write_text("# %%\nx = 2\n")
    assert runner.check_executed(bad, out, quick=False) == ["its code cells are not those of the source"]


def test_missing_notebook_tools_fail_with_the_install_command(monkeypatch):
    """No silent skip: a missing tool of the dev extra fails with the install command and the variable."""
    monkeypatch.delenv(NOTEBOOK_VARIABLE, raising=False)
    monkeypatch.setitem(sys.modules, "nbclient", None)  # import nbclient now raises ImportError
    with pytest.raises(pytest.fail.Exception) as info:
        require_notebook_tools()
    message = str(info.value)
    assert "nbclient" in message and NOTEBOOK_INSTALL in message and NOTEBOOK_VARIABLE in message


def test_the_notebook_variable_skips_with_its_name(monkeypatch):
    monkeypatch.setenv(NOTEBOOK_VARIABLE, "1")
    with pytest.raises(pytest.skip.Exception) as info:
        require_notebook_tools()
    assert NOTEBOOK_VARIABLE in str(info.value)
