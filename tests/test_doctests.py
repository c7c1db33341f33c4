"""The examples in the docstrings of the foundation modules run and give what they show."""

from __future__ import annotations

import doctest
import importlib

import pytest

MODULES = [
    "moving_bogie._exact",
    "moving_bogie.errors",
    "moving_bogie.params",
    "moving_bogie.physical",
    "moving_bogie.cases",
    "moving_bogie.paramfile",
]


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name):
    result = doctest.testmod(importlib.import_module(name), optionflags=doctest.ELLIPSIS)
    assert result.failed == 0
