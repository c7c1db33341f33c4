"""The index page of a ``reproduce`` run: ``index.html`` (with its CSS) and ``index.md``.

Per artefact: the paper's caption, verbatim, then the rebuilt figure or table and its notes, or the reason
it is not covered. The HTML page needs no JavaScript: the captions' inline TeX is rendered as plain HTML.
"""

from __future__ import annotations

import datetime
import html
import re

from moving_bogie.paper.report import Report

__all__ = ["caption_html", "write_index"]

_TEX = [
    (r"\\tilde\{(\w)\}", lambda m: m.group(1) + "\u0303"),
    (r"\\eta", lambda m: "η"),
    (r"\\kappa", lambda m: "κ"),
    (r"\\alpha", lambda m: "α"),
    (r"_(\w)", lambda m: f"<sub>{m.group(1)}</sub>"),
]


def caption_html(text: str) -> str:
    """The caption text with its bold markers and inline TeX rendered as plain HTML (no JavaScript)."""
    parts = re.split(r"(\$[^$]*\$)", text)
    out = []
    for part in parts:
        if part.startswith("$") and part.endswith("$") and len(part) > 1:
            tex = html.escape(part[1:-1].strip())
            for pattern, repl in _TEX:
                tex = re.sub(pattern, repl, tex)
            out.append(f"<i>{tex}</i>")
        else:
            out.append(re.sub(r"\*\*(.+?)\*\*", r"<strong>\1</strong>", html.escape(part)))
    return "".join(out)


_CSS = """
body { font-family: system-ui, sans-serif; max-width: 1000px; margin: 2em auto; padding: 0 1em; color: #222; }
section { border-top: 1px solid #ccc; padding: 1em 0; }
.caption { background: #f6f6f2; padding: .6em .8em; border-left: 4px solid #999; }
.status { font-size: .85em; padding: .1em .5em; border-radius: 3px; }
.covered { background: #d9f2d9; } .notcovered { background: #eee; } .failed { background: #f8d0d0; }
.notbuilt { background: #f2f2d9; }
table.data { border-collapse: collapse; font-size: .85em; margin: .8em 0; }
table.data td, table.data th { border: 1px solid #ccc; padding: .2em .5em; text-align: right; }
table.data tr.unstable td { color: #b00; }
td.digits { font-family: monospace; font-size: .8em; text-align: left; }
img { max-width: 100%; }
ul.notes { font-size: .85em; color: #444; }
table.toc td { padding: .1em .6em; }
"""


def write_index(report: Report) -> None:
    """Write ``index.html`` and ``index.md`` for `report` into its output folder."""
    (report.out / "index.html").write_text(_index_html(report), encoding="utf-8")
    (report.out / "index.md").write_text(_index_md(report), encoding="utf-8")


def _header_facts(report: Report) -> tuple[str, str]:
    from moving_bogie import __version__

    mode = "quick (reduced grids and time windows)" if report.quick else "full"
    when = datetime.datetime.now(datetime.UTC).strftime("%Y-%m-%d %H:%M UTC")
    summary = (
        f"{report.count('covered')} covered, {report.count('not covered')} not covered, "
        f"{report.count('failed')} failed"
        + (f", {report.count('not built')} not built in this run" if report.count("not built") else "")
    )
    facts = f"moving-bogie {__version__}, mode: {mode}, {when}, {report.seconds:.0f} s"
    return facts, summary


