"""The committed ``generated/`` and ``docs/proofs.md`` are what ``derivations/`` produces now.

docs/architecture.md, examples 1-3: generated files carry a header with the generator command, "do not
edit" and the inputs hash; a regeneration into a temporary folder is byte-identical to the committed files
and to a second regeneration; ``python -m derivations --check`` fails with the diff and the command that
updates the files. The runtime never imports SymPy, whichever of its modules is imported.

Each derivation run costs many seconds of SymPy, so a module fixture runs them once for the tests that
compare them, all three in parallel: a full regeneration, a partial one (``--only``), and a partial
``--check`` of a tampered copy of the committed files under another hash seed, which is the second
derivation the determinism test compares with the first. Those tests are slow.

The full regeneration is the longest of the three, and a function of its inputs alone: the sources of
``derivations/`` and the versions of Python, SymPy and mpmath. Its files are kept in pytest's cache folder
(``.pytest_cache``, ``--cache-clear`` empties it) under a sha256 of those inputs, so a later run with the
same inputs compares the committed files with them without deriving again. A hand edit of a committed file
is still a difference from the kept regeneration; an edit of a derivation source, or another SymPy, is
another key, hence a new regeneration. The partial run is kept the same way, under that key and the names
it derives. The ``--check`` run always runs: the determinism test compares its derivation, under another
hash seed, with the kept one.
"""

from __future__ import annotations

import ast
import difflib
import hashlib
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from derivation_support import require_sympy

REPO = Path(__file__).resolve().parents[1]
UPDATE_COMMAND = "python -m derivations"
TIMEOUT = 900  # a guard against a hung run; a shared machine can stretch a regeneration to minutes

require_sympy()


def _derivations(*args, env=None) -> subprocess.Popen:
    """Start ``python -m derivations *args`` from the repository root (derivations/ is not installed)."""
    return subprocess.Popen(
        [sys.executable, "-m", "derivations", *args],
        cwd=REPO,
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )


def _finish(proc: subprocess.Popen) -> subprocess.CompletedProcess:
    try:
        out, err = proc.communicate(timeout=TIMEOUT)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.communicate()
        raise
    return subprocess.CompletedProcess(proc.args, proc.returncode, out, err)


def _committed_files() -> dict[str, bytes]:
    """Every committed generated file, relative path -> bytes (the files ``--root`` writes)."""
    files = {
        str(p.relative_to(REPO)): p.read_bytes()
        for p in sorted((REPO / "src/moving_bogie/generated").glob("*.py"))
    }
    files["docs/proofs.md"] = (REPO / "docs" / "proofs.md").read_bytes()
    return files


def _written_files(root: Path) -> dict[str, bytes]:
    return {str(p.relative_to(root)): p.read_bytes() for p in sorted(root.rglob("*")) if p.is_file()}


#: What the partial run of the fixture below derives (``--only``): a beam and a vehicle of the catalogue
#: (the one-layer Euler-Bernoulli beam and the two masses: the cheapest pair, a third of a full run).
ONLY = ("eb", "masses")
#: The two files the ``--check`` of the fixture finds tampered with, and how (old text, new text).
TAMPERED = {
    "src/moving_bogie/generated/foundation_eb.py": ("4 - 4*q**2", "4 - 5*q**2"),
    "src/moving_bogie/generated/vehicle_masses.py": ("x0*K0**2", "x0*K0**3"),
}
#: The hash seed of the ``--check`` run: another than the one the command pins (0), see the fixture.
OTHER_SEED = "12345"


def _inputs_key() -> str:
    """sha256 of everything a full regeneration depends on: each derivation source (path and bytes) and the
    versions of Python, SymPy and mpmath (the generated headers name the SymPy version)."""
    import mpmath
    import sympy

    h = hashlib.sha256()
    h.update(f"{sys.version_info[:3]} sympy {sympy.__version__} mpmath {mpmath.__version__}\n".encode())
    for path in sorted((REPO / "derivations").rglob("*.py")):
        h.update(str(path.relative_to(REPO)).encode() + b"\0" + path.read_bytes() + b"\0")
    return h.hexdigest()


