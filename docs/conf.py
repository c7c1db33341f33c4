"""Sphinx configuration of the documentation site (built by `.ci/run`, warnings as errors).

The pages are the Markdown files of this folder (MyST). Three things are generated at build time and
never committed:

- ``cli.md``, the command line reference, rendered from the argparse parsers by
  :func:`moving_bogie.cli.docs.render`;
- ``_generated/uic60-series.png``, the home page's figure, drawn by ``moving-bogie timeseries``, and
  ``_generated/soil-dispersion.png``, soil.md's, by ``moving-bogie critical-velocity`` (``FIGURES``);
- ``tutorials/*.ipynb``, the notebooks of ``notebooks/`` (jupytext percent ``.py`` files) executed in quick
  mode (``MOVING_BOGIE_QUICK=1``) by ``notebooks/run.py``, the runner the tests use; an executed notebook is
  kept while it is newer than its source and the package (delete ``docs/tutorials/`` to run them again).

The API reference (``api.md``) is generated from the docstrings by autosummary into ``_autosummary/``.
"""

from __future__ import annotations

import importlib.util
import os
import re
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
NOTEBOOKS = ROOT / "notebooks"
TUTORIALS = DOCS / "tutorials"

if (ROOT / "src" / "moving_bogie").is_dir():  # build from the checkout's sources, installed or not
    sys.path.insert(0, str(ROOT / "src"))

import moving_bogie  # noqa: E402
from moving_bogie.cli.docs import render  # noqa: E402