def _index_html(report: Report) -> str:
    facts, summary = _header_facts(report)
    toc = []
    sections = []
    for o in report.outcomes:
        a = o.artifact
        cls = o.status.replace(" ", "")
        toc.append(
            f'<tr><td><a href="#{a.id}">{a.label}</a></td>'
            f'<td><span class="status {cls}">{o.status}</span></td>'
            f"<td>{html.escape(o.reason if o.status != 'covered' else '')}</td></tr>"
        )
        printed = (
            f" <small>(printed as “{html.escape(a.caption.printed_label)}.”)</small>"
            if a.caption.printed_label
            else ""
        )
        body = [
            f'<section id="{a.id}">',
            f'<h2>{a.label} <span class="status {cls}">{o.status}</span></h2>',
            f'<p class="caption"><strong>{a.label}.</strong>{printed} {caption_html(a.caption.text)}</p>',
        ]
        if o.status == "covered":
            for rel in o.built.files:
                if rel.endswith(".png"):
                    body.append(f'<p><img src="{html.escape(rel)}" alt="{a.label}"></p>')
            if o.built.html:
                body.append(o.built.html)
            others = [rel for rel in o.built.files if not rel.endswith(".png")]
            if others:
                links = ", ".join(f'<a href="{html.escape(r)}">{html.escape(r)}</a>' for r in others)
                body.append(f"<p>Files: {links}</p>")
        elif o.status == "failed":
            link = f' (<a href="{html.escape(o.built.files[0])}">traceback</a>)' if o.built.files else ""
            body.append(f"<p><strong>Failed:</strong> {html.escape(o.reason)}{link}</p>")
        else:
            body.append(f"<p><strong>{o.status.capitalize()}:</strong> {html.escape(o.reason)}</p>")
        notes = list(o.built.notes)
        if o.seconds:
            notes.append(f"Built in {o.seconds:.1f} s.")
        if notes:
            body.append('<ul class="notes">' + "".join(f"<li>{html.escape(n)}</li>" for n in notes) + "</ul>")
        body.append("</section>")
        sections.append("\n".join(body))
    return (
        '<!DOCTYPE html>\n<html lang="en">\n<head>\n<meta charset="utf-8">\n'
        "<title>moving-bogie: the paper's tables and figures, rebuilt</title>\n"
        f"<style>{_CSS}</style>\n</head>\n<body>\n"
        "<h1>The paper's tables and figures, rebuilt</h1>\n"
        "<p>Z. Dimitrovová, <em>Instability of a Moving Bogie: Analysis of Vibrations and Possibility of "
        "Instability in Subcritical Velocity Range</em>, preprint doi 10.20944/preprints202501.1517.v1 "
        "(2025). "
        "Each artifact is shown under the paper's caption, quoted verbatim.</p>\n"
        f"<p>{html.escape(facts)}.<br><strong>{html.escape(summary)}.</strong></p>\n"
        f'<table class="toc">\n{"".join(toc)}\n</table>\n' + "\n".join(sections) + "\n</body>\n</html>\n"
    )


def _index_md(report: Report) -> str:
    facts, summary = _header_facts(report)
    lines = [
        "# The paper's tables and figures, rebuilt",
        "",
        "Z. Dimitrovová, *Instability of a Moving Bogie: Analysis of Vibrations and Possibility of "
        "Instability in Subcritical Velocity Range*, preprint doi 10.20944/preprints202501.1517.v1 (2025). "
        "Each artifact is "
        "shown under the paper's caption, quoted verbatim.",
        "",
        f"{facts}. **{summary}.**",
        "",
        "| artifact | status | reason |",
        "|---|---|---|",
    ]
    for o in report.outcomes:
        reason = o.reason.replace("|", "\\|") if o.status != "covered" else ""
        lines.append(f"| [{o.artifact.label}](#{o.artifact.id}) | {o.status} | {reason} |")
    for o in report.outcomes:
        a = o.artifact
        printed = f' (printed as "{a.caption.printed_label}.")' if a.caption.printed_label else ""
        lines += [
            "",
            f'<a id="{a.id}"></a>',
            "",
            f"## {a.label} — {o.status}",
            "",
            f"> **{a.label}.**{printed} {a.caption.text}",
            "",
        ]
        if o.status == "covered":
            for rel in o.built.files:
                if rel.endswith(".png"):
                    lines += [f"![{a.label}]({rel})", ""]
            if o.built.markdown:
                lines += [o.built.markdown, ""]
            others = [rel for rel in o.built.files if not rel.endswith(".png")]
            if others:
                lines += ["Files: " + ", ".join(f"[{r}]({r})" for r in others), ""]
        elif o.status == "failed":
            lines += [
                f"**Failed:** {o.reason}" + (f" ([traceback]({o.built.files[0]}))" if o.built.files else ""),
                "",
            ]
        else:
            lines += [f"**{o.status.capitalize()}:** {o.reason}", ""]
        notes = list(o.built.notes) + ([f"Built in {o.seconds:.1f} s."] if o.seconds else [])
        lines += [f"- {n}" for n in notes]
    return "\n".join(lines).rstrip() + "\n"