#: The file that marks a kept regeneration as complete (written last, inside its folder).
COMPLETE = "complete"
#: The folders of pytest's cache that keep the full and the partial (:data:`ONLY`) regeneration.
KEPT = ("derivations-regeneration", "derivations-only")


def _kept_keys() -> tuple[str, str]:
    """The keys of the full regeneration (:func:`_inputs_key`) and of the partial one (that key and the
    names it derives)."""
    key = _inputs_key()
    return key, hashlib.sha256(f"{key} --only {' '.join(ONLY)}".encode()).hexdigest()


def _kept_regeneration(cache, key: str, name: str) -> Path | None:
    """The folder of a complete regeneration kept under ``key`` in the cache folder ``name`` of pytest's
    cache, or None (also when the cache is off: ``-p no:cacheprovider``)."""
    if cache is None:
        return None
    folder = cache.mkdir(name) / key
    return folder if (folder / COMPLETE).is_file() else None


def _keep_regeneration(cache, key: str, root: Path, name: str) -> None:
    """Keep the regeneration written into ``root`` under ``key`` in the cache folder ``name``; the ones of
    other inputs go."""
    if cache is None:
        return
    base = cache.mkdir(name)
    for old in base.iterdir():
        shutil.rmtree(old, ignore_errors=True)
    partial = base / f"{key}.{os.getpid()}"
    shutil.copytree(root, partial)
    (partial / COMPLETE).write_text(key + "\n")
    try:
        partial.rename(base / key)
    except OSError:  # another session kept the same regeneration first
        shutil.rmtree(partial, ignore_errors=True)


@pytest.fixture(scope="module")
def regenerations(request, tmp_path_factory) -> tuple[dict[str, bytes], dict[str, bytes], dict]:
    """Three derivations in parallel: (first, only, check).

    The first regeneration (into an empty folder, or the one kept in pytest's cache for the same inputs,
    :func:`_inputs_key`); a partial one deriving only :data:`ONLY` (``--only``, what the scratch tests of
    a new beam, track or vehicle use; kept likewise, :func:`_kept_keys`); and ``--check --only`` on a copy of
    the committed files with the two :data:`TAMPERED` edits (both in modules that :data:`ONLY` derives), under
    another PYTHONHASHSEED (the command must pin the seed itself: SymPy's CSE and ordering can depend on
    string hashing). The check's diff shows what it derived, so it serves both the tampered-file test and
    the determinism test. ``check`` holds the completed process and the tampered texts (path -> text).
    """
    base = tmp_path_factory.mktemp("regenerated")
    roots = [base / "first", base / "only"]
    only = [arg for name in ONLY for arg in ("--only", name)]
    copy = base / "tampered"
    for rel, data in _committed_files().items():
        (copy / rel).parent.mkdir(parents=True, exist_ok=True)
        (copy / rel).write_bytes(data)
    tampered = {}
    for rel, (old, new) in TAMPERED.items():
        original = (copy / rel).read_text()
        tampered[rel] = original.replace(old, new, 1)
        assert tampered[rel] != original, f"{rel}: the text to tamper with is gone: pick another one"
        (copy / rel).write_text(tampered[rel])
    env_other_seed = dict(os.environ, PYTHONHASHSEED=OTHER_SEED)
    keys, cache = _kept_keys(), getattr(request.config, "cache", None)
    kept = [_kept_regeneration(cache, key, name) for key, name in zip(keys, KEPT)]
    procs = [
        None if kept[0] else _derivations("--root", str(roots[0])),
        None if kept[1] else _derivations("--root", str(roots[1]), *only),
        _derivations("--check", "--root", str(copy), *only, env=env_other_seed),
    ]
    results = [proc and _finish(proc) for proc in procs]
    for result in results[:2]:
        assert result is None or result.returncode == 0, result.stdout + result.stderr
    for i, (key, name) in enumerate(zip(keys, KEPT)):
        if kept[i] is None:
            _keep_regeneration(cache, key, roots[i], name)
        else:
            roots[i] = kept[i]
    first, partial = (_written_files(r) for r in roots)
    first.pop(COMPLETE, None)
    partial.pop(COMPLETE, None)
    written = {rel: (copy / rel).read_text() for rel in TAMPERED}
    return first, partial, {"result": results[2], "tampered": tampered, "after": written}


