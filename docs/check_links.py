"""Check the internal links of the built documentation site: ``python docs/check_links.py docs/_build/html``.

Every ``href`` and ``src`` of every HTML page that is not an external address (a scheme such as ``https:``
or ``mailto:``) must name a file of the build, and a ``#fragment`` must name an ``id`` of its target page.
No network is used. Prints one line per broken link and exits 1 when there is any.
"""

from __future__ import annotations

import sys
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit


class _Page(HTMLParser):
    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.links: list[str] = []
        self.ids: set[str] = set()

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        for name, value in attrs:
            if name in ("id", "name") and value:
                self.ids.add(value)
            elif name in ("href", "src") and value and not (tag == "link" and "preconnect" in str(attrs)):
                self.links.append(value)


def _parse(path: Path) -> _Page:
    page = _Page()
    page.feed(path.read_text(encoding="utf-8", errors="replace"))
    return page


def broken_links(site: Path) -> list[str]:
    """``page: link`` for every internal link of the site that does not resolve."""
    site = site.resolve()
    pages = {path: _parse(path) for path in sorted(site.rglob("*.html"))}
    problems = []
    # (folder, path of a link) -> (the file it names, whether it exists): most links (the theme's files,
    # the index, the neighbouring pages) recur on every page of a folder, and are resolved once
    found: dict[tuple[Path, str], tuple[Path, bool]] = {}
    for path, page in pages.items():
        for link in page.links:
            parts = urlsplit(link)
            if parts.scheme or parts.netloc:
                continue
            key = (path.parent, parts.path)
            if not parts.path:
                target, exists = path, True
            elif key in found:
                target, exists = found[key]
            else:
                target = (path.parent / unquote(parts.path)).resolve()
                if target.is_dir():
                    target = target / "index.html"
                target, exists = found[key] = (target, target.is_file())
            if not exists:
                problems.append(f"{path.relative_to(site)}: {link} (no such file)")
            elif parts.fragment and target.suffix == ".html":
                ids = pages[target].ids if target in pages else _parse(target).ids
                if unquote(parts.fragment) not in ids:
                    where = f"{path.relative_to(site)}: {link}"
                    problems.append(f"{where} (no id {parts.fragment!r} in {target.relative_to(site)})")
    return problems


def main(argv: list[str] | None = None) -> int:
    args = sys.argv[1:] if argv is None else argv
    site = Path(args[0] if args else "docs/_build/html")
    if not (site / "index.html").is_file():
        print(f"{site}: no built site (index.html missing)", file=sys.stderr)
        return 2
    problems = broken_links(site)
    for line in problems:
        print(line)
    pages = len(list(site.rglob("*.html")))
    print(f"{pages} pages, {len(problems)} broken internal links")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
