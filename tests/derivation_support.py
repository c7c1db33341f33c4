"""SymPy for the tests of derivations/ (present, or a clear failure; skipped only when asked to) and the
scratch copies of the source tree in which those tests add a model and regenerate.

Without SymPy the check that ``generated/`` and ``docs/proofs.md`` are current cannot run. A skip would
make it disappear from the summary of a CI run without anyone noticing, so a missing SymPy fails the
collection of these test files with the command that installs it. A developer who works without SymPy
on purpose sets ``MOVING_BOGIE_SKIP_DERIVATIONS=1`` (README, "Tests"); the files are then reported
as skipped with that reason.
"""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

from optional_tools import require

REPO = Path(__file__).resolve().parents[1]
SKIP_VARIABLE = "MOVING_BOGIE_SKIP_DERIVATIONS"
INSTALL = "pip install --no-deps -r requirements-derive.txt"


def require_sympy():
    """The ``sympy`` module; a module-level skip if :data:`SKIP_VARIABLE` is ``1``, else a failure."""
    (sympy,) = require(
        ("sympy",),
        needed_for="derivations/ (generated/ is current, kernels against the derivation, proofs)",
        install=INSTALL,
        variable=SKIP_VARIABLE,
    )
    return sympy


def regenerated_copy(root: Path, additions: dict, only: tuple) -> Path:
    """``derivations/`` and ``src/`` copied into ``root``, text appended to derivation files, regenerated.

    ``additions`` maps a file of derivations/ to the text appended to it; ``only`` names what they add
    (beams, tracks, vehicles): ``python -m derivations --root root --only NAME ...`` writes those models'
    modules and the catalogue-wide files, as a full run would, and keeps the copied (committed, current:
    ``test_derivations_current.py``) modules of everything else. A full regeneration would derive every
    model of the catalogue again for nothing.
    """
    ignore = shutil.ignore_patterns("__pycache__", "*.egg-info")
    for name in ("derivations", "src"):
        shutil.copytree(REPO / name, root / name, ignore=ignore)
    for name, addition in additions.items():
        path = root / "derivations" / name
        path.write_text(path.read_text() + addition)
    options = [arg for name in only for arg in ("--only", name)]
    run = subprocess.run(
        [sys.executable, "-m", "derivations", "--root", str(root), *options],
        cwd=root,
        capture_output=True,
        text=True,
    )
    assert run.returncode == 0, run.stdout + run.stderr
    return root
