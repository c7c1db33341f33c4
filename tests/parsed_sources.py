"""The repository's Python files parsed once per process, for the checks that read the source text
(``test_layout.py``, ``test_declared_dependencies.py``, ``test_docs.py``). Under ``-n 2`` those modules run on
one worker (``xdist_balance.TOGETHER``), so each file is parsed once for all of them."""

from __future__ import annotations

import ast
import functools
from pathlib import Path


@functools.cache
def parsed(path: Path) -> ast.Module:
    """The syntax tree of the file ``path`` (UTF-8); its callers only read it."""
    return ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