@pytest.mark.slow
def test_committed_files_are_current(regenerations):
    """What ``python -m derivations --check`` checks: a regeneration equals the committed files, file by file.

    The set of files must match too, so a generated module left behind by a removed model (which
    ``--check`` cannot see) is caught here.
    """
    first, _, _ = regenerations
    committed = _committed_files()
    assert sorted(first) == sorted(committed), (
        f"generator writes {sorted(first)}, repository has {sorted(committed)}; "
        f"remove stale files or run: {UPDATE_COMMAND}"
    )
    for rel, text in first.items():
        assert text == committed[rel], (
            f"{rel} is stale (differs from a regeneration). Update with: {UPDATE_COMMAND}"
        )


@pytest.mark.slow
def test_regeneration_is_deterministic(regenerations):
    """A derivation under another hash seed (the fixture's ``--check``) equals the first, byte for byte.

    ``--check`` compares every file it derives (those of :data:`ONLY` and the catalogue files) with the
    tampered copy of the committed files and prints the diff of each one that differs. Only the two
    tampered files may differ, and each by exactly the diff from the tampered text back to the first run's
    text (computed here with difflib, as the command prints it,
    ``n=1``): a unified diff of the tampered text determines the other side, so the check derived the first
    run's text there too. Any other byte derived differently would add a file or a line to the diff.
    """
    first, _, check = regenerations
    out = check["result"].stdout
    assert f"{len(TAMPERED)} generated file(s) are stale" in out, out
    for rel, tampered in check["tampered"].items():
        expected = difflib.unified_diff(
            tampered.splitlines(True), first[rel].decode().splitlines(True), f"a/{rel}", f"b/{rel}", n=1
        )
        assert "".join(expected) in out, f"{rel}: the second derivation differs from the first:\n{out}"
    printed = [line[len("--- a/") :] for line in out.splitlines() if line.startswith("--- a/")]
    assert sorted(printed) == sorted(TAMPERED), out


@pytest.mark.slow
def test_only_writes_the_named_modules_and_the_catalogue_as_a_full_run_does(regenerations):
    """``--only eb --only masses``: every model on the beam, the vehicle's module and the catalogue-wide
    files, each byte-identical to the full regeneration's; nothing else (the proofs neither).

    The expected files are read from the committed catalogue (``generated.MODULES``), not from the
    generator that writes them.
    """
    from moving_bogie import generated

    first, partial, _ = regenerations
    folder = "src/moving_bogie/generated"
    kernels = {module for (beam, _), module in generated.MODULES.items() if beam in ONLY}
    kernels |= {f"vehicle_{name}" for name in generated.VEHICLES if name in ONLY}
    expected = {f"{folder}/{module}.py" for module in (*kernels, "__init__", "asymptotics", "parameters")}
    assert len(kernels) == 4 and set(partial) == expected, sorted(partial)
    for rel, text in partial.items():
        assert text == first[rel], f"{rel}: --only wrote other text than the full run"


def test_only_refuses_an_unknown_name_naming_the_option_and_the_known_ones(tmp_path):
    result = _finish(_derivations("--root", str(tmp_path), "--only", "ballast"))
    assert result.returncode == 2 and "--only" in result.stderr and "ballast" in result.stderr, result.stderr
    assert "eb, tr" in result.stderr and "bogie" in result.stderr and "Traceback" not in result.stderr
    assert not any(tmp_path.iterdir()), "nothing is written for a refused name"


