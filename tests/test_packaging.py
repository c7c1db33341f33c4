"""The installed package: import boundaries and packaged data."""

from __future__ import annotations

import subprocess
import sys


def _python(code: str, cwd) -> subprocess.CompletedProcess[str]:
    """Run `code` in a fresh interpreter outside the source tree, so only the installed package is seen."""
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=cwd, timeout=60)


def test_runtime_never_imports_sympy(tmp_path):
    code = "import moving_bogie, moving_bogie.cli, sys; assert 'sympy' not in sys.modules, 'sympy imported'"
    result = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, cwd=tmp_path, timeout=60
    )
    assert result.returncode == 0, result.stderr


def test_generated_package_and_data_are_importable_outside_the_repo(tmp_path):
    code = (
        "import moving_bogie.generated, moving_bogie.data, importlib.resources as r;"
        "names = {p.name for p in r.files('moving_bogie.data').iterdir()};"
        "assert {'table1_cases.csv', 'table2_induced_frequencies.csv'} <= names, names"
    )
    result = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, cwd=tmp_path, timeout=60
    )
    assert result.returncode == 0, result.stderr


def test_version_is_set():
    import moving_bogie

    assert moving_bogie.__version__ != "0+unknown"
