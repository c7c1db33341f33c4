"""The records the benchmark scripts write with ``--record``, read by ``performance_page.py``.

A benchmark run with ``--record`` writes ``benchmarks/results/<script-stem>.json``::

    {"title": ..., "date": "YYYY-MM-DD",
     "machine": {"platform": ..., "processor": ..., "cores": ..., "memory_gib": ..., "python": ...},
     "command": ..., "rows": [{"work": ..., "measured": ..., "alternative": ..., "target": ...}],
     "sources": {"src/moving_bogie": "<hash>"}}

``work`` says what was run, ``measured`` what it cost (with its unit), ``alternative`` the same work done
another way in the same run ("-" when none was run) and ``target`` the aim ("-" when there is none).
``sources`` holds, for each folder of the repository whose code the benchmark measures, the hash of its
files as they were when the record was written (:func:`source_hash`; leave the code alone while a benchmark
runs): the page marks a record stale when a hash no longer matches. The file is written atomically, so an
interrupted run leaves the previous record in place.
"""

from __future__ import annotations

import datetime
import hashlib
import json
import os
import platform
import sys
from pathlib import Path

RESULTS = Path(__file__).resolve().parent / "results"
ROOT = RESULTS.parent.parent
FIELDS = ("work", "measured", "alternative", "target")
#: The code a benchmark measures unless it names narrower folders: the whole package.
PACKAGE = ("src/moving_bogie",)


def source_hash(folder: str, root: Path = ROOT) -> str:
    """SHA-256 of the files of ``folder`` (relative to ``root``) as they are on disk: every file git tracks
    or would track there (untracked files too, ignored ones such as ``__pycache__`` not), each by its path
    and bytes; every ``*.py`` file when ``root`` is not a git checkout. Any edit, committed or not, changes
    it. A single file is hashed the same way, without asking git."""
    if (root / folder).is_file():
        names = [folder]
    else:
        names = _listed(folder, root)
    digest = hashlib.sha256()
    for name in names:
        path = root / name
        if path.is_file():  # a tracked file deleted on disk is left out
            digest.update(name.encode() + b"\0" + path.read_bytes() + b"\0")
    return digest.hexdigest()[:16]


def _listed(folder: str, root: Path) -> list[str]:
    """The files of ``folder`` that git tracks or would track, sorted (every ``*.py`` file outside git)."""
    import subprocess

    try:
        listed = subprocess.run(
            ["git", "-C", str(root), "ls-files", "-co", "--exclude-standard", "-z", "--", folder],
            capture_output=True,
            check=True,
        ).stdout.decode()
        return sorted(n for n in listed.split("\0") if n)
    except (OSError, subprocess.CalledProcessError):
        return sorted(str(p.relative_to(root)) for p in (root / folder).rglob("*.py"))


def stale_sources(record: dict, root: Path = ROOT) -> list[str] | None:
    """The folders of ``record["sources"]`` whose files changed since the record was made; None when the
    record names no sources (whether its code changed is unknown)."""
    sources = record.get("sources")
    if not sources:  # None or empty
        return None
    return [folder for folder, digest in sources.items() if source_hash(folder, root) != digest]


def machine() -> dict:
    """The machine a record was measured on: platform, cores, memory, Python."""
    try:
        memory = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") / 2**30
    except (ValueError, OSError, AttributeError):  # not every platform reports it
        memory = None
    return {
        "platform": platform.platform(),
        "processor": platform.machine(),
        "cores": os.cpu_count(),
        "memory_gib": None if memory is None else round(memory, 1),
        "python": platform.python_version(),
    }


def source_revision(src: Path) -> str:
    """``commit <hash>`` of the git checkout that holds the folder ``src`` (the code a benchmark compares
    with), or the folder's name when it is not in a git checkout."""
    import subprocess

    try:
        out = subprocess.run(
            ["git", "-C", str(src), "rev-parse", "--short", "HEAD"],
            capture_output=True,
            text=True,
            check=True,
        )
    except (OSError, subprocess.CalledProcessError):
        return Path(src).name
    return f"commit {out.stdout.strip()}"


def row(work: str, measured: str, alternative: str = "-", target: str = "-") -> dict:
    """One row of a record (every field a string, as the page shows it)."""
    return {"work": work, "measured": measured, "alternative": alternative, "target": target}


def write_record(
    script: str,
    title: str,
    rows: list[dict],
    placeholders: dict[str, str] | None = None,
    sources: tuple[str, ...] = PACKAGE,
    entries: tuple[str, ...] | None = None,
) -> Path:
    """Write the record of the benchmark ``script`` (its ``__file__``); returns the path written.
    ``placeholders``: arguments of the command shown as a name (a local path as ``SRC``); ``sources``: the
    folders of the code measured, whose hashes the record keeps; ``entries``: the modules the work of child
    processes starts from (``()`` when all of it ran here), which replace ``sources`` by the files of the
    package loaded in this process and of the import closure of ``entries``
    (:func:`import_closure.measured_files`), so that an edit to another part of the package leaves the
    record current."""
    if entries is not None:
        from import_closure import measured_files

        sources = tuple(measured_files(entries))
    for r in rows:
        missing = [f for f in FIELDS if f not in r]
        if missing:
            raise ValueError(f"record row {r!r} lacks {missing}")
    stem = Path(script).stem
    record = {
        "title": title,
        "date": datetime.date.today().isoformat(),
        "machine": machine(),
        "command": " ".join(
            ["python", f"benchmarks/{Path(script).name}"]
            + [(placeholders or {}).get(arg, arg) for arg in sys.argv[1:]]
        ),
        "rows": [{f: str(r[f]) for f in FIELDS} for r in rows],
        "sources": {folder: source_hash(folder) for folder in sources},
    }
    RESULTS.mkdir(exist_ok=True)
    path = RESULTS / f"{stem}.json"
    partial = path.with_suffix(".json.partial")
    partial.write_text(json.dumps(record, indent=2, ensure_ascii=False) + "\n", encoding="utf-8")
    partial.replace(path)
    print(f"recorded {path.relative_to(RESULTS.parent.parent)}")
    return path


def add_record_option(parser) -> None:
    """The ``--record`` option every recording benchmark takes."""
    parser.add_argument(
        "--record",
        action="store_true",
        help="write benchmarks/results/<script>.json for benchmarks/performance_page.py",
    )