@pytest.mark.slow
def test_check_reports_a_tampered_file_with_a_diff_and_the_command(regenerations):
    _, _, check = regenerations
    result = check["result"]
    assert result.returncode == 1, result.stdout + result.stderr
    out = result.stdout
    assert (
        "--- a/src/moving_bogie/generated/foundation_eb.py" in out
        and "+++ b/src/moving_bogie/generated/foundation_eb.py" in out
    ), out
    assert "-        4 - 5*q**2" in out and "+        4 - 4*q**2" in out, out
    assert "--- a/src/moving_bogie/generated/vehicle_masses.py" in out, out
    assert "-    return pi**2 + x0*K0**3" in out and "+    return pi**2 + x0*K0**2" in out, out
    assert "2 generated file(s) are stale" in out, out
    assert f"Update them with: {UPDATE_COMMAND}" in out, out
    assert check["after"] == check["tampered"], "--check must not write"


def test_generated_headers_name_the_command_the_sympy_version_and_the_model_hash():
    import re

    import sympy

    hashes = {}
    for path in sorted((REPO / "src/moving_bogie/generated").glob("*.py")):
        head = path.read_text().split('"""', 2)[1]
        assert f"Generated by `{UPDATE_COMMAND}` (SymPy {sympy.__version__}) - do not edit." in head, (
            path.name
        )
        match = re.search(r"Model hash: ([0-9a-f]{64})\n", head)
        assert match, path.name
        hashes[path.name] = match.group(1)
    # The hash is of what defines each file's model, not of the derivation sources as a whole: two models
    # never share one, and a file unrelated to the models (the proofs) carries none.
    assert len(set(hashes.values())) == len(hashes)
    assert "hash" not in (REPO / "docs" / "proofs.md").read_text().lower()


def test_generated_code_has_no_float_literals():
    """Full-precision constants (example 5): a float literal would round mpmath evaluations to 53 bits."""
    for path in sorted((REPO / "src/moving_bogie/generated").glob("*.py")):
        tree = ast.parse(path.read_text())
        floats = [
            node.lineno
            for node in ast.walk(tree)
            if isinstance(node, ast.Constant) and isinstance(node.value, float)
        ]
        assert not floats, f"{path.name}: float literals on lines {floats}"
        imports = [node.lineno for node in ast.walk(tree) if isinstance(node, ast.Import | ast.ImportFrom)]
        assert not imports, f"{path.name}: generated kernels import nothing (lines {imports})"


def test_runtime_never_imports_sympy(tmp_path):
    """``import moving_bogie`` and every runtime and generated module, in a fresh interpreter elsewhere.

    ``moving_bogie.generated``'s modules are walked explicitly as well, so a missing kernel module is
    named. ``__main__`` modules run the
    CLI on import and are skipped (``moving_bogie.cli`` itself is imported).
    """
    code = """
import importlib, pkgutil, sys
import moving_bogie
assert 'sympy' not in sys.modules, 'import moving_bogie imported sympy'
import moving_bogie.generated as generated
names = [m.name for m in pkgutil.walk_packages(moving_bogie.__path__, 'moving_bogie.')]
names += [m.name for m in pkgutil.walk_packages(generated.__path__, 'moving_bogie.generated.')]
names = [n for n in names if not n.endswith('__main__')]
expected = {f'moving_bogie.generated.foundation_{n}' for n in generated.FOUNDATIONS}
expected |= {f'moving_bogie.generated.vehicle_{n}' for n in generated.VEHICLES}
assert expected <= set(names), sorted(expected - set(names))
for name in names:
    importlib.import_module(name)
    assert 'sympy' not in sys.modules, f'importing {name} imported sympy'
assert 'derivations' not in sys.modules
print(len(names))
"""
    result = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, cwd=tmp_path, timeout=120
    )
    assert result.returncode == 0, result.stdout + result.stderr
    assert int(result.stdout.strip()) >= 20
