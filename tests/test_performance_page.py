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
    module = _page_module()
    page = (ROOT / "docs" / "performance.md").read_text(encoding="utf-8")
    assert page == module.render(module.load_records()), "run python benchmarks/performance_page.py"


def test_check_mode_reports_a_stale_page(tmp_path, capsys):
    module = _page_module()
    stale = tmp_path / "performance.md"
    stale.write_text("# old\n")
    assert module.main(["--check", "--output", str(stale)]) == 1
    assert "out of date" in capsys.readouterr().out
    assert module.main(["--output", str(stale)]) == 0
    assert module.main(["--check", "--output", str(stale)]) == 0
