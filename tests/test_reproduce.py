"""``moving-bogie reproduce``: every artifact of the paper is listed, built or explained, never faked.

Every artifact with a recipe must be *covered* by the quick run: a recipe whose module or function moved
fails loudly instead of turning into "not covered".
"""

from __future__ import annotations

import html
import re
import time

import numpy as np
import pytest

from moving_bogie.cli import main
from moving_bogie.kernels.bound import bind
from moving_bogie.kernels.characteristic import CharacteristicArray
from moving_bogie.model.cases import table1_case
from moving_bogie.paper import reproduce as driver
from moving_bogie.paper.captions import CAPTIONS
from moving_bogie.paper.index_page import caption_html
from moving_bogie.paper.recipe import BuildContext
from moving_bogie.paper.registry import ARTIFACTS, NOT_COMPUTED, Artifact
from moving_bogie.paper.reproduce import build_artifact, quick_from_env, reproduce


@pytest.fixture(scope="module")
def quick_run(tmp_path_factory):
    """One ``reproduce --quick`` run shared by the tests below (the CI check that everything builds).

    Every figure a recipe saves is kept too (``name -> Figure``), so that the tests read the data back
    from its artists instead of judging the PNG by its size; so is every ``(label, fraction)`` the command
    hands its progress bar within an artefact (``progress``, a list).
    Returns (out, status, seconds, figures, progress).
    """
    out = tmp_path_factory.mktemp("reproduce")
    figures, seen = {}, []
    save = BuildContext.save_figure

    def keep(self, fig, name, **kwargs):
        figures[name] = fig
        return save(self, fig, name, **kwargs)

    def recorded(*args, artifact_progress, **kwargs):
        def part(label, fraction):
            seen.append((label, fraction))
            artifact_progress(label, fraction)

        return reproduce(*args, artifact_progress=part, **kwargs)

    start = time.perf_counter()
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(BuildContext, "save_figure", keep)
        patch.setattr(driver, "reproduce", recorded)  # what the command calls
        status = main(["reproduce", "--out", str(out), "--quick", "--no-progress"])
    return out, status, time.perf_counter() - start, figures, seen


@pytest.mark.slow
def test_quick_run_succeeds_and_fails_nothing(quick_run):
    out, status, seconds, _, _ = quick_run
    index = (out / "index.md").read_text(encoding="utf-8")
    assert status == 0, index
    assert "| failed |" not in index
    print(f"reproduce --quick: {seconds:.0f} s")


@pytest.mark.slow
def test_reproduce_reports_progress_within_each_artifact(quick_run):
    """The command's bar moves inside an artefact: Table 2 reports after each of its 13 cases, up to 1."""
    _, _, _, _, seen = quick_run
    labels = [label for label, _ in seen]
    assert labels[0] == "Table 1" and "Table 2" in labels
    assert set(labels) <= {a.label for a in ARTIFACTS if a.recipe is not None}
    table2 = [f for label, f in seen if label == "Table 2"]
    assert len(table2) >= 13 and table2 == sorted(table2) and table2[-1] == 1.0


@pytest.mark.slow
def test_index_lists_every_artifact_with_its_caption(quick_run):
    out, _, _, _, _ = quick_run
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


@pytest.mark.slow
def test_every_covered_figure_has_its_image_and_the_rest_a_reason(quick_run):
    out, _, _, _, _ = quick_run
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
                    assert (out / rel).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", rel
                    assert f'src="{html.escape(rel)}"' in page
        else:
            assert artifact.recipe is None, f"{artifact.label} has a recipe but is {status}"
            assert status == "not covered", f"{artifact.label}: {status}"
            assert "**Not covered:** " in section
            assert not re.findall(r"!\[", section), f"{artifact.label} is not covered but shows an image"
    # no stray images: every PNG written belongs to a covered artifact shown in the index
    for png in (out / "figures").glob("*.png") if (out / "figures").exists() else ():
        assert f"figures/{png.name}" in md


@pytest.mark.slow
def test_table2_shows_confirmed_digits_and_the_print(quick_run):
    out, _, _, _, _ = quick_run
    page = (out / "index.html").read_text(encoding="utf-8")
    section = page.split('<section id="table2">', 1)[1].split("</section>", 1)[0]
    assert "±0.307227" in section  # Case 1, root 1: computed and printed
    assert section.count("±0.307227") >= 2
    assert "digits confirmed" in section
    assert "withheld" in section  # Cases 7-13 have no printed row
    assert (out / "table2.txt").is_file() and (out / "table2.json").is_file()


