"""Random and hostile command lines and parameter files: every run ends in exit status 0, 1 or 2, with no
traceback and no file left behind by a refused run.

The command line is driven in-process through :func:`moving_bogie.cli.main`, every command and option taken
from the parser itself (so a new option is driven with no edit here). The computations are replaced by a
stand-in that stops the run where the work would start (``Reached``): what is tested is the parsing and the
validation, which must refuse a bad value with one line naming the option, or let it through to the work.
The parameter-file loader is driven with random TOML tables of the model's keys and hostile values.

``tests/data/hostile_inputs.json`` keeps the cases found (the issue's list first): each is replayed by
:func:`test_corpus_case`, with the option its one-line message must name.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

from moving_bogie.cli import build_parser, main
from moving_bogie.errors import ParameterError
from moving_bogie.model.files import dimensionless_keys, parse_params_toml, physical_keys

ROOT = Path(__file__).resolve().parents[1]
CORPUS = json.loads((Path(__file__).parent / "data" / "hostile_inputs.json").read_text())


class Reached(Exception):
    """The run got past every check to the work (a valid command line)."""


#: The entries where the commands' work starts (each imported by the command when it runs).
WORK = [
    ("moving_bogie.roots.frequencies", "induced_frequencies"),
    ("moving_bogie.response.cut_integral", "branch_cut_for"),
    ("moving_bogie.response.closed_form", "closed_form_response"),
    ("moving_bogie.response.closed_form", "deflection_shape_details"),
    ("moving_bogie.validation.compare", "validate"),
    ("moving_bogie.stability.maps.map", "stability_map"),
    ("moving_bogie.stability.maps.map", "map_columns"),
    ("moving_bogie.stability.lines.instability_lines", "instability_lines"),
    ("moving_bogie.stability.lines.frequency_lines", "frequency_lines"),
    ("moving_bogie.stability.stiffness.critical_stiffness", "critical_stiffness"),
    ("moving_bogie.stability.figures.track_comparison", "compare_tracks"),
    ("moving_bogie.sweep.engine", "run_sweep"),
    ("moving_bogie.roots.table2", "compute_table2"),
    ("moving_bogie.paper.reproduce", "reproduce"),
    ("moving_bogie.roots.strip", "floquet_frequencies"),
    ("moving_bogie.stability.maps.sleeper_map", "sleeper_map"),
    ("moving_bogie.response.sleeper_series", "sleeper_series"),
    ("moving_bogie.validation.sleepers_check", "check_sleepers"),
    ("moving_bogie.soil.rayleigh", "soil_modes"),
    ("moving_bogie.soil.critical", "critical_velocity"),
    ("moving_bogie.soil.moving_load", "moving_load"),
    *[("moving_bogie.paper.stability_figures", f"figure{n}") for n in (2, 3, 4, 7, 8, 16)],
]


@pytest.fixture(scope="module")
def no_work():
    """Every work entry of :data:`WORK` replaced by a stand-in raising :class:`Reached` for the module's
    tests; afterwards also where a module first imported meanwhile took the stand-in by name."""
    import importlib
    import sys

    patch = pytest.MonkeyPatch()
    originals, stand_ins = {}, []  # the stand-ins kept alive, so that their ids stay theirs
    for module, name in WORK:
        target = importlib.import_module(module)
        stand_ins.append(_stand_in())
        originals[id(stand_ins[-1])] = getattr(target, name)
        patch.setattr(target, name, stand_ins[-1])
    yield
    patch.undo()
    for loaded in list(sys.modules.values()):
        for attr, value in list(vars(loaded).items()):
            if id(value) in originals:
                setattr(loaded, attr, originals[id(value)])


def _stand_in() -> object:
    def reached(*args: object, **kwargs: object) -> None:
        raise Reached

    return reached


def _options() -> dict[str, dict[str, tuple[int, tuple[str, ...]]]]:
    """Every command's options, from the parser: option -> (values it takes: 0 for a flag, 1 otherwise;
    its choices, if any)."""
    parser = build_parser()
    out = {}
    for name, sub in parser.commands.items():
        actions = sub._option_string_actions  # noqa: SLF001 (argparse has no public list)
        out[name] = {
            option: (0 if action.nargs == 0 else 1, tuple(map(str, action.choices or ())))
            for option, action in sorted(actions.items())
            if option.startswith("--") and option not in ("--help", "--version")
        }
    return out


OPTIONS = _options()

#: Values no option should take without a one-line refusal, and some it should take.
HOSTILE = [
    "0", "-5", "-3", "1", "2", "3", "200", "100000", "1e400", "-1e400", "1e-400", "1e31", "1e30", "1e140",
    "-1e20", "nan", "inf", "-inf", "NaN", "0.5", "-0", "3/4", "1/0", "", " ", "abc", "1,2", "0,0", "1:2",
    "2:1", "1:2:3", "1:1e400:3", "=", "v=", "=80", "v=80", "v=1e400", "v=nan", "M=0:3000", "M=-1:3000",
    "v=0:400", "alpha=0:1.2", "alpha=1:0", "alpha=0:nan", "eta_M=0:200", "alpha=0.3:1:5", "alpha=0.3:1:0",
    "eta_M=1:200:-3", "sobol:8", "sobol:0", "sobol:-1", "halton:8", "x=1", "d=2.5", "tcp://nowhere:1",
]  # fmt: skip

#: Parameter files: valid ones and hostile ones (written into the test's folder by name).
FILES = {
    "uic60": (ROOT / "examples" / "uic60-bogie.toml").read_text(),
    "sleepers": (ROOT / "examples" / "sleepers.toml").read_text(),
    "soil": (ROOT / "examples" / "soil-ballasted.toml").read_text(),
    "empty": "",
    "model-only": '[model]\nvehicle = "masses"\n',
    "not-toml": "[physical\nv = ",
    "wrong-types": '[physical]\nEI = "stiff"\nm = true\nk_f = [1, 2]\n',
    "huge": (ROOT / "examples" / "uic60-bogie.toml").read_text().replace("v = 80", "v = 1e400"),
    "nan": (ROOT / "examples" / "uic60-bogie.toml").read_text().replace("v = 80", "v = nan"),
    "negative": (ROOT / "examples" / "uic60-bogie.toml").read_text().replace("M = 1000", "M = -1000"),
    "case-text": 'case = "seven"\n',
    "case-huge": "case = 99999999999999999999\n",
}
BASES = [[], ["--case", "1"], ["--case", "7"], ["--file", "{uic60}"], ["--file", "{sleepers}"]]
BASES += [["--file", "{" + name + "}"] for name in FILES if name not in ("uic60", "sleepers", "soil")]
BASES += [["--file", "{soil}"]]
BASES += [["--file", "{missing}"], ["--file", "{folder}"]]


@st.composite
def command_lines(draw: st.DrawFn) -> list[str]:
    command = draw(st.sampled_from(sorted(OPTIONS)))
    argv = [command]
    if command in ("sweep-plot",):
        argv.append(draw(st.sampled_from(["{missing}", "{folder}", "{uic60}"])))
    if command == "stability-figure":
        argv.append(draw(st.sampled_from(["3", "5", "-1", "abc"])))
    if command not in ("models", "table2", "reproduce", "sweep-plot", "stability-figure"):
        argv += draw(st.sampled_from(BASES))
    for _ in range(draw(st.integers(0, 4))):
        option = draw(st.sampled_from(sorted(OPTIONS[command])))
        takes, choices = OPTIONS[command][option]
        argv.append(option)
        if takes:
            values = [st.sampled_from(HOSTILE), st.text(max_size=6), st.floats().map(repr)]
            argv.append(draw(st.one_of(st.sampled_from(choices), *values) if choices else st.one_of(*values)))
    if command in ("sweep", "stability-map") and draw(st.booleans()):
        argv += ["--out", "{out}/s.zarr"]
    return argv


def _run(argv: list[str], folder: Path) -> int:
    """Run ``argv`` in ``folder`` (names in braces filled in); the exit status, or 0 for a run that reached
    the work; the folder must hold afterwards what it held before (a refused run writes nothing)."""
    names = {name: str(folder / f"{name}.toml") for name in FILES}
    names |= {"missing": str(folder / "missing.toml"), "folder": str(folder), "out": str(folder / "out")}
    argv = [re.sub(r"\{([\w-]+)\}", lambda m: names.get(m.group(1), m.group(0)), a) for a in argv]
    before = sorted(folder.rglob("*"))
    try:
        status = main(argv)
    except Reached:
        status = 0
    except SystemExit as exc:  # --help, --version
        status = exc.code if isinstance(exc.code, int) else 2
    assert status in (0, 1, 2), argv
    if status == 2:
        assert sorted(folder.rglob("*")) == before, f"a refused run left files behind: {argv}"
    return status


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    folder = tmp_path_factory.mktemp("hostile")
    for name, text in FILES.items():
        (folder / f"{name}.toml").write_text(text)
    (folder / "out").mkdir()
    return folder


@pytest.mark.parametrize("case", CORPUS, ids=[" ".join(c["argv"])[:60] for c in CORPUS])
def test_corpus_case(case, folder, no_work, capsys):
    """Each case found: exit status 2 and one line naming the option (a hint line may follow)."""
    status = _run(case["argv"], folder)
    err = capsys.readouterr().err.strip().splitlines()
    assert status == case["status"], err
    if status == 2:
        assert case["names"] in err[0], err
        assert all(line.startswith("see: ") for line in err[1:]), err


def _quiet(capsys: pytest.CaptureFixture[str]) -> None:
    out = capsys.readouterr()
    assert "Traceback" not in out.err


@settings(max_examples=40, deadline=None, suppress_health_check=list(HealthCheck))
@given(argv=command_lines())
@example(argv=["stability-map", "--case", "1", "--n", "0"])
@example(argv=["frequencies", "--file", "{uic60}", "--set", "v=80", "--set", "v=90"])
def test_random_command_lines_end_cleanly(argv, folder, no_work, capsys):
    _run(argv, folder)
    _quiet(capsys)


@pytest.mark.slow
# 400 random command lines (about 18 s); the cases found are kept in the corpus, replayed by the fast tests
@settings(max_examples=400, deadline=None, suppress_health_check=list(HealthCheck))
@given(argv=command_lines())
def test_many_random_command_lines_end_cleanly(argv, folder, no_work, capsys):
    _run(argv, folder)
    _quiet(capsys)


TOML_VALUES = st.one_of(
    st.sampled_from(
        ["1", "-1", "0", "1e400", "-1e400", "1e-400", "nan", "inf", "-inf", "0.5", "1e30", "1e31"]
    ),
    st.sampled_from(['"text"', "true", "[1, 2]", "{a = 1}", '"eb"', '"masses"', '"sleepers"', "2026-01-01"]),
    st.integers(-(10**30), 10**30).map(str),
    st.floats(allow_nan=False, allow_infinity=False).map(repr),
)


@st.composite
def parameter_files(draw: st.DrawFn) -> str:
    lines = []
    if draw(st.booleans()):
        lines.append(f"case = {draw(TOML_VALUES)}")
    tables = draw(st.lists(st.sampled_from(["model", "physical", "dimensionless", "junk"]), unique=True))
    keys = {
        "model": ["beam", "track", "vehicle", "wheels"],
        "physical": [*physical_keys(), "nonsense"],
        "dimensionless": [*dimensionless_keys(), "nonsense"],
        "junk": ["x"],
    }
    for table in tables:
        lines.append(f"[{table}]")
        for key in draw(st.lists(st.sampled_from(keys[table]), unique=True, max_size=14)):
            lines.append(f"{key} = {draw(TOML_VALUES)}")
    return "\n".join(lines) + "\n"


@settings(max_examples=25, deadline=None)
@given(text=parameter_files())
@example(text="")
@example(text="[physical]\nv = 1e400\n")
def test_random_parameter_files_load_or_name_the_key(text):
    """The loader returns parameters or refuses with a ParameterError; nothing else escapes."""
    try:
        params, physical = parse_params_toml(text, source="random.toml")
    except ParameterError as exc:
        assert str(exc) and exc.parameter
    else:
        for value in params.values().values():  # every value within the range of model/exact.py
            assert value == 0 or 1e-31 < abs(float(value)) < 1e31


def test_corpus_starts_with_the_issue_cases():
    argvs = [" ".join(case["argv"]) for case in CORPUS]
    assert "stability-map --case 1 --n 0" in argvs and "stability-map --n 100000" in argvs
