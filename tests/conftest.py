"""Shared fixtures: every test starts with the same mpmath precision, whatever the previous one did."""

from __future__ import annotations

import mpmath
import pytest


@pytest.fixture(autouse=True)
def _restore_mp_dps():
    """Save ``mpmath.mp.dps`` before each test and restore it after, so no test leaks a changed global."""
    dps = mpmath.mp.dps
    yield
    mpmath.mp.dps = dps
