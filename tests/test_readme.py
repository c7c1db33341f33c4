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

What a ``console`` block shows after a command is what the command prints on stdout, line for line; a line
``...`` stands for lines left out (the README says so), nothing else may differ. The README's other claims
are checked below: which commands take ``--json`` and ``--plot``, that every command has ``--help`` and
refuses a bad option in one error line with exit status 2, that the model options offer every beam, track
and vehicle, and that every reference to a section of the README names one that exists.
"""

import json
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

import moving_bogie
from moving_bogie.cli import build_parser, main

ROOT = Path(__file__).resolve().parent.parent
README = ROOT / "README.md"
SHELL_LANGUAGES = {"", "console", "shell", "sh", "bash"}
COMMANDS = ("moving-bogie", "python", "pytest", "pip", "jupytext", ".ci/run")
NOT_RUN = re.compile(r"^<!--\s*not run:\s*(.+?)\s*-->$")
SHORTENED = "..."  # a line of a console block's output that stands for lines left out
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


def console_outputs(body) -> list[list[str]]:
    """The output shown after each ``$ `` command of a console block (one list of lines per command)."""
    outputs: list[list[str]] = []
    for line in body:
        if line.startswith("$ "):
            outputs.append([])
        elif outputs:
            outputs[-1].append(line.rstrip())
    return outputs


def shown_matches(shown: list[str], printed: list[str]) -> bool:
    """Whether ``shown`` is ``printed`` with runs of lines left out where it has a ``...`` line (and only
    there); trailing blank lines aside."""
    pattern = ""
    for line in shown:
        pattern += "(?:[^\n]*\n)*?" if line == SHORTENED else re.escape(line) + "\n"
    text = "".join(line.rstrip() + "\n" for line in printed)
    return re.fullmatch(pattern, text.rstrip("\n") + "\n" if text.strip() else "") is not None


def runnable_blocks():
    blocks = []
    for line, lang, body, reason in readme_blocks(README.read_text()):
        if lang == "python":
            blocks.append(pytest.param("python", "\n".join(body), reason, None, id=f"README.md:{line}"))
        elif lang in SHELL_LANGUAGES and shell_commands(lang, body):
            script = "\n".join(shell_commands(lang, body))
            shown = console_outputs(body) if lang == "console" else None
            blocks.append(pytest.param("shell", script, reason, shown, id=f"README.md:{line}"))
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
@pytest.mark.parametrize(("kind", "code", "reason", "shown"), runnable_blocks())
def test_readme_block_runs(tmp_path, kind, code, reason, shown):
    """Each block runs; a console block prints what it shows (``...`` for the lines it leaves out)."""
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
    for k, command in enumerate(code.splitlines()):
        proc = subprocess.run(
            ["bash", "-c", _as_this_interpreter(command)],
            cwd=tmp_path,
            env=env,
            capture_output=True,
            text=True,
            timeout=TIMEOUT,
        )
        assert proc.returncode == 0, f"{command}\n{proc.stderr[-3000:]}"
        if shown is not None:
            printed = proc.stdout.splitlines()
            assert shown_matches(shown[k], printed), (
                f"{command}: shows\n" + "\n".join(shown[k]) + ("\nbut prints\n" + proc.stdout)
            )


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


def test_shown_output_matches_only_with_its_shortening_marked():
    printed = ["a", "b", "c", "d"]
    assert shown_matches(["a", "b", "c", "d"], printed)
    assert shown_matches(["a", "...", "d"], printed) and shown_matches(["...", "c", "d"], printed)
    assert shown_matches(["a", "..."], printed) and shown_matches(["a", "...", "c", "..."], printed)
    assert not shown_matches(["a", "d"], printed)  # lines left out without the mark
    assert not shown_matches(["a", "b", "c"], printed)
    assert not shown_matches(["a", "...", "x"], printed)  # a line that is not printed
    assert not shown_matches(["b", "a", "..."], printed)  # out of order
    assert console_outputs(["$ x", "1", "...", "$ y", "2"]) == [["1", "..."], ["2"]]


def _commands() -> dict:
    return dict(build_parser().commands)


def _backticked(sentence: str) -> list[str]:
    return re.findall(r"`([a-z0-9-]+)`", sentence)


def _readme_sentence(start: str) -> str:
    """The README's sentence that starts with ``start`` (lines joined)."""
    text = " ".join(README.read_text().split())
    begin = text.index(start)
    return text[begin : text.index(". ", begin) + 1]


