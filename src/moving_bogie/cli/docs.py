"""Write the command line reference ``docs/cli.md`` from the argparse parser itself.

``python -m moving_bogie.cli.docs`` renders ``moving-bogie --help`` and every subcommand's ``--help``
into Markdown and writes ``docs/cli.md`` (``--output`` elsewhere, ``-`` for stdout); the documentation
site's build (``docs/conf.py``) calls :func:`render` and writes that page, which is not committed.
``--check`` writes nothing and exits 1 when the file differs from what the parser gives now. The help is
rendered at a fixed width, so the text does not depend on the terminal; argparse's layout changes between
Python minor versions, so the page records the version it was made with.
"""

from __future__ import annotations

import argparse
import contextlib
import difflib
import os
import sys
from collections.abc import Iterator, Sequence
from pathlib import Path

#: Width of the rendered help (columns).
WIDTH = 100
#: Default output, relative to the repository root.
DEFAULT_OUTPUT = Path("docs") / "cli.md"
COMMAND = "python -m moving_bogie.cli.docs"


@contextlib.contextmanager
def _columns(width: int) -> Iterator[None]:
    """argparse wraps help to ``shutil.get_terminal_size()``, which honours $COLUMNS."""
    old = os.environ.get("COLUMNS")
    os.environ["COLUMNS"] = str(width)
    try:
        yield
    finally:
        if old is None:
            del os.environ["COLUMNS"]
        else:
            os.environ["COLUMNS"] = old


def python_version() -> str:
    """``"3.11"``: the minor version whose argparse layout the file holds."""
    return f"{sys.version_info.major}.{sys.version_info.minor}"


def subcommands(parser: argparse.ArgumentParser) -> dict[str, argparse.ArgumentParser]:
    """The subcommand parsers of `parser`, in the order ``--help`` lists them."""
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            return dict(action.choices)
    return {}


def render(width: int = WIDTH) -> str:
    """The Markdown reference of the ``moving-bogie`` command line."""
    from . import build_parser

    with _columns(width):
        parser = build_parser()
        commands = subcommands(parser)
        lines = [
            "# Command line reference",
            "",
            f"Generated from the argparse parser by `{COMMAND}` "
            f"(Python {python_version()}, {width} columns).",
            "The documentation build writes this page; change the subcommand's module in",
            "`src/moving_bogie/cli/` to change it.",
            "",
            "| command | what it does |",
            "|---|---|",
        ]
        helps = _help_lines(parser)
        for name in commands:
            lines.append(f"| [`moving-bogie {name}`](#moving-bogie-{name}) | {helps.get(name, '')} |")
        lines += ["", "## moving-bogie", "", "```", parser.format_help().rstrip(), "```"]
        for name, sub in commands.items():
            lines += ["", f"## moving-bogie {name}", "", "```", sub.format_help().rstrip(), "```"]
    from moving_bogie.model.catalogue import default_catalogue

    from .models_cmd import format_catalogue

    lines += [
        "",
        "## The models and their parameters",
        "",
        "The output of `moving-bogie models --verbose`: every model of the generated catalogue (from "
        "`derivations/`).",
        "",
        "```",
        format_catalogue(default_catalogue().models()),
        "```",
    ]
    return "\n".join(lines) + "\n"


def _help_lines(parser: argparse.ArgumentParser) -> dict[str, str]:
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            return {
                choice.dest: (choice.help or "").replace("|", "\\|") for choice in action._choices_actions
            }
    return {}


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog=COMMAND, description=__doc__.splitlines()[0])
    parser.add_argument(
        "--output",
        default=None,
        help=f"file to write (default: {DEFAULT_OUTPUT} in the repository; - for stdout)",
    )
    parser.add_argument(
        "--check", action="store_true", help="exit 1 if the file is out of date; write nothing"
    )
    args = parser.parse_args(argv)
    text = render()
    if args.output == "-":
        sys.stdout.write(text)
        return 0
    path = Path(args.output) if args.output else _repository_root() / DEFAULT_OUTPUT
    if args.check:
        old = path.read_text(encoding="utf-8") if path.exists() else ""
        if old == text:
            print(f"{path} is current")
            return 0
        sys.stdout.writelines(
            difflib.unified_diff(old.splitlines(True), text.splitlines(True), str(path), "parser")
        )
        print(f"\n{path} is out of date. Update it with: {COMMAND}")
        return 1
    from .common import atomic_write

    atomic_write(path, text)
    print(f"wrote {path}")
    return 0


def _repository_root() -> Path:
    """The source checkout holding this package (``src/moving_bogie/cli`` -> repository root)."""
    root = Path(__file__).resolve().parents[3]
    if not (root / "pyproject.toml").is_file():
        raise SystemExit(f"{COMMAND}: not running from a source checkout; pass --output FILE")
    return root


if __name__ == "__main__":
    sys.exit(main())
