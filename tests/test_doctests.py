"""The examples in the docstrings of the foundation modules run and give what they show (each module listed
has at least one: a module whose examples were removed fails, it is not passed for running none)."""

from __future__ import annotations

import doctest
import importlib

import pytest

MODULES = [
    "moving_bogie.model.exact",
    "moving_bogie.errors",
    "moving_bogie.model.params",
    "moving_bogie.model.physical",
    "moving_bogie.model.cases",
    "moving_bogie.model.files",
    "moving_bogie.kernels.polynomial",
]


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name):
    result = doctest.testmod(importlib.import_module(name), optionflags=doctest.ELLIPSIS)
    assert result.attempted > 0, f"{name}: no docstring example ran"
    assert result.failed == 0
