"""benchmarks/import_closure.py: the files a benchmark record depends on.

The reference is a run: the modules of the package that a real command loads in a fresh interpreter must
all lie in the closure read from the source (else an edit to one of them would leave a record current that
it made wrong). A small package written here checks what the closure leaves out.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

from scripts import load_script

ROOT = Path(__file__).resolve().parent.parent

#: Runs a command in this interpreter and prints the package's modules loaded by the work alone (those the
#: command line's parser loads for ``--help``, the subcommand table, are taken away).
PROBE = """
import json, sys
from moving_bogie.cli import build_parser, main
build_parser()
base = set(sys.modules)
main(sys.argv[1:])
print(json.dumps(sorted(m for m in set(sys.modules) - base if m.startswith("moving_bogie"))))
"""


def _closure_module():
    return load_script("benchmarks/import_closure.py")


def test_a_command_loads_only_modules_of_its_closure(tmp_path):
    closure = _closure_module()
    argv = ["params", "--case", "1"]
    out = subprocess.run(
        [sys.executable, "-c", PROBE, *argv], capture_output=True, text=True, check=True, cwd=tmp_path
    ).stdout
    work = json.loads(out.strip().splitlines()[-1])
    assert len(work) > 20  # the command's own modules (lazy imports inside ``run``) were loaded
    files = set(closure.closure(("moving_bogie.__main__", "moving_bogie.cli.params_cmd")))
    for name in work:
        path = closure.module_file(name)
        assert path is not None and str(path.relative_to(ROOT)) in files, name


def test_the_closure_follows_imports_inside_functions_and_leaves_the_rest(tmp_path):
    closure = _closure_module()
    pkg = tmp_path / "moving_bogie"
    (pkg / "sub").mkdir(parents=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "sub" / "__init__.py").write_text("")
    (pkg / "sub" / "table.csv").write_text("a,b\n")
    (pkg / "entry.py").write_text("def run():\n    from .sub import lazy\n")
    (pkg / "sub" / "lazy.py").write_text("from moving_bogie import helper\n")
    (pkg / "helper.py").write_text("")
    (pkg / "other.py").write_text("import moving_bogie.entry\n")
    got = closure.closure(("moving_bogie.entry",), tmp_path)
    expected = ["__init__.py", "entry.py", "helper.py", "sub/__init__.py", "sub/lazy.py", "sub/table.csv"]
    assert got == [f"{tmp_path.name}/moving_bogie/{name}" for name in expected]


def test_a_record_of_entries_hashes_each_file_of_its_closure():
    records = load_script("benchmarks/records.py")
    closure = _closure_module()
    files = closure.closure(("moving_bogie.soil.critical",))
    assert "src/moving_bogie/soil/strip.py" in files
    assert "src/moving_bogie/cli/sweep_cmd.py" not in files
    made = {f: records.source_hash(f) for f in files[:3]}
    assert records.stale_sources({"sources": made}) == []
    changed = dict(made, **{files[0]: "0" * 16})
    assert records.stale_sources({"sources": changed}) == [files[0]]
