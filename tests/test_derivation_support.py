"""A missing SymPy fails the derivation tests with the install command; only the documented variable skips."""

from __future__ import annotations

import sys

import pytest
from derivation_support import INSTALL, SKIP_VARIABLE, require_sympy


def test_missing_sympy_fails_with_the_install_command(monkeypatch):
    monkeypatch.delenv(SKIP_VARIABLE, raising=False)
    monkeypatch.setitem(sys.modules, "sympy", None)  # import sympy now raises ImportError
    with pytest.raises(pytest.fail.Exception) as info:
        require_sympy()
    assert INSTALL in str(info.value) and SKIP_VARIABLE in str(info.value)


def test_the_variable_skips_with_its_name(monkeypatch):
    monkeypatch.setenv(SKIP_VARIABLE, "1")
    with pytest.raises(pytest.skip.Exception) as info:
        require_sympy()
    assert SKIP_VARIABLE in str(info.value)


def test_sympy_present_is_returned(monkeypatch):
    monkeypatch.delenv(SKIP_VARIABLE, raising=False)
    assert require_sympy().__name__ == "sympy"