def test_the_commands_with_json_and_plot_are_those_the_readme_names():
    """README: every command has --json but the commands it names, and the commands it names have --plot."""
    commands = _commands()
    json_sentence = _readme_sentence("Every command prints JSON for scripts with `--json` except").split(";")[
        0
    ]
    without_json = {name for name, sub in commands.items() if "--json" not in sub._option_string_actions}
    assert {n for n in _backticked(json_sentence) if n[0] != "-"} == without_json, json_sentence
    plot_sentence = _readme_sentence("the commands that draw a figure write it with `--plot F.png`")
    named = [n for n in _backticked(plot_sentence.split("(")[0]) if n[0] != "-"]
    with_plot = {name for name, sub in commands.items() if "--plot" in sub._option_string_actions}
    assert set(named) == with_plot, plot_sentence
    others = [n for n in _backticked(plot_sentence.split("(", 1)[1]) if n[0] != "-"]
    for name in others:  # the others write their figure with --out
        assert (
            "--out" in commands[name]._option_string_actions
            and "--plot" not in commands[name]._option_string_actions
        )


@pytest.mark.parametrize("name", sorted(_commands()))
def test_every_command_has_help_and_refuses_a_bad_option_in_one_error_line(name, capsys):
    with pytest.raises(SystemExit) as done:
        main([name, "--help"])
    assert done.value.code == 0 and f"usage: moving-bogie {name}" in capsys.readouterr().out
    assert main([name, "--no-such-option"]) == 2
    captured = capsys.readouterr()
    errors = [line for line in captured.err.splitlines() if "error" in line]
    assert len(errors) == 1, captured.err
    # the option refused, or first the required ones missing (argparse checks those before the others)
    assert "--no-such-option" in errors[0] or "arguments are required: " in errors[0], captured.err
    assert captured.out == ""


def test_json_of_the_quick_commands_is_json(capsys):
    """--json, as promised, on the commands that answer in well under a second (the others run in the
    README's blocks and their own tests)."""
    file = str(ROOT / "examples" / "uic60-bogie.toml")
    for argv in (["models"], ["params", "--file", file], ["critical-velocity", "--file", file]):
        assert main([*argv, "--json"]) == 0
        assert isinstance(json.loads(capsys.readouterr().out), dict), argv


def test_model_options_offer_every_beam_track_and_vehicle():
    """README: every command that takes a model offers each beam, track and vehicle of the catalogue."""
    from moving_bogie.model.catalogue import default_catalogue

    catalogue = default_catalogue()
    declared = {"--beam": catalogue.beams, "--track": catalogue.tracks, "--vehicle": catalogue.vehicles}
    taking = 0
    for name, sub in _commands().items():
        options = sub._option_string_actions
        for option, choices in declared.items():
            if option in options:
                assert set(options[option].choices) == set(choices), (name, option)
        taking += "--track" in options
    assert taking >= 10


def test_references_to_readme_sections_name_sections_that_exist():
    """Comments and docstrings cite the README's sections as (README, "Tests") or README.md "Tests"."""
    headings = {
        line.lstrip("#").strip() for line in README.read_text().splitlines() if line.startswith("## ")
    }
    cited = re.compile(r'README(?:\.md)?,? "([^"]+)"')
    files = [ROOT / "pyproject.toml", ROOT / ".ci" / "run"]
    for folder in ("src", "tests", "docs", "benchmarks", "notebooks", "derivations"):
        files += [p for p in (ROOT / folder).rglob("*") if p.suffix in (".py", ".md", ".toml")]
    found = 0
    for path in files:
        for title in cited.findall(path.read_text(encoding="utf-8", errors="replace")):
            found += 1
            assert title in headings, f"{path.relative_to(ROOT)} cites the README's section {title!r}: none"
    assert found >= 3
