"""Results shown as HTML tables in Jupyter (``_repr_html_``, as xarray and pandas objects show themselves).

A result's table opens with its verdict (coloured: STABLE green, UNSTABLE red, anything else amber), then
its facts as name/value rows, then at most one table of items (the induced frequencies, the quantities
compared). Every text is escaped: a parameter file's name or a note cannot inject markup.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from html import escape

__all__ = ["html_table", "verdict_colour"]

#: Colour of a verdict's word (anything not listed: amber, as for UNDETERMINED).
VERDICT_COLOURS = {"STABLE": "#1a7f37", "UNSTABLE": "#cf222e", "AGREES": "#1a7f37", "DISAGREES": "#cf222e"}


def verdict_colour(state: str) -> str:
    """The colour of a verdict's first word (``#9a6700``, amber, for UNDETERMINED and the rest)."""
    return VERDICT_COLOURS.get(state.split()[0].upper() if state else "", "#9a6700")


def _cell(value: object, tag: str = "td") -> str:
    return f"<{tag} style='text-align:left'>{escape(str(value))}</{tag}>"


def html_table(
    title: str,
    verdict: str,
    rows: Iterable[tuple[str, object]],
    *,
    reasons: Sequence[str] = (),
    items: tuple[Sequence[str], Iterable[Sequence[object]]] | None = None,
) -> str:
    """An HTML fragment: ``title``, the ``verdict`` (with its ``reasons``), the name/value ``rows`` and
    an optional table ``items`` = (header, rows). Every text is escaped."""
    head = escape(verdict)
    out = [
        "<div class='moving-bogie-result'>",
        f"<p><b>{escape(title)}</b>: <b style='color:{verdict_colour(verdict)}'>{head}</b></p>",
    ]
    if reasons:
        out.append("<ul>" + "".join(f"<li>{escape(str(r))}</li>" for r in reasons) + "</ul>")
    out.append("<table>")
    out += [f"<tr>{_cell(name, 'th')}{_cell(value)}</tr>" for name, value in rows]
    out.append("</table>")
    if items is not None:
        header, lines = items
        out.append("<table><tr>" + "".join(_cell(h, "th") for h in header) + "</tr>")
        out += ["<tr>" + "".join(_cell(v) for v in line) + "</tr>" for line in lines]
        out.append("</table>")
    out.append("</div>")
    return "\n".join(out)
