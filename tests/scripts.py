"""The repository's scripts, loaded as modules by the tests.

``benchmarks/``, ``docs/`` and ``notebooks/`` are folders of scripts, not packages: a test that calls a
script's functions (a benchmark's reference scan, the link checker, the notebook runner) loads it from its
path, once per test process.
"""

from __future__ import annotations

import functools
import importlib.util
import sys
from pathlib import Path
from types import ModuleType

ROOT = Path(__file__).resolve().parent.parent


@functools.cache
def load_script(relative: str) -> ModuleType:
    """The script ``ROOT / relative`` as a module (kept: later calls return the same module).

    While it runs, its folder is on ``sys.path`` (a benchmark imports ``records.py`` beside it) and the module
    is in ``sys.modules`` under a name of its own (a dataclass looks its module up there when it is made).
    """
    path = ROOT / relative
    name = f"_script_{path.parent.name}_{path.stem}"
    spec = importlib.util.spec_from_file_location(name, path)
    if spec is None or spec.loader is None:
        raise ImportError(f"cannot load {path}")
    module = importlib.util.module_from_spec(spec)
    sys.path.insert(0, str(path.parent))
    sys.modules[name] = module
    try:
        spec.loader.exec_module(module)
    finally:
        sys.path.remove(str(path.parent))
        sys.modules.pop(name, None)
    return module
