"""``moving-bogie reproduce``: every artifact of the paper is listed, built or explained, never faked.

Every artifact with a recipe must be *covered* by the quick run: a recipe whose module or function moved
fails loudly instead of turning into "not covered".
"""

from __future__ import annotations

import html
import re
import time

import pytest

from moving_bogie.cli import main
from moving_bogie.paper.captions import CAPTIONS
from moving_bogie.paper.index_page import caption_html
from moving_bogie.paper.recipe import BuildContext
from moving_bogie.paper.registry import ARTIFACTS, NOT_COMPUTED, Artifact
from moving_bogie.paper.reproduce import build_artifact, quick_from_env


@pytest.fixture(scope="module")
def quick_run(tmp_path_factory):
    """One ``reproduce --quick`` run shared by the tests below (the CI check that everything builds)."""
    out = tmp_path_factory.mktemp("reproduce")
    start = time.perf_counter()
    status = main(["reproduce", "--out", str(out), "--quick", "--no-progress"])
    return out, status, time.perf_counter() - start


def test_quick_run_succeeds_and_fails_nothing(quick_run):
    out, status, seconds = quick_run
    index = (out / "index.md").read_text(encoding="utf-8")
    assert status == 0, index
    assert "| failed |" not in index
    print(f"reproduce --quick: {seconds:.0f} s")


def test_index_lists_every_artifact_with_its_caption(quick_run):
    out, _, _ = quick_run
    page = (out / "index.html").read_text(encoding="utf-8")
    md = (out / "index.md").read_text(encoding="utf-8")
    assert [a.id for a in ARTIFACTS] == [c.id for c in CAPTIONS]
    for artifact in ARTIFACTS:
        assert f'<section id="{artifact.id}">' in page
        assert caption_html(artifact.caption.text) in page
        assert f"## {artifact.label} — " in md
        assert artifact.caption.text in md
    labels = [a.label for a in ARTIFACTS]
    assert labels[:3] == ["Figure 1", "Table 1", "Table 2"]
    expected = {f"Figure {n}" for n in range(2, 17)} | {f"Figure A{n}" for n in range(1, 8)}
    assert expected <= set(labels)


def test_every_covered_figure_has_its_image_and_the_rest_a_reason(quick_run):
    out, _, _ = quick_run
    md = (out / "index.md").read_text(encoding="utf-8")
    page = (out / "index.html").read_text(encoding="utf-8")
    for artifact in ARTIFACTS:
        section = md.split(f'<a id="{artifact.id}"></a>', 1)[1].split("<a id=", 1)[0]
        status = re.search(rf"## {re.escape(artifact.label)} — (.+)", section).group(1)
        if status == "covered":
            if artifact.kind == "figure":
                images = re.findall(r"!\[[^\]]*\]\(([^)]+)\)", section)
                assert images, f"{artifact.label} is covered but shows no image"
                for rel in images:
                    assert (out / rel).is_file() and (out / rel).stat().st_size > 1000, rel
                    assert f'src="{html.escape(rel)}"' in page
        else:
            assert artifact.recipe is None, f"{artifact.label} has a recipe but is {status}"
            assert status == "not covered", f"{artifact.label}: {status}"
            assert "**Not covered:** " in section
            assert not re.findall(r"!\[", section), f"{artifact.label} is not covered but shows an image"
    # no stray images: every PNG written belongs to a covered artifact shown in the index
    for png in (out / "figures").glob("*.png") if (out / "figures").exists() else ():
        assert f"figures/{png.name}" in md


def test_table2_shows_confirmed_digits_and_the_print(quick_run):
    out, _, _ = quick_run
    page = (out / "index.html").read_text(encoding="utf-8")
    section = page.split('<section id="table2">', 1)[1].split("</section>", 1)[0]
    assert "±0.307227" in section  # Case 1, root 1: computed and printed
    assert section.count("±0.307227") >= 2
    assert "digits confirmed" in section
    assert "withheld" in section  # Cases 7-13 have no printed row
    assert (out / "table2.txt").is_file() and (out / "table2.json").is_file()


def test_list_and_bad_selection(capsys):
    assert main(["reproduce", "--list"]) == 0
    listed = capsys.readouterr().out.split()
    assert all(a.id in listed for a in ARTIFACTS)
    assert main(["reproduce", "--out", "unused", "--only", "figure99"]) == 2
    assert "figure99" in capsys.readouterr().err


def test_every_artifact_has_a_recipe_or_a_reason():
    assert {a.id for a in ARTIFACTS if a.recipe is None} == set(NOT_COMPUTED) == {"figure1"}
    assert all(a.reason for a in ARTIFACTS if a.recipe is None)
    assert sum(a.recipe is not None for a in ARTIFACTS) == 24  # Tables 1-2, Figures 2-16 and A1-A7


def test_a_failing_recipe_is_failed_with_its_traceback(tmp_path):
    def recipe(ctx):
        from moving_bogie.response import no_such_module  # noqa: F401  (a recipe that lost its import)

    artifact = Artifact(CAPTIONS[1], "table", recipe)
    outcome = build_artifact(artifact, BuildContext(tmp_path, quick=True, dps=20))
    assert outcome.status == "failed" and not outcome.ok
    assert "no_such_module" in outcome.reason
    assert "ImportError" in (tmp_path / outcome.built.files[0]).read_text(encoding="utf-8")


def test_quick_switch_from_environment(monkeypatch):
    monkeypatch.delenv("MOVING_BOGIE_QUICK", raising=False)
    assert quick_from_env() is False
    for value, expected in (("1", True), ("yes", True), ("0", False), ("false", False)):
        monkeypatch.setenv("MOVING_BOGIE_QUICK", value)
        assert quick_from_env() is expected