def _notebook_runner():
    """``notebooks/run.py``, the runner that executes the notebooks, loaded from its path (for its rule of
    when an executed copy is current, :func:`is_current`)."""
    spec = importlib.util.spec_from_file_location("notebook_runner", NOTEBOOKS / "run.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


RUNNER = _notebook_runner()

project = "moving-bogie"
author = "the moving-bogie authors"
copyright = "the moving-bogie authors"  # noqa: A001 - Sphinx's name
release = moving_bogie.__version__
version = release

extensions = [
    "myst_nb",  # Markdown pages (MyST) and executed notebooks
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "sphinx-mathjax-offline",  # MathJax served from the site itself: the equations render without network
    "numpydoc",
]
source_suffix = {".rst": "restructuredtext", ".md": "myst-nb", ".ipynb": "myst-nb"}  # .rst: autosummary
exclude_patterns = ["_build", "_generated", "**/.ipynb_checkpoints", "check_links.py"]
templates_path = ["_templates"]
root_doc = "index"
highlight_language = "none"  # code fences without a language (help texts, commands) stay plain

myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence", "deflist"]
myst_heading_anchors = 4
myst_dmath_double_inline = True
nb_execution_mode = "off"  # executed beforehand by notebooks/run.py (below)
nb_merge_streams = True

autosummary_generate = True
autosummary_imported_members = False
autodoc_default_options = {"members": True, "show-inheritance": False}
autodoc_typehints = "none"  # numpydoc shows the types of the docstrings
autodoc_member_order = "bysource"
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False

html_theme = "furo"
html_title = "moving-bogie"
html_static_path = ["_static"]
html_css_files = ["tables.css"]  # tables wrap their text to the page's width
html_theme_options = {"navigation_with_keys": True}
nitpicky = False


def write_cli_reference() -> None:
    """``cli.md`` from the parsers (rewritten only when it changes, so Sphinx rebuilds only then)."""
    path = DOCS / "cli.md"
    text = render()
    if not path.exists() or path.read_text(encoding="utf-8") != text:
        path.write_text(text, encoding="utf-8")


def _execute(source: Path) -> str:
    """Run one notebook through ``notebooks/run.py --quick`` into ``tutorials/``."""
    out = TUTORIALS / f"{source.stem}.ipynb"
    partial = TUTORIALS / f"{source.stem}.partial.ipynb"
    env = dict(os.environ, MPLBACKEND="module://matplotlib_inline.backend_inline")  # figures as outputs
    env["PYTHONPATH"] = os.pathsep.join(p for p in (str(ROOT / "src"), env.get("PYTHONPATH")) if p)
    argv = [sys.executable, str(NOTEBOOKS / "run.py"), str(source), "--quick", "--out", str(partial)]
    proc = subprocess.run(argv, env=env, capture_output=True, text=True)
    if proc.returncode != 0:
        partial.unlink(missing_ok=True)
        raise RuntimeError(f"{source.name} failed in notebooks/run.py:\n{proc.stderr[-4000:]}")
    partial.replace(out)
    return proc.stdout.strip()


def execute_notebooks() -> None:
    """``tutorials/NAME.ipynb``: every notebook executed in quick mode, two at a time."""
    TUTORIALS.mkdir(exist_ok=True)
    sources = sorted(NOTEBOOKS.glob("[0-9][0-9]-*.py"))
    for old in TUTORIALS.glob("*.ipynb"):
        if ".partial" in old.name or not (NOTEBOOKS / f"{old.stem}.py").exists():
            old.unlink()
    newest = RUNNER.newest_package_file()  # once for every notebook
    stale = [s for s in sources if not RUNNER.is_current(s, TUTORIALS / f"{s.stem}.ipynb", newest)]
    if stale:
        with ThreadPoolExecutor(min(2, len(stale))) as pool:
            for line in pool.map(_execute, stale):
                print(line, flush=True)


#: The figures the pages show, drawn by the command line: name -> its arguments (``--plot`` added).
FIGURES = {
    # the home page's: the walkthrough's time series
    "uic60-series.png": "timeseries --file examples/uic60-bogie.toml --set v=83.3 --tmax 1".split(),
    # soil.md's: the dispersion figure of the ballasted track on soil
    "soil-dispersion.png": "critical-velocity --file examples/soil-ballasted.toml".split(),
}


def make_home_figure() -> None:
    """``_generated/*.png`` of :data:`FIGURES`, each drawn by the command line when older than the package."""
    for name, args in FIGURES.items():
        out = DOCS / "_generated" / name
        if out.exists() and out.stat().st_mtime >= RUNNER.newest_package_file():
            continue
        out.parent.mkdir(exist_ok=True)
        env = dict(os.environ, MPLBACKEND="Agg")
        env["PYTHONPATH"] = os.pathsep.join(p for p in (str(ROOT / "src"), env.get("PYTHONPATH")) if p)
        argv = [sys.executable, "-m", "moving_bogie", *args, "--plot", str(out)]
        subprocess.run(argv, cwd=ROOT, env=env, check=True, capture_output=True)


_LITERAL = re.compile(r"(``.+?``|`[^`]+`)")
_TABLE = re.compile(r"\s*(\+[-=]|\| )")


def escape_bars(app, what, name, obj, options, lines) -> None:
    """The docstrings write absolute values as ``|q|``: keep them text, not reST substitutions."""
    for k, line in enumerate(lines):
        if _TABLE.match(line):  # a grid table's border or row, or a line block
            continue
        parts = _LITERAL.split(line)
        lines[k] = "".join(p if i % 2 else p.replace("|", "\\|") for i, p in enumerate(parts))


#: Abbreviations a summary does not end at: autosummary takes a docstring's first sentence, and "Closed-form
#: time series, Eqs. (35)-(43)." would otherwise read "Closed-form time series, Eqs.".
SUMMARY_ABBREVIATIONS = ("Eq.", "Eqs.", "Fig.", "Figs.", "Sec.", "cf.", "approx.")


def keep_abbreviations_in_summaries() -> None:
    """Add :data:`SUMMARY_ABBREVIATIONS` to the abbreviations after which autosummary does not end a
    sentence (``sphinx.ext.autosummary.WELL_KNOWN_ABBREVIATIONS``, read at each summary)."""
    from sphinx.ext import autosummary

    known = tuple(autosummary.WELL_KNOWN_ABBREVIATIONS)
    autosummary.WELL_KNOWN_ABBREVIATIONS = known + tuple(a for a in SUMMARY_ABBREVIATIONS if a not in known)


def setup(app) -> None:
    keep_abbreviations_in_summaries()
    app.connect("autodoc-process-docstring", escape_bars, priority=400)


write_cli_reference()
make_home_figure()
execute_notebooks()