def _drawn(ax) -> list[np.ndarray]:
    """The finite data points of every line, collection and mesh drawn on `ax` (not the axes' decoration)."""
    data = [np.column_stack([ln.get_xdata(), ln.get_ydata()]).astype(float) for ln in ax.get_lines()]
    for collection in ax.collections:
        offsets = np.asarray(collection.get_offsets(), dtype=float)
        array = collection.get_array()
        data.append(offsets if array is None else np.asarray(array, dtype=float).reshape(-1, 1))
    return [d[np.all(np.isfinite(d), axis=1)] for d in data if d.size]


@pytest.mark.slow
def test_every_panel_of_every_figure_shows_data(quick_run):
    """No blank panel: each axes with a title or a label draws finite data inside its limits."""
    _, _, _, figures, _ = quick_run
    covered = {a.id for a in ARTIFACTS if a.recipe is not None and a.kind == "figure"}
    assert covered <= set(figures), f"figures not drawn: {sorted(covered - set(figures))}"
    for name, fig in figures.items():
        panels = [ax for ax in fig.axes if ax.get_title() or ax.get_xlabel() or ax.get_ylabel()]
        assert panels, f"{name}: no panel"
        for ax in panels:
            points = [d for d in _drawn(ax) if len(d)]
            assert points, f"{name}: panel '{ax.get_title()}' draws nothing"
            x0, x1 = sorted(ax.get_xlim())
            inside = [d for d in points if d.shape[1] == 1 or np.any((d[:, 0] >= x0) & (d[:, 0] <= x1))]
            assert inside, f"{name}: panel '{ax.get_title()}' draws nothing inside its limits"


@pytest.mark.slow
def test_figure2_points_are_induced_frequencies(quick_run):
    """Figure 2 by content: the plotted (alpha, Re q, Im q) are roots of E_chr of Case 1 (Eq. (38)).

    Reference: E_chr evaluated in the test in double precision (numpy kernels) at points read back from the
    plotted lines, against its size a small step away (a simple root: |E(q + h)| ~ |E'| h).
    """
    _, _, _, figures, _ = quick_run
    fig = figures["figure2"]
    checked = 0
    for ax in fig.axes:
        twins = [other for other in fig.axes if other is not ax and other.bbox.bounds == ax.bbox.bounds]
        if not ax.get_ylabel().startswith("Re") or not twins:
            continue
        (re_line,) = [ln for ln in ax.get_lines() if len(ln.get_xdata()) > 2]
        (im_line,) = [ln for ln in twins[0].get_lines() if len(ln.get_xdata()) > 2]
        alpha = np.asarray(re_line.get_xdata(), float)
        q = np.asarray(re_line.get_ydata(), float) + 1j * np.asarray(im_line.get_ydata(), float)
        for k in np.linspace(0, len(alpha) - 1, 4).astype(int):
            chr_ = CharacteristicArray(bind(table1_case(1).replace(alpha=float(alpha[k]))))
            h = 1e-4 * (1 + abs(q[k]))
            assert abs(chr_(q[k])) < 1e-5 * abs(chr_(q[k] + h)), (alpha[k], q[k])
            checked += 1
    assert checked >= 4, "Figure 2 shows no frequency line"


@pytest.mark.slow
def test_figure8_marks_the_timoshenko_rayleigh_critical_velocity_of_eq66(quick_run):
    """Figure 8 by content: each panel's grey dotted line is Eq. (66) for the panel's S and r.

    Reference: Eq. (66) as printed, evaluated here from the S and r of the panel's title (the closed form
    agrees with the numerical alpha_cr, docs/errata.md, item 10 quotes 0.998 for S = 100, r = 0.03).
    """
    _, _, _, figures, _ = quick_run
    panels = [ax for ax in figures["figure8"].axes if "S" in ax.get_title()]
    assert len(panels) == 2
    for ax in panels:
        S, r = (float(x) for x in re.findall(r"= ([0-9.]+)", ax.get_title()))
        r2 = r * r
        eq66 = (r2 - S - 8 * r2 * S * S + 4 * S**1.5 * (4 * r2 * r2 * S - r2 + S) ** 0.5) ** 0.5 / (
            2 * (S - r2)
        )
        grey = [ln for ln in ax.get_lines() if ln.get_linestyle() == ":" and ln.get_color() == "grey"]
        assert [float(ln.get_xdata()[0]) for ln in grey] == [pytest.approx(eq66, rel=1e-12)], ax.get_title()


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
