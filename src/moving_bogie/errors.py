"""Exceptions and warnings raised by moving-bogie.

Every error the package raises on purpose is a :class:`MovingBogieError`, so the command line can
report it as one line without a traceback.
"""

from __future__ import annotations

import re

__all__ = ["MovingBogieError", "MovingBogieWarning", "ParameterError"]


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

    def __reduce__(self):
        # Errors raised in worker processes must survive pickling with their parameter name.
        return (type(self), (self.parameter, str(self)))


class MovingBogieWarning(UserWarning):
    """Category of every warning issued by moving-bogie (turned into errors by the test suite)."""
