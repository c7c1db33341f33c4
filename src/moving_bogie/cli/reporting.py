"""How the command line reports a failure: one line naming the option, or a JSON object with ``--json``.

- Usage errors (unknown option, a value argparse refuses): ``moving-bogie CMD: error: <what>`` and one hint
  line (``see: moving-bogie CMD --help``) on stderr, exit status 2, instead of argparse's usage block.
- Expected failures while running (:class:`~moving_bogie.errors.MovingBogieError`, invalid TOML, files that
  cannot be read or written): ``moving-bogie: error: <message>`` on stderr, exit status 2; Ctrl-C 130.
- With ``--json`` on the command line, either kind is instead one JSON object on **stdout**,
  ``{"error": "<message>", "option": "--alpha"}`` (``option`` null when no single option is to blame),
  with the same exit status, so that a script reading stdout always gets JSON.

Other exceptions are bugs and keep their traceback.
"""

from __future__ import annotations

import argparse
import functools
import json
import os
import re
import sys
import tomllib
from collections.abc import Callable, Mapping, Sequence
from typing import Any, NoReturn

from moving_bogie.errors import JobInterrupted, MovingBogieError, ParameterError, did_you_mean

PROG = "moving-bogie"

__all__ = ["Parser", "UsageError", "fail", "handle_errors", "suggest_option"]


class UsageError(Exception):
    """argparse refused the command line; ``option`` is the option it names (or None)."""

    def __init__(self, message: str, option: str | None, prog: str) -> None:
        self.option = option
        self.prog = prog
        super().__init__(message)


def _blamed_option(message: str) -> str | None:
    """The option an argparse message is about ('argument --alpha: ...', 'required: --out', ...)."""
    match = re.match(r"argument ([^:\s]+)", message)
    if match:
        return match.group(1).split("/")[0]
    match = re.search(r"(?:required|unrecognized arguments|not allowed with argument):? (-[-\w]+)", message)
    if match:
        return match.group(1)
    return None


class Parser(argparse.ArgumentParser):
    """ArgumentParser whose errors raise :class:`UsageError` (reported by :func:`main` in one line); a value
    outside an option's choices gets the closest choices suggested."""

    #: The subcommand parsers by name (set by :func:`~moving_bogie.cli.build_parser`).
    commands: Mapping[str, argparse.ArgumentParser]

    def error(self, message: str) -> NoReturn:  # noqa: D102 (argparse API)
        match = re.search(r"invalid choice: '([^']*)' \(choose from (.*)\)$", message)
        if match:
            hint = did_you_mean(match.group(1), re.findall(r"'([^']*)'", match.group(2)))
            message += f"; {hint}" if hint else ""
        raise UsageError(message, _blamed_option(message), self.prog)


def suggest_option(
    exc: UsageError, argv: Sequence[str], commands: Mapping[str, argparse.ArgumentParser]
) -> UsageError:
    """``exc`` with the closest options of the command named in ``argv`` suggested for an unrecognized one."""
    message = str(exc)
    if not message.startswith("unrecognized arguments") or not argv or argv[0] not in commands:
        return exc
    known = list(commands[argv[0]]._option_string_actions)  # noqa: SLF001 (argparse has no public list)
    unknown = [a.split("=", 1)[0] for a in message.split(":", 1)[1].split() if a.startswith("--")]
    hints = [f"{a}: {hint}" for a in unknown if (hint := did_you_mean(a, known))]
    if not hints:
        return exc
    return UsageError(f"{message} ({'; '.join(hints)})", exc.option, f"{exc.prog} {argv[0]}")


def fail(
    message: str, option: str | None = None, *, json_mode: bool = False, code: int = 2, hint: str = ""
) -> int:
    """Report a failure (see the module docstring) and return the exit status ``code``."""
    if json_mode:
        json.dump({"error": message, "option": option}, sys.stdout)
        sys.stdout.write("\n")
    else:
        print(f"{PROG}: error: {message}", file=sys.stderr)
        if hint:
            print(hint, file=sys.stderr)
    return code


def usage_failure(exc: UsageError, argv: Sequence[str]) -> int:
    """Report an argparse refusal in one line plus a hint."""
    json_mode = "--json" in argv
    if json_mode:
        return fail(str(exc), exc.option, json_mode=True)
    print(f"{exc.prog}: error: {exc}", file=sys.stderr)
    print(f"see: {exc.prog} --help", file=sys.stderr)
    return 2


def _parameter_option(parameter: str, argv: Sequence[str]) -> str | None:
    """The option the user typed for ``parameter`` (``eta_M`` -> ``--eta-M``), ``--set`` for a value given
    as ``--set NAME=VALUE``, ``--file`` for a file value."""
    given = {a.split("=", 1)[0] for a in argv if a.startswith("--")}
    if parameter.startswith("--"):  # the error names the option itself (--vary, --range, --units)
        return parameter
    for option in ("--" + parameter.replace("_", "-"), "--" + parameter):
        if option in given:
            return option
    settings = [b for a, b in zip(argv, argv[1:]) if a == "--set"] + [
        a.split("=", 1)[1] for a in argv if a.startswith("--set=")
    ]
    if any(s.split("=", 1)[0].strip() == parameter for s in settings):  # a value the user set
        return "--set"
    return "--file" if "--file" in given else None


def _path_option(filename: str | bytes | os.PathLike[str], args: argparse.Namespace) -> str | None:
    for option, path, *_ in getattr(args, "output_paths", ()):
        if os.fspath(path) == os.fspath(filename):
            return option
    file = getattr(args, "file", None)
    return "--file" if file is not None and os.fspath(file) == os.fspath(filename) else None


def handle_errors(func: Callable[..., int | None], argv: Sequence[str] = ()) -> Callable[..., int]:
    """Decorate a command ``func(args)`` so that expected failures are reported as above."""

    @functools.wraps(func)
    def wrapper(args: Any, *rest: Any, **kwargs: Any) -> int:
        json_mode = bool(getattr(args, "json", False))
        try:
            return func(args, *rest, **kwargs) or 0
        except ParameterError as exc:
            return fail(str(exc), _parameter_option(exc.parameter, argv), json_mode=json_mode)
        except MovingBogieError as exc:
            return fail(str(exc), getattr(exc, "option", None), json_mode=json_mode)
        except tomllib.TOMLDecodeError as exc:
            return fail(f"not a valid TOML file: {exc}", "--file", json_mode=json_mode)
        except BrokenPipeError:
            # The reader went away (e.g. `| head`): stop quietly, without a second error at exit.
            os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
            return 1
        except OSError as exc:
            if exc.filename is None:
                raise
            option = _path_option(exc.filename, args)
            return fail(f"{exc.strerror}: {exc.filename}", option, json_mode=json_mode)
        except JobInterrupted as exc:  # a long job that kept its finished parts
            return fail(exc.advice(), json_mode=json_mode, code=130)
        except KeyboardInterrupt:
            return fail("interrupted", json_mode=json_mode, code=130)

    return wrapper
