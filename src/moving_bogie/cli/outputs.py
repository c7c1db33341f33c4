"""Output options (``--csv``, ``--plot``, ``--npz``, ``--out`` ...): declared once, checked before any work.

An output option is added with :func:`add_output_option`; its value is recorded on the parsed namespace
(``args.output_paths``), and :func:`check_output_paths` (called by ``main`` before the command runs) makes
sure every one of them can be written: not an existing folder (or, for a folder option, not an existing file),
inside a folder that exists or can be created, where a file can actually be created. The error names the
option, so nothing is computed only to fail at the end.
"""

from __future__ import annotations

import argparse
import os
import tempfile
from pathlib import Path

from moving_bogie.errors import MovingBogieError

__all__ = ["OutputError", "OutputPath", "add_output_option", "check_output_paths"]


class OutputError(MovingBogieError):
    """An output option names a path that cannot be written; ``option`` is the option as typed."""

    def __init__(self, option: str, message: str) -> None:
        self.option = option
        super().__init__(f"{option}: {message}")


class OutputPath(argparse.Action):
    """Store the path and remember (option, path, is_folder) in ``namespace.output_paths``."""

    def __init__(self, option_strings, dest, folder=False, **kwargs):
        self.folder = folder
        super().__init__(option_strings, dest, **kwargs)

    def __call__(self, parser, namespace, values, option_string=None):
        path = Path(values)
        setattr(namespace, self.dest, path)
        recorded = [o for o in getattr(namespace, "output_paths", []) if o[0] != self.option_strings[0]]
        namespace.output_paths = recorded + [(self.option_strings[0], path, self.folder)]


def add_output_option(parser, *flags: str, folder: bool = False, **kwargs) -> argparse.Action:
    """Add an output option (a file, or a folder if ``folder``) that :func:`check_output_paths` will check.

    ``flags`` are the option strings, the preferred spelling first (the others are kept as aliases).
    """
    kwargs.setdefault("metavar", "DIR" if folder else "F")
    return parser.add_argument(*flags, action=OutputPath, folder=folder, **kwargs)


def _existing_ancestor(path: Path) -> Path:
    for candidate in (path, *path.parents):
        if candidate.exists() or candidate.is_symlink():
            return candidate
    return Path(".")


def _probe(folder: Path) -> str | None:
    """Create and remove a file in ``folder``; the reason it failed, or None."""
    try:
        fd, name = tempfile.mkstemp(dir=folder, prefix=".moving-bogie-probe.")
    except OSError as exc:
        return exc.strerror or str(exc)
    os.close(fd)
    os.unlink(name)
    return None


def check_output_path(option: str, path: Path, folder: bool = False) -> None:
    """Raise :class:`OutputError` naming ``option`` unless ``path`` can be written (a file, or a folder)."""
    path = Path(os.path.expanduser(path))
    if str(path) in ("", "."):
        if not folder:
            raise OutputError(option, "needs a file name")
    if folder:
        if path.exists() and not path.is_dir():
            raise OutputError(option, f"{path} exists and is not a folder")
    elif path.is_dir():
        raise OutputError(option, f"{path} is a folder; give a file name")
    elif path.exists() and not os.access(path, os.W_OK):
        raise OutputError(option, f"{path} exists and is not writable")
    start = path if folder else path.parent
    ancestor = _existing_ancestor(start)
    if not ancestor.is_dir():
        raise OutputError(option, f"cannot create {path}: {ancestor} is not a folder")
    reason = _probe(ancestor)
    if reason is not None:
        where = "" if ancestor == start else f" (the folder {ancestor} would hold it)"
        raise OutputError(option, f"cannot write {path}{where}: {reason}")


def check_output_paths(args: argparse.Namespace) -> None:
    """Check every output option given on the command line (see :func:`add_output_option`)."""
    for option, path, folder in getattr(args, "output_paths", ()):
        check_output_path(option, path, folder)
