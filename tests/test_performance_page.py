"""docs/performance.md is the page benchmarks/performance_page.py assembles from the committed records.

The records (``benchmarks/results/*.json``) are what the benchmark scripts wrote with ``--record``; the
page must be their current rendering, and every record must have the fields the page shows.
"""

from __future__ import annotations

import json
from pathlib import Path

from scripts import load_script

ROOT = Path(__file__).resolve().parent.parent
BENCHMARKS = ROOT / "benchmarks"


def _page_module():
    return load_script("benchmarks/performance_page.py")


def test_every_record_has_the_fields_of_the_page():
    records = sorted((BENCHMARKS / "results").glob("*.json"))
    assert records, "no benchmark records in benchmarks/results/"
    for path in records:
        record = json.loads(path.read_text(encoding="utf-8"))
        assert {"title", "date", "machine", "command", "rows"} <= record.keys(), path.name
        assert {"platform", "cores", "memory_gib"} <= record["machine"].keys(), path.name
        assert record["command"].startswith(f"python benchmarks/{path.stem}.py"), path.name
        for row in record["rows"]:
            assert set(row) == {"work", "measured", "alternative", "target"}, path.name


def test_committed_page_is_current():
    """The page renders the committed records. Whether each record is still current depends on the files
    of the checkout at the time the page is made, which every commit may change: those marks are left out
    of the comparison (``performance_page.py --check`` compares them too)."""
    module = _page_module()
    page = (ROOT / "docs" / "performance.md").read_text(encoding="utf-8")
    expected = module.render(module.load_records(), marks=False)
    assert module.without_marks(page) == expected, "run python benchmarks/performance_page.py"


def test_a_record_is_marked_stale_when_its_code_changed(tmp_path):
    """A record keeps the hash of the files it measured; a changed file, an unknown hash or no hash at all
    each get their mark, and the page with its marks taken out is the page without them."""
    module = _page_module()
    records = load_script("benchmarks/records.py")
    folder = tmp_path / "pkg"
    folder.mkdir()
    (folder / "a.py").write_text("x = 1\n")
    made = records.source_hash("pkg", tmp_path)
    assert records.stale_sources({"sources": {"pkg": made}}, tmp_path) == []
    (folder / "a.py").write_text("x = 2\n")
    assert records.stale_sources({"sources": {"pkg": made}}, tmp_path) == ["pkg"]
    assert records.stale_sources({}, tmp_path) is None

    current = {"src/moving_bogie": records.source_hash("src/moving_bogie")}
    base = {
        "title": "T",
        "date": "2026-01-01",
        "machine": {},
        "command": "python benchmarks/x.py",
        "rows": [],
    }
    assert module.freshness(base | {"sources": current}) is None
    stale = module.freshness(base | {"sources": {"src/moving_bogie": "0" * 16}})
    assert stale.startswith(module.STALE) and "`src/moving_bogie`" in stale
    assert module.freshness(base).startswith(module.UNKNOWN)
    page = module.render([base, base | {"sources": current}])
    assert page.count(module.UNKNOWN) == 1 and module.STALE not in page
    assert module.without_marks(page) == module.render([base, base | {"sources": current}], marks=False)


def test_check_mode_reports_a_stale_page(tmp_path, capsys):
    module = _page_module()
    stale = tmp_path / "performance.md"
    stale.write_text("# old\n")
    assert module.main(["--check", "--output", str(stale)]) == 1
    assert "out of date" in capsys.readouterr().out
    assert module.main(["--output", str(stale)]) == 0
    assert module.main(["--check", "--output", str(stale)]) == 0
