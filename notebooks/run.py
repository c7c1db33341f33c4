"""Run a notebook headless: ``python notebooks/run.py notebooks/02-table2.py [--quick] [--out F.ipynb]``.

The notebooks are jupytext percent-format ``.py`` files. This converts one to a notebook in memory and
executes every cell with nbclient on a kernel that runs *this* interpreter (a ``python3`` kernelspec written
to a temporary JUPYTER_PATH, so no kernel has to be installed), in the notebook's own folder. ``--quick``
sets ``MOVING_BOGIE_QUICK=1`` (coarse grids, short windows: what ``tests/test_notebooks.py`` runs, through
this same function); ``--out`` keeps the executed notebook with its outputs. A failing cell prints its
traceback and exits with status 1. Needs the dev extra (``pip install -e '.[dev]'``: jupytext, nbformat,
nbclient, ipykernel).

An executed notebook records how it ran (``metadata["moving_bogie_run"]``, quick or not). The documentation
build keeps its runs while :func:`is_current`; the tests check such a run with :func:`check_executed`
instead of running the notebook again.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile
import time
from contextlib import contextmanager
from pathlib import Path

#: What ``python -m ipykernel_launcher`` does (the working folder off sys.path while ipykernel loads; the
#: kernel puts it back), with debugpy made unimportable: the kernel then starts without its debugger
#: (ipykernel's own fallback when debugpy is missing), which saves about a tenth of a second of CPU at every
#: start. A headless run steps through nothing.
KERNEL_START = (
    "import sys; del sys.path[0]; sys.modules['debugpy'] = None; "
    "from ipykernel import kernelapp; kernelapp.launch_new_instance()"
)


@contextmanager
def this_interpreter_kernel():
    """A temporary JUPYTER_PATH whose ``python3`` kernel starts this interpreter (restored afterwards)."""
    with tempfile.TemporaryDirectory(prefix="moving-bogie-kernel-") as root:
        spec = Path(root) / "kernels" / "python3"
        spec.mkdir(parents=True)
        kernel = {
            "argv": [sys.executable, "-c", KERNEL_START, "-f", "{connection_file}"],
            "display_name": "Python 3 (moving-bogie)",
            "language": "python",
        }
        (spec / "kernel.json").write_text(json.dumps(kernel))
        old = os.environ.get("JUPYTER_PATH")
        os.environ["JUPYTER_PATH"] = root + (os.pathsep + old if old else "")
        try:
            yield root
        finally:
            if old is None:
                os.environ.pop("JUPYTER_PATH", None)
            else:
                os.environ["JUPYTER_PATH"] = old


class CellFailed(RuntimeError):
    """A cell raised: the message holds the cell's traceback."""


def run_notebook(path, *, quick: bool = False, out=None, timeout: int = 600) -> float:
    """Execute the jupytext notebook ``path`` top to bottom; returns the seconds it took.

    Raises
    ------
    CellFailed
        With the failing cell's traceback.
    """
    import jupytext
    import nbclient
    import nbformat

    path = Path(path).resolve()
    notebook = nbformat.reads(jupytext.writes(jupytext.read(path), fmt="ipynb"), as_version=4)
    saved = {k: os.environ.get(k) for k in ("MOVING_BOGIE_QUICK",)}
    if quick:
        os.environ["MOVING_BOGIE_QUICK"] = "1"
    start = time.perf_counter()
    try:
        with this_interpreter_kernel():
            client = nbclient.NotebookClient(
                notebook,
                kernel_name="python3",
                timeout=timeout,
                resources={"metadata": {"path": str(path.parent)}},
            )
            notebook.metadata[RUN_METADATA] = {"quick": bool(quick)}
            try:
                client.execute()
            except nbclient.exceptions.CellExecutionError as exc:
                raise CellFailed(f"{path.name}: a cell failed\n{exc}") from None
    finally:
        for key, value in saved.items():
            if value is None:
                os.environ.pop(key, None)
            else:
                os.environ[key] = value
        if out is not None:
            nbformat.write(notebook, str(out))
    return time.perf_counter() - start


#: The key of the executed notebook's metadata under which :func:`run_notebook` records how it ran.
RUN_METADATA = "moving_bogie_run"


def newest_package_file(package=None) -> float:
    """The modification time of the newest ``.py`` file of the package folder ``package`` (by default that of
    the imported ``moving_bogie``)."""
    if package is None:
        import moving_bogie

        package = Path(moving_bogie.__file__).resolve().parent
    return max(p.stat().st_mtime for p in Path(package).rglob("*.py"))


def is_current(source, executed, newest: float | None = None) -> bool:
    """Whether the executed notebook ``executed`` is newer than its ``source`` and than every file of the
    package (``newest``: :func:`newest_package_file`, when already known): the documentation build keeps
    such a copy instead of running the notebook again."""
    source, executed = Path(source), Path(executed)
    if not executed.is_file():
        return False
    newest = newest_package_file() if newest is None else newest
    return executed.stat().st_mtime >= max(source.stat().st_mtime, newest)


def check_executed(source, executed, *, quick: bool) -> list[str]:
    """What keeps ``executed`` from being a complete run of the jupytext notebook ``source`` as it is now
    (empty when nothing does): a code cell whose text is not the source's, one that did not run, an error
    among its outputs, or a run in another mode than ``quick``."""
    import jupytext
    import nbformat

    expected = [c.source for c in jupytext.read(Path(source)).cells if c.cell_type == "code"]
    notebook = nbformat.read(str(executed), as_version=4)
    cells = [c for c in notebook.cells if c.cell_type == "code"]
    problems = []
    if [c.source for c in cells] != expected:
        problems.append("its code cells are not those of the source")
    if notebook.metadata.get(RUN_METADATA, {}).get("quick") is not bool(quick):
        problems.append(f"it was not run with quick={bool(quick)}")
    for k, cell in enumerate(cells):
        if cell.get("execution_count") is None:
            problems.append(f"code cell {k} did not run")
        errors = [o for o in cell.get("outputs", ()) if o.get("output_type") == "error"]
        if errors:
            problems.append(f"code cell {k} raised {errors[0].get('ename')}")
    return problems


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(
        prog="python notebooks/run.py", description="Run notebooks headless (every cell, top to bottom)."
    )
    parser.add_argument("notebooks", nargs="+", type=Path, metavar="NOTEBOOK.py", help="jupytext notebooks")
    parser.add_argument("--quick", action="store_true", help="coarse grids and short windows (as the tests)")
    parser.add_argument("--out", type=Path, metavar="F.ipynb", help="keep the executed notebook (one only)")
    parser.add_argument(
        "--timeout", type=int, default=600, metavar="S", help="seconds per cell (default 600)"
    )
    args = parser.parse_args(argv)
    if args.out is not None and len(args.notebooks) > 1:
        parser.error("--out takes one notebook")
    for path in args.notebooks:
        if not path.is_file():
            parser.error(f"no notebook at {path}")
    try:
        import jupytext  # noqa: F401
        import nbclient  # noqa: F401
    except ImportError as exc:
        print(f"{parser.prog}: error: {exc.name} is missing: pip install -e '.[dev]'", file=sys.stderr)
        return 2
    status = 0
    for path in args.notebooks:
        try:
            seconds = run_notebook(path, quick=args.quick, out=args.out, timeout=args.timeout)
        except CellFailed as exc:
            print(exc, file=sys.stderr)
            status = 1
            continue
        print(f"{path.name}: ok, {seconds:.1f} s")
    return status


if __name__ == "__main__":
    sys.exit(main())
