"""Starting worker processes safely: Ctrl-C handled by the calling process alone, and the guard a script
needs before its work can start processes that import the script again.

A worker process started by "spawn" or "forkserver" (Dask's workers always; Python's pools on macOS and
Windows) imports the calling script again, as ``__mp_main__``: every statement of the script outside
``if __name__ == "__main__":`` runs again in each worker, and a call that starts workers there starts them
again, recursively, until the start fails ("Nanny failed to start"). :func:`require_main_guard` says so
before anything is started or written.
"""

from __future__ import annotations

import ast
import signal
import sys
from functools import cache
from types import FrameType

from moving_bogie.errors import MovingBogieError

__all__ = ["ignore_interrupts", "require_main_guard", "unguarded_script_line"]


def ignore_interrupts() -> None:
    """Initializer of a worker process: SIGINT ignored (Ctrl-C in a terminal reaches the whole process
    group; the calling process handles it, and the workers print no traceback)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def unguarded_script_line(frame: FrameType | None = None) -> tuple[str, int] | None:
    """(script, line) when the code calling this runs at the top level of a script file outside its
    ``if __name__ == "__main__":`` block; None otherwise (a guarded call, an interactive session,
    ``python -c``, a package's ``__main__``, which spawned processes do not import again)."""
    main = sys.modules.get("__main__")
    path = getattr(main, "__file__", None)
    spec_name = getattr(getattr(main, "__spec__", None), "name", None) or ""
    if main is None or path is None or spec_name == "__main__" or spec_name.endswith(".__main__"):
        return None
    frame = frame or sys._getframe(1)
    while frame is not None:
        if frame.f_globals is vars(main) and frame.f_code.co_name == "<module>":
            return None if _guarded(str(path), frame.f_lineno) else (str(path), frame.f_lineno)
        frame = frame.f_back
    return None


def require_main_guard(call: str) -> None:
    """Raise :class:`~moving_bogie.errors.MovingBogieError` (naming the guard) when ``call``, about to start
    worker processes, runs at the top level of a script outside ``if __name__ == "__main__":``."""
    where = unguarded_script_line(sys._getframe(1))
    if where is not None:
        script, line = where
        raise MovingBogieError(
            f"{call} starts worker processes, which run the script {script} again from its top: put the "
            f'calls of line {line} under `if __name__ == "__main__":` (docs/sweeps.md); nothing was started '
            "or written"
        )


@cache
def _guard_lines(path: str) -> tuple[tuple[int, int], ...]:
    """The line ranges of the ``if __name__ == "__main__":`` bodies of the file at ``path``."""
    try:
        with open(path, encoding="utf-8") as handle:
            tree = ast.parse(handle.read())
    except (OSError, SyntaxError, ValueError):
        return ((1, sys.maxsize),)  # not readable: no judgement, as if guarded
    return tuple(
        (node.body[0].lineno, node.body[-1].end_lineno or node.body[-1].lineno)
        for node in ast.walk(tree)
        if isinstance(node, ast.If) and _is_main_test(node.test)
    )


def _is_main_test(test: ast.expr) -> bool:
    """``__name__ == "__main__"`` (either side)."""
    if not (isinstance(test, ast.Compare) and len(test.ops) == 1 and isinstance(test.ops[0], ast.Eq)):
        return False
    sides = [test.left, test.comparators[0]]
    names = {s.id for s in sides if isinstance(s, ast.Name)}
    texts = {s.value for s in sides if isinstance(s, ast.Constant)}
    return names == {"__name__"} and texts == {"__main__"}


def _guarded(path: str, line: int) -> bool:
    return any(lo <= line <= hi for lo, hi in _guard_lines(path))
