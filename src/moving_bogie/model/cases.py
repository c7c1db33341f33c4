"""The paper's tested cases: Table 1 (input data) and Table 2 (induced frequencies as printed).

Both tables ship as CSV files in :mod:`moving_bogie.data`; numbers are read exactly from their text.
"""

from __future__ import annotations

import csv
import functools
import operator
from importlib import resources
from typing import SupportsIndex

from moving_bogie.errors import ParameterError
from moving_bogie.model.params import DimensionlessParams

__all__ = ["TABLE1_CASES", "table1_case", "table2_printed"]

_TABLE1 = "table1_cases.csv"
_TABLE2 = "table2_induced_frequencies.csv"


def _rows(filename: str) -> list[dict[str, str]]:
    """Rows of a packaged CSV file; lines starting with '#' are comments."""
    text = resources.files("moving_bogie.data").joinpath(filename).read_text(encoding="utf-8")
    lines = [line for line in text.splitlines() if line.strip() and not line.startswith("#")]
    return list(csv.DictReader(lines))


@functools.cache
def _table1() -> dict[int, dict[str, str]]:
    return {int(row.pop("case")): row for row in _rows(_TABLE1)}


#: Case numbers of Table 1, in order.
TABLE1_CASES: tuple[int, ...] = tuple(_table1())


def _check_case(n: object) -> int:
    try:
        case = operator.index(n) if isinstance(n, SupportsIndex) and not isinstance(n, bool) else None
    except TypeError:
        case = None
    if case is None or case not in _table1():
        valid = ", ".join(str(c) for c in TABLE1_CASES)
        raise ParameterError("case", f"unknown case {n!r}; valid cases of Table 1: {valid}")
    return case


def table1_case(n: int) -> DimensionlessParams:
    """Dimensionless parameters of case `n` of Table 1 (Euler-Bernoulli beam, no shear layer).

    The table gives ``cf1`` and ``cf2``; ``mu_v`` and ``J_b`` follow from Eq. (63). Values are
    converted exactly from the CSV text (``"0.05"`` is 1/20).

    Raises
    ------
    ParameterError
        Naming ``case`` and listing the valid case numbers.

    Examples
    --------
    >>> table1_case(7).to_dict()["alpha"]
    '0.4'
    """
    return DimensionlessParams.from_coefficients(**_table1()[_check_case(n)])


def table2_printed(n: int) -> list[tuple[str, str]]:
    """Induced frequencies of case `n` as printed in Table 2: ``(re, im)`` decimal strings, 6 decimals.

    One root of each pair ``q, -conj(q)`` is listed, the one with positive real part, in the paper's
    order. Rows withheld from the reference data (Cases 7-13) give ``[]``.

    Raises
    ------
    ParameterError
        Naming ``case`` for a case that is not in Table 1.
    """
    n = _check_case(n)
    rows = [row for row in _rows(_TABLE2) if int(row["case"]) == n]
    rows.sort(key=lambda row: int(row["root"]))
    return [(row["re"], row["im"]) for row in rows]
