"""Every code block of the README runs: Python blocks as scripts, shell blocks command by command.

Which blocks run
----------------
- ```python blocks: each is run as a script of its own (a fresh interpreter).
- Shell blocks (fence without a language, or ``console``, ``shell``, ``sh``, ``bash``): in ``console`` blocks
  the lines that start with ``$ `` are the commands; in the others every line whose first word is a command
  (``moving-bogie``, ``python``, ``pytest``, ``pip``, ``jupytext``, ``.ci/run``) is one. A shell block with no
  command (a diagram) is not code. Other languages (``toml``, ...) are data, not run.
- A block that must not run here (installs, the test suite itself, jobs of minutes) carries the HTML comment
  ``<!-- not run: REASON -->`` on the line right above its opening fence (invisible on the rendered page);
  it is reported as skipped with that reason.

Everything runs in a temporary folder (output files land there) that links ``examples/``, with the
package under test first on PYTHONPATH; ``moving-bogie`` and ``python`` are this interpreter.
"""

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

import moving_bogie

ROOT = Path(__file__).resolve().parent.parent
README = ROOT / "README.md"
SHELL_LANGUAGES = {"", "console", "shell", "sh", "bash"}
COMMANDS = ("moving-bogie", "python", "pytest", "pip", "jupytext", ".ci/run")
NOT_RUN = re.compile(r"^<!--\s*not run:\s*(.+?)\s*-->$")
FENCE = re.compile(r"^```(\S*)\s*$")
TIMEOUT = 300  # seconds per block


def readme_blocks(text: str):
    """(line number, language, body lines, reason not to run or None) of every fenced block."""
    lines = text.splitlines()
    out, k = [], 0
    while k < len(lines):
        m = FENCE.match(lines[k])
        if not m:
            k += 1
            continue
        start, lang = k, m.group(1).lower()
        end = k + 1
        while end < len(lines) and not lines[end].startswith("```"):
            end += 1
        above = lines[start - 1].strip() if start else ""
        marker = NOT_RUN.match(above)
        out.append((start + 1, lang, lines[start + 1 : end], marker.group(1) if marker else None))
        k = end + 1
    return out


def shell_commands(lang: str, body) -> list[str]:
    if lang == "console":
        return [line[2:] for line in body if line.startswith("$ ")]
    return [line for line in body if line.split()[:1] and line.split()[0] in COMMANDS]


def runnable_blocks():
    blocks = []
    for line, lang, body, reason in readme_blocks(README.read_text()):
        if lang == "python":
            blocks.append(pytest.param("python", "\n".join(body), reason, id=f"README.md:{line}"))
        elif lang in SHELL_LANGUAGES and shell_commands(lang, body):
            script = "\n".join(shell_commands(lang, body))
            blocks.append(pytest.param("shell", script, reason, id=f"README.md:{line}"))
    return blocks


def _environment():
    env = dict(os.environ, MPLBACKEND="Agg")
    src = str(Path(moving_bogie.__file__).resolve().parent.parent)
    env["PYTHONPATH"] = os.pathsep.join(p for p in (src, str(ROOT), env.get("PYTHONPATH")) if p)
    return env


def _as_this_interpreter(command: str) -> str:
    python = f'"{sys.executable}"'
    command = re.sub(r"(^|&&\s*|\|\s*|;\s*)moving-bogie\b", rf"\g<1>{python} -m moving_bogie", command)
    return re.sub(r"(^|&&\s*|\|\s*|;\s*)python\b", rf"\g<1>{python}", command)


@pytest.mark.slow
@pytest.mark.parametrize(("kind", "code", "reason"), runnable_blocks())
def test_readme_block_runs(tmp_path, kind, code, reason):
    if reason:
        pytest.skip(f"not run: {reason}")
    (tmp_path / "examples").symlink_to(ROOT / "examples")
    env = _environment()
    if kind == "python":
        script = tmp_path / "block.py"
        script.write_text(code + "\n")
        argv = [sys.executable, str(script)]
        proc = subprocess.run(argv, cwd=tmp_path, env=env, capture_output=True, text=True, timeout=TIMEOUT)
        assert proc.returncode == 0, proc.stderr[-3000:]
        return
    for command in code.splitlines():
        proc = subprocess.run(
            ["bash", "-c", _as_this_interpreter(command)],
            cwd=tmp_path,
            env=env,
            capture_output=True,
            text=True,
            timeout=TIMEOUT,
        )
        assert proc.returncode == 0, f"{command}\n{proc.stderr[-3000:]}"


def test_blocks_are_found_and_markers_sit_on_blocks():
    text = README.read_text()
    blocks = readme_blocks(text)
    assert any(lang == "python" for _, lang, _, _ in blocks)
    assert len(runnable_blocks()) >= 5
    lines = text.splitlines()
    for k, line in enumerate(lines):
        if NOT_RUN.match(line.strip()):
            where = f"README.md:{k + 1}"
            assert k + 1 < len(lines) and FENCE.match(lines[k + 1]), f"{where}: marker not above a fence"


def test_shell_command_detection():
    body = ["moving-bogie table2", "derivations/  -->  generated/", " rigid bar"]
    body.append("python -m derivations --check")
    assert shell_commands("", body) == ["moving-bogie table2", "python -m derivations --check"]
    assert shell_commands("console", ["$ moving-bogie params --case 1", "Dimensionless parameters"]) == [
        "moving-bogie params --case 1"
    ]


def test_ci_runs_the_readme_test_command():
    """``.ci/run`` repeats the README's whole-suite setup in its comment and runs its pytest command."""
    setups = [
        line
        for _, lang, body, _ in readme_blocks(README.read_text())
        if lang in SHELL_LANGUAGES
        for line in body
        if "pip install -e '.[dev]'" in line and "&& pytest" in line
    ]
    assert len(setups) == 1, setups
    (setup,) = setups
    command = setup.rsplit("&& ", 1)[1]
    assert command.split()[:2] == ["pytest", "-q"], command
    ci = (ROOT / ".ci" / "run").read_text()
    assert f"#   {setup}\n" in ci, "the comment of .ci/run quotes another setup than the README's"
    assert f"\n{command} || status=$?\n" in ci, f".ci/run does not run the README's `{command}`"
