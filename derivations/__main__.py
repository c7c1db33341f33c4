"""``python -m derivations [--check] [--root DIR] [--only NAME]``: regenerate generated/ and docs/proofs.md.

With ``--check`` nothing is written: the command exits 1 and prints a unified diff when any committed
file differs from what the derivation produces now (stale kernels), 0 otherwise. ``--only NAME`` (a beam,
track or vehicle; repeatable) derives only the kernel modules of the named ones plus the catalogue-wide
files (``__init__.py``, ``asymptotics.py``, ``parameters.py``): after adding a beam, track or vehicle, and
nothing else, it writes what a full run would write, in a fraction of the time.
"""

import argparse
import difflib
import os
import sys
from pathlib import Path


def main(argv=None) -> int:
    # CSE and SymPy's internal ordering may depend on string hashing: pin it so output is byte-identical.
    if os.environ.get("PYTHONHASHSEED") != "0":
        env = dict(os.environ, PYTHONHASHSEED="0")
        args = [sys.executable, "-m", "derivations", *(sys.argv[1:] if argv is None else argv)]
        os.execve(sys.executable, args, env)
    parser = argparse.ArgumentParser(prog="python -m derivations", description=__doc__.splitlines()[0])
    parser.add_argument(
        "--check", action="store_true", help="compare with the committed files, write nothing"
    )
    parser.add_argument(
        "--root",
        type=Path,
        default=Path(__file__).resolve().parent.parent,
        help="repository root to write into",
    )
    parser.add_argument(
        "--only",
        action="append",
        metavar="NAME",
        help="derive only this beam's, track's or vehicle's modules and the catalogue files (repeatable)",
    )
    ns = parser.parse_args(argv)
    from .generate import outputs, selectable

    unknown = sorted(set(ns.only or ()) - set(selectable()))
    if unknown:
        parser.error(f"--only: unknown name(s) {', '.join(unknown)}; known: {', '.join(selectable())}")
    files = outputs(ns.root, only=None if ns.only is None else frozenset(ns.only))
    stale = []
    for path, text in files.items():
        old = path.read_text() if path.exists() else ""
        if old == text:
            continue
        stale.append(path)
        if ns.check:
            rel = path.relative_to(ns.root)
            diff = difflib.unified_diff(
                old.splitlines(True), text.splitlines(True), f"a/{rel}", f"b/{rel}", n=1
            )
            sys.stdout.writelines(list(diff)[:200])
        else:
            path.parent.mkdir(parents=True, exist_ok=True)
            tmp = path.with_suffix(path.suffix + ".tmp")
            tmp.write_text(text)
            tmp.replace(path)
    if ns.check:
        if stale:
            print(f"\n{len(stale)} generated file(s) are stale. Update them with: python -m derivations")
            return 1
        print(f"generated files are current ({len(files)} checked)")
        return 0
    print(f"wrote {len(stale)} of {len(files)} file(s)" + ("" if stale else " (all were current)"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
