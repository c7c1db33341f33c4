"""Output options (``--csv``, ``--plot``, ``--npz``, ``--out`` ...): declared once, checked before any work.

An output option is added with :func:`add_output_option`; its value is recorded on the parsed namespace
(``args.output_paths``), and :func:`check_output_paths` (called by ``main`` before the command runs) makes
sure every one of them can be written: a format the option writes (a figure: one of :data:`FIGURE_FORMATS`),
not an existing folder (or, for a folder option, not an existing file), inside a folder that exists (none is
created), where a file can actually be created. The error names the option, so nothing is computed only to
fail at the end, and nothing is created on the way. The checks import nothing heavy (no matplotlib).
"""

from __future__ import annotations

import argparse
import os
import tempfile
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import Any

from moving_bogie.errors import MovingBogieError, did_you_mean

__all__ = [
    "FIGURE_FORMATS",
    "OutputError",
    "OutputPath",
    "add_figure_option",
    "add_output_option",
    "check_input_paths",
    "check_output_paths",
]

#: Input options read from a path: dest -> (option as typed, what it names).
INPUT_PATHS = {"file": ("--file", "file"), "store": ("S.zarr", "store")}

#: The file suffixes matplotlib writes (``Figure().canvas.get_supported_filetypes()``; a test compares the
#: two), listed here so that checking a figure's name does not import matplotlib.
FIGURE_FORMATS = (
    "png", "pdf", "svg", "svgz", "eps", "ps", "pgf", "jpg", "jpeg", "tif", "tiff", "webp", "avif", "gif",
    "raw", "rgba",
)  # fmt: skip


class OutputError(MovingBogieError):
    """An output option names a path that cannot be written; ``option`` is the option as typed."""

    def __init__(self, option: str, message: str) -> None:
        self.option = option
        super().__init__(f"{option}: {message}")


class OutputPath(argparse.Action):
    """Store the path and remember (option, path, is_folder, suffixes) in ``namespace.output_paths``."""

    def __init__(
        self,
        option_strings: Sequence[str],
        dest: str,
        folder: bool = False,
        formats: Iterable[str] = (),
        **kwargs: Any,
    ) -> None:
        self.folder = folder
        self.formats = tuple(formats)
        super().__init__(option_strings, dest, **kwargs)

    def __call__(
        self,
        parser: argparse.ArgumentParser,
        namespace: argparse.Namespace,
        values: str | Sequence[Any] | None,
        option_string: str | None = None,
    ) -> None:
        if not isinstance(values, str):  # one path per option (no nargs, no type)
            raise TypeError(f"{self.option_strings[0]} takes one path")
        path = Path(values)
        setattr(namespace, self.dest, path)
        recorded = [o for o in getattr(namespace, "output_paths", []) if o[0] != self.option_strings[0]]
        namespace.output_paths = recorded + [(self.option_strings[0], path, self.folder, self.formats)]


def add_output_option(
    parser: argparse._ActionsContainer,
    *flags: str,
    folder: bool = False,
    formats: tuple[str, ...] = (),
    **kwargs: Any,
) -> argparse.Action:
    """Add an output option (a file, or a folder if ``folder``) that :func:`check_output_paths` will check.

    ``flags`` are the option strings, the preferred spelling first (the others are kept as aliases);
    ``formats``, when given, the file suffixes (without the dot) the option can write.
    """
    kwargs.setdefault("metavar", "DIR" if folder else "F")
    return parser.add_argument(*flags, action=OutputPath, folder=folder, formats=formats, **kwargs)


def add_figure_option(parser: argparse._ActionsContainer, *flags: str, **kwargs: Any) -> argparse.Action:
    """Add an output option for a figure: its suffix must be one of :data:`FIGURE_FORMATS`."""
    kwargs.setdefault("metavar", "F.png")
    return add_output_option(parser, *flags, formats=FIGURE_FORMATS, **kwargs)


def _probe(folder: Path) -> str | None:
    """Create and remove a file in ``folder``; the reason it failed, or None."""
    try:
        fd, name = tempfile.mkstemp(dir=folder, prefix=".moving-bogie-probe.")
    except OSError as exc:
        return exc.strerror or str(exc)
    os.close(fd)
    os.unlink(name)
    return None


def _check_format(option: str, path: Path, formats: tuple[str, ...]) -> None:
    suffix = path.suffix.lower().lstrip(".")
    if formats and suffix not in formats:
        hint = did_you_mean(suffix, formats) if suffix else ""
        got = f"'.{suffix}' is not a format it writes" if suffix else "no suffix says the format"
        shown = ", ".join("." + f for f in formats)
        raise OutputError(option, f"{path}: {got}; {hint or 'use one of ' + shown}")


def check_output_path(option: str, path: Path, folder: bool = False, formats: tuple[str, ...] = ()) -> None:
    """Raise :class:`OutputError` naming ``option`` unless ``path`` can be written (a file, or a folder) in
    one of ``formats`` (file suffixes; any when empty), in a folder that exists."""
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
    _check_format(option, path, formats)
    parent = path.parent
    if not parent.is_dir():
        what = "is not a folder" if parent.exists() else "does not exist (create it first)"
        raise OutputError(option, f"cannot write {path}: the folder {parent} {what}")
    reason = _probe(parent)
    if reason is not None:
        raise OutputError(option, f"cannot write {path}: {reason}")


def check_output_paths(args: argparse.Namespace) -> None:
    """Check every output option given on the command line (see :func:`add_output_option`)."""
    for option, path, folder, formats in getattr(args, "output_paths", ()):
        check_output_path(option, path, folder, formats)


def check_input_paths(args: argparse.Namespace) -> None:
    """Check that every input path given (``--file``, a sweep store) exists, naming its option."""
    for dest, (option, what) in INPUT_PATHS.items():
        path = getattr(args, dest, None)
        if path is None:
            continue
        path = Path(os.path.expanduser(path))
        if not path.exists():
            raise OutputError(option, f"{path}: no such {what}")
        if what == "file" and path.is_dir():
            raise OutputError(option, f"{path} is a folder; give a TOML file")
        if what == "file" and not os.access(path, os.R_OK):
            raise OutputError(option, f"{path} is not readable")
