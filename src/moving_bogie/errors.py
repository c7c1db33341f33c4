"""Exceptions and warnings raised by moving-bogie.

Every error the package raises on purpose is a :class:`MovingBogieError`, so the command line can
report it as one line without a traceback.
"""

from __future__ import annotations

import difflib
import re
from collections.abc import Iterable
from pathlib import Path

__all__ = [
    "JobInterrupted",
    "MovingBogieError",
    "MovingBogieWarning",
    "ParameterError",
    "did_you_mean",
    "suggestion",
]


class MovingBogieError(Exception):
    """Base class of all errors raised on purpose by moving-bogie."""


class ParameterError(MovingBogieError, ValueError):
    """An input parameter is missing, of the wrong type or out of its admissible range.

    Parameters
    ----------
    parameter : str
        Name of the offending parameter, as the user spells it (``"eta_M"``, ``"M"``, ``"case"``).
    message : str
        What is wrong. If it does not already mention the parameter's name as a word, the name is
        prefixed, so that every message names its parameter.

    Examples
    --------
    >>> str(ParameterError("eta_M", "must be a positive finite number (got -3)"))
    'eta_M must be a positive finite number (got -3)'
    >>> ParameterError("case", "unknown case 14; valid cases: 1-13").parameter
    'case'
    """

    def __init__(self, parameter: str, message: str) -> None:
        self.parameter = parameter
        if not re.search(rf"(?<!\w){re.escape(parameter)}(?!\w)", message):
            message = f"{parameter} {message}"
        super().__init__(message)

    def __reduce__(self) -> tuple[type[ParameterError], tuple[str, str]]:
        # Errors raised in worker processes must survive pickling with their parameter name.
        return (type(self), (self.parameter, str(self)))


class MovingBogieWarning(UserWarning):
    """Category of every warning issued by moving-bogie (turned into errors by the test suite)."""


def did_you_mean(name: str, known: Iterable[str]) -> str:
    """ "did you mean 'X'?" for the valid name closest to ``name`` (and any as close, within 0.05) by
    :class:`difflib.SequenceMatcher` ratio, as :func:`difflib.get_close_matches` scores them (at least 0.6),
    or "" when none is close.

    Examples
    --------
    >>> did_you_mean("bogy", ["mass", "masses", "bogie", "car"])
    "did you mean 'bogie'?"
    """
    scores = {str(k): difflib.SequenceMatcher(None, str(name), str(k)).ratio() for k in known}
    best = max(scores.values(), default=0.0)
    close = [k for k, score in scores.items() if score >= max(0.6, best - 0.05)]  # the best, and ties
    return ("did you mean " + " or ".join(repr(c) for c in close) + "?") if close else ""


def suggestion(name: str, known: Iterable[str], *, listing: str = "expected one of") -> str:
    """What to say after "unknown NAME": :func:`did_you_mean`, or, when no valid name is close, every valid
    name after ``listing``.

    Examples
    --------
    >>> suggestion("alpah", ["alpha", "eta_f", "eta_M"])
    "did you mean 'alpha'?"
    >>> suggestion("zzz", ["beam", "track"])
    'expected one of beam, track'
    """
    known = [str(k) for k in known]
    return did_you_mean(name, known) or f"{listing} {', '.join(known)}"


class JobInterrupted(KeyboardInterrupt):
    """Ctrl-C during a long job of parts (:func:`~moving_bogie.checkpoint.run_parts`): ``done`` of
    ``total`` parts (named ``what``) are kept in ``folder`` (None: no checkpoint), and the same job
    resumed computes the others."""

    def __init__(self, done: int, total: int, folder: Path | None, what: str = "parts") -> None:
        super().__init__(f"interrupted after {done} of {total} {what}")
        self.done, self.total, self.folder, self.what = done, total, folder, what

    def advice(self) -> str:
        """One line: what is kept and how to go on."""
        if self.folder is None:
            return f"{self}: nothing kept"
        return (
            f"{self}, kept in {self.folder}: run the same command with --resume to compute only the "
            f"{self.total - self.done} others"
        )
